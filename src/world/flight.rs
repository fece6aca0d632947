//! Free flight in closed form, and the first touch of two bodies found exactly (docs/world.md#flight).
//!
//! A body of finite mass flies on a parabola under the uniform gravity g, an immovable one on a straight line
//! (gravity does not move it). Two free bodies feel the same g, so their relative motion is a straight line and their
//! first touch a quadratic, as without gravity; a body against an immovable one is a parabola against a line: a
//! quadratic for a flat face, a quartic for a fixed sphere. The smallest root where the gap turns from open to
//! closed is isolated between the critical points of the polynomial (the roots of its derivative, recursively) and
//! polished by bisection on the polynomial and Newton steps on the gap itself — never by stepping in time.

use crate::body::Body;
use crate::geometry::Meeting;
use nalgebra::{UnitQuaternion, Vector3};

/// Where a body is and how it moves at one instant (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematic {
    /// Position of the centre (a flat body: a point of its face), m.
    pub position: Vector3<f64>,
    /// Velocity, m/s.
    pub velocity: Vector3<f64>,
    /// Angular velocity, rad/s: constant in flight for a sphere (only a contact's friction changes it); a rigid body
    /// that spins flies in an island (docs/world.md#rigid-bodies).
    pub spin: Vector3<f64>,
    /// The rotation from the scene axes at t = 0 (identity for a body whose orientation nobody reads: a sphere, a
    /// wall): constant in closed-form flight.
    pub orientation: UnitQuaternion<f64>,
}

/// The acceleration of `body` in free flight: g for a finite mass, none for an immovable body.
pub fn acceleration(body: &Body, gravity: &Vector3<f64>) -> Vector3<f64> {
    if body.is_immovable() { Vector3::zeros() } else { *gravity }
}

impl Kinematic {
    /// The flight `time` (s) later under the acceleration `a`.
    pub fn after(&self, time: f64, a: &Vector3<f64>) -> Kinematic {
        Kinematic {
            position: self.position + self.velocity * time + a * (0.5 * time * time),
            velocity: self.velocity + a * time,
            spin: self.spin,
            orientation: self.orientation,
        }
    }

    /// The displacement (m) `time` (s) later under the acceleration `a`.
    pub fn displacement(&self, time: f64, a: &Vector3<f64>) -> Vector3<f64> {
        self.velocity * time + a * (0.5 * time * time)
    }
}

