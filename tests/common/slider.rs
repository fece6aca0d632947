//! An independent integration of a frictional sphere meeting a flat wall under Kelvin–Voigt's linear law with a
//! constant tangential spring, capped at `mu |Fn|` (the magnitude cap): the normal motion in closed form
//! (docs/laws.md: `d = (v0/ωd) e^(-βt) sin(ωd t)` up to `t = π/ωd`, the damping from the map
//! `ζ = -ln e / sqrt(π² + ln² e)`, `c = 2 ζ sqrt(k m)`), and the tangential spring as the elastic–perfectly-plastic
//! slider of a DEM code (the spring loaded by the slip over a step, then cut to the limit), at a fixed step; the
//! slip of a solid sphere changes by `T (1/m + R²/I) = 7T/(2m)`.

/// The contact: a solid sphere of `radius` (m) and `density` (kg/m³) meeting an immovable wall at `normal_speed`
/// (m/s) while sliding along it at `slip` (m/s), without spin; `stiffness` (N/m), `restitution`, `friction` (mu),
/// `tangential_stiffness` (N/m).
pub struct Slider {
    pub radius: f64,
    pub density: f64,
    pub stiffness: f64,
    pub restitution: f64,
    pub friction: f64,
    pub tangential_stiffness: f64,
    pub normal_speed: f64,
    pub slip: f64,
}

impl Slider {
    /// The contact of the release tests (tests/wall_slide.rs, tests/world_friction.rs): a 1 cm alumina-density ball
    /// at 1 m/s onto the wall and 0.5 m/s along it, k = 1e7 N/m, e = 0.5, mu = 0.5, a soft spring of 1e4 N/m: the
    /// room under `mu |Fn|` dips below zero for about 2e-7 s of a 1.3e-4 s contact.
    pub const SOFT_SPRING: Slider = Slider {
        radius: 0.01,
        density: 4000.0,
        stiffness: 1e7,
        restitution: 0.5,
        friction: 0.5,
        tangential_stiffness: 1e4,
        normal_speed: 1.0,
        slip: 0.5,
    };

    /// The tangential velocity after (m/s) with the spring released and with it kept, at a million steps each; the
    /// two must lie more than 5e-4 m/s apart for a test against them to tell one from the other.
    pub fn released_and_kept(&self) -> (f64, f64) {
        let (released, kept) = (self.velocity_after(1_000_000, true), self.velocity_after(1_000_000, false));
        assert!((released - kept).abs() > 5e-4, "released {released}, kept {kept}: too close to tell apart");
        (released, kept)
    }

    /// The sphere's tangential velocity after the contact (m/s), integrated over `steps` fixed steps, the spring cut
    /// to the limit (`release`) or only its force capped, the spring kept (what a path that steps over a stretch
    /// where the limit is below the spring computes).
    pub fn velocity_after(&self, steps: usize, release: bool) -> f64 {
        let pi = std::f64::consts::PI;
        let m = self.density * 4.0 / 3.0 * pi * self.radius.powi(3);
        let (k, e, v0) = (self.stiffness, self.restitution, self.normal_speed);
        let zeta = -e.ln() / (pi * pi + e.ln().powi(2)).sqrt();
        let c = 2.0 * zeta * (k * m).sqrt();
        let beta = c / (2.0 * m);
        let omega = (k / m - beta * beta).sqrt();
        let duration = pi / omega;
        let normal_force = |t: f64| {
            let (sin, cos) = (omega * t).sin_cos();
            let decay = (-beta * t).exp();
            k * v0 / omega * decay * sin + c * v0 * decay * (cos - beta / omega * sin)
        };
        let dt = duration / steps as f64;
        let (mut spring, mut slip, mut impulse) = (0.0_f64, self.slip, 0.0);
        for i in 0..steps {
            let limit = self.friction * normal_force((i as f64 + 0.5) * dt).abs();
            spring -= self.tangential_stiffness * slip * dt;
            if release {
                spring = spring.clamp(-limit, limit);
            }
            let force = spring.clamp(-limit, limit);
            impulse += force * dt;
            slip += 3.5 * force / m * dt;
        }
        self.slip + impulse / m
    }
}
