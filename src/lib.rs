//! impact: simulate the collision of two bodies with a compliant contact law and measure what the
//! instantaneous-impact idealisation hides.

/// The crate's version (the command's `--version`, Python's `impact.__version__`).
pub const VERSION: &str = env!("CARGO_PKG_VERSION");

pub mod bench;
pub mod body;
pub mod calibrate;
pub mod cli;
pub mod draw;
pub mod dynamics;
pub mod eccentric;
pub mod fast;
pub mod files;
pub mod fixed_step;
pub mod geometry;
pub mod history;
pub mod idealisation;
pub mod impact;
pub mod instantaneous;
pub mod integrate;
pub mod law;
pub mod outcome;
pub mod output;
pub mod reference;
pub mod report;
pub mod rod_sweep;
pub mod scales;
pub mod scene;
pub mod setup;
pub mod slide_through;
pub mod stress;
pub mod sweep;
pub mod text;
pub mod translate;
pub mod units;
pub mod validate;
pub mod world;
pub mod world_run;
