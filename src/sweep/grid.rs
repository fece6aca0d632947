//! The grid of a sweep: each varied key with its values, and the points in lexicographic order (the first
//! `--vary` slowest, the last fastest).

use super::SweepError;
use super::key::SceneKey;
use crate::text::{MESSAGE_CHARS, cut};

/// How a range `START:STOP:COUNT` is filled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spacing {
    /// Evenly spaced values.
    Linear,
    /// Evenly spaced logarithms (a constant ratio); START and STOP must be non-zero and of the same sign.
    Geometric,
}

/// One varied key and its values, in sweep order. A range's values are computed when asked for, so an axis takes
/// the same memory whatever its count.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub key: SceneKey,
    /// The `--vary` argument (cut to a readable length), for messages.
    spec: String,
    values: Values,
}

#[derive(Debug, Clone, PartialEq)]
enum Values {
    /// `KEY=V1,V2,...`: as written, in that order.
    List(Vec<f64>),
    /// `KEY=START:STOP:COUNT`: both ends exact, the values between [`tidy`].
    Range { start: f64, stop: f64, count: usize, spacing: Spacing },
}

fn usage(message: String) -> SweepError {
    SweepError::Usage(message)
}

/// A finite number, or a usage error naming what it is.
fn number(text: &str, what: &str, spec: &str) -> Result<f64, SweepError> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(usage(format!("--vary {spec}: {what} `{}` is not a finite number", cut(text, MESSAGE_CHARS)))),
    }
}

impl Axis {
    /// Parses one `--vary`: `KEY=START:STOP:COUNT`, optionally followed by `:log` or `:lin` to choose the spacing
    /// of this range (otherwise `default` applies: geometric under `--log`), or `KEY=V1,V2,...`, an explicit list
    /// (taken as written, in that order). The values of a range are checked by [`Grid::new`], once the size of the
    /// whole grid is known to be sane.
    pub fn parse(spec: &str, default: Spacing) -> Result<Axis, SweepError> {
        let shown = cut(spec, MESSAGE_CHARS);
        let Some((key, range)) = spec.split_once('=') else {
            return Err(usage(format!(
                "--vary `{shown}`: expected KEY=START:STOP:COUNT (e.g. contact.restitution=0.1:0.9:9) or KEY=V1,V2,..."
            )));
        };
        // Scene keys are short; a long one is echoed cut rather than in full.
        if key.trim().chars().count() > MESSAGE_CHARS {
            return Err(usage(format!("--vary {shown}: `{}` is not a scene key", cut(key.trim(), MESSAGE_CHARS))));
        }
        let key = SceneKey::parse(key.trim())?;
        let values = if range.contains(':') {
            parse_range(&shown, range, default)?
        } else {
            Values::List(parse_list(&shown, range)?)
        };
        Ok(Axis { key, spec: shown, values })
    }

    /// Number of values.
    pub fn count(&self) -> usize {
        match &self.values {
            Values::List(values) => values.len(),
            Values::Range { count, .. } => *count,
        }
    }

    /// Value `i` (0-based, `i < count`).
    pub fn value(&self, i: usize) -> f64 {
        match &self.values {
            Values::List(values) => values[i],
            Values::Range { start, stop, count, spacing } => range_value(*start, *stop, *count, *spacing, i),
        }
    }

