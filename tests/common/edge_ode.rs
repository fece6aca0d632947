//! An independent reference for the laws whose damping term carries a fractional power of the penetration (Tsuji:
//! d^(1/4), Brilliantov: d^(1/2)), written for the tests: fixed-step RK4 in variables that make the motion smooth.
//!
//! Nondimensional (m* = K = v0 = 1): d'' = -(d^(3/2) + c d^q d'), with q = 1/4, c = a for Tsuji and q = 1/2,
//! c = b = (3/2) A v0/L for Brilliantov. Near the edges of the contact the time variable is not smooth (d ~ t - c
//! t^(7/2)...), so there the penetration is traded for s = d^q (d = s^p, p = 1/q) as the independent variable:
//! dv/ds = -p s^(p-1) (s^(3p/2) + c s v)/v, dt/ds = p s^(p-1)/v, dD/ds = p s^(p-1) c s v — polynomial in s, smooth
//! while |v| is bounded away from 0. In the middle (|v| small, d of order 1) the time is the variable. A force
//! separation is where d^(3/2 - q) + c v = 0, i.e. s^(3p/2 - 1) + c v = 0, located by re-stepping one RK4 step.

/// What the reference gives (nondimensional).
#[derive(Debug, Clone, Copy)]
pub struct EdgeContact {
    /// Separation speed / approach speed.
    pub restitution: f64,
    /// Contact time in T = L/v0.
    pub duration: f64,
    /// Penetration at separation, in L (0 for a penetration separation).
    pub separation_penetration: f64,
    /// Dissipated energy, in m* v0².
    pub dissipated: f64,
    /// Elastic energy (2/5) d^(5/2) left at separation, in m* v0².
    pub elastic_left: f64,
}

type State = [f64; 3]; // (v, t, D) in s-phases; (d, v, D) in the time phase (with t carried outside)

fn rk4(f: &dyn Fn(f64, &State) -> State, x: f64, y: &State, h: f64) -> State {
    let add = |y: &State, k: &State, c: f64| [y[0] + c * k[0], y[1] + c * k[1], y[2] + c * k[2]];
    let k1 = f(x, y);
    let k2 = f(x + h / 2.0, &add(y, &k1, h / 2.0));
    let k3 = f(x + h / 2.0, &add(y, &k2, h / 2.0));
    let k4 = f(x + h, &add(y, &k3, h));
    [
        y[0] + h / 6.0 * (k1[0] + 2.0 * k2[0] + 2.0 * k3[0] + k4[0]),
        y[1] + h / 6.0 * (k1[1] + 2.0 * k2[1] + 2.0 * k3[1] + k4[1]),
        y[2] + h / 6.0 * (k1[2] + 2.0 * k2[2] + 2.0 * k3[2] + k4[2]),
    ]
}

/// The contact of the Tsuji (`p = 4`) or Brilliantov (`p = 2`) law with damping `c`, ended at the force's zero
/// (`force = true`) or at d = 0, with `steps` RK4 steps per unit of the independent variable.
pub fn edge_contact(p: i32, c: f64, force: bool, steps: f64) -> EdgeContact {
    let pf = p as f64;
    let q_power = |s: f64| s.powi(3 * p / 2); // d^(3/2) = s^(3p/2)
    let in_s = move |s: f64, y: &State| -> State {
        let (v, jacobian) = (y[0], pf * s.powi(p - 1));
        [-jacobian * (q_power(s) + c * s * v) / v, jacobian / v, jacobian * c * s * v]
    };
    let in_t = move |_t: f64, y: &State| -> State {
        let (d, v) = (y[0].max(0.0), y[1]);
        let dq = d.powf(1.0 / pf);
        [v, -(d * d.sqrt() + c * dq * v), c * dq * v * v]
    };
    // Compression, in s, until v < 1/2.
    let h = 1.0 / steps;
    let (mut s, mut y) = (0.0, [1.0, 0.0, 0.0]);
    while y[0] >= 0.5 {
        y = rk4(&in_s, s, &y, h);
        s += h;
    }
    // The middle, in t, until v < -3/10.
    let mut t = y[1];
    let mut z = [s.powi(p), y[0], y[2]];
    while z[1] >= -0.3 {
        z = rk4(&in_t, t, &z, h);
        t += h;
    }
    // Restitution, in s, down to the separation.
    s = z[0].powf(1.0 / pf);
    y = [z[1], t, z[2]];
    let g = |s: f64, y: &State| s.powi(3 * p / 2 - 1) + c * y[0];
    let mut end = None;
    while s > 0.0 {
        let step = h.min(s);
        let next = rk4(&in_s, s, &y, -step);
        if force && g(s - step, &next) <= 0.0 {
            // Bisection on the length of one re-step from (s, y).
            let (mut lo, mut hi) = (0.0, step);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if g(s - mid, &rk4(&in_s, s, &y, -mid)) > 0.0 { lo = mid } else { hi = mid }
            }
            let at = s - hi;
            end = Some((at, rk4(&in_s, s, &y, -hi)));
            break;
        }
        y = next;
        s -= step;
    }
    let (s_end, y_end) = end.unwrap_or((0.0, y));
    let d_end = s_end.powi(p);
    EdgeContact {
        restitution: -y_end[0],
        duration: y_end[1],
        separation_penetration: d_end,
        dissipated: y_end[2],
        elastic_left: 0.4 * d_end * d_end * d_end.sqrt(),
    }
}

/// The reference, Richardson-extrapolated (RK4: error ~ h^4) from step counts N and 2N, with N doubled until two
/// successive extrapolations agree to `agreement` (relative, every field): the reference's own accuracy is thereby
/// checked, not assumed.
pub fn converged_edge_contact(p: i32, c: f64, force: bool, agreement: f64) -> EdgeContact {
    let extrapolate = |a: f64, b: f64| b + (b - a) / 15.0;
    let combine = |coarse: &EdgeContact, fine: &EdgeContact| EdgeContact {
        restitution: extrapolate(coarse.restitution, fine.restitution),
        duration: extrapolate(coarse.duration, fine.duration),
        separation_penetration: extrapolate(coarse.separation_penetration, fine.separation_penetration),
        dissipated: extrapolate(coarse.dissipated, fine.dissipated),
        elastic_left: extrapolate(coarse.elastic_left, fine.elastic_left),
    };
    let mut steps = 1000.0;
    let mut coarse = edge_contact(p, c, force, steps);
    let mut fine = edge_contact(p, c, force, 2.0 * steps);
    let mut previous = combine(&coarse, &fine);
    loop {
        steps *= 2.0;
        coarse = fine;
        fine = edge_contact(p, c, force, 2.0 * steps);
        let next = combine(&coarse, &fine);
        let close = |a: f64, b: f64| (a - b).abs() <= agreement * b.abs().max(1e-300);
        if close(previous.restitution, next.restitution)
            && close(previous.duration, next.duration)
            && close(previous.dissipated, next.dissipated)
            && close(previous.elastic_left, next.elastic_left)
        {
            return next;
        }
        assert!(steps < 1e6, "the edge reference does not converge for p = {p}, c = {c}: {previous:?} {next:?}");
        previous = next;
    }
}
