//! A ball that rests on a still flat face, its normal ringing died away, moved on in closed form
//! (docs/world.md#coasting).
//!
//! The ball presses the face with its weight alone (gravity along the face's normal), so its penetration and normal
//! force stand still: `Fn` constant and Mindlin's `kt` with them. Along the face the ball moves freely but for the
//! contact's tangential force `T` at its contact point, `-r n` from its centre (`n` the face's unit normal, into the
//! ball). A smooth contact has none: the ball slides at its velocity and keeps its spin. A sticking contact without
//! tangential damping is a spring on the slip `u = v - r w × n` of the contact point:
//!
//! `dT/dt = -kt u`, `m dv/dt = T`, `I dw/dt = -r n × T`, so `du/dt = T / m_t`, `1/m_t = 1/m + r²/I`,
//!
//! a harmonic oscillator of angular frequency `ω = sqrt(kt/m_t)` riding on uniform rolling. With `τ` the time since
//! the coast began, `T0`, `u0` the force and slip then and `J(τ) = ∫ T dτ`:
//!
//! * `T(τ) = T0 cos ωτ - (kt/ω) u0 sin ωτ`, `u(τ) = u0 cos ωτ + T0/(m_t ω) sin ωτ`;
//! * `J(τ) = (T0/ω) sin ωτ - m_t u0 (1 - cos ωτ)`; `v = v0 + J/m`, `w = w0 - (r/I) n × J`;
//! * `x = x0 + v0 τ + K/m`, `K(τ) = ∫ J dτ = (T0/ω²)(1 - cos ωτ) - m_t u0 (τ - sin(ωτ)/ω)`.
//!
//! The mean motion is uniform: velocity `v0 - (m_t/m) u0` (the rolling the slip settles to), position
//! `x0 + T0/(m ω²)` at `τ = 0`, and the centre never strays from it by more than
//! `(|T0|/ω + m_t |u0|)/(m ω)`. The force moves on an ellipse; the coast holds only while that ellipse stays inside
//! the Coulomb cap, so the contact sticks throughout and the closed form is the motion itself, not an approximation
//! of it. The spring's work on the slip, `∫ T·u dτ = -(|T|² - |T0|²)/(2 kt)`, is the energy it takes in.

use super::flight::Kinematic;
use super::island::Units;
use nalgebra::Vector3;

/// How far beyond the Coulomb cap (relative) the ringing's largest force may reach for the contact to coast: a graze.
/// A stick that follows a slide begins with its spring at the cap and rings back to it every period, to the
/// integration's noise (1e-12 of it); a force `ε` beyond the cap at a peak would slip for about `sqrt(ε)` of a period
/// and take about `ε^(3/2)` of the spring's energy, and the integration does not see it either.
pub const CAP_GRAZE: f64 = 1e-9;

/// A ball's coast: its state when it began and the constants of its motion (SI).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coast {
    /// Scene time when the coast began, s.
    pub since: f64,
    /// The ball's state then (its normal velocity removed).
    pub start: Kinematic,
    /// The tangential force on the ball then, N (zero on a smooth contact).
    pub force: Vector3<f64>,
    /// The slip of the ball's contact point on the face then, m/s.
    pub slip: Vector3<f64>,
    /// The face's unit normal, into the ball.
    pub normal: Vector3<f64>,
    /// The ball's mass (kg), moment of inertia (kg m²) and radius (m).
    pub mass: f64,
    pub inertia: f64,
    pub radius: f64,
    /// The tangential stiffness kt (N/m); zero on a smooth contact.
    pub stiffness: f64,
    /// The contact's tangential work when the coast began, J.
    pub work_before: f64,
    /// The normal force (N), constant through the coast, and the contact's normal impulse when it began (N s).
    pub normal_force: f64,
    pub impulse_before: f64,
    /// The units of the island the coast began in: an island that wakes the ball with no contact beginning takes them.
    pub units: Units,
}

/// The ball's state at a time of its coast, with its contact's tangential force and the spring's work since the
/// coast began, and its normal impulse since then.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Coasting {
    pub state: Kinematic,
    /// The tangential force on the ball, N.
    pub force: Vector3<f64>,
    /// `∫ T·u dt` since the coast began, J.
    pub work: f64,
    /// `∫ Fn dt` since the coast began, N s.
    pub impulse: f64,
}

