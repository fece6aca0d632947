//! A world run's scene (docs/scene.md#worlds): any number of bodies, a `[world]` table (gravity, when to stop) and
//! `[[pair]]` tables that give a pair of bodies contact keys of its own. Every pair that can touch is checked as the
//! two-body scene it makes (the same value rules, the same law rules), with the keys at fault renamed to where they
//! are written.

use super::{ContactSpec, OutputSpec, Scene, SetupError, SolverSpec};
use crate::body::Body;
use crate::geometry::Meeting;
use nalgebra::Vector3;

/// A validated world scene (SI units).
#[derive(Debug, Clone, PartialEq)]
pub struct WorldScene {
    /// Title for reports and figures (defaults to the file's stem).
    pub title: String,
    /// The bodies, in scene order (0-based indices in `[[pair]]` and in the report).
    pub bodies: Vec<Body>,
    /// The unit face normal of each flat body (pointing from the wall into the side the other bodies move in);
    /// `None` for a sphere.
    pub faces: Vec<Option<Vector3<f64>>>,
    /// The contact of every pair without a `[[pair]]` of its own.
    pub contact: ContactSpec,
    /// Pairs with their own contact keys.
    pub pairs: Vec<PairSpec>,
    pub world: WorldSpec,
    pub solver: SolverSpec,
    pub output: OutputSpec,
}

/// A `[[pair]]`: two bodies and their contact (the scene's `[contact]` with the pair's keys over it).
#[derive(Debug, Clone, PartialEq)]
pub struct PairSpec {
    pub bodies: [usize; 2],
    pub contact: ContactSpec,
    /// The contact keys the pair itself writes (the others come from `[contact]`).
    pub written: Vec<&'static str>,
}

/// The `[world]` table.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WorldSpec {
    /// Uniform acceleration of every body of finite mass, m/s².
    pub gravity: Vector3<f64>,
    /// Scene time at which the run stops, s.
    pub end_time: Option<f64>,
    /// The run stops when this many contacts have ended.
    pub max_contacts: u64,
    /// The run's budget of work: integration steps (accepted and rejected), each segment, flight and contact taken at
    /// once counting as one more; a run that spends it stops with a note (docs/world.md#budgets).
    pub max_steps: u64,
    /// How a damping map that depends on the approach speed applies to a pair's successive contacts.
    pub damping_map: DampingMap,
    /// The neighbour list's skin, m (`None`: the default, docs/world.md#neighbours; infinite: every pair).
    pub skin: Option<f64>,
    /// Whether a ball that rests on a still face, its normal ringing died away, moves on in closed form
    /// (docs/world.md#coasting); `false` integrates it throughout.
    pub coast: bool,
}

/// How a law's damping follows from a nominal e when its map depends on the approach speed (the hysteresis family:
/// alpha = chi(e)/v0).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DampingMap {
    /// Each contact maps e at its own approach speed: every impact of the pair has the nominal e (a DEM code's
    /// constant e).
    #[default]
    EachContact,
    /// The pair's first contact fixes the damping, a material constant: later, slower impacts are livelier.
    FirstContact,
}

impl DampingMap {
    /// Every choice, by its scene spelling.
    pub const ALL: [(&'static str, DampingMap); 2] =
        [("each-contact", DampingMap::EachContact), ("first-contact", DampingMap::FirstContact)];

    /// The scene spelling.
    pub fn name(self) -> &'static str {
        DampingMap::ALL.iter().find(|(_, m)| *m == self).map_or("each-contact", |(name, _)| name)
    }
}

/// The most contacts a run may be asked to end after: a run keeps a record of every contact for its report (about
/// 300 bytes each, and about 1 kB of JSON), so this bounds its memory to a few GB.
pub const MAX_CONTACTS_LIMIT: u64 = 10_000_000;

/// The default of `[world] max_contacts`.
pub const DEFAULT_MAX_CONTACTS: u64 = 1000;

/// The default of `[world] max_steps`: twenty million steps, a few minutes of a small island's integration.
pub const DEFAULT_MAX_STEPS: u64 = 20_000_000;

/// The largest `[world] max_steps`: ten billion steps, about a day of a small island's integration.
pub const MAX_STEPS_LIMIT: u64 = 10_000_000_000;

impl Default for WorldSpec {
    fn default() -> Self {
        WorldSpec {
            gravity: Vector3::zeros(),
            end_time: None,
            max_contacts: DEFAULT_MAX_CONTACTS,
            max_steps: DEFAULT_MAX_STEPS,
            damping_map: DampingMap::EachContact,
            skin: None,
            coast: true,
        }
    }
}

/// One contact sphere of a world's body as the scene places it (a flat body's face is its one site, of infinite
/// radius): the sphere `sphere` of body `body`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Site {
    pub body: usize,
    /// Its index among the body's spheres (0 for a body of one `radius`).
    pub sphere: usize,
    /// Its centre relative to the body's mass centre, m, in scene axes at t = 0.
    pub offset: Vector3<f64>,
    /// m (infinite for a face).
    pub radius: f64,
    /// Its centre at t = 0 (a flat body: the point of its face), m.
    pub centre: Vector3<f64>,
}

impl WorldScene {
    /// How bodies `i` and `j` meet: as two spheres, or a sphere against a flat body's face.
    pub fn meeting(&self, i: usize, j: usize) -> Meeting {
        Meeting::between(&self.bodies[i], self.faces[i], &self.bodies[j], self.faces[j])
    }

