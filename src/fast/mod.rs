//! The fast, accurate path for the normal contact problem: a Taylor-series integrator of the
//! regularised equations of docs/numerics.md#the-fast-path.
//!
//! * **Equations** (`regularised.rs`). With `w = δ^((n+1)/2)` and `dτ = δ^((n-1)/2) dt` every covered law
//!   becomes a polynomial system in `(w, v)`, smooth through `δ = 0` — one system for every `n`, no fractional
//!   power per step. Kelvin–Voigt and Tsuji become linear.
//! * **Steps** (`taylor.rs`). Each step expands `w` and `v` in a Taylor series by the standard recursions (the
//!   product `w v` by Cauchy sums), of order `K = ⌈ln(1/eps)/2⌉ + 6` (13, 18, 21 and
//!   26 at a per-step eps of 1e-6, 1e-10, 1e-13 and the floor 1e-17; measured best, since a step's fixed work
//!   favours long steps). Its size comes from the last two coefficients: `h = ρ eps^(1/(K+1))`, `ρ` the smaller of
//!   `|c_K|^(-1/K)`, `|c_(K-1)|^(-1/(K-1))` relative to the state, so that the first omitted term is `eps`
//!   (the per-step tolerance, a tenth of the requested one). In restitution the rate is also measured against
//!   itself, so that a small e keeps its relative accuracy — for a force separation of an overdamped linear law
//!   against `p/c²` of itself, the share of it that the force `w + c v` is on the slow manifold. The impulse and
//!   the work follow from the rate (momentum and energy: `J + v` and `W + v²/2` are constant); the dissipation is
//!   a Gauss–Legendre integral of its integrand on the step's polynomials, with the few nodes the step's distance
//!   to its singularities asks for ([`Run::dissipated`]).
//! * **Events**, located on the step's polynomials (safeguarded Newton), never at the first step past them:
//!   maximum compression `v = 0` and the force peak `dF/dτ = 0` inside the step; the separation `w = 0`, or for
//!   the laws that turn tensile under `separation = "force"` the zero of the force's continued expression
//!   `w + c v`, where the step is cut.
//! * **Time** (`panels.rs`, `quadrature.rs`). `t = ∫ w^(-γ) dτ` over each phase (to the force peak, to maximum
//!   compression, to separation) by Gauss rules that span several steps, each node on the polynomial of its
//!   step: Gauss–Jacobi where a zero of `w` ends the range (first contact, penetration separation),
//!   Gauss–Legendre elsewhere, with the nodes that the steps' discs of convergence (or a conjugate pair of
//!   singularities two steps agree on) and the zeros of `w` allow; after a force separation, to the penetration's
//!   zero less the piece past the force's (in closed form for a light damping, where the two are ulps apart).
//!   The time neither shortens nor adds steps: a timed run takes the steps of an untimed one.
//! * **Endings**: separation; `NeverSeparates` for an overdamped linear law with separation at zero penetration
//!   (decided exactly at maximum compression); `Settled`, `StepBudget`, `TimeLimit` otherwise, never a hang.
//!   Very heavy damping (x >> 100) creeps and is stiff for an explicit method: the steps grow like x (x = 1e4:
//!   about 1500 steps, 1 ms), accurate throughout.
//!
//! Everything is scaled as in [`crate::scales::Scales`]: lengths in `L`, speeds in `v0`, time in `T`, force in
//! `F0`, impulse in `m* v0`, energy in `m* v0²`.

mod first_integral;
mod first_integral_times;
mod panels;
mod quadrature;
mod regularised;
mod taylor;

use crate::scales::Scales;
// Scaled `δ + |v|` below which the relative motion counts as died out: the general path's level.
use crate::law::{ContactLaw, Family, Separation};
use crate::outcome::SETTLED;
pub use first_integral::{MAX_DAMPING, TIMED_FROM, TIMED_TOLERANCE, times as first_integral_times};
pub use first_integral_times::Times;
use panels::{End, Segments};
use quadrature::{JacobiRules, node_digits, nodes_needed};
use regularised::{Expansion, Regularised, State};
pub use taylor::HARDWARE_FMA;

/// One normal impact to integrate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Request {
    /// The contact law (SI parameters); every family but Brilliantov's ([`covers`]).
    pub law: ContactLaw,
    /// The units of the scaled variables: those of `law` (`Scales::new(m*, K, n, v0)`).
    pub scales: Scales,
    /// Which event ends the contact (matters only for the laws that turn tensile).
    pub separation: Separation,
    /// Relative accuracy wanted on every reported quantity (e.g. 1e-10; a scene's `rtol` maps to it). Values
    /// below about 1e-15 ask for the rounding floor.
    pub tolerance: f64,
    /// What to compute besides the motion, the impulses and the work.
    pub quantities: Quantities,
}

/// What an integration computes besides the motion, the impulses and the work (which give e by all three
/// definitions, `V0`, the maximum penetration and the kinetic energies). A quantity left out costs nothing and is
/// NaN in the [`Outcome`]: a caller that asks for e alone (a sweep's `--columns`) skips the time quadrature (and
/// keeping the steps for it), the force peak's location and the dissipation's quadrature. None of them changes
/// the steps: e, the impulses and the maximum penetration are the same numbers whatever is asked for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Quantities {
    /// Physical times: of maximum compression, of separation, of the force peak.
    pub time: bool,
    /// The largest compressive force (its time also needs `time`).
    pub peak: bool,
    /// The energy dissipated by the damping (a Gauss–Legendre integral over each step).
    pub dissipation: bool,
}

