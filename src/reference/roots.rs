//! A bracketed root-find of a decreasing function that may be noisy or jump (a simulated e against its damping):
//! the Illinois variant of regula falsi with a bisection safeguard. The calibration's root-finds on the simulation
//! and on closed forms use it, and so does the map of `hertz-dashpot` (`law::dashpot`).

/// A sign change of a decreasing function: `f(lo) > 0 > f(hi)` (either may be 0).
#[derive(Debug, Clone, Copy)]
pub struct Bracket {
    pub lo: f64,
    pub f_lo: f64,
    pub hi: f64,
    pub f_hi: f64,
}

/// When a root-find stops: `|f| <= residual`, or the bracket narrower than `relative_width` of its upper end.
#[derive(Debug, Clone, Copy)]
pub struct Stop {
    pub residual: f64,
    pub relative_width: f64,
    pub max_evaluations: u32,
}

/// The evaluated point of smallest |f|, and the final bracket.
#[derive(Debug, Clone, Copy)]
pub struct Root {
    pub x: f64,
    pub residual: f64,
    pub bracket: Bracket,
}

/// The Illinois variant of regula falsi (Dowell & Jarratt 1971): the secant through the bracket's ends, halving
/// the value kept at an end that survives twice in a row; a bisection whenever two steps did not halve the
/// bracket, so that a noisy or jumping `f` (a simulation, a non-separating contact) still converges.
pub fn illinois<E>(mut f: impl FnMut(f64) -> Result<f64, E>, mut b: Bracket, stop: Stop) -> Result<Root, E> {
    let mut best = if b.f_lo.abs() <= b.f_hi.abs() { (b.lo, b.f_lo) } else { (b.hi, b.f_hi) };
    // The values the secant is drawn through: f at the ends, scaled down at an end kept twice in a row.
    let (mut weight_lo, mut weight_hi) = (b.f_lo, b.f_hi);
    let mut evaluations = 0;
    let mut kept_lo_last = None;
    let mut widths = [f64::INFINITY; 2];
    while evaluations < stop.max_evaluations && best.1.abs() > stop.residual {
        let width = b.hi - b.lo;
        if width <= stop.relative_width * b.hi.abs() {
            break;
        }
        let secant = b.hi - weight_hi * width / (weight_hi - weight_lo);
        let slow = width > 0.5 * widths[0];
        let x = if slow || !(secant > b.lo && secant < b.hi) { b.lo + 0.5 * width } else { secant };
        if !(x > b.lo && x < b.hi) {
            break; // the bracket is down to adjacent floating-point numbers
        }
        widths = [widths[1], width];
        let fx = f(x)?;
        evaluations += 1;
        if fx.abs() < best.1.abs() {
            best = (x, fx);
        }
        if fx > 0.0 {
            (b.lo, b.f_lo, weight_lo) = (x, fx, fx);
            if kept_lo_last == Some(false) {
                weight_hi *= 0.5;
            }
            kept_lo_last = Some(false);
        } else {
            (b.hi, b.f_hi, weight_hi) = (x, fx, fx);
            if kept_lo_last == Some(true) {
                weight_lo *= 0.5;
            }
            kept_lo_last = Some(true);
        }
    }
    Ok(Root { x: best.0, residual: best.1, bracket: b })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn find(f: impl Fn(f64) -> f64, lo: f64, hi: f64) -> Root {
        let bracket = Bracket { lo, f_lo: f(lo), hi, f_hi: f(hi) };
        let stop = Stop { residual: 0.0, relative_width: 4.0 * f64::EPSILON, max_evaluations: 200 };
        illinois(|x| Ok::<_, ()>(f(x)), bracket, stop).unwrap()
    }

    #[test]
    fn illinois_finds_a_smooth_root_to_rounding() {
        // exp(-x) = 0.3 at x = ln(10/3).
        let root = find(|x| (-x).exp() - 0.3, 0.0, 50.0);
        assert!((root.x - (10.0f64 / 3.0).ln()).abs() < 4e-16, "{}", root.x);
    }

    #[test]
    fn illinois_closes_in_on_a_jump_without_claiming_a_root() {
        // A contact that stops separating at A = 0.7: the bracket shrinks onto the jump, the residual stays large.
        let root = find(|x| if x < 0.7 { 0.2 } else { -1.0 }, 0.0, 4.0);
        assert!(root.bracket.lo < 0.7 && root.bracket.hi >= 0.7 && root.bracket.hi - root.bracket.lo < 1e-14);
        assert!(root.residual.abs() >= 0.2);
    }
}