impl Coast {
    /// `1/m_t = 1/m + r²/I`: the mass the slip's force moves, kg.
    fn slip_mass(&self) -> f64 {
        1.0 / (1.0 / self.mass + self.radius * self.radius / self.inertia)
    }

    /// The ringing's angular frequency ω, rad/s (zero on a smooth contact).
    pub fn frequency(&self) -> f64 {
        if self.stiffness > 0.0 { (self.stiffness / self.slip_mass()).sqrt() } else { 0.0 }
    }

    /// The largest tangential force of the ringing, N: the semi-major axis of the ellipse `T0 cos - B sin`,
    /// `B = (kt/ω) u0`.
    pub fn largest_force(&self) -> f64 {
        if self.stiffness <= 0.0 {
            return 0.0;
        }
        let b = self.slip * (self.stiffness / self.frequency());
        let (a2, b2, ab) = (self.force.norm_squared(), b.norm_squared(), self.force.dot(&b));
        let half = 0.5 * (a2 - b2);
        (0.5 * (a2 + b2) + (half * half + ab * ab).sqrt()).sqrt()
    }

    /// How far (m) the centre may stray from its mean line: `(|T0|/ω + m_t |u0|)/(m ω)`.
    pub fn reach(&self) -> f64 {
        if self.stiffness <= 0.0 {
            return 0.0;
        }
        let omega = self.frequency();
        (self.force.norm() / omega + self.slip_mass() * self.slip.norm()) / (self.mass * omega)
    }

    /// The first time (s after the coast began, > 0) at which the slip's component along `direction` falls through
    /// zero: `u(τ)·d = a cos ωτ + b sin ωτ = R cos(ωτ - φ)`, `a = u0·d`, `b = T0·d/(m_t ω)`, falling through zero where
    /// `ωτ - φ = π/2` (mod 2π). `None` on a smooth contact, or where the slip has no component along `direction`.
    pub fn slip_falls_through_zero(&self, direction: &Vector3<f64>) -> Option<f64> {
        if self.stiffness <= 0.0 {
            return None;
        }
        let omega = self.frequency();
        let (a, b) = (self.slip.dot(direction), self.force.dot(direction) / (self.slip_mass() * omega));
        if a == 0.0 && b == 0.0 {
            return None;
        }
        let turn = 2.0 * std::f64::consts::PI;
        let theta = (b.atan2(a) + 0.5 * std::f64::consts::PI).rem_euclid(turn);
        Some(if theta > 0.0 { theta } else { turn } / omega)
    }

    /// The mean motion at scene time `t`: uniform, with the mean velocity and spin (the ball flies on it with no
    /// acceleration, its centre within [`Coast::reach`] of it).
    pub fn mean(&self, t: f64) -> Kinematic {
        let tau = t - self.since;
        if self.stiffness <= 0.0 {
            return Kinematic { position: self.start.position + self.start.velocity * tau, ..self.start };
        }
        let (m, mt, omega) = (self.mass, self.slip_mass(), self.frequency());
        let velocity = self.start.velocity - self.slip * (mt / m);
        let spin = self.start.spin + self.normal.cross(&self.slip) * (self.radius * mt / self.inertia);
        let position = self.start.position + self.force / (m * omega * omega) + velocity * tau;
        Kinematic { position, velocity, spin, orientation: self.start.orientation }
    }