impl Default for Quantities {
    fn default() -> Quantities {
        Quantities::ALL
    }
}

impl Quantities {
    /// Everything (a run's report).
    pub const ALL: Quantities = Quantities { time: true, peak: true, dissipation: true };
    /// The motion, the impulses and the work alone.
    pub const MOTION: Quantities = Quantities { time: false, peak: false, dissipation: false };
}

/// The scaled state at an event.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhasePoint {
    /// Time since first contact, in `T` (NaN unless asked for: [`Quantities`]).
    pub time: f64,
    /// Penetration `d/L`.
    pub penetration: f64,
    /// Penetration rate `d'/v0` (0 at maximum compression by definition).
    pub rate: f64,
    /// `∫ F dt` since first contact, in `m* v0`.
    pub impulse: f64,
    /// `∫ F d' dt` since first contact (kinetic energy of the relative motion lost so far), in `m* v0²`.
    pub work: f64,
    /// `∫ F_dissipative d' dt` since first contact, in `m* v0²` (NaN unless asked for: [`Quantities`]).
    pub dissipated: f64,
    /// Elastic energy stored, `∫_0^d F_elastic dd`, in `m* v0²` (non-zero at the end only for a force separation).
    pub elastic: f64,
    /// Contact force, in `F0`.
    pub force: f64,
}

/// How the integration ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// The separation event was reached with the bodies parting.
    Separated,
    /// The relative motion died out in contact (`δ + |v| < 1e-10`): e = 0, e.g. an overdamped Kelvin–Voigt
    /// contact with separation at zero penetration.
    Settled,
    /// The bodies never part: the law is linear in the regularised variables (Kelvin–Voigt, Tsuji), overdamped
    /// (`c² >= 4p`, i.e. zeta >= 1) and the separation is at zero penetration. Past maximum compression the motion
    /// is then a sum of two decaying exponentials (or `(C1 + C2 τ) e^(λτ)`, critically damped) that keeps `w`
    /// positive for ever: e = 0 (docs/references.md#kelvin-voigt; Tsuji with `a >= sqrt(5)` in
    /// docs/references.md#tsuji). The integration stops at maximum compression.
    NeverSeparates,
    /// The step budget ran out (a creeping, extremely damped restitution).
    StepBudget,
    /// The scaled time limit was passed without separation.
    TimeLimit,
}

/// The result of one impact, all scaled (lengths `L`, speeds `v0`, time `T`, force `F0`, impulse `m* v0`,
/// energy `m* v0²`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome {
    /// The state where the penetration rate is zero (end of compression).
    pub max_compression: PhasePoint,
    /// The separation (or where the integration stopped, see `ending`).
    pub end: PhasePoint,
    /// `∫ F dt` over the restitution alone, in `m* v0` (integrated from maximum compression, so that it is
    /// accurate relative to itself when e is small; `end.impulse` is the deformation impulse plus this).
    pub restitution_impulse: f64,
    /// Energy returned in restitution, `-∫ F d' dt` from maximum compression, in `m* v0²` (`e²/2` at a
    /// penetration separation); integrated on its own like `restitution_impulse`.
    pub restitution_work: f64,
    /// Largest compressive force, in `F0` (NaN unless asked for: [`Quantities`]).
    pub peak_force: f64,
    /// When it acts, in `T` since first contact (NaN unless the peak and the time are asked for).
    pub peak_force_time: f64,
    /// Whether the bodies parted (`ending == Ending::Separated`).
    pub separated: bool,
    pub ending: Ending,
    /// Taylor steps taken (expansions computed).
    pub steps: u64,
    /// Cost in force evaluations: Taylor coefficients of the force series computed (order × expansions).
    pub force_evaluations: u64,
    /// The Taylor order used (0 for the first integral).
    pub order: usize,
    /// Whether the exact first integral gave the outcome, without a time integration ([`first_integral`]: the
    /// hysteresis family, no time asked for).
    pub first_integral: bool,
}

/// Why an impact could not be integrated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FastError {
    #[error("the fast path does not cover the `{0}` law (its force is not smoothed by the regularisation)")]
    NotCovered(&'static str),
    #[error("invalid request: {0}")]
    Invalid(String),
    #[error("no maximum compression within {0} steps")]
    Compression(u64),
    #[error(
        "the phase integrals could not be taken up to regularised time {} (a zero of the penetration too near a \
         Gauss panel's end, or a penetration that dips below zero inside the contact)",
        crate::units::brief(*.0, "")
    )]
    Stalled(f64),
}

/// Whether [`simulate_normal`] handles this law: every family but Brilliantov's viscoelastic law and Thornton's
/// elastic–plastic one (whose force remembers its deepest point).
pub fn covers(law: &ContactLaw) -> bool {
    !matches!(
        law.kind.family(),
        Family::Viscoelastic | Family::Plastic | Family::Dashpot | Family::Impedance | Family::Ramp
    )
}

/// One normal impact from first contact to separation: from the exact first integral where it answers for what is
/// asked (the hysteresis family without the time; with it, from `x >= TIMED_FROM`, by quadrature over the first
/// integral: [`first_integral::covers`]), by the Taylor integration otherwise.
pub fn simulate_normal(request: &Request) -> Result<Outcome, FastError> {
    let system = Regularised::new(&request.law, &request.scales)?;
    if first_integral::covers(&system, request.quantities, request.tolerance)
        && request.tolerance.is_finite()
        && request.tolerance > 0.0
    {
        return Ok(first_integral::impact(&system, request.quantities));
    }
    simulate_system(system, request)
}

