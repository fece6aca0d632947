//! The physical time over a phase of the contact, `t = ∫ w^(-γ) dτ`, by Gauss rules that span several steps.
//!
//! The integrand is analytic along a phase but for the zeros of `w` at the contact's ends (first contact, a
//! penetration separation), where `w^(-γ)` has a branch point; the solution's own singularities (the poles of
//! `1 + x v` of a heavy damping) lie off the real axis, no nearer to a step's start than the radius of convergence
//! its coefficients show. So one Gauss rule may span many steps, each node evaluated on the polynomial of the step
//! it falls in. Its error falls like `R^(-2m)` for `m` nodes, `R` the largest Bernstein ellipse about the panel
//! that stays inside every step's disc of convergence and clear of the zeros of `w` ([`Segments::nodes`]); a zero
//! at a panel's end is integrated exactly by the Gauss–Jacobi weight `s^(-γ)`, with `w = |τ - zero| Q(τ)` and
//! `Q^(-γ)` smooth. Where two consecutive steps' coefficients show the same conjugate pair of singularities, the
//! pair itself bounds the ellipse ([`conjugate_pair`]). A phase of a dozen steps takes a rule of 6 to 20 nodes
//! (`alpha v0 = 10`: 6, 9 and 15 to the force peak, to maximum compression and to separation at a tolerance of
//! 1e-9); a rule for each step took 4 to 10 nodes a step, and steps were cut short so that each stayed clear of the
//! next zero.
//!
//! The steps of the phase in progress are kept ([`Segments`], at most [`CAPACITY`]); their integrals are taken
//! when the phase ends, or for the older half when the store is full (a creeping restitution of thousands of
//! steps).

use super::quadrature::{JacobiRules, MAX_NODES, gauss_legendre, negative_power};
use super::regularised::Expansion;
use super::taylor::{self, Coefficients, MAX_ORDER};

/// Steps kept for the phase in progress (each its polynomial `w`: about 0.3 kB).
pub const CAPACITY: usize = 32;

/// Halvings of a range before its integral is given up: each halves a piece's length against its distance to a
/// zero of `w` just beyond an unweighted end (where only a lower bound on that zero's place is known).
const MAX_HALVINGS: u32 = 60;

/// One step's polynomial `w` over the part of the step that lies in the phase.
#[derive(Debug, Clone, Copy)]
struct Segment {
    /// `τ` at the step's start, where its polynomial is expanded.
    origin: f64,
    /// The part of the step in the phase, in `τ`.
    from: f64,
    to: f64,
    /// The radius of convergence that the step's coefficients show: `w` is analytic within it of `origin`.
    radius: f64,
    /// The singularities of `w` nearest to `origin`, `re ± i im` (`τ`), where the step's coefficients show a
    /// conjugate pair that the neighbouring step's confirm ([`Segments::push`]).
    pole: Option<(f64, f64)>,
    w: Coefficients,
}

const EMPTY: Segment = Segment { origin: 0.0, from: 0.0, to: 0.0, radius: 0.0, pole: None, w: [0.0; MAX_ORDER + 1] };

/// What lies at or beyond an end of an integrated range.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum End {
    /// `w` vanishes at the end itself (first contact, a penetration separation): the Gauss–Jacobi weight takes it.
    Zero,
    /// The nearest zero of `w` on this side lies at this `τ` or farther (`±∞`: none that matters).
    Clear(f64),
    /// (At the range's end only.) `w` vanishes at `zero` just past the end, inside the last kept step's reach (a
    /// force separation, where the penetration's zero follows within the step, possibly an ulp later): the range
    /// is integrated to that zero under the Gauss–Jacobi weight, less the piece from the end to it, which no rule
    /// clear of so near a zero could reach — `piece` where the caller has it in closed form, else a rule weighted
    /// at the zero.
    ZeroBeyond { zero: f64, piece: Option<f64> },
}

/// The steps of the phase in progress, oldest first.
pub struct Segments {
    list: [Segment; CAPACITY],
    len: usize,
    order: usize,
    /// The newest step kept: its origin, the conjugate pair its coefficients show and whether that pair was
    /// confirmed (a step cut by maximum compression is kept as two pieces, which share the decision: a step
    /// cannot confirm its own pair).
    last: Option<Kept>,
    /// `Q` at a zero of `w` at an end of the panel being summed (scratch).
    factor: Coefficients,
}

impl Default for Segments {
    fn default() -> Self {
        Segments { list: [EMPTY; CAPACITY], len: 0, order: 0, last: None, factor: [0.0; MAX_ORDER + 1] }
    }
}

/// What [`Segments::push`] remembers of the newest step: its origin, the conjugate pair its coefficients show
/// (`re ± i im`, in `τ`) and whether that pair was confirmed.
#[derive(Debug, Clone, Copy)]
struct Kept {
    origin: f64,
    pair: Option<(f64, f64)>,
    pole: Option<(f64, f64)>,
}

/// A panel's rule: which weight, over which range.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Weight {
    Legendre,
    /// `(τ - from)^(-γ)`: the zero of `w` at the panel's start.
    ZeroAtStart,
    /// `(to - τ)^(-γ)`: the zero of `w` at the panel's end.
    ZeroAtEnd,
}

