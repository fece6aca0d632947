//! Which pairs of bodies may touch soon: a neighbour list with a skin (docs/world.md#neighbours).
//!
//! Flight and the island look for first touches only among the pairs whose gap was below the skin `s` when the list
//! was built. The list holds while every body stays within `s/2` of where it was then: a gap shrinks by at most the
//! two bodies' displacements, so a pair left out cannot close its gap before some body has moved that far. The
//! driver rebuilds the list when a body reaches that bound: in flight at a closed-form time, in an island at a
//! located event on the solution. The list is built by sort and sweep along the axis over which the spheres spread
//! most (each sphere against the few whose extent along that axis comes within the skin of its own), and every flat
//! body against every sphere: O(N log N) for N bodies, where every pair would be O(N²).
//!
//! The list is of sites (docs/world.md#rigid-bodies): every contact sphere of every body, and each flat body's face
//! (in a world of spheres and walls, the bodies themselves). Two spheres of one body are never neighbours.

use super::flight::Kinematic;
use super::sites::Sites;
use crate::scene::WorldScene;
use nalgebra::Vector3;

/// Up to this many sites (bodies, in a world of spheres), every pair that can touch is a neighbour for the whole run (an infinite skin): no list
/// to rebuild, and the search of a few pairs costs less than the rebuilds would.
pub const ALL_PAIRS_UP_TO: usize = 32;

/// The default skin beyond [`ALL_PAIRS_UP_TO`] bodies, as a fraction of the smallest sphere's radius.
pub const SKIN_OF_RADIUS: f64 = 0.25;

/// The pairs that may touch before the list must be rebuilt, with what they were built from.
#[derive(Debug, Clone)]
pub struct Neighbours {
    /// The neighbour pairs (p < q, sites of two bodies that can touch), in increasing order.
    pub pairs: Vec<(usize, usize)>,
    /// Every site's centre when the list was built, m.
    reference: Vec<Vector3<f64>>,
    /// The skin, m; infinite for a list of every pair.
    skin: f64,
    /// For each site, the sites it is paired with in the list.
    adjacent: Vec<Vec<usize>>,
}

/// The skin of `scene` (m): its `[world] skin`, or the default — infinite (every pair) up to
/// [`ALL_PAIRS_UP_TO`] bodies, [`SKIN_OF_RADIUS`] of the smallest sphere's radius beyond.
pub fn skin(scene: &WorldScene, sites: &Sites) -> f64 {
    if let Some(skin) = scene.world.skin {
        return skin;
    }
    if sites.len() <= ALL_PAIRS_UP_TO {
        return f64::INFINITY;
    }
    let smallest = sites.list.iter().map(|s| s.radius).filter(|r| r.is_finite()).fold(f64::INFINITY, f64::min);
    SKIN_OF_RADIUS * smallest
}

impl Neighbours {
    /// The list of `scene`'s sites for its bodies at `states`, for `skin` (m; infinite: every pair that can touch).
    pub fn build(scene: &WorldScene, sites: &Sites, states: &[Kinematic], skin: f64) -> Neighbours {
        let reference: Vec<Vector3<f64>> = (0..sites.len()).map(|s| sites.centre(s, &states[sites.body(s)])).collect();
        let n = sites.len();
        let radius = |s: usize| sites.list[s].radius;
        let interacts = |p: usize, q: usize| sites.interacts(scene, p, q);
        let mut pairs = Vec::new();
        if skin.is_finite() {
            let flat = |s: usize| scene.faces[sites.body(s)].is_some();
            let spheres: Vec<usize> = (0..n).filter(|&k| !flat(k)).collect();
            // The axis of the largest spread of the centres.
            let mut low = Vector3::repeat(f64::INFINITY);
            let mut high = Vector3::repeat(f64::NEG_INFINITY);
            for &k in &spheres {
                low = low.inf(&reference[k]);
                high = high.sup(&reference[k]);
            }
            let axis = (high - low).imax();
            let mut order: Vec<(f64, usize)> = spheres.iter().map(|&k| (reference[k][axis] - radius(k), k)).collect();
            order.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (at, &(_, i)) in order.iter().enumerate() {
                let ri = radius(i);
                let extent = reference[i][axis] + ri + skin;
                for &(start, j) in &order[at + 1..] {
                    if start > extent {
                        break;
                    }
                    let reach = ri + radius(j);
                    if interacts(i, j) && (reference[j] - reference[i]).norm() - reach < skin {
                        pairs.push((i.min(j), i.max(j)));
                    }
                }
            }
            for f in (0..n).filter(|&k| flat(k)) {
                let face = scene.faces[sites.body(f)].expect("a flat body has a face");
                for &k in &spheres {
                    let height = face.dot(&(reference[k] - reference[f])) - radius(k);
                    if interacts(f, k) && height < skin {
                        pairs.push((f.min(k), f.max(k)));
                    }
                }
            }
            pairs.sort_unstable();
        } else {
            pairs = (0..n).flat_map(|i| (i + 1..n).map(move |j| (i, j))).filter(|&(i, j)| interacts(i, j)).collect();
        }
        let mut adjacent = vec![Vec::new(); n];
        for &(i, j) in &pairs {
            adjacent[i].push(j);
            adjacent[j].push(i);
        }
        Neighbours { pairs, reference, skin, adjacent }
    }

    /// The list rebuilt at `states` with the same skin.
    pub fn rebuild(&mut self, scene: &WorldScene, sites: &Sites, states: &[Kinematic]) {
        *self = Neighbours::build(scene, sites, states, self.skin);
    }

    /// How far each body may move from where the list was built (half the skin), m.
    pub fn reach(&self) -> f64 {
        self.skin / 2.0
    }

    /// The centres (m) of `sites` when the list was built.
    pub fn references(&self, sites: &[usize]) -> Vec<Vector3<f64>> {
        sites.iter().map(|&k| self.reference[k]).collect()
    }

    /// The sites paired with site `k` in the list.
    pub fn adjacent(&self, k: usize) -> &[usize] {
        &self.adjacent[k]
    }

    /// Whether the list holds every pair for the whole run (an infinite skin).
    pub fn is_everything(&self) -> bool {
        self.skin.is_infinite()
    }

    /// How far (m) site `k`, now at `position`, may still move before the list must be rebuilt (negative: beyond).
    pub fn margin(&self, k: usize, position: &Vector3<f64>) -> f64 {
        if self.is_everything() {
            return f64::INFINITY;
        }
        self.reach() - (position - self.reference[k]).norm()
    }

    /// A flight time (s) within which site `k`, now at `state` (its centre, and its body's motion) and flying under the acceleration `a`, surely stays
    /// within its margin m: the positive root of |v| t + |a| t²/2 = m, written without cancellation as
    /// 2m / (|v| + sqrt(|v|² + 2 |a| m)) (infinite for a body at rest, zero for one already at its margin). `slack`
    /// (m) is taken from the margin: how far the site may stray from `state`'s motion (a coasting ball's padding).
    pub fn flight_bound(&self, k: usize, state: &Kinematic, a: &Vector3<f64>, slack: f64) -> f64 {
        if state.velocity == Vector3::zeros() && *a == Vector3::zeros() {
            return f64::INFINITY;
        }
        let margin = self.margin(k, &state.position) - slack;
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
