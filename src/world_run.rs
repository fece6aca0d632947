//! A world scene run to its report (docs/world.md): the world's driver ([`crate::world`]) and the report built from its
//! outcome ([`crate::report::world`]). A world of two bodies without gravity has at most one contact: it runs as
//! today's two-body impact ([`crate::impact`]), the world's special case, and its contact is that impact's to the bit.
//! It sits above `world`, `report` and `impact`, so that the world's driver needs neither the report nor the two-body
//! run.

use crate::scene::WorldScene;
use crate::world::record::{self, WorldOutcome};
use crate::world::{WorldError, driver};
use std::time::Instant;

/// A world run's products.
#[derive(Debug, Clone)]
pub struct WorldSimulation {
    pub report: crate::report::world::WorldReport,
    /// What the driver kept of the run (`None` for a world of two bodies run as one impact).
    pub outcome: Option<WorldOutcome>,
}

/// Runs a world scene and builds its report.
pub fn simulate(scene: &WorldScene) -> Result<WorldSimulation, WorldError> {
    simulate_watched(scene, driver::Watchers::default())
}

/// Runs a world scene with `observer` shown every instant of its series (never as one impact: a series needs the
/// world's own run).
pub fn simulate_observed(
    scene: &WorldScene,
    observer: &mut dyn record::Observer,
) -> Result<WorldSimulation, WorldError> {
    simulate_watched(scene, driver::Watchers { observer: Some(observer), progress: None })
}

/// Runs a world scene with its watchers (an observer of its series: never as one impact, since a series needs the
/// world's own run; a progress count, which a world of two bodies run as one impact leaves untold).
pub fn simulate_watched<'a>(
    scene: &'a WorldScene,
    watchers: driver::Watchers<'a>,
) -> Result<WorldSimulation, WorldError> {
    if watchers.observer.is_none()
        && let Some(simulation) = as_one_impact(scene)?
    {
        return Ok(simulation);
    }
    let clock = Instant::now();
    let outcome = driver::run_watched(scene, watchers)?;
    let report = crate::report::world::build(scene, &outcome, clock.elapsed().as_secs_f64());
    Ok(WorldSimulation { report, outcome: Some(outcome) })
}

/// A world of two bodies without gravity, run as today's impact of the pair — when they meet, part, and do so
/// before any end time (otherwise the world's driver takes it).
fn as_one_impact(scene: &WorldScene) -> Result<Option<WorldSimulation>, WorldError> {
    // (A frictional pair runs in the world's driver too: its report then has the rigid-body frictional sequential model
    // beside it, the same for every world. So does a rigid body, which may strike again as it turns.)
    let (contact, _) = scene.contact_of(0, 1);
    if scene.bodies.len() != 2
        || scene.world.gravity != nalgebra::Vector3::zeros()
        || !scene.interacts(0, 1)
        || contact.friction > 0.0
        || scene.bodies.iter().any(|b| b.is_eccentric() || !b.spheres.is_empty())
    {
        return Ok(None);
    }
    let mut pair = scene.pair_scene(0, 1);
    // A flat body's face gives the contact normal, from body 0 to body 1.
    let face = match (scene.faces[0], scene.faces[1]) {
        (Some(face), _) => Some(face),
        (_, Some(face)) => Some(-face),
        _ => None,
    };
    pair.contact.normal_given = face;
    pair.contact.normal = face;
    if crate::setup::Setup::new(&pair).is_err() {
        return Ok(None);
    }
    // (With the verdicts on the idealisation: the report's contact takes the impact's `constant_e` trial.)
    let options = crate::impact::Options { idealisation: true, ..crate::impact::Options::default() };
    let simulation = crate::impact::simulate_with(&pair, options).map_err(|error| match error {
        crate::impact::SimulationError::Setup(error) => WorldError::Setup(scene.rename(0, 1, error)),
        crate::impact::SimulationError::Integration(error) => WorldError::Integration(error),
        crate::impact::SimulationError::Compression(why) => {
            WorldError::Integration(crate::integrate::IntegrationError::Solver { time: 0.0, reason: why })
        }
    })?;
    let contact = &simulation.report.contact;
    let in_time = match (scene.world.end_time, contact.end_time) {
        (Some(end), Some(parted)) => parted <= end,
        (Some(_), None) => false,
        (None, _) => contact.separated,
    };
    if !in_time {
        return Ok(None);
    }
    let report = crate::report::world::from_impact(scene, &simulation.report);
    Ok(Some(WorldSimulation { report, outcome: None }))
}