impl Segments {
    /// Forgets every step (a new impact).
    pub fn clear(&mut self, order: usize) {
        self.len = 0;
        self.order = order;
        self.last = None;
    }

    pub fn is_full(&self) -> bool {
        self.len == CAPACITY
    }

    /// Keeps the part from `from` to `to` (`τ`) of the step expanded at `origin`, whose series converges within
    /// `radius`.
    pub fn push(&mut self, expansion: &Expansion, origin: f64, from: f64, to: f64, radius: f64) {
        debug_assert!(self.len < CAPACITY && from <= to);
        // A conjugate pair of singularities, where the step's coefficients show one at the distance their size
        // does and the step before showed the same pair (a pole of a heavy damping: `1 + x v` is an
        // exponential of `x ∫ w`): both steps' pieces are then bounded by the pair itself, not by their discs.
        let (pair, pole) = match self.last {
            // The second piece of the same step: the first piece's decision.
            Some(Kept { origin: last_origin, pair, pole }) if last_origin == origin => (pair, pole),
            last => {
                let pair = conjugate_pair(&expansion.w[..=self.order], radius).map(|(re, im)| (origin + re, im));
                let mut pole = None;
                if let (Some(now), Some(Kept { pair: Some(before), .. })) = (pair, last) {
                    let distance2 = (now.0 - origin).powi(2) + now.1 * now.1;
                    let apart2 = (now.0 - before.0).powi(2) + (now.1 - before.1).powi(2);
                    if apart2 <= PAIR_AGREEMENT * PAIR_AGREEMENT * distance2 {
                        pole = Some(now);
                        if let Some(previous) = self.len.checked_sub(1).map(|i| &mut self.list[i])
                            && previous.to == from
                        {
                            previous.pole.get_or_insert(before);
                        }
                    }
                }
                (pair, pole)
            }
        };
        self.last = Some(Kept { origin, pair, pole });
        // (Whole arrays: a fixed-size copy, where the order's length would call memcpy.)
        self.list[self.len] = Segment { origin, from, to, radius, pole, w: expansion.w };
        self.len += 1;
    }

    /// Drops the steps that end at or before `tau` (after their integrals were taken up to it).
    pub fn drop_until(&mut self, tau: f64) {
        let gone = self.list[..self.len].iter().take_while(|s| s.to <= tau).count();
        self.list.copy_within(gone..self.len, 0);
        self.len -= gone;
    }

    /// `τ` at the end of the older half of the steps kept (where a full store is integrated up to).
    pub fn half_way(&self) -> f64 {
        self.list[self.len / 2 - 1].to
    }

    /// `∫_a^b w^(-gamma) dτ` over the kept steps (`a`, `b` within their span), `start` and `end` saying where the
    /// zeros of `w` lie. One rule over the whole range if [`MAX_NODES`] nodes suffice ([`Segments::nodes`]),
    /// else the range split in two (between steps, or within one step) and each part taken the same way.
    /// `digits` is `ln(1/eps)` and a margin ([`super::quadrature::node_digits`]). `None` if `w <= 0` at a node of
    /// the time's rule, or if no part near a zero of `w` just beyond `b` is short enough.
    #[allow(clippy::too_many_arguments)]
    pub fn integral(
        &mut self,
        gamma: f64,
        a: f64,
        b: f64,
        start: End,
        end: End,
        digits: f64,
        jacobi: &mut JacobiRules,
    ) -> Option<f64> {
        if b <= a {
            return Some(0.0);
        }
        debug_assert!(self.len > 0 && b <= self.list[self.len - 1].to && !matches!(start, End::ZeroBeyond { .. }));
        debug_assert!(!(start == End::Zero && end == End::Zero), "a zero at both ends: split the range first");
        if let End::ZeroBeyond { zero, piece } = end {
            // ∫_a^b = ∫_a^zero - ∫_b^zero, both under the weight at the zero (the last step's polynomial reaches
            // it).
            let left = match start {
                End::Zero => End::Clear(a),
                other => other,
            };
            let whole = self.range_to(gamma, a, zero, start, digits, jacobi)?;
            let piece = match piece {
                Some(piece) => piece,
                None => self.range_to(gamma, b, zero, left, digits, jacobi)?,
            };
            return Some(whole - piece);
        }
        let first = self.list[..self.len].iter().position(|s| s.to > a)?;
        let last = first + self.list[first..self.len].iter().position(|s| s.to >= b)?;
        let range = Range { from: a, to: b, first, last, start, end };
        self.range_integral(gamma, range, digits, jacobi, 0)
    }

    /// `∫_a^zero w^(-gamma) dτ` under the weight at `zero`, a zero of `w` at or past the end of the last kept step
    /// (whose polynomial reaches it; `a` within or at the end of the kept steps).
    fn range_to(
        &mut self,
        gamma: f64,
        a: f64,
        zero: f64,
        start: End,
        digits: f64,
        jacobi: &mut JacobiRules,
    ) -> Option<f64> {
        if zero <= a {
            return Some(0.0);
        }
        let last = self.len - 1;
        let first = self.list[..self.len].iter().position(|s| s.to > a).unwrap_or(last);
        let range = Range { from: a, to: zero, first, last, start, end: End::Zero };
        self.range_integral(gamma, range, digits, jacobi, 0)
    }