/// [`simulate_normal`] by the Taylor integration alone, whatever is asked for (what `impact bench` compares with
/// the first integral, and the tests hold to it).
pub fn simulate_taylor(request: &Request) -> Result<Outcome, FastError> {
    simulate_system(Regularised::new(&request.law, &request.scales)?, request)
}

/// [`simulate_normal`] by the first integral alone, whatever is asked for: the times too, by quadrature over it
/// ([`first_integral_times`]: what `impact bench` measures as `first-integral-timed`, against the Taylor integration
/// of every quantity). For the hysteresis family with `x <= MAX_DAMPING` ([`FastError::Invalid`] otherwise).
pub fn simulate_first_integral(request: &Request) -> Result<Outcome, FastError> {
    let system = Regularised::new(&request.law, &request.scales)?;
    if !first_integral::covers_law(&system) {
        return Err(FastError::Invalid(format!(
            "the first integral answers for the hysteresis family with a scaled damping x = alpha v0 up to {} only \
             (x = {})",
            crate::units::short(MAX_DAMPING),
            crate::units::short(system.damping)
        )));
    }
    Ok(first_integral::impact(&system, request.quantities))
}

fn simulate_system(system: Regularised, request: &Request) -> Result<Outcome, FastError> {
    let tolerance = request.tolerance;
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(FastError::Invalid(format!(
            "tolerance {} must be finite and positive",
            crate::units::short(tolerance)
        )));
    }
    let eps = (tolerance * TOLERANCE_FACTOR).clamp(EPS_FLOOR, EPS_CEILING);
    let force_criterion = request.separation == Separation::Force && system.can_turn_tensile();
    let quantities = request.quantities;
    WORKSPACE.with(|cell| match cell.try_borrow_mut() {
        Ok(mut workspace) => integrate(system, eps, force_criterion, quantities, quantities, &mut workspace),
        // Only if a caller re-entered on this thread (it cannot: nothing here calls back out).
        Err(_) => integrate(system, eps, force_criterion, quantities, quantities, &mut Workspace::default()),
    })
}

/// The scratch arrays of one integration (a few kilobytes): kept per thread and reused, so that an impact
/// neither allocates nor clears them. Every entry read is written first in the same integration.
#[derive(Default)]
struct Workspace {
    expansion: Expansion,
    jacobi: JacobiRules,
    segments: Segments,
}

thread_local! {
    static WORKSPACE: std::cell::RefCell<Workspace> = std::cell::RefCell::new(Workspace::default());
}

/// [`simulate_normal`] with its scratch space: computes `computed` and reports `reported` (what was asked for; the
/// rest is NaN, never a plausible number).
fn integrate(
    system: Regularised,
    eps: f64,
    force_criterion: bool,
    computed: Quantities,
    reported: Quantities,
    workspace: &mut Workspace,
) -> Result<Outcome, FastError> {
    let mut run = Run::new(system, eps, computed, workspace);
    let Some((mut max_compression, ending)) = run.integrate(force_criterion)? else {
        // Untimed, the contact grew long enough that the time limit might apply: the same run timed, so that how
        // it ends does not depend on what was asked for.
        let timed = Quantities { time: true, ..computed };
        return integrate(system, eps, force_criterion, timed, reported, workspace);
    };
    let mut restitution = run.point();
    for point in [&mut max_compression, &mut restitution] {
        if !reported.time {
            point.time = f64::NAN;
        }
        if !reported.dissipation {
            point.dissipated = f64::NAN;
        }
    }
    let peak = match reported {
        Quantities { peak: false, .. } => (f64::NAN, f64::NAN),
        Quantities { time: false, .. } => (run.peak.force, f64::NAN),
        _ => (run.peak.force, run.peak.time),
    };
    let (end, restitution_impulse, restitution_work) = if ending == Ending::NeverSeparates {
        (max_compression, 0.0, 0.0)
    } else {
        // The restitution's integrals ran from zero at maximum compression (accurate relative to themselves).
        let end = PhasePoint {
            impulse: max_compression.impulse + restitution.impulse,
            work: max_compression.work + restitution.work,
            ..restitution
        };
        (end, restitution.impulse, -restitution.work)
    };
    Ok(Outcome {
        max_compression,
        end,
        restitution_impulse,
        restitution_work,
        peak_force: peak.0,
        peak_force_time: peak.1,
        separated: ending == Ending::Separated,
        ending,
        steps: run.steps,
        force_evaluations: run.steps * run.order as u64,
        order: run.order,
        first_integral: false,
    })
}

/// Local (per-step) tolerance relative to the requested accuracy: the errors of a few steps add up.
const TOLERANCE_FACTOR: f64 = 0.1;
/// Smallest local tolerance: below it the rounding of the recursions dominates.
const EPS_FLOOR: f64 = 1e-17;
/// Largest local tolerance (loose requests still get a sensible order).
const EPS_CEILING: f64 = 1e-4;
/// Expansions allowed before a restitution is declared creeping without end.
const STEP_BUDGET: u64 = 200_000;
/// Scaled time after which a contact that has not separated is declared stuck (elastic contacts last about 3).
const TIME_LIMIT: f64 = 1e4;
/// Estimated physical time after which a run that does not compute the time is run again timed: a quarter of
/// [`TIME_LIMIT`], far beyond any contact but a creeping one (elastic contacts last about 3).
const LONG_UNTIMED: f64 = 0.25 * TIME_LIMIT;
/// Smallest scale of the rate, relative to the state's, against which its series is measured in restitution
/// (see [`Run::expand`]): at most `RATE_FLOOR^(-1/(K+1))`, about 1.3 times, more steps.
const RATE_FLOOR: f64 = 0.01;
/// Relative accuracy of the estimate of the zero of `w` ahead ([`Run::zero_ahead`]: it sets node counts, never an
/// event).
const ZERO_ESTIMATE: f64 = 1e-6;
/// How far past a step, in step lengths, its polynomial is trusted to hold the zero of `w` that follows a force
/// separation ([`Run::zero_of_w`]): its truncation grows like `JUST_PAST^(K+1)` there, a few times the
/// step's own.
const JUST_PAST: f64 = 1.05;

