//! From a sweep's CSV to the data of its figure, so that `impact sweep --plot` and `impact merge --plot` draw
//! the same figure from the same table.
//!
//! y is `restitution_velocity_ratio` (the effective e). x is the first varied key, read as follows:
//! - `contact.restitution`: "nominal e", with the ideal diagonal e_eff = e_nominal;
//! - `contact.damping`: "damping" with the laws' symbol and units (e.g. "damping α (s/m)" for the hysteresis
//!   family, from the law table);
//! - a component of a body's velocity: the report's `approach_speed`, not the component itself;
//! - anything else: the key, as written, with its unit.
//!
//! On a linear axis, lengths, pressures and speeds are scaled to an SI prefix that suits them (mm, GPa, ...).
//!
//! One curve per law, and per combination of the other varied keys' values (labelled `law, key = value`), in the
//! order the rows first meet them. A row without a value (an error, bodies that never separate) is a gap. The x
//! axis is logarithmic when every x is positive and they span a factor of 100 or more.

use super::SweepError;
use super::key::SceneKey;
use super::table::split;
use crate::law::LawKind;
use crate::output::chart::prefix;
use crate::output::sweep_figure::{Curve, SweepFigure};
use crate::output::text::{TITLE_CHARS, cut};

/// The figure of the sweep whose CSV is `text` (the whole sweep or one shard).
pub fn from_csv(text: &str) -> Result<SweepFigure, SweepError> {
    let mut lines = text.lines().filter(|line| !line.starts_with('#'));
    let header: Vec<String> = split(lines.next().unwrap_or_default());
    let column = |name: &str| {
        header
            .iter()
            .position(|c| c == name)
            .ok_or_else(|| SweepError::Usage(format!("the CSV has no `{name}` column")))
    };
    let (law, y, speed) = (column("law")?, column("restitution_velocity_ratio")?, column("approach_speed")?);
    // Varied keys are the dotted columns, in --vary order.
    let keys: Vec<usize> = (0..header.len()).filter(|&i| header[i].contains('.')).collect();
    let Some(&first) = keys.first() else { return Err(SweepError::Usage("the CSV has no varied key column".into())) };
    let key = header[first].as_str();
    let velocity = SceneKey::parse(key).is_ok_and(|k| k.is_velocity());
    let x = if velocity { speed } else { first };

    let mut curves: Vec<(Vec<String>, Curve)> = Vec::new();
    for line in lines {
        let cells = split(line);
        let cell = |i: usize| cells.get(i).map_or("", String::as_str);
        let mut group = vec![cell(law).to_string()];
        group.extend(keys[1..].iter().map(|&k| cell(k).to_string()));
        let point = match (cell(x).parse::<f64>(), cell(y).parse::<f64>()) {
            (Ok(x), Ok(y)) if x.is_finite() && y.is_finite() => Some((x, y)),
            _ => None,
        };
        match curves.iter_mut().find(|(g, _)| *g == group) {
            Some((_, curve)) => curve.points.push(point),
            None => {
                let mut label = group[0].clone();
                for (&k, value) in keys[1..].iter().zip(&group[1..]) {
                    label += &format!(", {} = {value}", header[k]);
                }
                curves.push((group, Curve { label: cut(&label, TITLE_CHARS), points: vec![point] }));
            }
        }
    }
    let mut curves: Vec<Curve> = curves.into_iter().map(|(_, curve)| curve).collect();
    let xs: Vec<f64> = curves.iter().flat_map(|c| c.points.iter().flatten().map(|p| p.0)).collect();
    let (low, high) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let log_x = !xs.is_empty() && low > 0.0 && high / low >= 100.0;

    let (title, quantity, unit) = match key {
        "contact.restitution" => ("Effective against nominal restitution".to_string(), "nominal e".to_string(), ""),
        "contact.damping" => {
            let (quantity, unit) = damping_label(&curves);
            ("Effective restitution against damping".into(), quantity, unit)
        }
        _ if velocity => ("Effective restitution against approach speed".into(), "approach speed v0".into(), "m/s"),
        // A column name comes from a file that may be forged: cut, so that the figure renders at once.
        other => (
            format!("Effective restitution against {}", cut(other, TITLE_CHARS)),
            cut(other, TITLE_CHARS),
            unit_of(other),
        ),
    };
    // Scale a prefixable unit on a linear axis (a log axis shows powers of ten of the unit itself).
    let (factor, unit) = match unit {
        "m" | "Pa" | "m/s" if !log_x && high.is_finite() => {
            let (factor, prefix) = prefix(low.abs().max(high.abs()));
            (factor, format!("{prefix}{unit}"))
        }
        _ => (1.0, unit.to_string()),
    };
    if factor != 1.0 {
        for point in curves.iter_mut().flat_map(|c| c.points.iter_mut().flatten()) {
            point.0 /= factor;
        }
    }
    let x_label = if unit.is_empty() { quantity } else { format!("{quantity} ({unit})") };
    Ok(SweepFigure {
        title,
        x_label,
        y_label: "effective e (separation / approach speed)".into(),
        diagonal: key == "contact.restitution",
        log_x,
        curves,
    })
}

/// The unit of a varied scene key's number (empty for a pure number).
fn unit_of(key: &str) -> &'static str {
    let field = key.split('.').rfind(|part| !part.bytes().all(|b| b.is_ascii_digit())).unwrap_or_default();
    match field {
        "radius" | "position" => "m",
        "mass" => "kg",
        "density" => "kg/m³",
        "young" => "Pa",
        "velocity" => "m/s",
        "angular_velocity" => "rad/s",
        "stiffness" => "N/m^n",
        _ => "",
    }
}

/// The damping axis's quantity and unit, from the law table: the symbol and units the laws with a value share
/// (`alpha in s/m` gives `damping α` and `s/m`), or a plain "damping (each law's own units)" if they differ.
fn damping_label(curves: &[Curve]) -> (String, &'static str) {
    let mut units: Vec<&'static str> = curves
        .iter()
        .filter(|curve| curve.points.iter().any(Option::is_some))
        .filter_map(|curve| LawKind::from_name(curve.label.split(',').next().unwrap_or_default()))
        .map(|law| law.info().damping_units)
        .collect();
    units.sort_unstable();
    units.dedup();
    let [written] = units.as_slice() else { return ("damping".into(), "each law's own units") };
    let (symbol, unit) = match written.split_once(" in ") {
        Some((symbol, unit)) => (symbol, unit),
        None => (written.split(',').next().unwrap_or_default(), ""),
    };
    let symbol = if symbol == "alpha" { "α" } else { symbol };
    let quantity = if symbol.is_empty() || symbol == "-" { "damping".into() } else { format!("damping {symbol}") };
    (quantity, unit)
}