    /// [`Segments::integral`] over one range, split while it needs more than [`MAX_NODES`] nodes (`depth` splits
    /// so far).
    fn range_integral(
        &mut self,
        gamma: f64,
        range: Range,
        digits: f64,
        jacobi: &mut JacobiRules,
        depth: u32,
    ) -> Option<f64> {
        let Range { from, to, first, last, start, end } = range;
        let weight = match (start, end) {
            (End::Zero, _) => Weight::ZeroAtStart,
            (_, End::Zero) => Weight::ZeroAtEnd,
            _ => Weight::Legendre,
        };
        let m = self.nodes(&range, weight, digits);
        if m <= MAX_NODES {
            return self.panel(gamma, &range, weight, m, jacobi);
        }
        if depth >= MAX_HALVINGS {
            return None;
        }
        // Between the two steps nearest the middle, or the one step's piece halved; the new ends are clear of the
        // zeros beyond the old ones.
        let middle = from + 0.5 * (to - from);
        let (cut, left_last) = if first < last {
            let k = (first..last)
                .min_by(|&i, &j| (self.list[i].to - middle).abs().total_cmp(&(self.list[j].to - middle).abs()))?;
            (self.list[k].to, k)
        } else {
            (middle, first)
        };
        let right_first = if cut >= self.list[left_last].to { left_last + 1 } else { left_last };
        let zero_left = match start {
            End::Zero => End::Clear(from),
            other => other,
        };
        let zero_right = match end {
            End::Zero => End::Clear(to),
            other => other,
        };
        let left = Range { from, to: cut, first, last: left_last, start, end: zero_right };
        let right = Range { from: cut, to, first: right_first, last, start: zero_left, end };
        Some(
            self.range_integral(gamma, left, digits, jacobi, depth + 1)?
                + self.range_integral(gamma, right, digits, jacobi, depth + 1)?,
        )
    }

    /// The nodes a rule over `range` needs: `m = ln(1/eps)/(2 ln R)` (`digits` is `ln(1/eps)` and a margin), `R`
    /// the largest Bernstein ellipse about the range that lies inside the union of its steps' discs of
    /// convergence and clear of the zeros of `w` (but one at a weighted end); more than [`MAX_NODES`] if none
    /// is wide enough.
    ///
    /// With `s = (R + 1/R)/2` the ellipse about `[c - L, c + L]` has semi-axes `L s` and `L sqrt(s² - 1)`; each
    /// constraint bounds `s`:
    /// * a zero of `w` at `z`: the semi-major axis below `|z - c|`;
    /// * a step's piece `[lo, hi]` of the range, its disc of radius `ρ` about the step's origin: the ellipse
    ///   above the piece, at most `sqrt(s² - 1) sqrt(L² - u²/s²)` high (`u` the piece's distance from `c`), within
    ///   `ρ` of the origin with the piece's farthest end `dx` away: `(s² - 1)(L² - u²/s²) < ρ² - dx²`, a quadratic
    ///   in `s²`;
    /// * the ellipse's ends beyond the range, in the first and the last step's discs: within `e + L (s - 1)` of
    ///   the origin along the axis (`e` its distance from the range's end) and at most
    ///   `L (s - 1/s) <= 2 L (s - 1)` high: `(e + y)² + 4 y² < ρ²` for `y = L (s - 1)`.
    fn nodes(&self, range: &Range, weight: Weight, digits: f64) -> usize {
        let Range { from, to, first, last, start, end } = *range;
        let half = 0.5 * (to - from);
        let centre = from + half;
        let mut s2 = f64::INFINITY;
        // (A NaN bound stays NaN, where `min` would drop it: no rule then.)
        let tighten = |s2: &mut f64, bound: f64| *s2 = if bound.is_nan() || bound < *s2 { bound } else { *s2 };
        // The zeros of w.
        for (zero, weighted) in [(start, weight == Weight::ZeroAtStart), (end, weight == Weight::ZeroAtEnd)] {
            if let (End::Clear(z), false) = (zero, weighted) {
                tighten(&mut s2, ((z - centre) / half).powi(2));
            }
        }
        // The steps' pieces: each bounded by its conjugate pair of singularities where it has one (the ellipse
        // through a point z has s = (|z - from| + |z - to|)/(to - from)), else by its disc.
        for segment in &self.list[first..=last] {
            if let Some((re, im)) = segment.pole {
                let im = POLE_MARGIN * im;
                tighten(&mut s2, ((norm(re - from, im) + norm(re - to, im)) / (to - from)).powi(2));
                continue;
            }
            let (lo, hi) = (segment.from.max(from), segment.to.min(to));
            let dx = (lo - segment.origin).abs().max((hi - segment.origin).abs());
            let room = segment.radius * segment.radius - dx * dx;
            if room.is_nan() || room <= 0.0 {
                return usize::MAX;
            }
            let u = if lo <= centre && centre <= hi { 0.0 } else { (lo - centre).abs().min((hi - centre).abs()) };
            let (l2, u2) = (half * half, u * u);
            let sum = l2 + u2 + room;
            tighten(&mut s2, (sum + (sum * sum - 4.0 * l2 * u2).max(0.0).sqrt()) / (2.0 * l2));
        }
        // The ellipse's ends, where a disc bounds the end's step.
        for (segment, e) in
            [(&self.list[first], from - self.list[first].origin), (&self.list[last], to - self.list[last].origin)]
        {
            if segment.pole.is_some() {
                continue;
            }
            let e = e.abs();
            let y = (-e + (5.0 * segment.radius * segment.radius - 4.0 * e * e).max(0.0).sqrt()) / 5.0;
            if y.is_nan() || y <= 0.0 {
                return usize::MAX;
            }
            tighten(&mut s2, (1.0 + y / half).powi(2));
        }
        if s2.is_nan() || s2 <= 1.0 {
            return usize::MAX;
        }
        let s = s2.sqrt();
        let r = s + (s2 - 1.0).sqrt();
        let m = digits / (2.0 * taylor::rough_log2(r) * std::f64::consts::LN_2);
        if m.is_finite() { (m.ceil() as usize).max(2) } else { usize::MAX }
    }

