//! Views of the report: each a function of the [`crate::report::Report`] (or the history), none recomputing physics.

pub mod bench_figure;
pub mod chart;
pub mod csv;
pub mod figures;
pub mod incidence_figure;
pub mod json;
pub mod map_figure;
pub mod render;
pub mod rod_sweep_figure;
pub mod sweep_figure;
pub mod table;
pub mod world_figures;
pub mod world_series;
pub mod world_table;