    /// The values in order.
    pub fn values(&self) -> impl Iterator<Item = f64> + '_ {
        (0..self.count()).map(|i| self.value(i))
    }

    /// Checks that a range's values are finite and distinct once rounded (`-1e308:1e308:3` would reach inf on the
    /// way, `0.1:0.10000000000000002:4` repeat 0.1). A list was checked as it was read.
    fn check_values(&self) -> Result<(), SweepError> {
        let Values::Range { start, stop, count, spacing } = self.values else { return Ok(()) };
        if well_spaced(start, stop, count, spacing) {
            return Ok(());
        }
        // Near the ends of double precision or with values a few ulps apart: look at each value (a range is
        // monotonic, so equal values are neighbours).
        let mut previous: Option<f64> = None;
        for i in 0..count {
            let x = self.value(i);
            if !x.is_finite() {
                return Err(usage(format!(
                    "--vary {}: value {} of the range is {}: keep START and STOP within double precision",
                    self.spec,
                    i + 1,
                    crate::units::short(x)
                )));
            }
            if previous == Some(x) {
                return Err(usage(format!(
                    "--vary {}: values {} and {} of the range are both {} at 15 significant digits: widen the \
                     range or give fewer values",
                    self.spec,
                    i,
                    i + 1,
                    crate::units::short_exact(x)
                )));
            }
            previous = Some(x);
        }
        Ok(())
    }
}

/// Most values a world sweep's `--vary` may take (its values are kept in memory; a world row can take seconds).
pub const MAX_WORLD_VALUES: usize = 1_000_000;

/// Parses a world sweep's `--vary` (docs/world.md#sweeps): the dotted key as written (any number of the scene, which
/// the sweep checks against the scene itself) and its values, in order, finite and distinct.
pub fn parse_world(spec: &str, default: Spacing) -> Result<(String, Vec<f64>), SweepError> {
    let shown = cut(spec, MESSAGE_CHARS);
    let Some((key, range)) = spec.split_once('=') else {
        return Err(usage(format!(
            "--vary `{shown}`: expected KEY=START:STOP:COUNT (e.g. bodies.2.position.0=0.04:0.041:11) or KEY=V1,V2,..."
        )));
    };
    let key = key.trim();
    if key.is_empty() || key.chars().count() > MESSAGE_CHARS {
        return Err(usage(format!("--vary {shown}: `{}` is not a scene key", cut(key, MESSAGE_CHARS))));
    }
    let values = if range.contains(':') {
        parse_range(&shown, range, default)?
    } else {
        Values::List(parse_list(&shown, range)?)
    };
    let count = match &values {
        Values::List(list) => list.len(),
        Values::Range { count, .. } => *count,
    };
    if count > MAX_WORLD_VALUES {
        return Err(usage(format!("--vary {shown}: a world sweep takes at most {MAX_WORLD_VALUES} values a key")));
    }
    let axis = Axis { key: SceneKey::parse("solver.rtol")?, spec: shown, values };
    axis.check_values()?;
    Ok((key.to_string(), axis.values().collect()))
}

fn parse_list(spec: &str, list: &str) -> Result<Vec<f64>, SweepError> {
    let values = list.split(',').map(|item| number(item, "value", spec)).collect::<Result<Vec<_>, _>>()?;
    // Sorted, so that a list as long as a command line allows is checked at once.
    let mut sorted = values.clone();
    sorted.sort_by(f64::total_cmp);
    if let Some(pair) = sorted.windows(2).find(|pair| pair[0] == pair[1]) {
        return Err(usage(format!("--vary {spec}: the value {} is listed twice", crate::units::short_exact(pair[0]))));
    }
    Ok(values)
}