    /// One panel's rule of `m` nodes over `range`.
    fn panel(&mut self, gamma: f64, range: &Range, weight: Weight, m: usize, jacobi: &mut JacobiRules) -> Option<f64> {
        match m {
            0..=4 => self.panel_lanes::<4>(gamma, range, weight, m, jacobi),
            5..=8 => self.panel_lanes::<8>(gamma, range, weight, m, jacobi),
            9..=12 => self.panel_lanes::<12>(gamma, range, weight, m, jacobi),
            13..=16 => self.panel_lanes::<16>(gamma, range, weight, m, jacobi),
            _ => self.panel_lanes::<MAX_NODES>(gamma, range, weight, m, jacobi),
        }
    }

    /// [`Segments::panel`] in `N >= m` lanes: the nodes in `τ` order, each step's nodes on its polynomial ([`LANES`]
    /// at once: one vector Horner chain in even and odd parts, [`taylor::values_split`]), then the power at every
    /// node at once, then the weighted sum. (The arrays are written and read in whole vectors: a vector read of
    /// lanes just written one by one waits for the stores.)
    #[inline(always)]
    fn panel_lanes<const N: usize>(
        &mut self,
        gamma: f64,
        range: &Range,
        weight: Weight,
        m: usize,
        jacobi: &mut JacobiRules,
    ) -> Option<f64> {
        let k = self.order;
        let Range { from, to, first, last, .. } = *range;
        let length = to - from;
        // The nodes in ascending τ with their weights (the lanes past m at the last node), and the factor.
        let (nodes, rule_weights) = match weight {
            Weight::Legendre => gauss_legendre(m),
            _ => jacobi.rule(gamma, m),
        };
        let mut at = [0.0; PADDED];
        let mut weights = [0.0; N];
        for i in 0..m {
            (at[i], weights[i]) = match weight {
                Weight::Legendre => (taylor::mul_add(0.5 * length, nodes[i], from + 0.5 * length), rule_weights[i]),
                Weight::ZeroAtStart => (taylor::mul_add(length, nodes[i], from), rule_weights[i]),
                Weight::ZeroAtEnd => (taylor::mul_add(-length, nodes[m - 1 - i], to), rule_weights[m - 1 - i]),
            };
        }
        for i in m..PADDED {
            at[i] = at[m - 1];
        }
        let scale = match weight {
            Weight::Legendre => 0.5 * length,
            _ => negative_power(length, gamma - 1.0),
        };
        // Q at a weighted end: w = (τ - from) Q about a zero at the first step's origin (Q_j = w_(j+1)), or
        // w = (to - τ) Q at a zero inside the last step (synthetic division: Q = -R, w = (σ - z) R + w(z)).
        match weight {
            Weight::ZeroAtStart => {
                let s = &self.list[first];
                debug_assert!(s.origin == from);
                self.factor[..k].copy_from_slice(&s.w[1..=k]);
                self.factor[k] = 0.0;
            }
            Weight::ZeroAtEnd => {
                let s = &self.list[last];
                let zero = to - s.origin;
                let mut r = s.w[k];
                self.factor[k] = 0.0;
                self.factor[k - 1] = -r;
                for j in (1..k).rev() {
                    r = taylor::mul_add(zero, r, s.w[j]);
                    self.factor[j - 1] = -r;
                }
            }
            Weight::Legendre => {}
        }
        // Each step's nodes on its polynomial (or Q), LANES lanes from the step's first node: the lanes beyond its
        // nodes are written over by the next step's.
        let mut w = [1.0; PADDED];
        let mut node = 0;
        for step in first..=last {
            let segment = &self.list[step];
            let end =
                if step == last { m } else { node + at[node..m].iter().take_while(|&&t| t <= segment.to).count() };
            let uses_factor = match weight {
                Weight::ZeroAtStart => step == first,
                Weight::ZeroAtEnd => step == last,
                Weight::Legendre => false,
            };
            let polynomial = if uses_factor { &self.factor } else { &segment.w };
            while node < end {
                let lanes: &[f64; LANES] = at[node..node + LANES].try_into().expect("PADDED >= MAX_NODES + LANES");
                let offsets = lanes.map(|tau| tau - segment.origin);
                let mut values = taylor::values_split(&polynomial[..=k], offsets);
                // w into Q off the weighted end's step.
                if !uses_factor && weight != Weight::Legendre {
                    for (value, &tau) in values.iter_mut().zip(lanes) {
                        *value /= if weight == Weight::ZeroAtStart { tau - from } else { to - tau };
                    }
                }
                w[node..node + LANES].copy_from_slice(&values);
                node = end.min(node + LANES);
            }
        }
        if w[..m].iter().any(|&q| !(q.is_finite() && q > 0.0)) {
            return None;
        }
        let mut values = [0.0; N];
        for i in 0..N {
            values[i] = negative_power(w[i], gamma);
        }
        Some(scale * taylor::dot(&values[..m], &weights[..m]))
    }
}