/// When bodies `i` and `j`, flying freely from `now` (their states `a` and `b`, accelerations `ga` and `gb`), next
/// begin a contact: the smallest time τ >= 0 (s, after now) at which the gap closes while they approach — τ = 0 when
/// they touch (within `tolerance`, m) and approach already; for a pair that starts overlapping (parted by a contact's
/// force), when its gap closes again after opening, or when it presses deeper than it starts by `tolerance`. `None`
/// if they never do within `horizon` (s).
#[allow(clippy::too_many_arguments)]
pub fn first_touch(
    meeting: &Meeting,
    a: &Kinematic,
    b: &Kinematic,
    ga: &Vector3<f64>,
    gb: &Vector3<f64>,
    tolerance: f64,
    horizon: f64,
) -> Option<f64> {
    let r0 = b.position - a.position;
    let w = b.velocity - a.velocity;
    let acc = gb - ga;
    if w == Vector3::zeros() && acc == Vector3::zeros() {
        // Moving together (at rest on each other, or given one velocity): the gap never changes.
        return None;
    }
    let (gap0, _) = meeting.penetration(&r0);
    let gap0 = -gap0;
    // The gap as a polynomial in τ (its zeros are the gap's); its rate and curvature at τ = 0 (negative: closing),
    // each with the size of its own rounding, below which it counts as zero.
    let (poly, closing, closing_rounding, curving, curving_rounding): (Vec<f64>, f64, f64, f64, f64) = match *meeting {
        Meeting::Spheres { reach } => {
            // |r0 + w τ + acc τ²/2|² - reach²; the constant term without cancellation: (|r0| - R)(|r0| + R).
            let distance = r0.norm();
            let c0 = gap0 * (distance + reach);
            let c1 = 2.0 * r0.dot(&w);
            let c2 = w.norm_squared() + r0.dot(&acc);
            let c3 = w.dot(&acc);
            let c4 = 0.25 * acc.norm_squared();
            let rounding = 16.0 * f64::EPSILON;
            let curving_rounding = rounding * (w.norm_squared() + distance * acc.norm());
            (vec![c0, c1, c2, c3, c4], c1, rounding * distance * w.norm(), c2, curving_rounding)
        }
        Meeting::Face { face, sign, .. } => {
            // height - radius = gap0 + sign f·w τ + sign f·acc τ²/2.
            let c1 = sign * face.dot(&w);
            let c2 = 0.5 * sign * face.dot(&acc);
            (vec![gap0, c1, c2], c1, 16.0 * f64::EPSILON * w.norm(), c2, 16.0 * f64::EPSILON * acc.norm())
        }
    };
    if gap0.abs() <= tolerance {
        // Touching: they begin now if the gap closes — at a speed beyond its rounding, or, not opening, under an
        // acceleration that closes it (a ball resting on a floor under gravity).
        let approaching = closing < -closing_rounding;
        let pressed = closing <= closing_rounding && curving < -curving_rounding;
        if approaching || pressed {
            return Some(0.0);
        }
        // Touching and parting, or sliding along: the next touch is a later closing of the gap.
    }
    // How far below zero the gap polynomial must dip for a contact: a graze within the rounding of the positions is
    // none (the polynomial of two spheres is the gap times |r| + R).
    let depth = match *meeting {
        Meeting::Spheres { reach } => tolerance * 2.0 * reach,
        Meeting::Face { .. } => tolerance,
    };
    let closing = first_closing(&poly, horizon, depth);
    if gap0 < -tolerance {
        // Overlapping beyond the tolerance (a contact its force ended while the bodies still overlapped): the next
        // touch is the gap's closing after it opens, or — sooner, when they part too slowly for the gap to open
        // before gravity brings them back — their pressing deeper than they start, by the tolerance. That is the
        // gap falling through gap0 - tolerance: for two spheres |r|² through (|r0| - tolerance)².
        let mut deeper = poly.clone();
        deeper[0] = match *meeting {
            Meeting::Spheres { .. } => tolerance * (2.0 * r0.norm() - tolerance),
            Meeting::Face { .. } => tolerance,
        };
        let pressed = first_closing(&deeper, horizon, 0.0);
        return match (closing, pressed) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
    }
    closing
}

/// The first root of `poly` in (0, horizon] where it crosses from positive to below `-depth` (a tangency, a graze of
/// zero depth, is no crossing).
fn first_closing(poly: &[f64], horizon: f64, depth: f64) -> Option<f64> {
    let roots = real_roots(&trim(poly), 0.0, horizon);
    let value = |t: f64| evaluate(poly, t);
    for (k, &root) in roots.iter().enumerate() {
        if root <= 0.0 {
            continue;
        }
        let before = if k == 0 { 0.0 } else { roots[k - 1] };
        let after = roots.get(k + 1).copied().unwrap_or(if horizon.is_finite() { horizon } else { 2.0 * root + 1.0 });
        let open_before = if before < root { value(0.5 * (before + root)) > 0.0 } else { false };
        let closed_after = value(0.5 * (root + after)) < -depth;
        if open_before && closed_after {
            return Some(root);
        }
    }
    None
}

/// The polynomial without its vanishing leading coefficients.
fn trim(poly: &[f64]) -> Vec<f64> {
    let mut p = poly.to_vec();
    while p.len() > 1 && p.last() == Some(&0.0) {
        p.pop();
    }
    p
}

/// p(t) by Horner's rule (coefficients from the constant term up).
pub fn evaluate(poly: &[f64], t: f64) -> f64 {
    poly.iter().rev().fold(0.0, |acc, &c| acc * t + c)
}

fn derivative(poly: &[f64]) -> Vec<f64> {
    poly.iter().enumerate().skip(1).map(|(k, &c)| k as f64 * c).collect()
}

