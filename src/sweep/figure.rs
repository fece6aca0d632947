//! From a sweep's CSV to the data of its figure, so that `impact sweep --plot` and `impact merge --plot` draw
//! the same figure from the same table ([`plot_from_csv`]): the effective-e figure ([`from_csv`]), or, for a sweep
//! over a body's angle of incidence, the oblique-impact figure ([`incidence_from_csv`]).
//!
//! The effective-e figure:
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
use crate::output::incidence_figure::{IncidenceFigure, IncidenceSeries, Threshold};
use crate::output::sweep_figure::{Curve, SweepFigure, SweepPlot};
use crate::text::{TITLE_CHARS, cut};

/// The figure of the sweep whose CSV is `text` (the whole sweep or one shard).
pub fn from_csv(text: &str) -> Result<SweepFigure, SweepError> {
    let mut lines = text.lines().filter(|line| !line.starts_with('#'));
    let header: Vec<String> = split(lines.next().unwrap_or_default());
    let column = |name: &str| find_column(&header, name);
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
pub(super) fn unit_of(key: &str) -> &'static str {
    let field = key.split('.').rfind(|part| !part.bytes().all(|b| b.is_ascii_digit())).unwrap_or_default();
    match field {
        "radius" | "position" => "m",
        "mass" => "kg",
        "density" => "kg/m³",
        "young" | "yield_stress" => "Pa",
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

/// The index of the column `name` of a sweep CSV's header, or the error that names it.
fn find_column(header: &[String], name: &str) -> Result<usize, SweepError> {
    header.iter().position(|c| c == name).ok_or_else(|| SweepError::Usage(format!("the CSV has no `{name}` column")))
}

/// The columns [`from_csv`] reads.
const RESTITUTION_COLUMNS: [&str; 3] = ["law", "restitution_velocity_ratio", "approach_speed"];
/// The columns [`incidence_from_csv`] reads.
const INCIDENCE_COLUMNS: [&str; 11] = [
    "law",
    "restitution_velocity_ratio",
    "incidence_from_normal_deg",
    "tangential_restitution_centre",
    "rigid_tangential_restitution_centre",
    "spin_after_1",
    "spin_after_2",
    "rigid_spin_after_1",
    "rigid_spin_after_2",
    "rebound_from_normal_deg",
    "rigid_rebound_from_normal_deg",
];

/// Whether a sweep whose CSV header line is `header` has the columns its figure ([`plot_from_csv`]) reads; the
/// error names the first missing one. (`impact sweep --plot --columns ...` checks before any row runs.)
pub fn check_columns(header: &str) -> Result<(), SweepError> {
    let header = split(header);
    let needed: &[&str] = if incidence_first(&header) { &INCIDENCE_COLUMNS } else { &RESTITUTION_COLUMNS };
    needed.iter().try_for_each(|name| find_column(&header, name).map(|_| ()))
}

/// Whether the first varied key of a sweep's header is a body's angle of incidence.
fn incidence_first(header: &[String]) -> bool {
    let first = header.iter().find(|c| c.contains('.'));
    first.is_some_and(|key| SceneKey::parse(key).is_ok_and(|k| k.is_incidence()))
}

/// What `impact sweep --plot` and `impact merge --plot` draw from a sweep's CSV: the oblique-impact figure when
/// the first varied key is a body's angle of incidence (`bodies.I.incidence_deg`), the effective-e figure
/// ([`from_csv`]) otherwise.
pub fn plot_from_csv(text: &str) -> Result<SweepPlot, SweepError> {
    let header = text.lines().find(|line| !line.starts_with('#')).map(split).unwrap_or_default();
    if incidence_first(&header) {
        incidence_from_csv(text).map(SweepPlot::Incidence)
    } else {
        from_csv(text).map(SweepPlot::Restitution)
    }
}

/// A rigid-body rebound angle at most this far from zero (degrees) is the rolling contact of a sticking impact; the
/// theory gives zero to rounding.
const ROLLING: f64 = 1e-9;

/// The oblique-impact figure of a sweep over the angle of incidence (the first varied key): against it, the
/// centre's tangential restitution, the rebound spin and the contact points' rebound angle, simulated and by
/// rigid-body theory, one series per law (and per combination of the other varied keys' values), with the rigid
/// sliding threshold located from the table (see [`rigid_threshold`]).
pub fn incidence_from_csv(text: &str) -> Result<IncidenceFigure, SweepError> {
    let mut lines = text.lines().filter(|line| !line.starts_with('#'));
    let header: Vec<String> = split(lines.next().unwrap_or_default());
    let column = |name: &str| find_column(&header, name);
    let law = column("law")?;
    let keys: Vec<usize> = (0..header.len()).filter(|&i| header[i].contains('.')).collect();
    let Some(&first) = keys.first() else { return Err(SweepError::Usage("the CSV has no varied key column".into())) };
    let rows: Vec<Vec<String>> = lines.map(split).collect();
    let number = |row: &[String], i: usize| row.get(i).and_then(|c| c.parse::<f64>().ok()).filter(|v| v.is_finite());
    // The spin of the body that turns: body 1's, unless only body 2's does (body 1 a wall).
    let spins = |name: &str| -> Result<bool, SweepError> {
        let i = column(name)?;
        Ok(rows.iter().any(|row| number(row, i).is_some_and(|v| v != 0.0)))
    };
    let spin_body = if !spins("spin_after_1")? && spins("spin_after_2")? { 2 } else { 1 };
    let spin = format!("spin_after_{spin_body}");
    let rigid_spin = format!("rigid_spin_after_{spin_body}");
    let panels = [
        (column("tangential_restitution_centre")?, column("rigid_tangential_restitution_centre")?),
        (column(&spin)?, column(&rigid_spin)?),
        (column("rebound_from_normal_deg")?, column("rigid_rebound_from_normal_deg")?),
    ];
    let (incidence, restitution) = (column("incidence_from_normal_deg")?, column("restitution_velocity_ratio")?);

    let mut groups: Vec<(Vec<String>, IncidenceSeries, Vec<RigidRow>)> = Vec::new();
    for row in &rows {
        let cell = |i: usize| row.get(i).map_or("", String::as_str);
        let mut group = vec![cell(law).to_string()];
        group.extend(keys[1..].iter().map(|&k| cell(k).to_string()));
        let index = match groups.iter().position(|(g, _, _)| *g == group) {
            Some(index) => index,
            None => {
                let mut label = group[0].clone();
                for (&k, value) in keys[1..].iter().zip(&group[1..]) {
                    label += &format!(", {} = {value}", header[k]);
                }
                let series = IncidenceSeries { label: cut(&label, TITLE_CHARS), ..IncidenceSeries::default() };
                groups.push((group, series, Vec::new()));
                groups.len() - 1
            }
        };
        let (_, series, rigid) = &mut groups[index];
        let x = number(row, first);
        for (panel, &(simulated, theory)) in panels.iter().enumerate() {
            series.simulated[panel].push(x.zip(number(row, simulated)));
            series.rigid[panel].push(x.zip(number(row, theory)));
        }
        if let (Some(x), Some(theta), Some(e), Some(rebound)) =
            (x, number(row, incidence), number(row, restitution), number(row, panels[2].1))
        {
            rigid.push(RigidRow { x, incidence: theta, restitution: e, rebound });
        }
    }
    let series = groups
        .into_iter()
        .map(|(_, mut series, rows)| {
            series.threshold = rigid_threshold(rows);
            series
        })
        .collect();
    let body = |key: &str| key.split('.').nth(1).and_then(|i| i.parse::<usize>().ok()).map_or(1, |i| i + 1);
    Ok(IncidenceFigure {
        title: "Oblique impact against the angle of incidence: simulation and rigid-body theory".into(),
        x_label: format!("angle of incidence of body {} from the normal (°)", body(&header[first])),
        spin_body,
        series,
    })
}

/// One row's rigid-body values: the varied angle `x`, the contact points' incidence and the rigid rebound angle
/// (degrees from the normal), the simulated e the theory was given.
#[derive(Debug, Clone, Copy)]
struct RigidRow {
    x: f64,
    incidence: f64,
    restitution: f64,
    rebound: f64,
}

/// Where rigid-body theory changes from sticking (the contact points leave rolling: rebound angle zero) to sliding,
/// on the x axis, from the first pair of neighbouring rows (in x) on either side.
///
/// Sliding throughout, the slip changes by k mu (1 + e) v_n (k from the masses and inertias), so the rebound angle
/// of a sliding row obeys e tan(rebound) = tan(incidence) - k mu (1 + e), and the theory sticks exactly when
/// tan(incidence) <= k mu (1 + e): the threshold is tan(theta*) = tan(incidence) - e tan(rebound) of the sliding row
/// (for a sphere on a wall, k = 7/2). When that angle does not fall between the two rows (a slip that turns, e.g.
/// with an initial spin across it), only the interval is known: [`Threshold::Between`].
fn rigid_threshold(mut rows: Vec<RigidRow>) -> Option<Threshold> {
    rows.sort_by(|a, b| a.x.total_cmp(&b.x));
    let sticks = |row: &RigidRow| row.rebound.abs() <= ROLLING;
    let pair = rows.windows(2).find(|pair| sticks(&pair[0]) != sticks(&pair[1]))?;
    let (stick, slide) = if sticks(&pair[0]) { (pair[0], pair[1]) } else { (pair[1], pair[0]) };
    let radians = f64::to_radians;
    let tangent = radians(slide.incidence).tan() - slide.restitution * radians(slide.rebound).tan();
    let theta = tangent.atan().to_degrees();
    let (low, high) = (stick.incidence.min(slide.incidence), stick.incidence.max(slide.incidence));
    let slack = 1e-9 * high.abs().max(1.0);
    if !(theta >= low - slack && theta <= high + slack) {
        return Some(Threshold::Between(pair[0].x, pair[1].x));
    }
    // On the varied angle's axis: the same angle for a body hitting a wall at rest, else interpolated.
    let x = if (stick.x - stick.incidence).abs() <= slack && (slide.x - slide.incidence).abs() <= slack {
        theta
    } else if high > low {
        stick.x + (slide.x - stick.x) * (theta - stick.incidence) / (slide.incidence - stick.incidence)
    } else {
        (stick.x + slide.x) / 2.0
    };
    Some(Threshold::At { x, degrees: theta })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sphere on a wall by rigid-body theory (docs/oblique.md#rigid-body-theory): the slip changes by
    /// (7/2) mu (1 + e) v_n while it slides, so it sticks below tan(theta*) = (7/2) mu (1 + e), and a sliding row's
    /// rebound angle is atan((tan(theta) - (7/2) mu (1 + e)) / e).
    fn sphere_on_wall(degrees: f64, mu: f64, e: f64) -> RigidRow {
        let limit = 3.5 * mu * (1.0 + e);
        let tangent = degrees.to_radians().tan();
        let rebound = if tangent <= limit { 0.0 } else { ((tangent - limit) / e).atan().to_degrees() };
        RigidRow { x: degrees, incidence: degrees, restitution: e, rebound }
    }

    #[test]
    fn the_rigid_threshold_is_located_from_a_sliding_row() {
        let (mu, e): (f64, f64) = (0.092, 0.98);
        let exact = (3.5 * mu * (1.0 + e)).atan().to_degrees();
        // In any order; the first change of regime counts.
        let rows = [45.0, 5.0, 30.0, 35.0, 60.0].map(|d| sphere_on_wall(d, mu, e)).to_vec();
        let Some(Threshold::At { x, degrees }) = rigid_threshold(rows) else { panic!("a located threshold") };
        assert!((degrees - exact).abs() < 1e-10 && (x - exact).abs() < 1e-10, "{degrees} against {exact}");
        assert!((exact - 32.52).abs() < 0.01, "Chung & Ooi's 32.5 degrees: {exact}");
    }

    #[test]
    fn the_threshold_goes_on_the_varied_axis_and_falls_back_to_an_interval() {
        let (mu, e): (f64, f64) = (0.2, 0.5);
        let exact = (3.5 * mu * (1.0 + e)).atan().to_degrees();
        // The varied angle is not the contact points' incidence (x = incidence + 10): interpolated between the rows.
        let shifted = |d: f64| RigidRow { x: d + 10.0, ..sphere_on_wall(d, mu, e) };
        let Some(Threshold::At { x, degrees }) = rigid_threshold(vec![shifted(40.0), shifted(50.0)]) else {
            panic!("a located threshold")
        };
        assert!((degrees - exact).abs() < 1e-10 && (x - (exact + 10.0)).abs() < 1e-10, "{x}, {degrees}");
        // A sliding row whose rebound does not fit the sliding law (a turning slip): only the interval is known.
        let mut odd = sphere_on_wall(50.0, mu, e);
        odd.rebound = 45.0;
        assert_eq!(rigid_threshold(vec![sphere_on_wall(40.0, mu, e), odd]), Some(Threshold::Between(40.0, 50.0)));
        // Sliding throughout (or smooth): no change of regime, no threshold.
        assert_eq!(rigid_threshold(vec![sphere_on_wall(50.0, mu, e), sphere_on_wall(60.0, mu, e)]), None);
    }
}