/// The pair's distance from the real axis that a panel's ellipse keeps clear of, as a fraction of the fitted
/// distance: room for the fit's drift along a contact (a few per cent) and for the integrand's growth towards the
/// pair, which the error bound `M R^(-2m)` takes on the ellipse.
const POLE_MARGIN: f64 = 0.9;

/// Largest distance, relative to the distance from the step, between the conjugate pairs of two consecutive
/// steps for them to count as one pair of singularities ([`Segments::push`]).
const PAIR_AGREEMENT: f64 = 0.05;

/// The conjugate pair of singularities `re ± i im` (offsets from the expansion point) that the last four Taylor
/// coefficients `c` show, if they decay like one: `c_k = a c_(k-1) + b c_(k-2)` fitted to them (Hunter and
/// Guerrieri's two-term recurrence; a pair `p`, `p̄` of poles gives `a = 2 Re(1/p)`, `b = -1/|p|²`), complex roots,
/// and the pair at the distance `radius` that the coefficients' size shows (within `0.8` to `1.6` times: a
/// polynomial or an entire function's factorial decay fits a "pair" about `e` times farther).
fn conjugate_pair(c: &[f64], radius: f64) -> Option<(f64, f64)> {
    let k = c.len() - 1;
    if k < 4 {
        return None;
    }
    let [c3, c2, c1, c0] = [c[k - 3], c[k - 2], c[k - 1], c[k]];
    // a = a_d/d, b = b_d/d by Cramer's rule; the tests multiplied through by d (no division for a step that
    // shows no pair, most of them).
    let d = c2 * c2 - c1 * c3;
    let (a_d, b_d) = (c1 * c2 - c0 * c3, c2 * c0 - c1 * c1);
    // Roots of x² - a x - b (x = 1/p) complex: a² + 4b < 0, i.e. a_d² + 4 b_d d < 0 (which makes b < 0).
    let discriminant = a_d * a_d + 4.0 * b_d * d;
    if discriminant.is_nan() || discriminant >= 0.0 {
        return None;
    }
    // |p|² = 1/|x|² = -1/b = -d/b_d, Re p = Re(x)/|x|² = (a/2)/(-b) = -a_d/(2 b_d).
    let distance2 = -d / b_d;
    let r2 = radius * radius;
    if !(distance2 >= 0.64 * r2 && distance2 <= 2.56 * r2) {
        return None;
    }
    let re = -0.5 * a_d / b_d;
    Some((re, (distance2 - re * re).max(0.0).sqrt()))
}

/// `sqrt(a² + b²)` (the operands here are far from overflow; `hypot` guards against it at several times the cost).
fn norm(a: f64, b: f64) -> f64 {
    taylor::mul_add(a, a, b * b).sqrt()
}

/// Nodes of one step evaluated at once (a step holds two or three of a panel's nodes as a rule: one vector).
const LANES: usize = 4;
/// Lanes of a panel's node arrays: the largest rule and a vector beyond it.
const PADDED: usize = MAX_NODES + LANES;

/// A range to integrate: `τ` from `from` to `to`, over the kept steps `first..=last`, the zeros of `w` at or
/// beyond its ends.
#[derive(Debug, Clone, Copy)]
struct Range {
    from: f64,
    to: f64,
    first: usize,
    last: usize,
    start: End,
    end: End,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fast::quadrature::{composite_gauss_legendre, node_digits};

    /// Steps over `sin τ` (exact Taylor coefficients about each break, order 24, so that the polynomials are
    /// `sin` to rounding), each with a radius of convergence three times its length, as a Taylor step sees it.
    fn sine(breaks: &[f64]) -> Segments {
        let order = 24;
        let mut segments = Segments::default();
        segments.clear(order);
        let mut expansion = Expansion::default();
        for pair in breaks.windows(2) {
            let (origin, to) = (pair[0], pair[1]);
            let mut factorial = 1.0;
            for k in 0..=order {
                if k > 0 {
                    factorial *= k as f64;
                }
                expansion.w[k] = (origin + k as f64 * std::f64::consts::FRAC_PI_2).sin() / factorial;
            }
            segments.push(&expansion, origin, origin, to, 3.0 * (to - origin));
        }
        segments
    }