    /// The ball's exact state at scene time `t`.
    pub fn at(&self, t: f64) -> Coasting {
        let tau = t - self.since;
        let start = &self.start;
        if self.stiffness <= 0.0 {
            let state = Kinematic { position: start.position + start.velocity * tau, ..*start };
            return Coasting { state, force: Vector3::zeros(), work: 0.0, impulse: self.normal_force * tau };
        }
        let (m, mt, omega, kt) = (self.mass, self.slip_mass(), self.frequency(), self.stiffness);
        let (s, c) = (omega * tau).sin_cos();
        // 1 - cos ωτ and ωτ - sin ωτ without cancellation at small ωτ.
        let half = (0.5 * omega * tau).sin();
        let one_less_cos = 2.0 * half * half;
        let beyond_sin = if (omega * tau).abs() < 1e-2 {
            let x = omega * tau;
            let x3 = x * x * x;
            x3 / 6.0 * (1.0 - x * x / 20.0 * (1.0 - x * x / 42.0))
        } else {
            omega * tau - s
        };
        let force = self.force * c - self.slip * (kt / omega * s);
        let impulse = self.force * (s / omega) - self.slip * (mt * one_less_cos);
        let moment = self.force * (one_less_cos / (omega * omega)) - self.slip * (mt * beyond_sin / omega);
        let state = Kinematic {
            position: start.position + start.velocity * tau + moment / m,
            velocity: start.velocity + impulse / m,
            spin: start.spin - self.normal.cross(&impulse) * (self.radius / self.inertia),
            orientation: start.orientation,
        };
        let work = -(force.norm_squared() - self.force.norm_squared()) / (2.0 * kt);
        Coasting { state, force, work, impulse: self.normal_force * tau }
    }
}