    /// The indices of body `k`'s contact spheres (one for a body of one `radius` or a face).
    pub fn sites_of(&self, k: usize) -> std::ops::Range<usize> {
        0..self.bodies[k].spheres.len().max(1)
    }

    /// Contact sphere `s` of body `k`, placed at t = 0.
    pub fn site(&self, k: usize, s: usize) -> Site {
        let body = &self.bodies[k];
        let sphere = body.spheres.get(s).copied().unwrap_or(crate::body::ContactSphere {
            offset: if body.is_flat() { Vector3::zeros() } else { body.contact_offset },
            radius: body.radius,
        });
        let position = body.position.unwrap_or_default();
        // (A sphere at its body's centre is there exactly: no zero added.)
        let centre = if sphere.offset == Vector3::zeros() { position } else { position + sphere.offset };
        Site { body: k, sphere: s, offset: sphere.offset, radius: sphere.radius, centre }
    }

    /// How two contact spheres meet: as two spheres, or a sphere against a flat body's face.
    pub fn site_meeting(&self, a: &Site, b: &Site) -> Meeting {
        Meeting::of_radii(a.radius, self.faces[a.body], b.radius, self.faces[b.body])
    }

    /// Body `k` as the contact of its sphere `s` sees it: the body with that sphere's radius, at its centre (what a
    /// contact law's Hertz stiffness and a pair's rules read). A body of one centred sphere is itself.
    pub fn site_body(&self, k: usize, s: usize) -> Body {
        let body = &self.bodies[k];
        match body.spheres.get(s) {
            Some(sphere) => {
                Body { radius: sphere.radius, spheres: Vec::new(), contact_offset: Vector3::zeros(), ..body.clone() }
            }
            None => body.clone(),
        }
    }

    /// Re-derives what follows from written values (masses from densities, inertias, exponents).
    pub fn resolve(&mut self) {
        for body in &mut self.bodies {
            body.resolve();
        }
        self.contact.resolve();
        for pair in &mut self.pairs {
            pair.contact.resolve();
        }
        for face in self.faces.iter_mut().flatten() {
            let length = face.norm();
            if length > 0.0 && length.is_finite() {
                *face /= length;
            }
        }
    }

    /// The contact of bodies `i` and `j`: their `[[pair]]`'s, or the scene's `[contact]`; with the index of the pair.
    pub fn contact_of(&self, i: usize, j: usize) -> (&ContactSpec, Option<usize>) {
        let found = self.pairs.iter().position(|p| p.bodies == [i, j] || p.bodies == [j, i]);
        match found {
            Some(k) => (&self.pairs[k].contact, Some(k)),
            None => (&self.contact, None),
        }
    }

    /// Whether bodies `i` and `j` can ever touch: not two immovable bodies, not two flat ones.
    pub fn interacts(&self, i: usize, j: usize) -> bool {
        let (a, b) = (&self.bodies[i], &self.bodies[j]);
        i != j && !(a.is_immovable() && b.is_immovable()) && !(a.is_flat() && b.is_flat())
    }

    /// The two-body scene of bodies `i` and `j` (in that order) with their contact: what the value and law rules
    /// check, and what a world of two bodies without gravity runs as today's impact.
    pub fn pair_scene(&self, i: usize, j: usize) -> Scene {
        let (contact, _) = self.contact_of(i, j);
        Scene {
            title: self.title.clone(),
            bodies: [self.bodies[i].clone(), self.bodies[j].clone()],
            contact: contact.clone(),
            solver: self.solver,
            output: OutputSpec::default(),
        }
    }

    /// A broken rule of the contact of sites `a` and `b` (their bodies as the pair scene's two), renamed as
    /// [`WorldScene::rename`] renames it, and a clump's `radius` to its sphere's.
    pub fn rename_sites(&self, a: &Site, b: &Site, error: SetupError) -> SetupError {
        let sphere = |site: &Site, key: &str| {
            if key == "radius" && !self.bodies[site.body].spheres.is_empty() {
                Some(format!("bodies.{}.spheres.{}.radius", site.body, site.sphere))
            } else {
                None
            }
        };
        let own = if let Some(leaf) = error.key.strip_prefix("bodies.0.") {
            sphere(a, leaf)
        } else if let Some(leaf) = error.key.strip_prefix("bodies.1.") {
            sphere(b, leaf)
        } else {
            None
        };
        match own {
            Some(key) => SetupError { key, message: error.message },
            None => self.rename(a.body, b.body, error),
        }
    }

    /// A broken rule of the pair scene of bodies `i` and `j`, renamed to the world's keys: `bodies.0` and `bodies.1`
    /// become the bodies' own indices, and a contact key the pair writes becomes `pair.K.key`.
    pub fn rename(&self, i: usize, j: usize, error: SetupError) -> SetupError {
        let (_, pair) = self.contact_of(i, j);
        let key = if let Some(rest) = error.key.strip_prefix("bodies.0.") {
            format!("bodies.{i}.{rest}")
        } else if let Some(rest) = error.key.strip_prefix("bodies.1.") {
            format!("bodies.{j}.{rest}")
        } else if let (Some(leaf), Some(k)) = (error.key.strip_prefix("contact."), pair) {
            let written = &self.pairs[k].written;
            // A key missing for the pair's own law belongs beside that law.
            let own_law = leaf == "yield_pressure" && written.contains(&"law");
            if written.contains(&leaf) || own_law { format!("pair.{k}.{leaf}") } else { error.key.clone() }
        } else {
            error.key.clone()
        };
        SetupError { key, message: error.message }
    }
}
