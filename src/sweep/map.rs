//! From a sweep's CSV to its idealisation map (`impact sweep --map`, docs/idealisation.md#the-idealisation-map): the
//! grid of the two varied keys, each cell the first assumption that fails there (the `first_failure` column; where
//! none fails, the first marginal one), and the line where each assumption's ratio reaches its failing threshold.
//!
//! x is the first varied key — for a component of a body's velocity, the report's `approach_speed` (when it is one
//! number per value of the key and grows or falls with it) — and y the second, each on a logarithmic axis when its
//! values are evenly spaced in ratio rather than in difference. Lengths, pressures and speeds are scaled to an SI
//! prefix that suits them (mm, GPa, ...).
//!
//! One more line is not an assumption's: where a bouncing ball's contact lasts a tenth of its flight to the next
//! bounce under standard gravity, t_c / (2 e v0 / g) = 0.1 (the world's `instantaneous`), from the `duration`,
//! `restitution_velocity_ratio` and `approach_speed` columns.

use super::SweepError;
use super::figure::unit_of;
use super::key::SceneKey;
use super::table::{VERDICT_COLUMNS, split};
use crate::idealisation::{SEVERITY, STANDARD_GRAVITY, limits};
use crate::output::chart::prefix;
use crate::output::map_figure::{Boundary, IdealisationMap, Verdict};
use crate::text::{TITLE_CHARS, cut};

/// The result columns the map reads, which `--map` adds to a sweep's columns: the approach speed, the first failure
/// and the first marginal assumption, each assumption's ratio and verdict, then the contact's duration and e (for
/// the flight line, [`FLIGHT_COLUMNS`]).
pub fn columns() -> Vec<&'static str> {
    let mut names = vec!["approach_speed"];
    names.extend(VERDICT_COLUMNS);
    names.extend(&FLIGHT_COLUMNS[1..]);
    names
}

/// The columns the flight line reads: the approach speed v0, the contact time t_c and e (the velocity ratio). A CSV
/// without one of them (shards written with older `--columns`) has its map without the line.
pub const FLIGHT_COLUMNS: [&str; 3] = ["approach_speed", "duration", "restitution_velocity_ratio"];

/// The flight line's threshold: the contact lasts a tenth of the flight between bounces.
pub const FLIGHT_THRESHOLD: f64 = 0.1;

/// The contact time against the flight to the next bounce under standard gravity, t_c / (2 e v0 / g), computed as
/// g t_c / (2 e v0); infinite where there is no bounce (e ≤ 0: never divided by zero); NaN where a number is missing.
pub fn flight_ratio(duration: Option<f64>, e: Option<f64>, speed: Option<f64>) -> f64 {
    match (duration, e, speed) {
        (Some(_), Some(e), Some(_)) if e <= 0.0 => f64::INFINITY,
        (Some(t), Some(e), Some(v)) if v > 0.0 => STANDARD_GRAVITY * t / (2.0 * e * v),
        _ => f64::NAN,
    }
}

/// Whether a sweep over `keys` varied keys under `laws` laws can have a map: exactly two keys, at most one law.
pub fn check(keys: usize, laws: usize) -> Result<(), SweepError> {
    if keys != 2 {
        return Err(SweepError::Usage(format!(
            "--map: the idealisation map needs exactly two varied keys (give --vary twice: x, then y); this sweep has \
             {keys}"
        )));
    }
    if laws > 1 {
        return Err(SweepError::Usage("--map: the map shows one law; give at most one --law".into()));
    }
    Ok(())
}

