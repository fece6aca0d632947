//! Random draws, the same on every machine: one ChaCha8 stream per case (a seed and the case's index), for the
//! stress run's random scenes and worlds and for the unit tests' random cases.

use nalgebra::Vector3;
use rand_chacha::ChaCha8Rng;
use rand_chacha::rand_core::{RngCore, SeedableRng};

/// The random stream of one case.
pub struct Draw(ChaCha8Rng);

impl Draw {
    /// Stream `index` of seed `seed`.
    pub fn new(seed: u64, index: u64) -> Draw {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        rng.set_stream(index);
        Draw(rng)
    }

    /// Uniform in [0, 1), 53 random bits.
    pub fn unit(&mut self) -> f64 {
        (self.0.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }

    pub fn uniform(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * self.unit()
    }

    /// Log-uniform in [low, high] (both > 0).
    pub fn log(&mut self, low: f64, high: f64) -> f64 {
        (low.ln() + (high.ln() - low.ln()) * self.unit()).exp()
    }

    pub fn chance(&mut self, probability: f64) -> bool {
        self.unit() < probability
    }

    pub fn pick<T: Copy>(&mut self, items: &[T]) -> T {
        items[((self.unit() * items.len() as f64) as usize).min(items.len() - 1)]
    }

    /// A unit vector, uniform on the sphere.
    pub fn direction(&mut self) -> Vector3<f64> {
        let z = self.uniform(-1.0, 1.0);
        let phi = self.uniform(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).sqrt();
        Vector3::new(r * phi.cos(), r * phi.sin(), z)
    }

    /// A unit vector across `normal`, uniform on the circle.
    pub fn across(&mut self, normal: &Vector3<f64>) -> Vector3<f64> {
        loop {
            let v = self.direction();
            let t = v - normal * v.dot(normal);
            if t.norm() > 1e-3 {
                return t.normalize();
            }
        }
    }
}