    /// `∫_0^δ sin(u)^(-γ) du` by the substitution `u = s^p`, `p = 1/(1 - γ)`, which turns it into the smooth
    /// `p ∫_0^(δ^(1-γ)) (sin(s^p)/s^p)^(-γ) ds`, summed by composite Gauss–Legendre (independent of the panels).
    fn sine_power_near_zero(delta: f64, gamma: f64) -> f64 {
        let p = 1.0 / (1.0 - gamma);
        let integrand = |s: f64| {
            let u = s.powf(p);
            let ratio = if u == 0.0 { 1.0 } else { u.sin() / u };
            p * ratio.powf(-gamma)
        };
        composite_gauss_legendre(integrand, 0.0, delta.powf(1.0 - gamma), 40, 20)
    }

    /// `∫_0^(π/2) sin^(-γ) = ∫_(π/2)^π sin^(-γ) = B((1-γ)/2, 1/2)/2`: the zero at first contact and the one at
    /// separation, each under the Gauss–Jacobi weight, over several steps.
    #[test]
    fn the_sine_power_over_either_half_is_the_beta_function() {
        let pi = std::f64::consts::PI;
        let breaks = [0.0, 0.3, 0.7, 1.2, 0.5 * pi, 2.0, 2.6, 2.95, pi];
        let mut jacobi = JacobiRules::default();
        for gamma in [0.2, 0.375, -0.3] {
            let exact = 0.5 * crate::reference::beta(0.5 * (1.0 - gamma), 0.5);
            for eps in [1e-10, 1e-17] {
                let mut segments = sine(&breaks);
                let digits = node_digits(eps);
                let compression =
                    segments.integral(gamma, 0.0, 0.5 * pi, End::Zero, End::Clear(pi), digits, &mut jacobi).unwrap();
                let restitution =
                    segments.integral(gamma, 0.5 * pi, pi, End::Clear(0.0), End::Zero, digits, &mut jacobi).unwrap();
                for (got, what) in [(compression, "compression"), (restitution, "restitution")] {
                    let error = (got / exact - 1.0).abs();
                    assert!(error < eps.max(2e-15), "γ = {gamma}, eps = {eps:e}, {what}: {error:e}");
                }
            }
        }
    }

    /// A range that ends a hair before a zero of `w` it does not weight (a force separation just before the
    /// penetration's) is split towards that end until each part's rule reaches it.
    #[test]
    fn a_zero_just_beyond_the_range_is_approached_by_halving() {
        let pi = std::f64::consts::PI;
        let mut jacobi = JacobiRules::default();
        let gamma = 0.2;
        let half = 0.5 * crate::reference::beta(0.5 * (1.0 - gamma), 0.5);
        for delta in [1e-3, 1e-7] {
            let mut segments = sine(&[0.5 * pi, 2.2, 2.8, pi - delta]);
            let got = segments
                .integral(gamma, 0.5 * pi, pi - delta, End::Clear(0.0), End::Clear(pi), node_digits(1e-13), &mut jacobi)
                .unwrap();
            let exact = half - sine_power_near_zero(delta, gamma);
            assert!((got / exact - 1.0).abs() < 1e-13, "δ = {delta:e}: {got} vs {exact}");
        }
    }

    /// The node count follows the ellipse: more for a longer range over the same steps, none that reaches a zero
    /// of `w` at an unweighted end.
    #[test]
    fn node_counts_follow_the_ellipse() {
        let pi = std::f64::consts::PI;
        let segments = sine(&[0.0, 0.4, 0.8, 1.2, 1.6]);
        let digits = node_digits(1e-10);
        let count = |to: f64, last: usize, start: End| {
            let range = Range { from: 0.0, to, first: 0, last, start, end: End::Clear(pi) };
            let weight = if start == End::Zero { Weight::ZeroAtStart } else { Weight::Legendre };
            segments.nodes(&range, weight, digits)
        };
        let (one, four) = (count(0.4, 0, End::Zero), count(1.6, 3, End::Zero));
        assert!(2 <= one && one < four && four <= MAX_NODES, "{one} {four}");
        // The same range with the zero at its start left to a plain Gauss–Legendre rule: no ellipse fits.
        assert!(count(1.6, 3, End::Clear(0.0)) > MAX_NODES);
    }