/// The slip (m/s) of a ball's contact point on a still face: the tangential part of `v - r w × n`.
pub fn slip(state: &Kinematic, normal: &Vector3<f64>, radius: f64) -> Vector3<f64> {
    let point = state.velocity - state.spin.cross(normal) * radius;
    point - normal * normal.dot(&point)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::UnitQuaternion;

    fn ball(force: Vector3<f64>, slip_velocity: Vector3<f64>) -> Coast {
        let (m, r) = (0.0329, 0.01);
        let inertia = 0.4 * m * r * r;
        let normal = Vector3::z();
        // A spin that gives the slip asked for with a velocity of 3 mm/s along x and a spin about the vertical.
        let velocity = Vector3::new(3e-3, 0.0, 0.0);
        // v - r w × n = slip: w × z = (v - slip)/r; w = z × (v - slip)/r (w ⊥ z) plus 2 rad/s about z.
        let spin = normal.cross(&(velocity - slip_velocity)) / r + normal * 2.0;
        let start = Kinematic {
            position: Vector3::new(0.01, -0.02, r),
            velocity,
            spin,
            orientation: UnitQuaternion::identity(),
        };
        assert!((slip(&start, &normal, r) - slip_velocity).norm() < 1e-15);
        Coast {
            since: 0.5,
            start,
            force,
            slip: slip_velocity,
            normal,
            mass: m,
            inertia,
            radius: r,
            stiffness: 5.3e6,
            work_before: 0.0,
            normal_force: m * 9.81,
            impulse_before: 0.0,
            units: Units::new(m, 1e10, 1.5, 1.0),
        }
    }

    /// The closed form against an independent integration of `dT/dt = -kt u`, `m dv/dt = T`, `I dw/dt = -r n × T`
    /// (classical RK4 at 20,000 steps a period), over 3.3 periods.
    #[test]
    fn the_closed_form_is_the_motion_of_the_sticking_spring() {
        let coast = ball(Vector3::new(0.02, -0.01, 0.0), Vector3::new(-4e-5, 7e-5, 0.0));
        let (m, i, r, kt, n) = (coast.mass, coast.inertia, coast.radius, coast.stiffness, coast.normal);
        type S = (Vector3<f64>, Vector3<f64>, Vector3<f64>, Vector3<f64>, f64);
        let rate = |s: &S| -> S {
            let (_x, v, w, t, _work) = *s;
            let u = v - w.cross(&n) * r;
            let u = u - n * n.dot(&u);
            (v, t / m, -n.cross(&t) * (r / i), -u * kt, t.dot(&u))
        };
        let add =
            |s: &S, k: &S, h: f64| -> S { (s.0 + k.0 * h, s.1 + k.1 * h, s.2 + k.2 * h, s.3 + k.3 * h, s.4 + k.4 * h) };
        let period = 2.0 * std::f64::consts::PI / coast.frequency();
        let span = 3.3 * period;
        let steps = 66_000;
        let h = span / steps as f64;
        let mut s: S = (Vector3::zeros(), coast.start.velocity, coast.start.spin, coast.force, 0.0);
        for _ in 0..steps {
            let k1 = rate(&s);
            let k2 = rate(&add(&s, &k1, h / 2.0));
            let k3 = rate(&add(&s, &k2, h / 2.0));
            let k4 = rate(&add(&s, &k3, h));
            s = (
                s.0 + (k1.0 + k2.0 * 2.0 + k3.0 * 2.0 + k4.0) * (h / 6.0),
                s.1 + (k1.1 + k2.1 * 2.0 + k3.1 * 2.0 + k4.1) * (h / 6.0),
                s.2 + (k1.2 + k2.2 * 2.0 + k3.2 * 2.0 + k4.2) * (h / 6.0),
                s.3 + (k1.3 + k2.3 * 2.0 + k3.3 * 2.0 + k4.3) * (h / 6.0),
                s.4 + (k1.4 + k2.4 * 2.0 + k3.4 * 2.0 + k4.4) * (h / 6.0),
            );
        }
        let at = coast.at(coast.since + span);
        let speed = 3e-3;
        // (Displacements: the reference's sum of 66,000 steps is rounded to about 1e-16 m.)
        let moved = at.state.position - coast.start.position;
        assert!((moved - s.0).norm() < 1e-9 * speed * span, "{moved:?} {:?}", s.0);
        assert!((moved - s.0).norm() < 1e-5 * coast.reach());
        assert!((at.state.velocity - s.1).norm() < 1e-10 * speed, "{:?} {:?}", at.state.velocity, s.1);
        assert!((at.state.spin - s.2).norm() * r < 1e-10 * speed);
        assert!((at.force - s.3).norm() < 1e-10 * coast.largest_force());
        assert!((at.work - s.4).abs() < 1e-10 * coast.largest_force().powi(2) / kt);
        // The mean motion holds the centre within its reach, and the largest force bounds every force.
        let mut largest: f64 = 0.0;
        for k in 0..2000 {
            let t = coast.since + span * k as f64 / 2000.0;
            let at = coast.at(t);
            assert!((at.state.position - coast.mean(t).position).norm() <= coast.reach() * (1.0 + 1e-12));
            largest = largest.max(at.force.norm());
        }
        assert!(largest <= coast.largest_force() * (1.0 + 1e-12) && largest > 0.999 * coast.largest_force());
        // The slip rolls on the spring alone: momentum along the face changes only by the force's impulse, and the
        // angular momentum about the contact point is kept (the force acts there).
        let am = |k: &Kinematic| (n * r).cross(&(k.velocity * m)) + k.spin * i;
        assert!((am(&at.state) - am(&coast.start)).norm() < 1e-12 * m * r * speed);
        // The slip along x falls through zero where the reference's does (sampled at 2000 instants a period).
        let direction = Vector3::x();
        let zero = coast.slip_falls_through_zero(&direction).expect("a ringing slip");
        let slip_x = |t: f64| slip(&coast.at(coast.since + t).state, &n, r).dot(&direction);
        assert!(slip_x(zero).abs() < 1e-12 * coast.slip.norm().max(1e-12));
        let h = period / 2000.0;
        assert!(slip_x(zero - h) > 0.0 && slip_x(zero + h) < 0.0);
        assert!(zero > 0.0 && zero <= period);
        let first = (1..2000).map(|k| k as f64 * h).find(|&t| slip_x(t - h) > 0.0 && slip_x(t) <= 0.0);
        assert!(first.is_some_and(|t| (t - zero).abs() <= h), "{first:?} against {zero}");
    }

    /// At the coast's start the closed form is its start, and a smooth contact slides uniformly.
    #[test]
    fn a_coast_begins_where_it_was_and_a_smooth_one_slides_on() {
        let coast = ball(Vector3::new(0.02, -0.01, 0.0), Vector3::new(-4e-5, 7e-5, 0.0));
        let at = coast.at(coast.since);
        assert_eq!((at.state, at.force, at.work, at.impulse), (coast.start, coast.force, 0.0, 0.0));
        let smooth = Coast { stiffness: 0.0, force: Vector3::zeros(), ..coast };
        let later = smooth.at(smooth.since + 2.0);
        assert_eq!(later.state.velocity, smooth.start.velocity);
        assert_eq!(later.state.spin, smooth.start.spin);
        assert!((later.state.position - (smooth.start.position + smooth.start.velocity * 2.0)).norm() < 1e-18);
        assert_eq!(smooth.reach(), 0.0);
        assert_eq!(smooth.mean(smooth.since + 2.0), later.state);
    }
}