/// The map of the sweep whose CSV is `text`.
pub fn from_csv(text: &str) -> Result<IdealisationMap, SweepError> {
    let mut lines = text.lines().filter(|line| !line.starts_with('#'));
    let header: Vec<String> = split(lines.next().unwrap_or_default());
    let column = |name: &str| {
        header
            .iter()
            .position(|c| c == name)
            .ok_or_else(|| SweepError::Usage(format!("--map: the CSV has no `{name}` column")))
    };
    let keys: Vec<usize> = (0..header.len()).filter(|&i| header[i].contains('.')).collect();
    check(keys.len(), 1)?;
    let (x_key, y_key) = (keys[0], keys[1]);
    let (law, failure, marginal) = (column("law")?, column("first_failure")?, column("first_marginal")?);
    let ratios: Vec<usize> = SEVERITY.iter().map(|key| column(&format!("{key}_ratio"))).collect::<Result<_, _>>()?;
    let speed = column("approach_speed").ok();
    let flight_columns: Option<Vec<usize>> = FLIGHT_COLUMNS.iter().map(|name| column(name).ok()).collect();
    let rows: Vec<Vec<String>> = lines.map(split).collect();
    let cell = |row: &[String], i: usize| row.get(i).map_or("", String::as_str).to_string();
    let number = |row: &[String], i: usize| cell(row, i).parse::<f64>().ok().filter(|v| v.is_finite());

    let mut laws: Vec<String> = rows.iter().map(|row| cell(row, law)).collect();
    laws.sort();
    laws.dedup();
    if laws.len() > 1 {
        return Err(SweepError::Usage(format!("--map: the map shows one law; the CSV has {}", laws.join(", "))));
    }
    let values = |k: usize| {
        let mut values: Vec<f64> = rows.iter().filter_map(|row| number(row, k)).collect();
        values.sort_by(f64::total_cmp);
        values.dedup();
        values
    };
    let (x_values, y_values) = (values(x_key), values(y_key));
    if x_values.is_empty() || y_values.is_empty() {
        return Err(SweepError::Usage("--map: the CSV has no rows".into()));
    }
    let at = |values: &[f64], v: f64| values.binary_search_by(|p| p.total_cmp(&v)).ok();

    // x: the approach speed for a velocity key, when it is a monotone function of the key.
    let velocity = SceneKey::parse(&header[x_key]).is_ok_and(|k| k.is_velocity());
    let speeds = speed.filter(|_| velocity).and_then(|s| approach_speeds(&rows, &x_values, x_key, s));
    let (x_shown, x_quantity, x_unit) = match &speeds {
        Some(speeds) => (speeds.clone(), "approach speed v0".to_string(), "m/s"),
        None => (x_values.clone(), quantity(&header[x_key]), unit_of(&header[x_key])),
    };
    // Columns in increasing order of what x shows (an approach speed may fall as the key grows).
    let mut order: Vec<usize> = (0..x_values.len()).collect();
    order.sort_by(|&a, &b| x_shown[a].total_cmp(&x_shown[b]));
    let column_of: Vec<usize> = {
        let mut column_of = vec![0; order.len()];
        for (position, &i) in order.iter().enumerate() {
            column_of[i] = position;
        }
        column_of
    };

    let (nx, ny) = (x_values.len(), y_values.len());
    let mut cells = vec![vec![Verdict::Unknown; nx]; ny];
    let mut ratio_of = vec![vec![vec![f64::NAN; nx]; ny]; SEVERITY.len()];
    let mut flight = flight_columns.as_ref().map(|_| vec![vec![f64::NAN; nx]; ny]);
    for row in &rows {
        let (Some(x), Some(y)) = (number(row, x_key), number(row, y_key)) else { continue };
        let (Some(i), Some(j)) = (at(&x_values, x), at(&y_values, y)) else { continue };
        let i = column_of[i];
        cells[j][i] = verdict_of(&cell(row, failure), &cell(row, marginal));
        for (a, &r) in ratios.iter().enumerate() {
            ratio_of[a][j][i] = number(row, r).map_or(f64::NAN, f64::abs);
        }
        if let (Some(levels), Some(c)) = (flight.as_mut(), flight_columns.as_deref()) {
            let ratio = flight_ratio(number(row, c[1]), number(row, c[2]), number(row, c[0]));
            // ln(inf / 0.1) = inf: beyond the line.
            levels[j][i] = (ratio / FLIGHT_THRESHOLD).ln();
        }
    }
    let boundaries = ratio_of.iter().enumerate().filter_map(|(a, ratios)| boundary(a, ratios)).collect();

    let xs: Vec<f64> = order.iter().map(|&i| x_shown[i]).collect();
    let (x_factor, x_label, log_x) = scaled(&xs, &x_quantity, x_unit);
    let (y_factor, y_label, log_y) = scaled(&y_values, &quantity(&header[y_key]), unit_of(&header[y_key]));
    let law = laws.first().map_or("", String::as_str);
    Ok(IdealisationMap {
        title: format!("The idealisation on trial: the first assumption to fail (law: {})", cut(law, TITLE_CHARS)),
        x_label,
        y_label,
        log_x,
        log_y,
        xs: xs.iter().map(|x| x / x_factor).collect(),
        ys: y_values.iter().map(|y| y / y_factor).collect(),
        cells,
        boundaries,
        flight,
    })
}

/// The line where assumption `a` starts to fail, if it crosses the grid of `ratios` (`ratios[j][i]`, sizes); else
/// the line where it starts to be marginal, if that one does (so that an assumption which fails only beyond the grid
/// still shows where it begins to weaken).
fn boundary(a: usize, ratios: &[Vec<f64>]) -> Option<Boundary> {
    let limits = limits(SEVERITY[a])?;
    [(true, limits.fails_from), (false, limits.holds_below)].into_iter().find_map(|(fails, threshold)| {
        let levels: Vec<Vec<f64>> =
            ratios.iter().map(|row| row.iter().map(|r| (r / threshold).ln()).collect()).collect();
        let finite = || levels.iter().flatten().filter(|v| v.is_finite());
        (finite().any(|&v| v >= 0.0) && finite().any(|&v| v < 0.0)).then_some(Boundary { assumption: a, fails, levels })
    })
}

/// A cell's verdict from its `first_failure` and `first_marginal` cells.
fn verdict_of(failure: &str, marginal: &str) -> Verdict {
    let index = |name: &str| SEVERITY.iter().position(|k| *k == name);
    match (index(failure), failure, index(marginal), marginal) {
        (Some(k), ..) => Verdict::Fails(k),
        (None, "none", Some(k), _) => Verdict::Marginal(k),
        (None, "none", None, "none") => Verdict::Holds,
        _ => Verdict::Unknown,
    }
}

