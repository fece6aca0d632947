//! The recorded contact history: every accepted integrator step and the located events, in SI units.
//! It exists only when a series or a figure asks for it.

use crate::dynamics::normal::{NormalContact, SIZE, index};
use crate::integrate::State;

/// One recorded instant of the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    /// Time since first contact, s.
    pub time: f64,
    /// Penetration d, m.
    pub penetration: f64,
    /// Penetration rate d', m/s.
    pub rate: f64,
    /// Contact force, N (compressive positive).
    pub force: f64,
    /// Impulse so far, N s.
    pub impulse: f64,
}

/// The contact history, in time order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct History {
    pub samples: Vec<Sample>,
}

impl History {
    /// Converts recorded scaled states to SI samples.
    pub fn new(points: Vec<(f64, State<SIZE>)>, model: &NormalContact) -> History {
        let s = &model.scales;
        let samples = points
            .iter()
            .map(|(t, y)| Sample {
                time: t * s.time,
                penetration: y[index::PENETRATION] * s.length,
                rate: y[index::RATE] * s.speed,
                force: model.force(y) * s.force,
                impulse: y[index::IMPULSE] * s.impulse,
            })
            .collect();
        History { samples }
    }
}