fn parse_range(spec: &str, range: &str, default: Spacing) -> Result<Values, SweepError> {
    let parts: Vec<&str> = range.split(':').collect();
    let (bounds, spacing) = match parts.as_slice() {
        [start, stop, count] => ([*start, *stop, *count], default),
        [start, stop, count, "log"] => ([*start, *stop, *count], Spacing::Geometric),
        [start, stop, count, "lin"] => ([*start, *stop, *count], Spacing::Linear),
        [_, _, _, other] => {
            return Err(usage(format!(
                "--vary {spec}: the spacing `{}` is not `log` or `lin`",
                cut(other, MESSAGE_CHARS)
            )));
        }
        _ => {
            return Err(usage(format!(
                "--vary {spec}: expected START:STOP:COUNT, optionally followed by :log or :lin"
            )));
        }
    };
    let start = number(bounds[0], "START", spec)?;
    let stop = number(bounds[1], "STOP", spec)?;
    let count = match bounds[2].trim().parse::<usize>() {
        Ok(count) if (1..=super::MAX_ROWS).contains(&count) => count,
        Ok(count) if count > super::MAX_ROWS => {
            return Err(usage(format!(
                "--vary {spec}: COUNT {count} is more than a sweep may have ({})",
                super::MAX_ROWS
            )));
        }
        _ => {
            return Err(usage(format!(
                "--vary {spec}: COUNT `{}` is not a whole number >= 1",
                cut(bounds[2], MESSAGE_CHARS)
            )));
        }
    };
    if count == 1 && start != stop {
        return Err(usage(format!(
            "--vary {spec}: COUNT = 1 takes one value, but START and STOP differ; give KEY=VALUE for a single value"
        )));
    }
    if count > 1 && start == stop {
        return Err(usage(format!(
            "--vary {spec}: START and STOP are equal, so the {count} values would all be {}",
            crate::units::short_exact(start)
        )));
    }
    if spacing == Spacing::Geometric && (start == 0.0 || stop == 0.0 || (start < 0.0) != (stop < 0.0)) {
        return Err(usage(format!(
            "--vary {spec}: geometric spacing (--log or :log) needs START and STOP non-zero and of the same sign"
        )));
    }
    Ok(Values::Range { start, stop, count, spacing })
}

/// Rounds to 15 significant digits, so that a grid lands on the decimals a user expects (0.1:0.9:5 gives 0.3, not
/// 0.30000000000000004) and is the same on every machine.
///
/// This is [`tidy_exactly`] (the correctly rounded 15-digit decimal, read back), found the quick way for all but a
/// few values, since a million-point sweep computes a million of them: by scaling ([`tidy_by_scaling`]) where the
/// scale is an exact power of ten and the processor has a fused multiply-add, else from the shortest digits, as
/// follows. Let `S` be the shortest decimal that reads back as `x` (zmij's, as ryu's: of the shortest, the nearest `x`) and `u`
/// the unit of `x`'s 15th significant digit. The decimals of `S`'s length that read back as `x` include `S`'s
/// neighbours only if they are as near, so `x` lies within half a step of that length from `S`: within `0.05 u`
/// when `S` has 16 digits, `0.005 u` when it has 17. So:
/// * `S` of at most 15 digits: the 15-digit decimal nearest `x` is no farther from `x` than `S`, so it too reads
///   back as `x`: `x` is returned;
/// * `S` of 16 or 17 digits rounds to 15 as `x` does unless the digits cut off are a half (`0.50 u`, `0.5 u`);
///   those within `0.05 u` of a half take the exact route (a tenfold margin for 17 digits).
///
/// (Checked bit for bit against the exact route in the tests, subnormals and powers of ten included.)
fn tidy(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return tidy_exactly(x);
    }
    // (The scaling needs a fused multiply-add: where the processor has none, the library's software one costs more
    // than the shortest digits.)
    if crate::fast::HARDWARE_FMA
        && let Some(value) = tidy_by_scaling(x)
    {
        return value;
    }
    let (digits, count, exponent) = super::table::shortest_digits(x);
    if count <= 15 {
        return x;
    }
    let value = |range: &[u8]| range.iter().fold(0u64, |v, &d| v * 10 + u64::from(d - b'0'));
    // The cut-off digits as hundredths of u.
    let cut = value(&digits[15..count]) * if count == 16 { 10 } else { 1 };
    if (45..=55).contains(&cut) {
        return tidy_exactly(x);
    }
    let kept = value(&digits[..15]) + u64::from(cut > 50);
    // kept × 10^(exponent - 14), read back (a carry to 10^15 reads as well; powers beyond 10^±22 from text).
    if let Some(magnitude) = times_power_of_ten(kept as f64, exponent - 14) {
        return magnitude.copysign(x);
    }
    let mut text = super::table::ShortText::default();
    if x < 0.0 {
        text.push(b"-");
    }
    let mut integer = itoa::Buffer::new();
    text.push(integer.format(kept).as_bytes());
    text.push(b"e");
    text.push(integer.format(exponent - 14).as_bytes());
    text.as_str().parse().unwrap_or_else(|_| tidy_exactly(x))
}