/// The approach speed of each value of the x key, when the rows give one (to 1e-9) for each and they are distinct
/// (so that they order the columns).
fn approach_speeds(rows: &[Vec<String>], x_values: &[f64], x_key: usize, speed: usize) -> Option<Vec<f64>> {
    let mut speeds = vec![f64::NAN; x_values.len()];
    for row in rows {
        let number = |i: usize| row.get(i).and_then(|c| c.parse::<f64>().ok()).filter(|v| v.is_finite());
        let (Some(x), Some(v)) = (number(x_key), number(speed)) else { continue };
        let i = x_values.binary_search_by(|p| p.total_cmp(&x)).ok()?;
        if speeds[i].is_nan() {
            speeds[i] = v;
        } else if (speeds[i] - v).abs() > 1e-9 * v.abs() {
            return None;
        }
    }
    let mut sorted = speeds.clone();
    sorted.sort_by(f64::total_cmp);
    let distinct = sorted.windows(2).all(|w| w[1] > w[0]);
    (distinct && sorted.iter().all(|v| v.is_finite() && *v > 0.0)).then_some(speeds)
}

/// What a varied key's axis is called: "radius of body 1", "velocity of body 2 (x)", or the key itself.
fn quantity(key: &str) -> String {
    let parts: Vec<&str> = key.split('.').collect();
    match parts.as_slice() {
        ["bodies", index, field, rest @ ..] if index.parse::<usize>().is_ok() => {
            let body = index.parse::<usize>().unwrap_or_default() + 1;
            let component = match rest {
                [c] => format!(" ({})", ["x", "y", "z"].get(c.parse::<usize>().unwrap_or(3)).unwrap_or(c)),
                _ => String::new(),
            };
            format!("{} of body {body}{component}", field.replace('_', " "))
        }
        _ => cut(key, TITLE_CHARS),
    }
}

/// The factor the values are divided by, the axis label with the prefixed unit, and whether the axis is
/// logarithmic: positive values evenly spaced in ratio rather than in difference (two values: a factor of 10 or
/// more apart).
fn scaled(values: &[f64], quantity: &str, unit: &str) -> (f64, String, bool) {
    let positive = values.iter().all(|v| *v > 0.0);
    let spread = |steps: Vec<f64>| {
        let mean = steps.iter().sum::<f64>() / steps.len() as f64;
        steps.iter().map(|s| (s - mean).abs()).fold(0.0, f64::max) / mean.abs()
    };
    let log = positive
        && match values {
            [] | [_] => false,
            [a, b] => b / a >= 10.0,
            _ => {
                let ratios = values.windows(2).map(|w| (w[1] / w[0]).ln()).collect();
                let differences = values.windows(2).map(|w| w[1] - w[0]).collect();
                spread(ratios) < spread(differences)
            }
        };
    let high = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let (factor, unit) = match unit {
        // (On a log axis, powers of ten of the unit itself.)
        "m" | "Pa" | "m/s" if high > 0.0 && !log => {
            let (factor, prefix) = prefix(high);
            (factor, format!("{prefix}{unit}"))
        }
        _ => (1.0, unit.to_string()),
    };
    let label = if unit.is_empty() { quantity.to_string() } else { format!("{quantity} ({unit})") };
    (factor, label, log)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axes_are_named_by_body_and_scaled() {
        assert_eq!(quantity("bodies.0.radius"), "radius of body 1");
        assert_eq!(quantity("bodies.1.velocity.0"), "velocity of body 2 (x)");
        assert_eq!(quantity("contact.restitution"), "contact.restitution");
        let (factor, label, log) = scaled(&[0.001, 0.01, 0.1], "radius of body 1", "m");
        assert_eq!((factor, label.as_str(), log), (1.0, "radius of body 1 (m)", true));
        let (factor, label, log) = scaled(&[0.001, 0.002, 0.003], "radius of body 1", "m");
        assert_eq!((factor, label.as_str(), log), (1e-3, "radius of body 1 (mm)", false));
        let (_, _, log) = scaled(&[0.1, 0.2, 0.3, 0.4], "e", "");
        assert!(!log);
    }

    #[test]
    fn the_flight_ratio_is_infinite_without_a_bounce_and_unknown_without_a_number() {
        // g t_c / (2 e v0): t_c = 1e-4 s, e = 0.5, v0 = 1 m/s.
        let ratio = flight_ratio(Some(1e-4), Some(0.5), Some(1.0));
        assert!((ratio - 9.80665e-4).abs() < 1e-15, "{ratio}");
        assert_eq!(flight_ratio(Some(1e-4), Some(0.0), Some(1.0)), f64::INFINITY);
        assert!(flight_ratio(None, Some(0.5), Some(1.0)).is_nan());
        assert!(flight_ratio(Some(1e-4), Some(0.5), None).is_nan());
    }
}