    /// A panel's sum at every node count (each lane width, the unused lanes, nodes falling in every one of three
    /// steps, both Jacobi weights) against the plain sum `Σ W_i q(τ_i)^(-γ)`, each node's `q` by Horner on its own
    /// step's polynomial and the power by `powf`.
    #[test]
    fn panel_sums_equal_the_plain_sum_at_every_node_count() {
        let order = 5;
        let mut segments = Segments::default();
        segments.clear(order);
        let mut expansion = Expansion::default();
        // Three steps over [1, 2.5], each w > 0 throughout; the last one's w vanishes at 2.5 (for ZeroAtEnd), the
        // first's at its origin 1 (for ZeroAtStart).
        let polynomials: [[f64; 6]; 3] = [
            [0.0, 0.9, -0.2, 0.05, 0.0, 0.001],
            [0.5, 0.3, -0.1, 0.02, -0.003, 0.0],
            [0.45, -0.6, -0.1, 0.0, 0.0, 0.0],
        ];
        let origins = [1.0, 1.5, 2.0];
        // The last one's zero: 0.45 - 0.6 σ - 0.1 σ² = 0.
        let zero = 2.0 + (-0.6 + (0.36f64 + 0.18).sqrt()) / 0.2;
        let ends = [1.5, 2.0, zero];
        for ((c, &origin), &end) in polynomials.iter().zip(&origins).zip(&ends) {
            expansion.w[..=order].copy_from_slice(c);
            segments.push(&expansion, origin, origin, end, 10.0);
        }
        let q = |tau: f64, weight: Weight| {
            let step = (0..3).find(|&i| tau <= ends[i]).unwrap_or(2);
            let w = crate::fast::taylor::value(&polynomials[step], tau - origins[step]);
            match weight {
                Weight::Legendre => w,
                Weight::ZeroAtStart => w / (tau - 1.0),
                Weight::ZeroAtEnd => w / (zero - tau),
            }
        };
        let gamma = 0.375;
        let mut jacobi = JacobiRules::default();
        for m in 1..=MAX_NODES {
            for weight in [Weight::Legendre, Weight::ZeroAtStart, Weight::ZeroAtEnd] {
                let (from, to) = match weight {
                    Weight::Legendre => (1.2, 2.3),
                    Weight::ZeroAtStart => (1.0, 2.3),
                    Weight::ZeroAtEnd => (1.2, zero),
                };
                // (The panel's weight is given; the range's ends only matter to the node count.)
                let clear = End::Clear(f64::INFINITY);
                let range = Range { from, to, first: 0, last: 2, start: clear, end: clear };
                let got = segments.panel(gamma, &range, weight, m, &mut jacobi).expect("q > 0 at every node");
                let plain: f64 = match weight {
                    Weight::Legendre => {
                        let (x, w) = gauss_legendre(m);
                        let half = 0.5 * (to - from);
                        x.iter().zip(w).map(|(&x, &w)| half * w * q(from + half * (1.0 + x), weight).powf(-gamma)).sum()
                    }
                    _ => {
                        let (s, w) = jacobi.rule(gamma, m);
                        let length = to - from;
                        let at =
                            |s: f64| if weight == Weight::ZeroAtStart { from + length * s } else { to - length * s };
                        let sum: f64 = s.iter().zip(w).map(|(&s, &w)| w * q(at(s), weight).powf(-gamma)).sum();
                        length.powf(1.0 - gamma) * sum
                    }
                };
                assert!((got / plain - 1.0).abs() < 1e-14, "{m} nodes, {weight:?}: {got} vs {plain}");
            }
        }
    }

    /// The two-term fit finds the poles `±i` of `1/(1 + τ²)` (coefficients `(-1)^j` at even orders) from an expansion
    /// about 0, and `a ± i b` of `1/((τ - a)² + b²)` about another point; it finds none in the factorial decay of
    /// an entire function (`sin`: its "pair" sits about `e` times beyond the radius the coefficients' size shows),
    /// nor in a real pole's geometric decay.
    #[test]
    fn conjugate_pairs_of_poles_are_found_and_entire_functions_have_none() {
        let order = 18;
        // 1/(1 + τ²) about 0: radius 1.
        let lorentz: Vec<f64> =
            (0..=order).map(|j| if j % 2 == 0 { if j % 4 == 0 { 1.0 } else { -1.0 } } else { 0.0 }).collect();
        let (re, im) = conjugate_pair(&lorentz, 1.0).expect("poles at ±i");
        assert!(re.abs() < 1e-12 && (im - 1.0).abs() < 1e-12, "{re} {im}");
        // 1/((τ - a)² + b²) = Im(1/(τ - p))/b with p = a + i b, expanded about 0: c_j = -Im(p^(-j-1))/b.
        let (a, b): (f64, f64) = (0.3, 0.8);
        let mut power = (1.0, 0.0); // p^(-j-1), built by multiplying with 1/p
        let inverse = (a / (a * a + b * b), -b / (a * a + b * b));
        let shifted: Vec<f64> = (0..=order)
            .map(|_| {
                power = (power.0 * inverse.0 - power.1 * inverse.1, power.0 * inverse.1 + power.1 * inverse.0);
                -power.1 / b
            })
            .collect();
        let radius = a.hypot(b);
        let (re, im) = conjugate_pair(&shifted, radius).expect("poles at a ± i b");
        assert!((re - a).abs() < 1e-10 && (im - b).abs() < 1e-10, "{re} {im}");
        // sin τ: the coefficients' size shows a radius of about K/e; the fit's pair lies near K, rejected.
        let mut factorial = 1.0;
        let sine: Vec<f64> = (0..=order)
            .map(|j| {
                if j > 0 {
                    factorial *= j as f64;
                }
                (j as f64 * std::f64::consts::FRAC_PI_2).sin() / factorial
            })
            .collect();
        let radius = (sine[order - 1].abs()).powf(-1.0 / (order - 1) as f64);
        assert_eq!(conjugate_pair(&sine, radius), None);
        // 1/(2 - τ): a real pole, no pair.
        let geometric: Vec<f64> = (0..=order).map(|j| 0.5f64.powi(j as i32 + 1)).collect();
        assert_eq!(conjugate_pair(&geometric, 2.0), None);
    }