/// [`tidy`] for the values whose 15-digit scale `10^k` is an exact double (`|k| <= 22`: magnitudes from about
/// `1e-8` to `1e36`, every grid a user writes), without the shortest digits: the product `|x| 10^k` (or quotient)
/// with its exact remainder from a fused multiply-add gives `x`'s fraction of a 15th-digit unit to far better than
/// `1e-3`; rounded to the nearest integer `n`, `n / 10^k` (or `n 10^-k`) is correctly rounded, both factors being
/// exact ([`times_power_of_ten`]) — what reading the 15-digit decimal gives. `None` when it cannot decide: the scale
/// estimated from `log10` was off by one, or the fraction is within `1e-3` of a half.
fn tidy_by_scaling(x: f64) -> Option<f64> {
    let magnitude = x.abs();
    let k = 14 - magnitude.log10().floor() as i32;
    let scale = *EXACT_POWERS_OF_TEN.get(k.unsigned_abs() as usize)?;
    // |x| 10^k = scaled + rest exactly (rest only approximately, for k < 0: enough to decide the rounding). The
    // remainders need a true fused multiply-add (f64::mul_add is one on every target, in software if need be).
    let (scaled, rest) = if k >= 0 {
        let scaled = magnitude * scale;
        (scaled, magnitude.mul_add(scale, -scaled))
    } else {
        let scaled = magnitude / scale;
        (scaled, (-scaled).mul_add(scale, magnitude) / scale)
    };
    if !(1e14..1e15).contains(&scaled) {
        return None;
    }
    let whole = scaled.floor();
    let fraction = (scaled - whole) + rest;
    if (fraction - 0.5).abs() < 1e-3 {
        return None;
    }
    let n = if fraction > 0.5 { whole + 1.0 } else { whole };
    Some(times_power_of_ten(n, -k)?.copysign(x))
}

/// `n 10^power` correctly rounded, for an integer `n < 2^53` and `|power| <= 22`: both factors are exact doubles,
/// so one product or quotient gives what reading the decimal gives (Clinger's fast path). `None` beyond `10^±22`.
fn times_power_of_ten(n: f64, power: i32) -> Option<f64> {
    let scale = *EXACT_POWERS_OF_TEN.get(power.unsigned_abs() as usize)?;
    Some(if power >= 0 { n * scale } else { n / scale })
}

/// `10^k` for `k = 0..=22`: every one an exact double (`5^22 < 2^53`).
const EXACT_POWERS_OF_TEN: [f64; 23] = [
    1e0, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9, 1e10, 1e11, 1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20,
    1e21, 1e22,
];

/// `x` correctly rounded to 15 significant digits and read back: the definition [`tidy`] follows.
fn tidy_exactly(x: f64) -> f64 {
    format!("{x:.14e}").parse().unwrap_or(x)
}

/// Value `i` of `count` from `start` to `stop`: both ends exact, the values between evenly spaced (or with a
/// constant ratio) and [`tidy`].
fn range_value(start: f64, stop: f64, count: usize, spacing: Spacing, i: usize) -> f64 {
    if i == 0 {
        return start;
    }
    if i + 1 == count {
        return stop;
    }
    let t = i as f64 / (count - 1) as f64;
    tidy(match spacing {
        Spacing::Linear => {
            let span = stop - start;
            // start + span t is what the sweeps have always used; when the span overflows (-1e308:1e308), the
            // weighted mean stays finite.
            if span.is_finite() { start + span * t } else { start * (1.0 - t) + stop * t }
        }
        Spacing::Geometric => {
            let (from, to) = (start.abs().ln(), stop.abs().ln());
            start.signum() * (from + (to - from) * t).exp()
        }
    })
}

