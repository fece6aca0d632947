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
pub use stepper::{Counters, Ending, RunEndOf, STEP_BUDGET, Scheme, Stepper, StepperOf, Tolerances};

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
}

/// A right-hand side of any dimension, what the stepper integrates: every [`Model`] is one, and a model whose size
/// is known only at run time implements it for `Dyn`.
pub trait ModelOf<D: Dim>
where
    DefaultAllocator: Allocator<D>,
{
    /// Writes f(t, y) into `dy`.
    fn derivative_of(&self, t: f64, y: &Vector<D>, dy: &mut Vector<D>);
}

impl<const N: usize, M: Model<N>> ModelOf<Const<N>> for M {
    fn derivative_of(&self, t: f64, y: &State<N>, dy: &mut State<N>) {
        self.derivative(t, y, dy);
    }
}

/// Why an integration failed.
#[derive(Debug, thiserror::Error)]
pub enum IntegrationError {
    #[error("the integrator gave up at scaled time {}: {reason}", crate::units::brief(*.time, ""))]
    Solver { time: f64, reason: String },
}