    /// A confirmed pair bounds the steps it was seen from by its own ellipse: `1/(1 + τ²)` over three steps of
    /// `[1, 2.5]`, each seeing the poles `±i` (its disc only reaches to `sqrt(1 + τ²)`), takes the nodes of the
    /// ellipse through `0.9 i` (the pair, a tenth of its distance kept clear) — fewer than the discs alone allow —
    /// and integrates `∫ (1 + τ²)^(0.3)` to the tolerance.
    #[test]
    fn a_confirmed_pair_of_poles_sets_the_ellipse() {
        let order = 24;
        let mut segments = Segments::default();
        segments.clear(order);
        let mut expansion = Expansion::default();
        let breaks = [1.0, 1.5, 2.0, 2.5];
        for pair in breaks.windows(2) {
            let origin = pair[0];
            // 1/(1 + τ²) = Im(1/(τ - i)) about origin: 1/(σ - q) = -Σ σ^j q^(-j-1), q = i - origin.
            let q = (-origin, 1.0); // i - origin
            let m2 = q.0 * q.0 + q.1 * q.1;
            let inverse = (q.0 / m2, -q.1 / m2);
            let mut power = (1.0, 0.0);
            for j in 0..=order {
                power = (power.0 * inverse.0 - power.1 * inverse.1, power.0 * inverse.1 + power.1 * inverse.0);
                expansion.w[j] = -power.1;
            }
            segments.push(&expansion, origin, origin, pair[1], (1.0 + origin * origin).sqrt());
        }
        assert!(segments.list[..3].iter().all(|s| s.pole.is_some()), "every step's pair confirmed");
        let digits = node_digits(1e-12);
        let range = Range {
            from: 1.0,
            to: 2.5,
            first: 0,
            last: 2,
            start: End::Clear(f64::NEG_INFINITY),
            end: End::Clear(f64::INFINITY),
        };
        let with_pair = segments.nodes(&range, Weight::Legendre, digits);
        // The ellipse through the pair, a tenth of its distance kept clear (0.9 i), about [1, 2.5]:
        // s = (|0.9 i - 1| + |0.9 i - 2.5|)/1.5, m = ceil(digits/(2 ln R)).
        let im = POLE_MARGIN;
        let s = ((1.0 + im * im).sqrt() + (6.25 + im * im).sqrt()) / 1.5;
        let r = s + (s * s - 1.0).sqrt();
        let expected = (digits / (2.0 * r.ln())).ceil() as usize;
        assert_eq!(with_pair, expected, "nodes against those of the ellipse through {im} i");
        for segment in &mut segments.list[..3] {
            segment.pole = None;
        }
        assert!(segments.nodes(&range, Weight::Legendre, digits) > with_pair);
        // ∫_1^2.5 (1 + τ²)^0.3 dτ, with w = 1/(1 + τ²) and γ = 0.3, against composite Gauss–Legendre of the
        // closed-form integrand.
        for segment in &mut segments.list[..3] {
            segment.pole = Some((0.0, 1.0));
        }
        let mut jacobi = JacobiRules::default();
        let got = segments
            .integral(0.3, 1.0, 2.5, End::Clear(f64::NEG_INFINITY), End::Clear(f64::INFINITY), digits, &mut jacobi)
            .unwrap();
        let exact = composite_gauss_legendre(|t| (1.0 + t * t).powf(0.3), 1.0, 2.5, 30, 20);
        assert!((got / exact - 1.0).abs() < 1e-12, "{got} vs {exact}");
    }

    /// A step cut by maximum compression is kept as two pieces of one expansion: the second piece repeats the
    /// first's decision, it does not confirm the pair its own coefficients show (alone, no pair is confirmed); a
    /// neighbouring step that shows the same pair confirms both itself and the piece before it.
    #[test]
    fn a_step_does_not_confirm_its_own_pair() {
        let order = 24;
        let expand = |origin: f64| {
            let mut expansion = Expansion::default();
            let q = (-origin, 1.0);
            let m2 = q.0 * q.0 + q.1 * q.1;
            let inverse = (q.0 / m2, -q.1 / m2);
            let mut power = (1.0, 0.0);
            for j in 0..=order {
                power = (power.0 * inverse.0 - power.1 * inverse.1, power.0 * inverse.1 + power.1 * inverse.0);
                expansion.w[j] = -power.1;
            }
            expansion
        };
        let mut segments = Segments::default();
        segments.clear(order);
        let first = expand(1.0);
        let radius = 2f64.sqrt();
        segments.push(&first, 1.0, 1.0, 1.2, radius);
        segments.push(&first, 1.0, 1.2, 1.5, radius);
        assert!(segments.list[..2].iter().all(|s| s.pole.is_none()), "one step alone confirms no pair");
        segments.push(&expand(1.5), 1.5, 1.5, 2.0, (1.0f64 + 2.25).sqrt());
        assert!(segments.list[1..3].iter().all(|s| s.pole.is_some()), "the next step confirms the pair");
    }
}