/// Whether a range's values are surely finite and distinct without computing them: its ends are far from the
/// largest double, so no value rounds to inf, and neighbours differ by more than 1e-12 relative, far more than the
/// 5e-15 by which [`tidy`] moves a value.
fn well_spaced(start: f64, stop: f64, count: usize, spacing: Spacing) -> bool {
    let magnitude = start.abs().max(stop.abs());
    let steps = count.saturating_sub(1).max(1) as f64;
    let relative_step = match spacing {
        Spacing::Linear => (stop - start).abs() / steps / magnitude,
        Spacing::Geometric => ((stop.abs().ln() - start.abs().ln()) / steps).abs(),
    };
    magnitude < 1e300 && relative_step > 1e-12
}

/// The product of the axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub axes: Vec<Axis>,
}

impl Grid {
    /// Checks that no key is varied twice, that no two varied keys exclude each other, that the grid has at most
    /// [`super::MAX_ROWS`] points (before any value is computed), and that every value is finite and distinct.
    pub fn new(axes: Vec<Axis>) -> Result<Grid, SweepError> {
        for (i, a) in axes.iter().enumerate() {
            if let Some(b) = axes[..i].iter().find(|b| b.key.conflicts_with(&a.key)) {
                return Err(usage(if a.key == b.key {
                    format!("--vary {}: the key is varied twice", a.key)
                } else {
                    format!("--vary {} and --vary {}: a scene gives one or the other, not both", b.key, a.key)
                }));
            }
        }
        let grid = Grid { axes };
        if grid.points().is_none_or(|points| points > super::MAX_ROWS) {
            return Err(usage(format!(
                "the grid has more than {} points: split the sweep into several",
                super::MAX_ROWS
            )));
        }
        for axis in &grid.axes {
            axis.check_values()?;
        }
        Ok(grid)
    }

    /// Number of points, or `None` if it does not fit in a `usize`.
    pub fn points(&self) -> Option<usize> {
        self.axes.iter().try_fold(1usize, |n, axis| n.checked_mul(axis.count()))
    }

    /// The values at point `point` (lexicographic order: the first axis slowest).
    pub fn values(&self, point: usize) -> Vec<f64> {
        let mut values = Vec::with_capacity(self.axes.len());
        self.values_into(point, &mut values);
        values
    }

