//! A sphere on a flat wall with friction, in a regularised time (docs/numerics.md#frictional-impacts-on-a-wall):
//! the 3-D model of [`super::pair::PairContact`], its equations unchanged, integrated in `σ` with
//! `dt = d^(3/4) dσ`, the penetration carried as its fourth root `q = d^(1/4)`.
//!
//! In physical time the forces of a contact are not smooth at its edges: Hertz's `d^(3/2)`, Mindlin's tangential
//! stiffness `d^(1/2)` and Tsuji's damping `d^(1/4)` have derivatives that blow up where `d -> 0`, and an adaptive
//! method shortens its steps there (the general path spends about 130 steps on Chung & Ooi's test 4 at the default
//! tolerances). Near an edge `d` vanishes linearly in `t`, so `q` vanishes linearly in `σ` (`dq/dσ = d'/4`), and
//! every term of the equations times `dt/dσ = q³` is `q^k` times a smooth function, `k >= 1`: `d^(1/2) q³ = q⁵`,
//! `d^(1/4) q³ = q⁴`, `d^n q³ = q^(4n+3)`. The system in `σ` is smooth through both edges, and Dop853 takes a
//! fraction of the steps. The physical time is one more state, `dt/dσ = q³`.
//!
//! The state is the pair model's (its displacement without its normal part, which `q` carries: the penetration of a
//! sphere on a wall is `d = -displacement·n`), then `q` and `t`. Every function of [`ContactModel`] is the pair
//! model's at the corresponding pair state, so the physics, the stick–slip switches and the snapshots are the same
//! functions; the events are located in `σ`, where they are the same zeros. [`ContactModel::penetration`] returns
//! `q`, whose zeros are the penetration's but simple (`d` has a zero of order four in `σ`).

use super::pair::{self, PairContact};
use super::{ContactModel, Scales, Snapshot};
use crate::body::Body;
use crate::integrate::{Model, State};
use crate::setup::Setup;
use nalgebra::Vector3;

/// Size of the state: the pair model's, `q` and the physical time.
pub const SIZE: usize = pair::SIZE + 2;

/// Where `q` and the time sit (the pair model's states keep their places, [`pair::index`]).
pub mod index {
    /// `q = d^(1/4)`, d in L (`d = q |q|³`, negative past the contact's end).
    pub const ROOT: usize = super::pair::SIZE;
    /// Physical time since first contact, in T.
    pub const TIME: usize = super::pair::SIZE + 1;
}

/// The contact of a sphere on a wall, in regularised time.
#[derive(Debug)]
pub struct WallContact<'a> {
    pair: PairContact<'a>,
    /// The wall's normal, from body 1 to body 2.
    normal: Vector3<f64>,
}

impl<'a> WallContact<'a> {
    /// The contact of a resolved scene whose bodies are a sphere and a flat wall; `None` for two spheres.
    pub fn new(bodies: &'a [Body; 2], setup: &'a Setup) -> Option<WallContact<'a>> {
        (bodies[0].is_flat() || bodies[1].is_flat())
            .then(|| WallContact { pair: PairContact::new(bodies, setup), normal: setup.normal })
    }

    /// The pair model's state at `y`: its displacement with the normal part `-d n`.
    fn pair_state(&self, y: &State<SIZE>) -> State<{ pair::SIZE }> {
        let mut p = State::<{ pair::SIZE }>::zeros();
        p.copy_from_slice(&y.as_slice()[..pair::SIZE]);
        let q = y[index::ROOT];
        let d = q * q.abs() * q * q;
        let at = pair::index::DISPLACEMENT;
        for i in 0..3 {
            p[at + i] -= self.normal[i] * d;
        }
        p
    }
}

impl Model<SIZE> for WallContact<'_> {
    fn derivative(&self, _sigma: f64, y: &State<SIZE>, dy: &mut State<SIZE>) {
        let p = self.pair_state(y);
        let mut dp = State::<{ pair::SIZE }>::zeros();
        self.pair.derivative(y[index::TIME], &p, &mut dp);
        let q = y[index::ROOT];
        let stretch = q.abs() * q * q;
        for i in 0..pair::SIZE {
            dy[i] = dp[i] * stretch;
        }
        // The displacement's rate is the relative velocity; its normal part is -d', carried by q.
        let at = pair::index::DISPLACEMENT;
        let velocity = Vector3::new(dp[at], dp[at + 1], dp[at + 2]);
        let rate = -velocity.dot(&self.normal);
        for i in 0..3 {
            dy[at + i] += self.normal[i] * rate * stretch;
        }
        dy[index::ROOT] = 0.25 * rate;
        dy[index::TIME] = stretch;
    }
}

impl ContactModel<SIZE> for WallContact<'_> {
    fn scales(&self) -> &Scales {
        self.pair.scales()
    }

    fn tolerance_factor(&self) -> f64 {
        self.pair.tolerance_factor()
    }

    fn start(&self) -> State<SIZE> {
        let mut y = State::<SIZE>::zeros();
        y.as_mut_slice()[..pair::SIZE].copy_from_slice(self.pair.start().as_slice());
        y
    }

    /// `q = d^(1/4)`: the penetration's sign and zeros, simple ones (see the module).
    fn penetration(&self, y: &State<SIZE>) -> f64 {
        y[index::ROOT]
    }

    fn rate(&self, y: &State<SIZE>) -> f64 {
        self.pair.rate(&self.pair_state(y))
    }

    fn force(&self, y: &State<SIZE>) -> f64 {
        self.pair.force(&self.pair_state(y))
    }

    fn force_rate(&self, y: &State<SIZE>) -> f64 {
        self.pair.force_rate(&self.pair_state(y))
    }

    fn separation_force(&self, y: &State<SIZE>) -> f64 {
        self.pair.separation_force(&self.pair_state(y))
    }

    fn uncut_force(&self, y: &State<SIZE>) -> Option<f64> {
        self.pair.uncut_force(&self.pair_state(y))
    }

    fn switch_function(&self, y: &State<SIZE>) -> Option<f64> {
        self.pair.switch_function(&self.pair_state(y))
    }

    fn switch(&self, y: &mut State<SIZE>) {
        let mut p = self.pair_state(y);
        self.pair.switch(&mut p);
        // (The switch sets the spring and the mode; the displacement is left as it was.)
        for i in pair::index::SPRING..pair::index::SPRING + 3 {
            y[i] = p[i];
        }
        y[pair::index::MODE] = p[pair::index::MODE];
    }

    fn sliding(&self, y: &State<SIZE>) -> bool {
        self.pair.sliding(&self.pair_state(y))
    }

    fn slip_along_start(&self, y: &State<SIZE>) -> Option<f64> {
        self.pair.slip_along_start(&self.pair_state(y))
    }

    fn tension_kink(&self) -> bool {
        self.pair.tension_kink()
    }

    fn kinks(&self, compressing: bool) -> crate::law::Kinks {
        self.pair.kinks(compressing)
    }

    fn time_of(&self, _sigma: f64, y: &State<SIZE>) -> f64 {
        y[index::TIME]
    }

    fn snapshot(&self, _sigma: f64, y: &State<SIZE>) -> Snapshot {
        self.pair.snapshot(y[index::TIME], &self.pair_state(y))
    }
}
