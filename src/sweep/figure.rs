//! From a sweep's CSV to the data of its figure, so that `impact sweep --plot` and `impact merge --plot` draw
//! the same figure from the same table.
//!
//! y is `restitution_velocity_ratio` (the effective e). x is the first varied key, read as follows:
//! - `contact.restitution`: "nominal e", with the ideal diagonal e_eff = e_nominal;
//! - `contact.damping`: "damping (law units)";
//! - a component of a body's velocity: the report's `approach_speed`, not the component itself;
//! - anything else: the key, as written.
//!
//! One curve per law, and per combination of the other varied keys' values (labelled `law, key = value`), in the
//! order the rows first meet them. A row without a value (an error, bodies that never separate) is a gap. The x
//! axis is logarithmic when every x is positive and they span a factor of 100 or more.

use super::SweepError;
use super::key::SceneKey;
use super::table::split;
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
    let curves: Vec<Curve> = curves.into_iter().map(|(_, curve)| curve).collect();
    let xs: Vec<f64> = curves.iter().flat_map(|c| c.points.iter().flatten().map(|p| p.0)).collect();
    let (low, high) = xs.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| (a.min(x), b.max(x)));
    let log_x = !xs.is_empty() && low > 0.0 && high / low >= 100.0;

    let (title, x_label) = match key {
        "contact.restitution" => ("Effective against nominal restitution".to_string(), "nominal e".to_string()),
        "contact.damping" => ("Effective restitution against damping".into(), "damping (law units)".into()),
        _ if velocity => ("Effective restitution against approach speed".into(), "approach speed (m/s)".into()),
        // A column name comes from a file that may be forged: cut, so that the figure renders at once.
        other => (format!("Effective restitution against {}", cut(other, TITLE_CHARS)), cut(other, TITLE_CHARS)),
    };
    Ok(SweepFigure {
        title,
        x_label,
        y_label: "effective e (separation / approach speed)".into(),
        diagonal: key == "contact.restitution",
        log_x,
        curves,
    })
}
