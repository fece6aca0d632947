//! The recorded contact history, in SI units: every accepted integrator step plus the located events, or a
//! uniform resampling on the integrator's solution. It exists only when a series or a figure asks for it.

use crate::body::{Body, after_normal_impulse};
use crate::dynamics::normal::{NormalContact, SIZE, index};
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

/// One recorded instant of the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time from the scene's t = 0, s.
    pub time: f64,
    /// Penetration d, m.
    pub penetration: f64,
    /// Penetration rate d', m/s.
    pub rate: f64,
    /// Contact force, N (compressive positive).
    pub force: f64,
    /// Impulse so far, N s.
    pub impulse: f64,
    /// Velocities of body 1 and body 2, m/s.
    pub velocities: [Vector3<f64>; 2],
    pub phase: Phase,
}

/// The contact history, in time order, with the frame it was recorded in.
#[derive(Debug, Clone, PartialEq)]
pub struct History {
    /// Unit contact normal (body 1 -> body 2).
    pub normal: Vector3<f64>,
    pub samples: Vec<Sample>,
}

/// How scaled states become samples: the model (force), the bodies (velocities) and the timing of the phases.
pub struct Frame<'a> {
    pub model: &'a NormalContact,
    pub bodies: &'a [Body; 2],
    pub normal: Vector3<f64>,
    /// First contact, s.
    pub contact_time: f64,
    /// Scaled time of maximum compression.
    pub max_compression: f64,
}

impl History {
    /// Converts scaled (time, state) points to SI samples.
    pub fn new(points: &[(f64, State<SIZE>)], frame: &Frame) -> History {
        let s = &frame.model.scales;
        let n = frame.normal;
        let samples = points
            .iter()
            .map(|(t, y)| {
                let impulse = y[index::IMPULSE] * s.impulse;
                Sample {
                    time: frame.contact_time + t * s.time,
                    penetration: y[index::PENETRATION] * s.length,
                    rate: y[index::RATE] * s.speed,
                    force: frame.model.force(y) * s.force,
                    impulse,
                    velocities: after_normal_impulse(frame.bodies, &n, impulse),
                    phase: if *t <= frame.max_compression { Phase::Compression } else { Phase::Restitution },
                }
            })
            .collect();
        History { normal: n, samples }
    }
}