/// The integration of one impact.
struct Run<'a> {
    system: Regularised,
    quantities: Quantities,
    order: usize,
    /// The local (per-step) tolerance.
    eps: f64,
    /// `eps^(1/(order+1))`, for the step size.
    eps_root: f64,
    /// `ln(1/eps)` and a margin, for the Gauss rules' node counts ([`node_digits`]).
    node_digits: f64,
    state: State,
    /// Regularised time since first contact.
    tau: f64,
    /// Physical time since first contact to [`Run::integrated_to`], in `T`, and its compensation (Neumaier
    /// summation).
    time: f64,
    time_carry: f64,
    /// `τ` up to which the time is integrated; the steps kept in `segments` carry on from it.
    integrated_to: f64,
    /// Whether the steps are kept for the time's integrals (asked for, and `γ != 0`).
    keeping: bool,
    expansion: &'a mut Expansion,
    /// The steps of the phase in progress beyond `integrated_to` ([`panels`]).
    segments: &'a mut Segments,
    /// Whether the run is past maximum compression (the step size then also measures v against itself).
    restituting: bool,
    /// The share of its own size to which the rate is held in restitution: 1, or for a force separation of a heavy
    /// linear damping `c > sqrt(p)`, `p/c²`. The force `w + c v` ends the contact; an overdamped restitution creeps
    /// on its slow manifold `v ≈ -w/c` where the force is only `~ p w/c²`, so an error `δv` moves it by `c δv`, a
    /// share `c² δv/(p |v|)` of itself.
    rate_weight: f64,
    /// The Gauss–Jacobi rules of this `γ` (computed once per thread and `γ`).
    jacobi: &'a mut JacobiRules,
    steps: u64,
    /// Gauss–Legendre nodes for the dissipation over a step or a piece of it ([`Run::dissipated`]). A step is at
    /// most `eps_root` times the radius of convergence `ρ` of its series, so the integrand is analytic within
    /// `ρ >= h/eps_root` of the step's start: the Bernstein ellipse through `ξ = 1/eps_root` half-lengths lies well
    /// inside (the disc's nearest point is at `ξ = 2/eps_root - 1`; the smaller ellipse keeps the integrand
    /// bounded on it). One node more than that ellipse asks for ([`nodes_needed`]): 8 nodes at a per-step
    /// tolerance of 1e-10, 11 at 1e-17. (One rule a step costs one vector evaluation of `w` and `v` a step, as a
    /// rule over several steps would: the integrand is cheap beside the time's power.)
    dissipation_nodes: usize,
    /// Largest compressive force so far, where (`τ`) and when (NaN until its time is integrated).
    peak: Peak,
    /// Untimed, an estimate of the physical time elapsed (in `T`; see [`Run::untimed_span`]).
    untimed: f64,
}

/// The largest compressive force so far.
#[derive(Debug, Clone, Copy)]
struct Peak {
    force: f64,
    tau: f64,
    /// NaN until integrated (the steps up to `tau` are kept until then).
    time: f64,
}

