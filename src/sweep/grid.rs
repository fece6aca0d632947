//! The grid of a sweep: each varied key with its values, and the points in lexicographic order (the first
//! `--vary` slowest, the last fastest).

use super::SweepError;
use super::key::SceneKey;

/// How a range `START:STOP:COUNT` is filled.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Spacing {
    /// Evenly spaced values.
    Linear,
    /// Evenly spaced logarithms (a constant ratio); START and STOP must be non-zero and of the same sign.
    Geometric,
}

/// One varied key and its values, in sweep order.
#[derive(Debug, Clone, PartialEq)]
pub struct Axis {
    pub key: SceneKey,
    pub values: Vec<f64>,
}

fn usage(message: String) -> SweepError {
    SweepError::Usage(message)
}

/// A finite number, or a usage error naming what it is.
fn number(text: &str, what: &str, spec: &str) -> Result<f64, SweepError> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(usage(format!("--vary {spec}: {what} `{text}` is not a finite number"))),
    }
}

impl Axis {
    /// Parses one `--vary`: `KEY=START:STOP:COUNT`, optionally followed by `:log` or `:lin` to choose the spacing
    /// of this range (otherwise `default` applies: geometric under `--log`), or `KEY=V1,V2,...`, an explicit list
    /// (taken as written, in that order). Every value must be finite.
    pub fn parse(spec: &str, default: Spacing) -> Result<Axis, SweepError> {
        let Some((key, range)) = spec.split_once('=') else {
            return Err(usage(format!(
                "--vary `{spec}`: expected KEY=START:STOP:COUNT (e.g. contact.restitution=0.1:0.9:9) or KEY=V1,V2,..."
            )));
        };
        let key = SceneKey::parse(key.trim())?;
        let values = if range.contains(':') { parse_range(spec, range, default)? } else { parse_list(spec, range)? };
        Ok(Axis { key, values })
    }
}

fn parse_list(spec: &str, list: &str) -> Result<Vec<f64>, SweepError> {
    let values = list.split(',').map(|item| number(item, "value", spec)).collect::<Result<Vec<_>, _>>()?;
    for (i, a) in values.iter().enumerate() {
        if values[..i].contains(a) {
            return Err(usage(format!("--vary {spec}: the value {a} is listed twice")));
        }
    }
    Ok(values)
}

fn parse_range(spec: &str, range: &str, default: Spacing) -> Result<Vec<f64>, SweepError> {
    let parts: Vec<&str> = range.split(':').collect();
    let (bounds, spacing) = match parts.as_slice() {
        [start, stop, count] => ([*start, *stop, *count], default),
        [start, stop, count, "log"] => ([*start, *stop, *count], Spacing::Geometric),
        [start, stop, count, "lin"] => ([*start, *stop, *count], Spacing::Linear),
        [_, _, _, other] => {
            return Err(usage(format!("--vary {spec}: the spacing `{other}` is not `log` or `lin`")));
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
        _ => return Err(usage(format!("--vary {spec}: COUNT `{}` is not a whole number >= 1", bounds[2]))),
    };
    if count == 1 && start != stop {
        return Err(usage(format!(
            "--vary {spec}: COUNT = 1 takes one value, but START and STOP differ; give KEY=VALUE for a single value"
        )));
    }
    if count > 1 && start == stop {
        return Err(usage(format!(
            "--vary {spec}: START and STOP are equal, so the {count} values would all be {start}"
        )));
    }
    match spacing {
        Spacing::Linear => Ok(linear(start, stop, count)),
        Spacing::Geometric => {
            if start == 0.0 || stop == 0.0 || (start < 0.0) != (stop < 0.0) {
                return Err(usage(format!(
                    "--vary {spec}: geometric spacing (--log or :log) needs START and STOP non-zero and of the same sign"
                )));
            }
            Ok(geometric(start, stop, count))
        }
    }
}

/// Rounds to 15 significant digits, so that a grid lands on the decimals a user expects (0.1:0.9:5 gives 0.3, not
/// 0.30000000000000004) and is the same on every machine.
fn tidy(x: f64) -> f64 {
    format!("{x:.14e}").parse().unwrap_or(x)
}

/// `count` evenly spaced values from `start` to `stop`, both included exactly (interior values [`tidy`]).
pub fn linear(start: f64, stop: f64, count: usize) -> Vec<f64> {
    fill(start, stop, count, |t| start + (stop - start) * t)
}

/// `count` values with a constant ratio from `start` to `stop` (same sign, non-zero), ends exact.
pub fn geometric(start: f64, stop: f64, count: usize) -> Vec<f64> {
    let (from, to) = (start.abs().ln(), stop.abs().ln());
    fill(start, stop, count, |t| start.signum() * (from + (to - from) * t).exp())
}

fn fill(start: f64, stop: f64, count: usize, at: impl Fn(f64) -> f64) -> Vec<f64> {
    (0..count)
        .map(|i| match i {
            0 => start,
            _ if i + 1 == count => stop,
            _ => tidy(at(i as f64 / (count - 1) as f64)),
        })
        .collect()
}

/// The product of the axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    pub axes: Vec<Axis>,
}

impl Grid {
    /// Checks that no key is varied twice and that no two varied keys exclude each other.
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
        Ok(Grid { axes })
    }

    /// Number of points, or `None` if it does not fit in a `usize`.
    pub fn points(&self) -> Option<usize> {
        self.axes.iter().try_fold(1usize, |n, axis| n.checked_mul(axis.values.len()))
    }

    /// The values at point `point` (lexicographic order: the first axis slowest).
    pub fn values(&self, mut point: usize) -> Vec<f64> {
        let mut values = vec![0.0; self.axes.len()];
        for (slot, axis) in values.iter_mut().zip(&self.axes).rev() {
            let count = axis.values.len();
            *slot = axis.values[point % count];
            point /= count;
        }
        values
    }
}
