//! The simulation measured against exact references (physics.md §3–4), where the law has them.

use crate::impact::Measured;
use crate::report::ReferenceReport;
use crate::scene::Scene;
use crate::setup::Setup;

/// Exact values for this contact and the relative errors of `measured` against them.
pub fn reference(_scene: &Scene, _setup: &Setup, _measured: Measured) -> Option<ReferenceReport> {
    None
}