impl<'a> Run<'a> {
    fn new(system: Regularised, eps: f64, quantities: Quantities, workspace: &'a mut Workspace) -> Run<'a> {
        let order = taylor::order_for(eps);
        let eps_root = eps.powf(1.0 / (order + 1) as f64);
        let keeping = quantities.time && system.time_exponent != 0.0;
        let node_digits = node_digits(eps);
        let dissipation_nodes = nodes_needed(1.0 / eps_root, node_digits) + 1;
        workspace.segments.clear(order);
        Run {
            system,
            quantities,
            order,
            eps,
            eps_root,
            node_digits,
            state: State::FIRST_CONTACT,
            tau: 0.0,
            time: 0.0,
            time_carry: 0.0,
            integrated_to: 0.0,
            keeping,
            expansion: &mut workspace.expansion,
            segments: &mut workspace.segments,
            jacobi: &mut workspace.jacobi,
            restituting: false,
            rate_weight: 1.0,
            steps: 0,
            dissipation_nodes,
            peak: Peak { force: 0.0, tau: 0.0, time: 0.0 },
            untimed: 0.0,
        }
    }

    fn time(&self) -> f64 {
        self.time + self.time_carry
    }

    /// The current state as a reported point (its time is that integrated so far: the caller integrates up to the
    /// state first).
    fn point(&self) -> PhasePoint {
        let s = &self.state;
        let penetration = self.system.penetration(s.w);
        PhasePoint {
            time: self.time(),
            penetration,
            rate: s.rate,
            impulse: s.impulse,
            work: s.work,
            dissipated: self.system.damping * s.dissipation,
            elastic: self.system.elastic_energy(s.w),
            force: self.system.force_at(s.w, penetration, s.rate),
        }
    }

    /// Expands the solution at the current state; returns the step size its coefficients allow and the radius of
    /// convergence they show (the step size at `eps = 1`, of `w` and `v` measured against the state).
    fn expand(&mut self) -> (f64, f64) {
        self.system.expand(&self.state, self.order, self.expansion);
        self.steps += 1;
        let e = &self.expansion;
        let k = self.order;
        let size = self.state.w.abs().max(self.state.rate.abs());
        // (The impulse, the work and the dissipation are integrals of the step's polynomials: as accurate as they
        // are, so that w and v alone set the step.)
        let norm = |i: usize, rate_size: f64| (e.w[i].abs() / size).max(e.rate[i].abs() / rate_size);
        let h = taylor::step_size(norm(k - 1, size), norm(k, size), k, self.eps_root);
        let radius = h / self.eps_root;
        if !self.restituting {
            return (h, radius);
        }
        // In restitution the rate is measured against itself where it is small beside w (heavy damping: v
        // creeps at about -1/x while w is still large): the restitution impulse and work (≈ e and e²/2) add
        // up every step's truncation of v with nothing to damp it, unlike v itself, which the slow manifold
        // pulls back. Floored, so that a rate passing through zero does not stall the step.
        let rate_size =
            self.rate_weight * self.state.rate.abs().max(taylor::value(&e.rate[..=k], h).abs()).max(RATE_FLOOR * size);
        if rate_size >= size {
            return (h, radius);
        }
        (h.min(taylor::step_size(norm(k - 1, rate_size), norm(k, rate_size), k, self.eps_root)), radius)
    }

    fn w(&self) -> &[f64] {
        &self.expansion.w[..=self.order]
    }

    fn rate(&self) -> &[f64] {
        &self.expansion.rate[..=self.order]
    }

    /// Offset of the first zero of `w` after `from` (where `w > 0`) up to `to`, looked for on the step's polynomial
    /// (samples at the middle and the end, then safeguarded Newton) and located to `precision`. `None` if the
    /// samples show none: past the step that rules nothing out — where `w` is small beside its series' truncation
    /// so far out, a zero just beyond can hide (a caller then takes a lower bound instead).
    fn zero_of_w(&self, from: f64, to: f64, precision: f64) -> Option<f64> {
        let w = self.w();
        let at = [from, from + 0.5 * (to - from), to];
        let samples = taylor::values(w, at);
        taylor::fall_in_halves(|s| taylor::value_and_slope(w, s), at, samples, precision)
    }

    /// Where the zero of `w` that ends a restitution lies, seen from the current state at `τ` (a step of length
    /// `h` expanded `offset` before it) when the contact ends elsewhere or goes on: the larger of a lower bound
    /// and the step polynomial's zero beyond, if it shows one ([`Run::zero_of_w`]).
    fn zero_ahead(&self, offset: f64, h: f64) -> End {
        let bound = self.tau + self.system.zero_distance_bound(self.state.w, self.state.rate);
        // (Up to 4 h, an estimate: the polynomial is near its radius of convergence there.)
        let estimate = self.zero_of_w(offset, 4.0 * h, ZERO_ESTIMATE).map_or(bound, |z| self.tau - offset + z);
        End::Clear(bound.max(estimate))
    }

    /// The force-peak function `g` at two offsets of the step (values only, for sampling).
    fn peak_values(&self, at: [f64; 2]) -> [f64; 2] {
        let (w, v) = (taylor::values(self.w(), at), taylor::values(self.rate(), at));
        [0, 1].map(|i| self.system.peak_value(w[i], v[i]))
    }

    /// The force-peak function `g` (falling zero at the peak) at offset `sigma` of the step, with its slope.
    fn peak_at(&self, sigma: f64) -> (f64, f64) {
        let (w, dw) = taylor::value_and_slope(self.w(), sigma);
        let (v, dv) = taylor::value_and_slope(self.rate(), sigma);
        self.system.peak_function(w, dw, v, dv)
    }

    /// Adds `dt` to the physical time (Neumaier summation: the time is a sum of a few to thousands of pieces).
    fn advance_time(&mut self, dt: f64) {
        let sum = self.time + dt;
        self.time_carry += if self.time.abs() >= dt.abs() { (self.time - sum) + dt } else { (dt - sum) + self.time };
        self.time = sum;
    }

    /// Keeps the larger of the peak so far and the force `force` at `tau` (its time, if known, `time`).
    fn offer_peak(&mut self, force: f64, tau: f64, time: f64) {
        if force > self.peak.force {
            self.peak = Peak { force, tau, time };
        }
    }

    /// Takes the time over the kept steps from [`Run::integrated_to`] to `to` (and the force peak's time, if it lies
    /// there), and forgets the steps before `to`. `end` says where the zero of `w` at or beyond `to` lies. With
    /// `t = τ` nothing is kept: the time is `τ`.
    fn integrate_to(&mut self, to: f64, end: End) -> Result<(), FastError> {
        let from = self.integrated_to;
        // The zero of w at first contact: an end of the range, or the zero on its left.
        let start = if from == 0.0 { End::Zero } else { End::Clear(0.0) };
        let stalled = move || FastError::Stalled(to);
        if self.keeping {
            // The range split at the force peak, if it lies inside: the time to it is the peak's time, and the
            // rest starts there (clear of first contact's zero).
            let (mut from, mut start) = (from, start);
            if self.peak.time.is_nan() && self.peak.tau <= to {
                if self.peak.tau > from {
                    let ahead = match end {
                        End::Zero => End::Clear(to),
                        clear => clear,
                    };
                    let piece = self.integral(from, self.peak.tau, start, ahead).ok_or_else(stalled)?;
                    self.advance_time(piece);
                    (from, start) = (self.peak.tau, End::Clear(0.0));
                }
                self.peak.time = self.time();
            }
            let piece = self.integral(from, to, start, end).ok_or_else(stalled)?;
            self.advance_time(piece);
        } else if self.quantities.time {
            if self.peak.time.is_nan() {
                self.peak.time = self.peak.tau;
            }
            self.advance_time(to - from);
        }
        self.integrated_to = to;
        self.segments.drop_until(to);
        Ok(())
    }

    /// `∫ w^(-γ) dτ` from `from` to `to` over the kept steps ([`Segments::integral`]).
    fn integral(&mut self, from: f64, to: f64, start: End, end: End) -> Option<f64> {
        let gamma = self.system.time_exponent;
        self.segments.integral(gamma, from, to, start, end, self.node_digits, self.jacobi)
    }

    /// `D̃` gained from offset `a` to `b` of the step: zero unless the dissipation is asked for and the law damps.
    fn dissipated(&self, a: f64, b: f64) -> f64 {
        if self.quantities.dissipation && self.system.damping > 0.0 {
            self.expansion.dissipation_between(self.system.form, a, b, self.dissipation_nodes)
        } else {
            0.0
        }
    }

    /// Keeps the part of the current step from `from` to `to` (offsets) for the time's integrals; a full store's
    /// older half is integrated, with `end` where the zero of `w` ahead lies.
    fn keep(&mut self, from: f64, to: f64, radius: f64, end: impl Fn(&Self) -> End) -> Result<(), FastError> {
        if !self.keeping {
            return Ok(());
        }
        if self.segments.is_full() {
            let half_way = self.segments.half_way();
            self.integrate_to(half_way, end(self))?;
        }
        self.segments.push(self.expansion, self.tau, self.tau + from, self.tau + to, radius);
        Ok(())
    }

    /// An estimate of the physical time `∫ w^(-γ) dτ` a step of `length` in `τ` takes, from `w` at its ends, for a
    /// run that does not compute the time. For `γ > 0` (n > 1): `length · w^(-γ)` at the smaller end (a bound where
    /// `w` is monotone over the step, or has its maximum inside), and at a zero of `w`, crossed at a non-zero rate,
    /// that of a linear approach, `length · w^(-γ) / (1 - γ)` at the other end; for `γ < 0`, `length · w^(-γ)` at
    /// the larger end (a bound). Cheap (rough powers): it decides only whether the run should be timed after all
    /// ([`LONG_UNTIMED`], a quarter of the limit, leaves room for the estimate's error).
    fn untimed_span(&self, w_start: f64, w_end: f64, length: f64, zero_at_an_end: bool) -> f64 {
        let gamma = self.system.time_exponent;
        if gamma == 0.0 {
            return length;
        }
        let larger = w_start.max(w_end);
        let w = if gamma < 0.0 || zero_at_an_end { larger } else { w_start.min(w_end) };
        if w.is_nan() || w <= 0.0 {
            return f64::INFINITY;
        }
        let span = length * taylor::rough_exp2(-gamma * taylor::rough_log2(w));
        if gamma > 0.0 && zero_at_an_end { span / (1.0 - gamma) } else { span }
    }

    /// Ends the run at the current state (not a zero of `w`): the integrals up to it, with the zero ahead from the
    /// last step (expanded `offset` before the state, of length `h`).
    fn stop(
        &mut self,
        point: PhasePoint,
        ending: Ending,
        offset: f64,
        h: f64,
    ) -> Result<Option<(PhasePoint, Ending)>, FastError> {
        if self.integrated_to < self.tau {
            let end = self.zero_ahead(offset, h);
            self.integrate_to(self.tau, end)?;
        }
        Ok(Some((point, ending)))
    }

    /// From first contact to separation (penetration back to zero, or for a law that turns tensile under the
    /// force criterion, the force back to zero), or until the motion dies out. Maximum compression (`v = 0`) and
    /// the force peak are located inside the steps, on their polynomials; a step is cut only where the contact
    /// ends. The time is integrated over each phase's steps when the phase ends ([`panels`]), the dissipation by a
    /// rule a step: neither shortens nor adds a step. Returns the maximum-compression point and how the contact ended
    /// (`self.state` then holds the end, with the restitution's impulse and work counted from maximum
    /// compression); `None` when a run that does not compute the time may be nearing the time limit
    /// ([`LONG_UNTIMED`]: the caller runs it again timed).
    fn integrate(&mut self, force_criterion: bool) -> Result<Option<(PhasePoint, Ending)>, FastError> {
        let system = self.system;
        if force_criterion {
            self.rate_weight = (system.rate_factor / (system.damping * system.damping)).min(1.0);
        }
        let Quantities { time: timed, peak: peaked, .. } = self.quantities;
        // The force at first contact is a candidate peak (Kelvin–Voigt's jump to c v0, its maximum for c >= 1).
        self.offer_peak(system.force(0.0, 1.0), 0.0, 0.0);
        let (g0, _) = system.peak_function(0.0, system.rate_factor, 1.0, -system.regular_force(0.0, 1.0));
        let mut rising = peaked && g0 > 0.0;
        let mut max_compression = None;
        // The last step's length (for the zero ahead where the run stops short of it).
        let mut last_step = 0.0;
        loop {
            if self.steps >= STEP_BUDGET {
                return match max_compression {
                    Some(point) => self.stop(point, Ending::StepBudget, last_step, last_step),
                    None => Err(FastError::Compression(self.steps)),
                };
            }
            // (With `t = τ` the time is `τ`; otherwise it is integrated up to the steps kept, at most `CAPACITY`
            // steps behind.)
            let elapsed = if system.time_exponent == 0.0 { self.tau } else { self.time() };
            if let Some(point) = max_compression
                && timed
                && elapsed > TIME_LIMIT
            {
                return self.stop(point, Ending::TimeLimit, last_step, last_step);
            }
            // Untimed, a contact that may be nearing the time limit is handed back, to be run timed (so that the
            // limit applies to it exactly as to a timed run).
            if !timed && self.untimed > LONG_UNTIMED {
                return Ok(None);
            }
            let compressing = max_compression.is_none();
            let from_zero = self.state.w == 0.0;
            let w_start = self.state.w;
            let (h, radius) = self.expand();
            let step = self.step(h, compressing, rising, force_criterion);
            if let Some(at) = step.peak {
                rising = false;
                let (w, v) = (taylor::value(self.w(), at), taylor::value(self.rate(), at));
                self.offer_peak(system.force(w, v), self.tau + at, f64::NAN);
            }
            if let Some(at) = step.turn {
                // The compression's integrals, to maximum compression; the zero of w that ends the restitution
                // lies at least as far beyond it (restitution is never shorter in τ than compression).
                let turn = self.tau + at;
                self.keep(0.0, at, radius, |_| End::Clear(2.0 * turn))?;
                self.integrate_to(turn, End::Clear(2.0 * turn))?;
                // The event's definition: the rate is zero there (the polynomial leaves an ulp).
                let mut state = State { rate: 0.0, ..self.expansion.state_at(at) };
                state.dissipation += self.dissipated(0.0, at);
                let penetration = system.penetration(state.w);
                let point = PhasePoint {
                    time: self.time(),
                    penetration,
                    rate: 0.0,
                    impulse: state.impulse,
                    work: state.work,
                    dissipated: system.damping * state.dissipation,
                    elastic: system.elastic_energy(state.w),
                    force: system.force_at(state.w, penetration, 0.0),
                };
                if peaked {
                    self.offer_peak(point.force, turn, point.time);
                }
                max_compression = Some(point);
                if !force_criterion && system.never_separates() {
                    // Overdamped linear law: w never returns to zero (see `Ending::NeverSeparates`).
                    self.state = state;
                    self.tau = turn;
                    return Ok(Some((point, Ending::NeverSeparates)));
                }
                // The restitution's integrals start from zero there, within this step.
                let (impulse, work) = self.expansion.increments(at, step.end);
                let dissipation = state.dissipation + self.dissipated(at, step.end);
                self.state = State { impulse, work, dissipation, ..step.state_at_end(self.expansion) };
                self.restituting = true;
                self.keep(at, step.end, radius, |_| End::Clear(2.0 * turn))?;
            } else {
                let dissipation = self.state.dissipation + self.dissipated(0.0, step.end);
                self.state = State { dissipation, ..step.state_at_end(self.expansion) };
                let (tau, restituting) = (self.tau + step.end, self.restituting);
                let state = self.state;
                let zero_ahead = move |run: &Self| {
                    if restituting {
                        End::Clear(tau + run.system.zero_distance_bound(state.w, state.rate))
                    } else {
                        End::Clear(2.0 * tau)
                    }
                };
                self.keep(0.0, step.end, radius, zero_ahead)?;
            }
            if !timed {
                let zero_at_an_end = from_zero || step.zero.is_some();
                self.untimed += self.untimed_span(w_start, self.state.w, step.end, zero_at_an_end);
            }
            self.tau += step.end;
            last_step = step.end;
            let Some(point) = max_compression else { continue };
            if step.force_zero.is_some() {
                // The zero of w beyond the force's: in this step (its polynomial reaches it; a light damping puts
                // it an ulp or a hair past the force's), or ahead.
                // (Past the step, up to JUST_PAST h, where its polynomial still holds the zero: located to rounding,
                // for a rule weighted at it.)
                let just_past = || self.zero_of_w(step.end, JUST_PAST * h, 0.0);
                let end = match step.zero.or_else(just_past) {
                    Some(zero) => {
                        // The time from the force's zero to the penetration's, in closed form where the damping is
                        // light enough for it (an ulp or two apart in τ, the time is ill-conditioned in τ but not
                        // in w, which is known there exactly).
                        let piece = system.time_past_force_zero(self.state.rate, self.eps);
                        let zero = self.tau - step.end + zero;
                        // A zero farther past the force's than half the range still to integrate only bounds a
                        // plain rule's ellipse (a few nodes more): the difference of two rules to it would lose
                        // digits to cancellation (a heavy damping's time past the force's zero is most of the
                        // whole: 8 ulps of the duration at the floor).
                        if piece.is_none() && zero - self.tau > 0.5 * (self.tau - self.integrated_to) {
                            End::Clear(zero)
                        } else {
                            End::ZeroBeyond { zero, piece }
                        }
                    }
                    None => self.zero_ahead(step.end, h),
                };
                self.integrate_to(self.tau, end)?;
                return Ok(Some((point, Ending::Separated)));
            }
            if step.zero.is_some() {
                self.state.w = 0.0;
                self.integrate_to(self.tau, End::Zero)?;
                return Ok(Some((point, if self.state.rate < 0.0 { Ending::Separated } else { Ending::Settled })));
            }
            // (The penetration, a power, only once the rate alone is below the threshold.)
            if self.state.rate.abs() < SETTLED && system.penetration(self.state.w) + self.state.rate.abs() < SETTLED {
                return self.stop(point, Ending::Settled, step.end, h);
            }
        }
    }

    /// The events of the step of size `h` just expanded: maximum compression (while compressing), then (only after
    /// it) the zero of `w`, the force's zero before that (under the force criterion), and the force peak (while
    /// the force rises).
    fn step(&self, h: f64, compressing: bool, rising: bool, force_criterion: bool) -> Step {
        let system = self.system;
        let (w, rate) = (self.w(), self.rate());
        // The state at the step's end and w, v at its middle, in one pass: the samples of the events' search from
        // the step's start, and the state it ends in when no event lies inside.
        let probe = self.expansion.probe(h);
        let value_slope = |c: &[f64], s: f64| taylor::value_and_slope(c, s);
        let fall = |c: &[f64], from: f64, start: f64, probed: [f64; 2]| {
            // (From the step's start, the samples are the probe's: first_fall samples at (from + h)/2, h.)
            let values = |at: [f64; 2]| if from == 0.0 { probed } else { taylor::values(c, at) };
            taylor::first_fall(values, |s| value_slope(c, s), from, h, start)
        };
        let (middle, full) = (probe.middle, probe.state);
        let turn = if compressing { fall(rate, 0.0, self.state.rate, [middle[1], full.rate]) } else { None };
        let restitution_from = if compressing { turn } else { Some(0.0) };
        // (At the step's start, w's value is its first coefficient.)
        let zero = restitution_from.and_then(|a| {
            let start = if a == 0.0 { w[0] } else { taylor::value(w, a) };
            fall(w, a, start, [middle[0], full.w])
        });
        let reach = zero.unwrap_or(h);
        let force_zero = match restitution_from {
            Some(a) if force_criterion => {
                let f = |s: f64| {
                    let (w, dw) = value_slope(w, s);
                    let (v, dv) = value_slope(rate, s);
                    (system.regular_force(w, v), dw + system.damping * dv)
                };
                let values = |at: [f64; 2]| {
                    let [w, v] = [taylor::values(w, at), taylor::values(rate, at)];
                    [0, 1].map(|i| system.regular_force(w[i], v[i]))
                };
                taylor::first_fall(values, f, a, reach, f(a).0)
            }
            _ => None,
        };
        let end = force_zero.or(zero).unwrap_or(h);
        // The force peak, if it lies in this step's compression (it precedes maximum compression for every damped
        // law).
        let peak = if rising {
            let until = turn.unwrap_or(end);
            // At the step's start: the polynomials' first two coefficients.
            let (g_start, _) = system.peak_function(w[0], w[1], rate[0], rate[1]);
            if g_start > 0.0 {
                // Sampled at until/2 and until: the probe's points when the step runs its full length.
                let samples = |at: [f64; 2]| {
                    if until == h {
                        [system.peak_value(middle[0], middle[1]), system.peak_value(full.w, full.rate)]
                    } else {
                        self.peak_values(at)
                    }
                };
                taylor::first_fall(samples, |s| self.peak_at(s), 0.0, until, g_start)
            } else {
                Some(0.0)
            }
        } else {
            None
        };
        Step { end, turn, peak, zero, force_zero, probe: full }
    }
}

/// What one step found (offsets from its start): where it ends, maximum compression and the force peak inside
/// it, and whether it ends at the zero of `w` or of the force.
struct Step {
    end: f64,
    turn: Option<f64>,
    peak: Option<f64>,
    zero: Option<f64>,
    force_zero: Option<f64>,
    /// The state at the step's full length (its end unless a zero ends it sooner).
    probe: State,
}

impl Step {
    /// The state at the step's end: the probe's, unless a zero of `w` or of the force ended the step sooner.
    fn state_at_end(&self, expansion: &Expansion) -> State {
        if self.zero.is_none() && self.force_zero.is_none() { self.probe } else { expansion.state_at(self.end) }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::law::LawKind;

    /// The first step's time (from first contact, where `w = 0`), by the panels' Gauss–Jacobi sum of `Q = w/σ`,
    /// against an independent quadrature of the same polynomial: `τ = s^5` turns `∫ τ^(-1/5) Q(τ)^(-1/5) dτ` into
    /// the smooth `∫ 5 s³ Q(s^5)^(-1/5) ds`, summed by composite Gauss–Legendre. Hunt–Crossley x = 0.5, n = 3/2.
    #[test]
    fn first_step_time_agrees_with_a_smooth_quadrature() {
        let law = ContactLaw {
            kind: LawKind::HuntCrossley,
            stiffness: 1.0,
            exponent: 1.5,
            damping: 0.5,
            tsuji_scale: 0.0,
            yield_penetration: f64::INFINITY,
            solimp: crate::law::NO_SOLIMP,
            ramp: f64::INFINITY,
        };
        let system = Regularised::new(&law, &Scales::new(1.0, 1.0, 1.5, 1.0)).unwrap();
        let mut e = Expansion::default();
        system.expand(&State::FIRST_CONTACT, 20, &mut e);
        let q = &e.w[1..=20];
        let mut rules = JacobiRules::default();
        for h in [0.1_f64, 0.2, 0.3] {
            let mut segments = Segments::default();
            segments.clear(20);
            // (The series' radius of convergence is beyond 1: that of the elastic contact, a half-period.)
            segments.push(&e, 0.0, 0.0, h, 1.0);
            let got =
                segments.integral(0.2, 0.0, h, End::Zero, End::Clear(2.8), node_digits(1e-17), &mut rules).unwrap();
            let smooth = |s: f64| 5.0 * s.powi(3) * taylor::value(q, s.powi(5)).powf(-0.2);
            let exact = quadrature::composite_gauss_legendre(smooth, 0.0, h.powf(0.2), 50, 24);
            assert!((got / exact - 1.0).abs() < 1e-15, "h = {h}: {got} vs {exact}");
        }
    }
}
