//! The contact spheres of a world (docs/world.md#rigid-bodies): every sphere of every body, and each flat body's face,
//! in body order. A contact is a pair of sites of two bodies, each located and measured as one impact's; the spheres
//! of one body never touch each other. A sphere is the body whose one site sits at its centre, so that in a world of
//! spheres and walls the sites are the bodies, one for one, and every pair of sites a pair of bodies.
//!
//! A site's centre is its body's position plus its offset turned with the body, `x + R b` (`b` in scene axes at
//! t = 0); a site at its body's centre is at the body's position exactly.

use super::flight::Kinematic;
use crate::body::Body;
use crate::geometry::Meeting;
use crate::scene::{Site, WorldScene};
use nalgebra::Vector3;
use std::ops::Range;

/// Every site of a world's scene, with what its contacts need of it.
#[derive(Debug, Clone)]
pub struct Sites {
    /// The sites, body by body (a body's spheres in its order).
    pub list: Vec<Site>,
    /// Body k's sites are `first[k]..first[k + 1]`.
    first: Vec<usize>,
    /// Each site's body as its contact law sees it: its sphere's radius (the body itself for a body of one sphere).
    pub bodies: Vec<Body>,
    /// Whether some body's orientation is integrated (a rigid body: docs/world.md#rigid-bodies).
    pub any_rigid: bool,
}

impl Sites {
    /// The sites of `scene`.
    pub fn of(scene: &WorldScene) -> Sites {
        let mut list = Vec::with_capacity(scene.bodies.len());
        let mut first = Vec::with_capacity(scene.bodies.len() + 1);
        let mut bodies = Vec::with_capacity(scene.bodies.len());
        for k in 0..scene.bodies.len() {
            first.push(list.len());
            for s in scene.sites_of(k) {
                list.push(scene.site(k, s));
                bodies.push(scene.site_body(k, s));
            }
        }
        first.push(list.len());
        Sites { list, first, bodies, any_rigid: scene.bodies.iter().any(Body::is_rigid) }
    }

    /// How many sites.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// Whether there are none.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// Body `k`'s sites.
    pub fn of_body(&self, k: usize) -> Range<usize> {
        self.first[k]..self.first[k + 1]
    }

    /// The body of site `s`.
    pub fn body(&self, s: usize) -> usize {
        self.list[s].body
    }

    /// The bodies of sites `p` and `q`.
    pub fn bodies_of(&self, [p, q]: [usize; 2]) -> [usize; 2] {
        [self.list[p].body, self.list[q].body]
    }

    /// Site `s`'s offset from its body's mass centre, turned with the body as `state` has it (m): zero for a site at
    /// its centre.
    pub fn lever(&self, s: usize, state: &Kinematic) -> Vector3<f64> {
        let offset = self.list[s].offset;
        if offset == Vector3::zeros() { offset } else { state.orientation * offset }
    }

    /// Site `s`'s centre for its body at `state` (m): the body's position exactly for a site at its centre.
    pub fn centre(&self, s: usize, state: &Kinematic) -> Vector3<f64> {
        if self.list[s].offset == Vector3::zeros() { state.position } else { state.position + self.lever(s, state) }
    }

    /// Site `s` moving with its body at `state` in closed-form flight: its centre, and its body's velocity and spin (a
    /// body that flies in closed form does not turn).
    pub fn kinematic(&self, s: usize, state: &Kinematic) -> Kinematic {
        Kinematic { position: self.centre(s, state), ..*state }
    }

    /// How sites `p` and `q` meet.
    pub fn meeting(&self, scene: &WorldScene, p: usize, q: usize) -> Meeting {
        scene.site_meeting(&self.list[p], &self.list[q])
    }

    /// Whether sites `p` and `q` can ever touch: of two bodies that can.
    pub fn interacts(&self, scene: &WorldScene, p: usize, q: usize) -> bool {
        scene.interacts(self.list[p].body, self.list[q].body)
    }

    /// The sphere index of site `s` on its body, as a report gives it: `None` for a flat body's face.
    pub fn sphere(&self, scene: &WorldScene, s: usize) -> Option<usize> {
        let site = &self.list[s];
        (!scene.bodies[site.body].is_flat()).then_some(site.sphere)
    }
}
