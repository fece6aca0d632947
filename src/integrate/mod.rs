//! Driving the ODE: the `ode_solvers` Dop853 (or Dopri5) adapter, with events located on the integrator's own solution.
//!
//! `ode_solvers` has no event location and no public interpolant, so a run stops (in `solout`) at the first
//! accepted step across which an event function changes sign, and the crossing is then located by re-stepping:
//! the true solution at a trial time is one Dop853 step from the step's start, and a safeguarded secant iteration
//! (started from the root of the step's cubic Hermite interpolant) drives the event function to zero. The located
//! time is thus as accurate as the integration itself, never the first step past the event (docs/numerics.md).

mod events;
mod stepper;

pub use events::{Crossing, Direction, Event};
pub use stepper::{Counters, Ending, STEP_BUDGET, Scheme, Stepper, Tolerances};

use nalgebra::SVector;

/// A state vector of `N` scaled quantities.
pub type State<const N: usize> = SVector<f64, N>;

/// A right-hand side y' = f(t, y): the physics of a model, a pure function of the state.
pub trait Model<const N: usize> {
    /// Writes f(t, y) into `dy`.
    fn derivative(&self, t: f64, y: &State<N>, dy: &mut State<N>);
}

/// Why an integration failed.
#[derive(Debug, thiserror::Error)]
pub enum IntegrationError {
    #[error("the integrator gave up at scaled time {time}: {reason}")]
    Solver { time: f64, reason: String },
}
