//! The recorded contact history, in SI units: every accepted integrator step plus the located events, or a
//! uniform resampling on the integrator's solution. It exists only when a series or a figure asks for it.

use crate::dynamics::ContactModel;
use crate::integrate::State;
use nalgebra::Vector3;

/// What to record during a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Recording {
    /// Nothing: the report only.
    #[default]
    Off,
    /// The integrator's accepted steps and the located events.
    Steps,
    /// `n` instants evenly spaced in time over the contact, first contact to separation inclusive.
    Uniform(usize),
}

/// Contact phase of a sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Phase {
    /// From first contact to maximum compression (inclusive).
    Compression,
    /// After maximum compression.
    Restitution,
}

impl Phase {
    /// Lower-case name, as written in series.
    pub fn name(self) -> &'static str {
        match self {
            Phase::Compression => "compression",
            Phase::Restitution => "restitution",
        }
    }
}

/// One recorded instant of the contact (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time from the scene's t = 0, s.
    pub time: f64,
    /// Penetration d, m.
    pub penetration: f64,
    /// Penetration rate d', m/s.
    pub rate: f64,
    /// Normal contact force, N (compressive positive).
    pub force: f64,
    /// Normal impulse so far, N s.
    pub impulse: f64,
    /// Velocities of body 1 and body 2, m/s.
    pub velocities: [Vector3<f64>; 2],
    pub phase: Phase,
    /// Unit normal at this instant (it turns with the line of centres of two spheres).
    pub normal: Vector3<f64>,
    /// Tangential force on body 1, N.
    pub tangential_force: Vector3<f64>,
    /// Slip of body 1's contact point relative to body 2's, m/s.
    pub slip: Vector3<f64>,
    /// Angular velocities of body 1 and body 2, rad/s.
    pub spins: [Vector3<f64>; 2],
    /// Whether a frictional contact was sliding (false when sticking or smooth).
    pub sliding: bool,
}

/// The contact history, in time order.
#[derive(Debug, Clone, PartialEq)]
pub struct History {
    /// Unit contact normal at first contact (body 1 -> body 2): the frame the velocities are split in.
    pub normal: Vector3<f64>,
    pub samples: Vec<Sample>,
}

impl History {
    /// Converts scaled (time, state) points of `model` to SI samples; `max_compression` is the scaled time that
    /// ends the compression phase, `contact_time` the scene time of first contact (s).
    pub fn new<const N: usize, M: ContactModel<N>>(
        points: &[(f64, State<N>)],
        model: &M,
        max_compression: f64,
        contact_time: f64,
    ) -> History {
        let samples: Vec<Sample> = points
            .iter()
            .map(|(t, y)| {
                let snapshot = model.snapshot(*t, y);
                Sample {
                    time: contact_time + snapshot.time,
                    penetration: snapshot.penetration,
                    rate: snapshot.rate,
                    force: snapshot.normal_force,
                    impulse: snapshot.normal_impulse,
                    velocities: snapshot.velocities,
                    phase: if *t <= max_compression { Phase::Compression } else { Phase::Restitution },
                    normal: snapshot.normal,
                    tangential_force: snapshot.tangential_force,
                    slip: snapshot.slip,
                    spins: snapshot.spins,
                    sliding: model.sliding(y),
                }
            })
            .collect();
        let normal = samples.first().map_or_else(Vector3::x, |s| s.normal);
        History { normal, samples }
    }
}
