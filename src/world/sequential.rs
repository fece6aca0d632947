//! The textbook's answer beside a world run (docs/world.md#the-sequential-model): each contact alone and
//! instantaneous, in the order the simulated contacts began, at the times they began — between them every body of
//! finite mass flies under gravity. A contact whose bodies no longer approach along its normal (the instantaneous
//! impacts before it have already parted them) gives no impulse. A contact still active when the run stopped (the
//! bodies at rest on it) is plastic in the model, and a body resting on an immovable one no longer falls into it.
//! A frictional contact is the rigid-body impact with Coulomb friction (docs/oblique.md): it slides throughout, or
//! its tangential impulse stops the contact points' slip, and the bodies' spins change with it.
//!
//! A contact of a rigid body (docs/world.md#rigid-bodies) is the instantaneous eccentric impact at its contact point
//! with Coulomb friction (`eccentric::frictional_impact`, docs/references.md#rigid-bodies-with-several-contacts: it sticks where the cone allows and slides
//! otherwise), at the levers and orientations the simulation had at its first touch (the model keeps velocities, not
//! positions). A rigid body keeps its angular momentum about its mass centre in flight; a pivoted body's swing
//! between its contacts is the simulation's (the model cannot fly a pendulum in closed form): its angular momentum
//! about the pivot changes by what the simulated swing changed it by, and its velocity follows its turning.

use super::island::turned_inertia;
use super::record::{ContactRecord, WorldOutcome};
use crate::eccentric::{RigidBody, frictional_impact, inverse_inertia};
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
    // A rigid body's angular momentum about its origin (mass centre or pivot), and for a pivoted one what the
    // simulation's had when it last left a contact (its swing since then is the simulation's).
    let rigid = |k: usize| bodies[k].is_rigid();
    let start_body = |k: usize| RigidBody {
        mass: bodies[k].mass,
        inertia: bodies[k].inertia_matrix(),
        centre: bodies[k].position.unwrap_or_default(),
        velocity: bodies[k].velocity,
        spin: bodies[k].angular_velocity,
        pivot: bodies[k].pivot,
    };
    let mut momenta: Vec<Vector3<f64>> =
        (0..bodies.len())
            .map(|k| {
                if rigid(k) {
                    start_body(k).inertia_about_pivot() * bodies[k].angular_velocity
                } else {
                    Vector3::zeros()
                }
            })
            .collect();
    let mut swung = momenta.clone();
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
        if rigid(i) || rigid(j) {
            let mut pair = [i, j].map(&start_body);
            for (side, k) in [i, j].into_iter().enumerate() {
                if !rigid(k) {
                    pair[side].velocity = velocities[k];
                    pair[side].spin = spins[k];
                    pair[side].centre = record.point - record.levers[side];
                    continue;
                }
                let body = &bodies[k];
                let orientation = record.orientations_before[side];
                let inertia = turned_inertia(body, &orientation);
                if body.pivot.is_some() {
                    momenta[k] += record.momenta_before[side] - swung[k];
                }
                let placed = RigidBody {
                    inertia,
                    centre: match body.pivot {
                        Some(pivot) => pivot + orientation * (body.position.unwrap_or_default() - pivot),
                        None => record.point - record.levers[side],
                    },
                    ..pair[side]
                };
                let spin = inverse_inertia(&placed.inertia_about_pivot()) * momenta[k];
                let velocity = match body.pivot {
                    Some(pivot) => spin.cross(&(placed.centre - pivot)),
                    None => velocities[k],
                };
                pair[side] = RigidBody { spin, velocity, ..placed };
            }
            let friction = scene.contact_of(i, j).0.friction;
            if let Some(after) = frictional_impact(&pair, &record.point, &n, e, friction) {
                for (side, k) in [i, j].into_iter().enumerate() {
                    velocities[k] = after.velocities_after[side];
                    spins[k] = after.spins_after[side];
                    if rigid(k) {
                        momenta[k] = pair[side].inertia_about_pivot() * spins[k];
                    }
                }
            } else {
                for (side, k) in [i, j].into_iter().enumerate() {
                    velocities[k] = pair[side].velocity;
                    spins[k] = pair[side].spin;
                }
            }
            for (side, k) in [i, j].into_iter().enumerate() {
                if bodies[k].pivot.is_some() {
                    swung[k] = record.end.map_or(record.momenta_before[side], |end| end.momenta[side]);
                }
            }
            after_each.push([velocities[i], velocities[j]]);
            continue;
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
    // Rigid bodies at the run's end: their angular momentum turned into a spin at the simulation's orientation (a
    // pivoted body's after the rest of its simulated swing).
    for (k, end) in outcome.bodies.iter().enumerate() {
        if !rigid(k) {
            continue;
        }
        let body = &bodies[k];
        if body.pivot.is_some() {
            momenta[k] += super::driver::angular_momentum(body, end) - swung[k];
        }
        let placed =
            RigidBody { inertia: turned_inertia(body, &end.orientation), centre: end.position, ..start_body(k) };
        spins[k] = inverse_inertia(&placed.inertia_about_pivot()) * momenta[k];
        if let Some(pivot) = body.pivot {
            velocities[k] = spins[k].cross(&(end.position - pivot));
        }
    }
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
