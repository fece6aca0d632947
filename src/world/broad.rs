//! Which pairs of bodies may touch soon: a neighbour list with a skin (docs/world.md#neighbours).
//!
//! Flight and the island look for first touches only among the pairs whose gap was below the skin `s` when the list
//! was built. The list holds while every body stays within `s/2` of where it was then: a gap shrinks by at most the
//! two bodies' displacements, so a pair left out cannot close its gap before some body has moved that far. The
//! driver rebuilds the list when a body reaches that bound: in flight at a closed-form time, in an island at a
//! located event on the solution. The list is built by sort and sweep along the axis over which the spheres spread
//! most (each sphere against the few whose extent along that axis comes within the skin of its own), and every flat
//! body against every sphere: O(N log N) for N bodies, where every pair would be O(N²).

use super::flight::Kinematic;
use crate::scene::WorldScene;
use nalgebra::Vector3;

/// Up to this many bodies, every pair that can touch is a neighbour for the whole run (an infinite skin): no list
/// to rebuild, and the search of a few pairs costs less than the rebuilds would.
pub const ALL_PAIRS_UP_TO: usize = 32;

/// The default skin beyond [`ALL_PAIRS_UP_TO`] bodies, as a fraction of the smallest sphere's radius.
pub const SKIN_OF_RADIUS: f64 = 0.25;

/// The pairs that may touch before the list must be rebuilt, with what they were built from.
#[derive(Debug, Clone)]
pub struct Neighbours {
    /// The neighbour pairs (i < j, bodies that can touch), in increasing order.
    pub pairs: Vec<(usize, usize)>,
    /// Every body's position when the list was built, m.
    reference: Vec<Vector3<f64>>,
    /// The skin, m; infinite for a list of every pair.
    skin: f64,
    /// For each body, the bodies it is paired with in the list.
    adjacent: Vec<Vec<usize>>,
}

/// The skin of `scene` (m): its `[world] skin`, or the default — infinite (every pair) up to
/// [`ALL_PAIRS_UP_TO`] bodies, [`SKIN_OF_RADIUS`] of the smallest sphere's radius beyond.
pub fn skin(scene: &WorldScene) -> f64 {
    if let Some(skin) = scene.world.skin {
        return skin;
    }
    if scene.bodies.len() <= ALL_PAIRS_UP_TO {
        return f64::INFINITY;
    }
    let smallest = scene.bodies.iter().filter(|b| !b.is_flat()).map(|b| b.radius).fold(f64::INFINITY, f64::min);
    SKIN_OF_RADIUS * smallest
}

impl Neighbours {
    /// The list of `scene`'s bodies at `states` for `skin` (m; infinite: every pair that can touch).
    pub fn build(scene: &WorldScene, states: &[Kinematic], skin: f64) -> Neighbours {
        let reference: Vec<Vector3<f64>> = states.iter().map(|s| s.position).collect();
        let n = scene.bodies.len();
        let mut pairs = Vec::new();
        if skin.is_finite() {
            let flat = |k: usize| scene.faces[k].is_some();
            let spheres: Vec<usize> = (0..n).filter(|&k| !flat(k)).collect();
            // The axis of the largest spread of the centres.
            let mut low = Vector3::repeat(f64::INFINITY);
            let mut high = Vector3::repeat(f64::NEG_INFINITY);
            for &k in &spheres {
                low = low.inf(&reference[k]);
                high = high.sup(&reference[k]);
            }
            let axis = (high - low).imax();
            let mut order: Vec<(f64, usize)> =
                spheres.iter().map(|&k| (reference[k][axis] - scene.bodies[k].radius, k)).collect();
            order.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (at, &(_, i)) in order.iter().enumerate() {
                let ri = scene.bodies[i].radius;
                let extent = reference[i][axis] + ri + skin;
                for &(start, j) in &order[at + 1..] {
                    if start > extent {
                        break;
                    }
                    let reach = ri + scene.bodies[j].radius;
                    if scene.interacts(i, j) && (reference[j] - reference[i]).norm() - reach < skin {
                        pairs.push((i.min(j), i.max(j)));
                    }
                }
            }
            for f in (0..n).filter(|&k| flat(k)) {
                let face = scene.faces[f].expect("a flat body has a face");
                for &k in &spheres {
                    let height = face.dot(&(reference[k] - reference[f])) - scene.bodies[k].radius;
                    if scene.interacts(f, k) && height < skin {
                        pairs.push((f.min(k), f.max(k)));
                    }
                }
            }
            pairs.sort_unstable();
        } else {
            pairs =
                (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j))).filter(|&(i, j)| scene.interacts(i, j)).collect();
        }
        let mut adjacent = vec![Vec::new(); n];
        for &(i, j) in &pairs {
            adjacent[i].push(j);
            adjacent[j].push(i);
        }
        Neighbours { pairs, reference, skin, adjacent }
    }

    /// The list rebuilt at `states` with the same skin.
    pub fn rebuild(&mut self, scene: &WorldScene, states: &[Kinematic]) {
        *self = Neighbours::build(scene, states, self.skin);
    }

    /// How far each body may move from where the list was built (half the skin), m.
    pub fn reach(&self) -> f64 {
        self.skin / 2.0
    }

    /// The positions (m) of `bodies` when the list was built.
    pub fn references(&self, bodies: &[usize]) -> Vec<Vector3<f64>> {
        bodies.iter().map(|&k| self.reference[k]).collect()
    }

    /// The bodies paired with body `k` in the list.
    pub fn adjacent(&self, k: usize) -> &[usize] {
        &self.adjacent[k]
    }

    /// Whether the list holds every pair for the whole run (an infinite skin).
    pub fn is_everything(&self) -> bool {
        self.skin.is_infinite()
    }

    /// How far (m) body `k`, now at `position`, may still move before the list must be rebuilt (negative: beyond).
    pub fn margin(&self, k: usize, position: &Vector3<f64>) -> f64 {
        if self.is_everything() {
            return f64::INFINITY;
        }
        self.reach() - (position - self.reference[k]).norm()
    }

    /// A flight time (s) within which body `k`, now at `state` and flying under the acceleration `a`, surely stays
    /// within its margin m: the positive root of |v| t + |a| t²/2 = m, written without cancellation as
    /// 2m / (|v| + sqrt(|v|² + 2 |a| m)) (infinite for a body at rest, zero for one already at its margin).
    pub fn flight_bound(&self, k: usize, state: &Kinematic, a: &Vector3<f64>) -> f64 {
        if state.velocity == Vector3::zeros() && *a == Vector3::zeros() {
            return f64::INFINITY;
        }
        let margin = self.margin(k, &state.position);
        if margin.is_infinite() {
            return f64::INFINITY;
        }
        if margin.is_nan() || margin <= 0.0 {
            return 0.0;
        }
        let (speed, pull) = (state.velocity.norm(), a.norm());
        2.0 * margin / (speed + (speed * speed + 2.0 * pull * margin).sqrt())
    }
}