/// The real roots of `poly` in [lo, hi], ascending: the critical points (roots of the derivative, found the same
/// way) cut [lo, hi] into pieces on which the polynomial is monotonic, and each piece whose ends differ in sign
/// holds one root, found by bisection to the last bit. A root of even multiplicity (a tangency) is found as a critical
/// point where the polynomial vanishes to rounding.
pub fn real_roots(poly: &[f64], lo: f64, hi: f64) -> Vec<f64> {
    let poly = trim(poly);
    if poly.len() <= 1 || hi.is_nan() || lo.is_nan() || hi <= lo {
        return Vec::new();
    }
    // A finite bracket: Cauchy's bound on the size of every root.
    let lead = poly[poly.len() - 1];
    let bound = 1.0 + poly[..poly.len() - 1].iter().map(|c| (c / lead).abs()).fold(0.0, f64::max);
    let (lo, hi) = (lo.max(-bound), hi.min(bound));
    if hi.is_nan() || lo.is_nan() || hi < lo {
        return Vec::new();
    }
    let mut cuts = vec![lo];
    cuts.extend(real_roots(&derivative(&poly), lo, hi).into_iter().filter(|&t| t > lo && t < hi));
    cuts.push(hi);
    // The rounding of p(t): eps times the sum of its terms' sizes there.
    let rounding = |t: f64| 8.0 * f64::EPSILON * poly.iter().rev().fold(0.0, |acc, &c| acc * t.abs() + c.abs());
    let mut roots: Vec<f64> = Vec::new();
    for piece in cuts.windows(2) {
        let (a, b) = (piece[0], piece[1]);
        let (fa, fb) = (evaluate(&poly, a), evaluate(&poly, b));
        if fa == 0.0 {
            roots.push(a);
        } else if fa.signum() != fb.signum() && fb != 0.0 {
            roots.push(bisect(&poly, a, b, fa));
        } else if fa.abs() <= rounding(a) && piece[0] != lo {
            // A tangency at a critical point.
            roots.push(a);
        }
    }
    if let Some(&last) = cuts.last()
        && evaluate(&poly, last) == 0.0
    {
        roots.push(last);
    }
    roots.dedup();
    roots
}

