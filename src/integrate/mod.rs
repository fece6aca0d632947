//! Driving the ODE: the `ode_solvers` Dop853 (or Dopri5) adapter, with events located on the integrator's own solution.
//!
//! `ode_solvers` has no event location and no public interpolant, so a run stops (in `solout`) at the first
//! accepted step across which an event function changes sign, and the crossing is then located by re-stepping:
//! the true solution at a trial time is one Dop853 step from the step's start, and a safeguarded secant iteration
//! (started from the root of the step's cubic Hermite interpolant) drives the event function to zero. The located
//! time is thus as accurate as the integration itself, never the first step past the event (docs/numerics.md).

mod events;
mod stepper;

pub use events::{Crossing, CrossingOf, Direction, Event, EventOf};
pub use stepper::{Counters, Ending, NO_SERIES, RunEndOf, STEP_BUDGET, Scheme, Stepper, StepperOf, Tolerances};

use nalgebra::allocator::Allocator;
use nalgebra::{Const, DefaultAllocator, Dim, OVector, SVector};

/// A state vector of `N` scaled quantities (a model of fixed size: one contact).
pub type State<const N: usize> = SVector<f64, N>;

/// A state vector of dimension `D`: `Const<N>` for a model of fixed size, `Dyn` for one whose size a run decides
/// (a world's island of bodies and contacts).
pub type Vector<D> = OVector<f64, D>;

/// A right-hand side y' = f(t, y) of fixed size: the physics of a model, a pure function of the state.
pub trait Model<const N: usize> {
    /// Writes f(t, y) into `dy`.
    fn derivative(&self, t: f64, y: &State<N>, dy: &mut State<N>);

    /// The Taylor coefficients of the solution through `y`, `series[k] = y^(k)(t)/k!` for `k` up to
    /// `series.len() - 1` (`series[0]` is `y`), for [`Scheme::Taylor`]; `false` where the model has none at this
    /// state (the scheme then gives up, and the caller takes another path).
    fn expansion(&self, _y: &State<N>, _series: &mut [State<N>]) -> bool {
        false
    }
}

/// A right-hand side of any dimension, what the stepper integrates: every [`Model`] is one, and a model whose size
/// is known only at run time implements it for `Dyn`.
pub trait ModelOf<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// Writes f(t, y) into `dy`.
    fn derivative_of(&self, t: f64, y: &Vector<D>, dy: &mut Vector<D>);

    /// [`Model::expansion`] at any dimension.
    fn expansion_of(&self, _y: &Vector<D>, _series: &mut [Vector<D>]) -> bool {
        false
    }
}

impl<const N: usize, M: Model<N>> ModelOf<Const<N>> for M {
    fn derivative_of(&self, t: f64, y: &State<N>, dy: &mut State<N>) {
        self.derivative(t, y, dy);
    }

    fn expansion_of(&self, y: &State<N>, series: &mut [State<N>]) -> bool {
        self.expansion(y, series)
    }
}

/// Highest Taylor order a step takes ([`Scheme::Taylor`] and the normal fast path).
pub const MAX_TAYLOR_ORDER: usize = 30;

/// The Taylor order used for a local tolerance `eps` (relative, per step): [`Scheme::Taylor`]'s and the normal fast
/// path's.
///
/// A step of size `h ≈ ρ eps^(1/(K+1))` (ρ the radius of convergence) costs `O(K²)` for the products of the
/// recursion; the number of steps falls like `eps^(-1/(K+1))`. The cost `K² eps^(-1/(K+1))` is least near
/// `K ≈ ln(1/eps)/2`; a few more orders pay for the fixed work of a step (events, quadrature).
pub fn taylor_order(eps: f64) -> usize {
    let wanted = (0.5 * (1.0 / eps).ln()).ceil() as usize + ORDER_MARGIN;
    wanted.clamp(MIN_ORDER, MAX_TAYLOR_ORDER)
}

/// Orders added to `ln(1/eps)/2` (see [`taylor_order`]): measured best from 1e-7 to 1e-17 for the normal fast path
/// (instruction counts over the reference impacts; a step's fixed work — events, time quadrature — favours longer
/// steps).
const ORDER_MARGIN: usize = 6;
/// Lowest order used, whatever the tolerance.
const MIN_ORDER: usize = 8;

/// Why an integration failed.
#[derive(Debug, thiserror::Error)]
pub enum IntegrationError {
    #[error("the integrator gave up at scaled time {}: {reason}", crate::units::brief(*.time, ""))]
    Solver { time: f64, reason: String },
}
