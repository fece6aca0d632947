//! The textbook's answer beside a world run (docs/world.md#the-sequential-model): each contact alone and
//! instantaneous, in the order the simulated contacts began, at the times they began — between them every body of
//! finite mass flies under gravity. A contact whose bodies no longer approach along its normal (the instantaneous
//! impacts before it have already parted them) gives no impulse. A contact still active when the run stopped (the
//! bodies at rest on it) is plastic in the model, and a body resting on an immovable one no longer falls into it.
//! A frictional contact is the rigid-body impact with Coulomb friction (docs/oblique.md): it slides throughout, or
//! its tangential impulse stops the contact points' slip, and the bodies' spins change with it.

use super::record::{ContactRecord, WorldOutcome};
use crate::instantaneous::rigid_body_impact;
use crate::scene::WorldScene;
use nalgebra::Vector3;

/// The sequential instantaneous model's velocities after the run, and how far the simulation is from them.
#[derive(Debug, Clone, PartialEq)]
pub struct Sequential {
    /// Every body's velocity at the run's end, m/s.
    pub velocity_after: Vec<Vector3<f64>>,
    /// Largest |simulated - sequential| velocity component over the bodies of finite mass, m/s.
    pub max_velocity_difference: f64,
    /// Every body's angular velocity at the run's end, rad/s.
    pub spin_after: Vec<Vector3<f64>>,
    /// The two bodies' velocities right after each contact in the model (in the order of the contacts), m/s.
    pub contact_velocities_after: Vec<[Vector3<f64>; 2]>,
}

/// The sequential model of `outcome`'s contacts with the e that `restitution` gives each (`None`: the model cannot
/// be formed, e.g. a pair without a nominal e).
pub fn sequential(
    scene: &WorldScene,
    outcome: &WorldOutcome,
    restitution: impl Fn(&ContactRecord) -> Option<f64>,
) -> Option<Sequential> {
    let bodies = &scene.bodies;
    let g = scene.world.gravity;
    let mut velocities: Vec<Vector3<f64>> = bodies.iter().map(|b| b.velocity).collect();
    let mut spins: Vec<Vector3<f64>> = bodies.iter().map(|b| b.angular_velocity).collect();
    let mut now = 0.0;
    // Bodies resting on an immovable one (a contact that had not separated when the run stopped): gravity no longer
    // moves them into it. (body, unit normal from it into the immovable body)
    let mut resting: Vec<(usize, Vector3<f64>)> = Vec::new();
    let fly = |velocities: &mut Vec<Vector3<f64>>, resting: &[(usize, Vector3<f64>)], from: f64, to: f64| {
        for (k, (v, body)) in velocities.iter_mut().zip(bodies).enumerate() {
            if !body.is_immovable() {
                let mut pull = g;
                for (_, n) in resting.iter().filter(|(rested, _)| *rested == k) {
                    pull -= n * pull.dot(n).max(0.0);
                }
                *v += pull * (to - from);
            }
        }
    };
    let mut after_each = Vec::with_capacity(outcome.contacts.len());
    for record in &outcome.contacts {
        // A contact still active when the run stopped is a resting contact: plastic (e = 0) in either model.
        let e = if record.end.is_some() { restitution(record)? } else { 0.0 };
        fly(&mut velocities, &resting, now, record.start_time);
        now = record.start_time;
        let [i, j] = record.bodies;
        let n = record.normal;
        if record.end.is_none() {
            if bodies[j].is_immovable() {
                resting.push((i, n));
            } else if bodies[i].is_immovable() {
                resting.push((j, -n));
            }
        }
        let approach = (velocities[i] - velocities[j]).dot(&n);
        if approach > 0.0 {
            let mut pair = [bodies[i].clone(), bodies[j].clone()];
            for (body, k) in pair.iter_mut().zip([i, j]) {
                body.velocity = velocities[k];
                body.angular_velocity = spins[k];
            }
            let effective_mass = crate::geometry::effective_mass(&pair[0], &pair[1])?;
            let arms = crate::geometry::touch_arms(&pair[0], &pair[1], &n);
            let slip = crate::geometry::slip(&n, [velocities[i], velocities[j]], [spins[i], spins[j]], arms);
            let friction = scene.contact_of(i, j).0.friction;
            let after = rigid_body_impact(&pair, &n, effective_mass, e, friction, &slip, 0.0);
            [velocities[i], velocities[j]] = after.velocity_after;
            [spins[i], spins[j]] = after.angular_velocity_after;
        }
        after_each.push([velocities[i], velocities[j]]);
    }
    fly(&mut velocities, &resting, now, outcome.end_time);
    let difference = outcome
        .bodies
        .iter()
        .zip(&velocities)
        .zip(bodies)
        .filter(|(_, body)| !body.is_immovable())
        .map(|((simulated, ideal), _)| (simulated.velocity - ideal).amax())
        .fold(0.0, f64::max);
    Some(Sequential {
        velocity_after: velocities,
        max_velocity_difference: difference,
        spin_after: spins,
        contact_velocities_after: after_each,
    })
}
