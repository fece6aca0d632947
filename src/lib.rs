//! impact: simulate the collision of two bodies with a compliant contact law and measure what the
//! instantaneous-impact idealisation hides.

pub mod reference;
pub mod body;
pub mod dynamics;
pub mod geometry;
pub mod integrate;
pub mod law;
pub mod scene;
pub mod setup;
pub mod accuracy;
pub mod history;
pub mod impact;
pub mod instantaneous;
pub mod report;
pub mod cli;
pub mod output;