    /// [`Grid::values`] into `values` (a sweep worker's, kept from row to row).
    pub fn values_into(&self, mut point: usize, values: &mut Vec<f64>) {
        values.clear();
        values.resize(self.axes.len(), 0.0);
        for (slot, axis) in values.iter_mut().zip(&self.axes).rev() {
            let count = axis.count();
            *slot = axis.value(point % count);
            point /= count;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The quick route of `tidy` gives what its definition, `tidy_exactly`, gives, bit for bit: on grid values of
    /// both spacings, on random bit patterns (every exponent, subnormals), on random short decimals, and on values a
    /// few ulps either side of the 15-digit half-way points, where the quick route must hand over.
    #[test]
    fn tidy_is_the_correctly_rounded_fifteen_digit_decimal() {
        let mut state = 0x2545_f491_4f6c_dd1d_u64;
        let mut next = move || {
            state ^= state << 13;
            state ^= state >> 7;
            state ^= state << 17;
            state
        };
        let mut values = vec![0.0, -0.0, 1.0, 0.1, 0.3, 0.30000000000000004, f64::MAX, f64::MIN_POSITIVE, 5e-324];
        values.extend([f64::INFINITY, f64::NAN, 1f64.next_down(), 1e23f64.next_down(), 1e23f64.next_up(), -2.5e-300]);
        for (start, stop) in [(0.01, 2.0), (0.1, 0.9), (-3.0, 7.5), (1e-7, 3e-7)] {
            for i in 0..20_000 {
                let t = i as f64 / 19_999.0;
                values.push(start + (stop - start) * t);
                values.push(start.abs() * (stop.abs() / start.abs()).powf(t));
            }
        }
        // Powers of ten a few ulps either side (where the 15-digit rounding carries into a new decade), and
        // subnormals.
        for power in -323..=308 {
            let ten = format!("1e{power}").parse::<f64>().unwrap();
            for nudge in -3i64..=3 {
                values.push(f64::from_bits((ten.to_bits() as i64 + nudge) as u64));
            }
        }
        for _ in 0..20_000 {
            values.push(f64::from_bits(next() % (1 << 52)));
        }
        for _ in 0..200_000 {
            let bits = next();
            values.push(f64::from_bits(bits));
            // A 15-digit decimal plus a half unit of its last digit, nudged by a few ulps: the ties' neighbourhood.
            let mantissa = 1e14 + (next() % 900_000_000_000_000) as f64;
            let power = (next() % 60) as i32 - 30;
            let half_way = (mantissa + 0.5) * 10f64.powi(power);
            let nudge = (next() % 9) as i64 - 4;
            values.push(f64::from_bits((half_way.to_bits() as i64 + nudge) as u64));
            values.push(((next() % 100_000_000) as f64) * 10f64.powi(power));
        }
        let mut quick = 0;
        for x in values {
            let (got, want) = (tidy(x), tidy_exactly(x));
            assert!(got.to_bits() == want.to_bits() || (got.is_nan() && want.is_nan()), "{x:e}: {got:e} vs {want:e}");
            quick += usize::from(x.is_finite() && x != 0.0 && super::super::table::shortest_digits(x).1 > 15);
        }
        // Most of the values above have 16 or 17 digits: the test reaches the rounding branch.
        assert!(quick > 200_000, "{quick}");
    }

    #[test]
    fn a_range_keeps_its_ends_and_tidies_the_values_between() {
        let axis = Axis::parse("contact.restitution=0.1:0.9:5", Spacing::Linear).expect("a range");
        assert_eq!(axis.values().collect::<Vec<_>>(), [0.1, 0.3, 0.5, 0.7, 0.9]);
        let axis = Axis::parse("contact.damping=1:100:3:log", Spacing::Linear).expect("a range");
        assert_eq!(axis.values().collect::<Vec<_>>(), [1.0, 10.0, 100.0]);
    }

    #[test]
    fn a_span_beyond_double_precision_is_split_between_the_ends() {
        // stop - start = 2e308 overflows; (1 - t) start + t stop does not.
        assert_eq!(range_value(-1e308, 1e308, 5, Spacing::Linear, 2), 0.0);
        assert_eq!(range_value(-1e308, 1e308, 5, Spacing::Linear, 1), -5e307);
    }

    #[test]
    fn only_crowded_or_extreme_ranges_are_checked_value_by_value() {
        assert!(well_spaced(0.01, 1.0, 100_000_000, Spacing::Linear));
        assert!(well_spaced(1e-3, 1e3, 1000, Spacing::Geometric));
        assert!(!well_spaced(0.1, 0.10000000000000002, 4, Spacing::Linear));
        assert!(!well_spaced(-1e308, 1e308, 3, Spacing::Linear));
    }

    #[test]
    fn the_size_of_a_grid_is_checked_before_its_values() {
        let huge = |key: &str| Axis::parse(&format!("{key}=0:1:100000000"), Spacing::Linear).expect("an axis");
        let error = Grid::new(vec![huge("contact.restitution"), huge("bodies.0.velocity.0")]).expect_err("too big");
        assert!(error.to_string().contains("more than 100000000 points"), "{error}");
    }
}
