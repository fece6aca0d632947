//! impact: simulate the collision of two bodies with a compliant contact law and measure what the
//! instantaneous-impact idealisation hides.

pub mod accuracy;
pub mod bench;
pub mod body;
pub mod calibrate;
pub mod cli;
pub mod dynamics;
pub mod fast;
pub mod geometry;
pub mod history;
pub mod impact;
pub mod instantaneous;
pub mod integrate;
pub mod law;
pub mod output;
pub mod reference;
pub mod report;
pub mod scene;
pub mod setup;
pub mod stress;
pub mod sweep;
pub mod world;