/// The root of `poly` in [a, b], where its sign changes (`fa` = p(a)), to the last bit.
fn bisect(poly: &[f64], mut a: f64, mut b: f64, fa: f64) -> f64 {
    for _ in 0..200 {
        let middle = 0.5 * (a + b);
        if middle <= a || middle >= b {
            break;
        }
        let fm = evaluate(poly, middle);
        if fm == 0.0 {
            return middle;
        }
        if fm.signum() == fa.signum() { a = middle } else { b = middle }
    }
    0.5 * (a + b)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn roots_of_a_quartic_with_four_real_roots_are_found_in_order() {
        // (t - 1)(t - 2)(t - 3)(t - 4) = t^4 - 10 t^3 + 35 t^2 - 50 t + 24.
        let roots = real_roots(&[24.0, -50.0, 35.0, -10.0, 1.0], 0.0, 10.0);
        assert_eq!(roots.len(), 4, "{roots:?}");
        for (root, expected) in roots.iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!((root - expected).abs() < 1e-13, "{roots:?}");
        }
        assert_eq!(real_roots(&[24.0, -50.0, 35.0, -10.0, 1.0], 2.5, 3.5).len(), 1);
        // No real root: t^2 + 1.
        assert!(real_roots(&[1.0, 0.0, 1.0], -10.0, 10.0).is_empty());
        // A double root (tangency): (t - 2)^2.
        let double = real_roots(&[4.0, -4.0, 1.0], 0.0, 5.0);
        assert!(double.iter().any(|r| (r - 2.0).abs() < 1e-12), "{double:?}");
    }

    /// A ball a contact's force parted from a floor while it still overlaps it by d0, rising at v: if v² > 2 g d0 its
    /// gap opens and closes again at (v + sqrt(v² - 2 g d0))/g; if not, gravity presses it deeper than it started,
    /// by the tolerance δ, at (v + sqrt(v² + 2 g δ))/g. Two spheres overlapping by d0 and moving apart never touch
    /// again without gravity; closing, they press deeper by δ when |r0| - w t = |r0| - δ, at δ/w.
    #[test]
    fn a_pair_that_starts_overlapping_touches_again_when_its_gap_closes_or_it_presses_deeper() {
        let (g, r, d0, tolerance) = (9.81, 0.01, 1e-4, 1e-15);
        let gravity = Vector3::new(0.0, 0.0, -g);
        let floor = Meeting::Face { face: Vector3::z(), radius: r, sign: 1.0 };
        let wall = Kinematic {
            position: Vector3::zeros(),
            velocity: Vector3::zeros(),
            spin: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        };
        for v in [0.1, 0.02] {
            let ball = Kinematic {
                position: Vector3::new(0.0, 0.0, r - d0),
                velocity: Vector3::new(0.0, 0.0, v),
                spin: Vector3::zeros(),
                orientation: UnitQuaternion::identity(),
            };
            let t = first_touch(&floor, &wall, &ball, &Vector3::zeros(), &gravity, tolerance, 100.0).unwrap();
            let expected = if v * v > 2.0 * g * d0 {
                (v + (v * v - 2.0 * g * d0).sqrt()) / g
            } else {
                (v + (v * v + 2.0 * g * tolerance).sqrt()) / g
            };
            assert!((t - expected).abs() < 1e-12 * expected, "{v}: {t} vs {expected}");
        }
        let spheres = Meeting::Spheres { reach: 0.02 };
        let (w, tolerance) = (0.5, 1e-9);
        let first = Kinematic {
            position: Vector3::zeros(),
            velocity: Vector3::zeros(),
            spin: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        };
        let apart = Kinematic {
            position: Vector3::new(0.02 - d0, 0.0, 0.0),
            velocity: Vector3::new(w, 0.0, 0.0),
            spin: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        };
        let none = Vector3::zeros();
        assert_eq!(first_touch(&spheres, &first, &apart, &none, &none, tolerance, 100.0), None);
        let closing = Kinematic { velocity: Vector3::new(-w, 0.0, 0.0), ..apart };
        let t = first_touch(&spheres, &first, &closing, &none, &none, tolerance, 100.0).unwrap();
        assert!((t - tolerance / w).abs() < 1e-6 * tolerance / w, "{t}");
    }

    /// A ball dropped from rest at height h above a floor (centre at h + r) touches after sqrt(2h/g); a ball thrown
    /// up at u first touches after (u + sqrt(u² + 2 g h))/g; a ball moving away from a fixed sphere never touches
    /// without gravity and comes back with it.
    #[test]
    fn first_touches_under_gravity_are_the_closed_forms() {
        let g = Vector3::new(0.0, 0.0, -9.81);
        let (h, r) = (1.0, 0.01);
        let floor = Meeting::Face { face: Vector3::z(), radius: r, sign: 1.0 };
        let wall = Kinematic {
            position: Vector3::zeros(),
            velocity: Vector3::zeros(),
            spin: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        };
        for u in [0.0, 3.0] {
            let ball = Kinematic {
                position: Vector3::new(0.0, 0.0, h + r),
                velocity: Vector3::new(0.5, 0.0, u),
                spin: Vector3::zeros(),
                orientation: UnitQuaternion::identity(),
            };
            let t = first_touch(&floor, &wall, &ball, &Vector3::zeros(), &g, 1e-14, 100.0).unwrap();
            let expected = (u + (u * u + 2.0 * 9.81 * h).sqrt()) / 9.81;
            assert!((t - expected).abs() < 1e-14 * expected.max(1.0), "{u}: {t} vs {expected}");
        }
        // A ball resting on the floor, just parted upwards at 1 m/s: the next touch is the parabola's, 2 u/g.
        let parted = Kinematic {
            position: Vector3::new(0.0, 0.0, r),
            velocity: Vector3::new(0.0, 0.0, 1.0),
            spin: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        };
        let t = first_touch(&floor, &wall, &parted, &Vector3::zeros(), &g, 1e-14, 100.0).unwrap();
        assert!((t - 2.0 / 9.81).abs() < 1e-14, "{t}");
        // A fixed sphere of radius 0.02 at the origin, a ball of 0.01 above it at 1 m, thrown up at 2 m/s: the quartic
        // of |x(t)|² = 0.03² has its first root at the ball's fall back, (2 + sqrt(4 + 2 g (1 - 0.03)))/g.
        let fixed = Meeting::Spheres { reach: 0.03 };
        let ball = Kinematic {
            position: Vector3::new(0.0, 0.0, 1.0),
            velocity: Vector3::new(0.0, 0.0, 2.0),
            spin: Vector3::zeros(),
            orientation: UnitQuaternion::identity(),
        };
        let t = first_touch(&fixed, &wall, &ball, &Vector3::zeros(), &g, 1e-14, 100.0).unwrap();
        let expected = (2.0 + (4.0 + 2.0 * 9.81 * 0.97f64).sqrt()) / 9.81;
        assert!((t - expected).abs() < 1e-12, "{t} vs {expected}");
        assert_eq!(first_touch(&fixed, &wall, &ball, &Vector3::zeros(), &Vector3::zeros(), 1e-14, 100.0), None);
    }
}
