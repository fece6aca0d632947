//! The readable terminal report: a title, then sections of labelled rows with the values in one aligned column.
//!
//! Numbers are in engineering form with six significant digits ([`crate::units`]); the JSON and CSV views keep
//! full precision. Each section is one small function of the [`Report`] returning a `Section` (or `None` when
//! the report has nothing for it), so a new part of the report is a new function and one line in [`render`].
//!
//! Two conventions make the numbers readable:
//! - a value whose size is below [`NOISE`] times the impact's own scale for its quantity (`Scales`) is double
//!   precision rounding, not physics, and is shown as 0 (V0 of a symmetric impact is 0, not 1e-16 m/s);
//! - times of the contact are measured from first contact; the scene time of first contact is given once.

use crate::idealisation::{Judgement, Verdict};
use crate::law::{Family, LawKind};
use crate::report::{InstantaneousReport, Report, Vec3};
use crate::units::{DIGITS, engineering, engineering_digits, plain, plain_digits, prefix_for, short};
use std::fmt::Write;

/// A value smaller than this fraction of its quantity's scale is shown as zero. Sums of terms of the scale's size
/// carry rounding errors of a few 1e-16 per operation; after the few hundred operations of one impact they stay
/// well below 1e-12, and anything the integrator can resolve (its tolerance is 1e-10 by default) stays above it.
pub const NOISE: f64 = 1e-12;

/// Significant digits of relative errors and of differences from the simulation: enough to read their order.
const ERROR_DIGITS: usize = 2;

/// Width of the exact-value column of the reference section, in characters.
const EXACT_WIDTH: usize = 14;

/// The impact's own size for each kind of quantity, from the report's own numbers.
#[derive(Debug, Clone, Copy)]
struct Scales {
    /// m/s: the approach speed v0, or the largest velocity component before the impact if larger (a body's
    /// velocity in the scene's frame carries rounding of its own size).
    speed: f64,
    /// N s: m* v0, the size of the deformation impulse — or, for a graze whose force is far weaker, the force's
    /// own impulse, Fmax times the contact's duration.
    impulse: f64,
    /// J: m* v0², the size of what the contact takes or leaves — or, for a graze, Fmax dmax.
    contact_energy: f64,
    /// J: m* v0², or the kinetic energy before if larger.
    energy: f64,
    /// rad/s: the speed scale over the smallest radius.
    spin: f64,
}

impl Scales {
    fn of(report: &Report) -> Scales {
        let v0 = report.approach_speed;
        let largest = report.bodies.iter().flat_map(|b| b.velocity_before).map(f64::abs).fold(0.0, f64::max);
        let m = report.effective_mass;
        let radius = report.bodies.iter().map(|b| b.radius).fold(f64::INFINITY, f64::min);
        let spins = report.bodies.iter().flat_map(|b| b.angular_velocity_before).map(f64::abs).fold(0.0, f64::max);
        let c = &report.contact;
        let duration = c.duration.unwrap_or(c.max_compression_time - c.start_time);
        Scales {
            speed: v0.max(largest),
            impulse: (m * v0).min(c.max_force * duration),
            contact_energy: (m * v0 * v0).min(c.max_force * c.max_penetration),
            energy: (m * v0 * v0).max(report.energy.kinetic_before),
            spin: (v0.max(largest) / radius).max(spins),
        }
    }
}

/// `value`, or 0 when it is below [`NOISE`] times `scale`.
fn denoise(value: f64, scale: f64) -> f64 {
    if value.abs() < NOISE * scale { 0.0 } else { value }
}

/// One block of the report: a title line and rows of (label, value); a row with an empty value is printed as a
/// sub-heading.
pub(super) struct Section {
    title: String,
    rows: Vec<(String, String)>,
}

impl Section {
    pub(super) fn new(title: impl Into<String>) -> Section {
        Section { title: title.into(), rows: Vec::new() }
    }

    pub(super) fn row(&mut self, label: impl Into<String>, value: impl Into<String>) {
        self.rows.push((label.into(), value.into()));
    }

    pub(super) fn heading(&mut self, text: impl Into<String>) {
        self.rows.push((text.into(), String::new()));
    }
}

/// The whole report as aligned text.
pub fn render(report: &Report) -> String {
    let scales = Scales::of(report);
    let sections: Vec<Section> = [
        idealisation(report),
        Some(law(report)),
        Some(impact(report)),
        Some(contact(report, &scales)),
        Some(restitution(report)),
        Some(energy(report, &scales)),
        oblique(report, &scales),
        Some(bodies(report, &scales)),
        // The simulated e is a measurement (six digits), the nominal e an input (as given).
        report.instantaneous.as_ref().map(|ideal| {
            instantaneous(format!("the simulated e = {}", plain(ideal.restitution)), ideal, report, &scales)
        }),
        report.instantaneous_nominal.as_ref().map(|ideal| {
            instantaneous(format!("the nominal e = {}", short(ideal.restitution)), ideal, report, &scales)
        }),
        reference(report, &scales),
        Some(solver(report)),
    ]
    .into_iter()
    .flatten()
    .collect();
    layout(&report.title, &sections, &report.notes)
}

/// The title, the sections with their values in one column, and the notes.
pub(super) fn layout(title: &str, sections: &[Section], notes: &[String]) -> String {
    // Headings (rows without a value) run across the value column and do not set its position.
    let width = sections
        .iter()
        .flat_map(|s| &s.rows)
        .filter(|(_, value)| !value.is_empty())
        .map(|(label, _)| label.chars().count())
        .max()
        .unwrap_or(0);
    let mut text = format!("{title}\n");
    for section in sections {
        let _ = writeln!(text, "\n{}", section.title);
        for (label, value) in &section.rows {
            let line = if value.is_empty() { format!("  {label}") } else { format!("  {label:<width$}  {value}") };
            let _ = writeln!(text, "{}", line.trim_end());
        }
    }
    if !notes.is_empty() {
        text.push('\n');
    }
    for note in notes {
        let _ = writeln!(text, "note: {note}");
    }
    text
}

/// The verdicts on the idealisation, first: one row per assumption (what is measured, its value against its scale,
/// the ratio, the verdict), and under a verdict that is not `holds` its meaning. `None` when the run did not judge
/// the idealisation (every verdict null).
fn idealisation(report: &Report) -> Option<Section> {
    let rows = report.idealisation.entries().map(|(key, verdict)| VerdictRow {
        key,
        verdict,
        place: None,
        named: None,
        why_not: why_not_judged(key, report.contact.separated),
    });
    verdict_table("the idealisation on trial (docs/idealisation.md)", &rows)
}

/// One row of a table of verdicts: the assumption, its verdict (and where it was measured: a world's contact), or
/// why it has none.
pub(super) struct VerdictRow<'a> {
    pub key: &'static str,
    pub verdict: Option<&'a Verdict>,
    pub place: Option<String>,
    /// Where, in the line of a meaning ("contact 3").
    pub named: Option<String>,
    pub why_not: &'static str,
}

/// A table of verdicts titled `title`: per row what is measured, where (when a row says), its value against its
/// scale, the ratio and the verdict, and under a verdict that is not `holds` its meaning. `None` when no row has a
/// verdict.
pub(super) fn verdict_table(title: &str, rows: &[VerdictRow]) -> Option<Section> {
    if rows.iter().all(|row| row.verdict.is_none()) {
        return None;
    }
    let placed = rows.iter().any(|row| row.place.is_some());
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|row| {
            let mut cells = match row.verdict {
                Some(v) => vec![
                    v.measure.to_string(),
                    // (A value below NOISE of its scale is rounding: a slope of 1e-15 is 0.)
                    format!(
                        "{} vs {}",
                        engineering_digits(denoise(v.value, v.compared_with), v.unit, 3),
                        engineering_digits(v.compared_with, v.unit, 3)
                    ),
                    ratio(denoise(v.ratio, 1.0)),
                    v.verdict.name().to_string(),
                ],
                None => vec![row.why_not.into(), String::new(), "n/a".into(), String::new()],
            };
            if placed {
                cells.insert(
                    1,
                    if row.verdict.is_some() { row.place.clone().unwrap_or_default() } else { String::new() },
                );
            }
            cells
        })
        .collect();
    let mut header: Vec<String> =
        ["measured", "value vs compared with", "ratio", "verdict"].into_iter().map(String::from).collect();
    if placed {
        header.insert(1, "worst".into());
    }
    let columns = header.len();
    let widths: Vec<usize> = (0..columns - 1)
        .map(|i| cells.iter().chain([&header]).map(|c| c[i].chars().count()).max().unwrap_or(0))
        .collect();
    let line = |c: &[String]| {
        let mut text = String::new();
        for (i, cell) in c.iter().enumerate() {
            let pad = widths.get(i).map_or(0, |w| w.saturating_sub(cell.chars().count()));
            // The ratio column (the one before the verdict) aligns right; the others left.
            if i == columns - 2 {
                text += &format!("{}{cell}  ", " ".repeat(pad));
            } else if i == columns - 1 {
                text += cell;
            } else {
                text += &format!("{cell}{}  ", " ".repeat(pad));
            }
        }
        text
    };
    let mut section = Section::new(title);
    section.row("assumption", line(&header));
    for (row, cell) in rows.iter().zip(&cells) {
        section.row(row.key, line(cell));
        if let Some(v) = row.verdict.filter(|v| v.verdict != Judgement::Holds) {
            let place = row.named.as_ref().map_or(String::new(), |p| format!(", {p}"));
            section.heading(format!("  {} {}{place}: {}", row.key, v.verdict.name(), v.meaning));
        }
    }
    Some(section)
}

/// Why an assumption has no verdict (docs/idealisation.md#the-eight-verdicts).
fn why_not_judged(key: &str, separated: bool) -> &'static str {
    match key {
        "elastic" => "no body has a finite yield_stress",
        "instantaneous" | "isolated" | "quasi_static" | "constant_e" | "smooth" if !separated => {
            "the bodies did not separate"
        }
        "quasi_static" => "no centred body with young and a density",
        "constant_e" => "e = 0, or a run at 0.9 or 1.1 v0 did not separate",
        _ => "does not apply",
    }
}

/// A verdict's ratio, to two digits: plain from 0.01 to 1000, in exponent form outside.
fn ratio(value: f64) -> String {
    let size = value.abs();
    if size == 0.0 || (1e-2..1e3).contains(&size) { plain_digits(value, 2) } else { format!("{value:.1e}") }
}

/// The law: its formula, parameters and separation criterion. Only what the law has: no damping for Hertz, no
/// exponent row for laws whose formula fixes it, no nominal e when the damping was given.
fn law(report: &Report) -> Section {
    let law = &report.law;
    // The law's formula and family are catalogue facts, looked up by name (no physics is computed here).
    let info = LawKind::from_name(law.name).map(|kind| kind.info());
    let formula = info.map_or("?", |i| i.formula);
    let family = info.map(|i| i.family);
    let mut section = Section::new(format!("law: {}, F = {formula}", law.name));
    let symbol = if family == Some(Family::Linear) { "k" } else { "K" };
    section.row(format!("stiffness {symbol}"), stiffness(law.stiffness, law.exponent));
    if formula.contains("d^n") {
        section.row("exponent n", short(law.exponent));
    }
    let damping = match family {
        Some(Family::Elastic | Family::Plastic) => None,
        Some(Family::Linear) => Some(("damping c", "N s/m")),
        Some(Family::Hysteresis) => Some(("damping alpha", "s/m")),
        Some(Family::Tsuji) => Some(("damping a", "")),
        Some(Family::Viscoelastic) => Some(("material time A", "s")),
        Some(Family::Dashpot) => Some(("damping c", "N s/m")),
        Some(Family::Impedance) => Some(("damping m* b", "N s/m")),
        Some(Family::Ramp) => Some(("full damping c_max", "N s/m")),
        None => Some(("damping", "")),
    };
    if let Some((label, unit)) = damping {
        let origin = if law.restitution_nominal.is_some() { " (from the nominal e by the law's map)" } else { "" };
        section.row(label, format!("{}{origin}", engineering(law.damping, unit)));
    }
    if let (Some(e), false) = (law.restitution_nominal, family == Some(Family::Elastic)) {
        section.row("nominal e", short(e));
    }
    if let Some(pressure) = law.yield_pressure {
        section.row("yield pressure p_y", engineering(pressure, "Pa"));
    }
    if let Some(speed) = law.yield_speed {
        section.row("yield speed V_y (e = 1 below it)", engineering(speed, "m/s"));
    }
    section.row("contact ends where", format!("the {} returns to zero", law.separation));
    section
}

/// K in N/m^n: with an SI prefix for a linear spring (N/m), in exponent form otherwise.
fn stiffness(value: f64, exponent: f64) -> String {
    if exponent == 1.0 { engineering(value, "N/m") } else { engineering(value, &format!("N/m^{}", short(exponent))) }
}

/// What the two bodies bring to the contact: m*, v0 and the normal.
fn impact(report: &Report) -> Section {
    let mut section = Section::new("impact");
    section.row("effective mass m*", engineering(report.effective_mass, "kg"));
    section.row("approach speed v0", engineering(report.approach_speed, "m/s"));
    let n = report.normal.map(|c| denoise(c, 1.0));
    section.row("contact normal n (body 1 to 2)", format!("[{}, {}, {}]", short(n[0]), short(n[1]), short(n[2])));
    section
}

/// The phases of the contact, times since first contact.
fn contact(report: &Report, scales: &Scales) -> Section {
    let c = &report.contact;
    // A time since first contact is a difference of scene times: rounding of the size of either.
    let scale = (c.max_compression_time - c.start_time).max(c.start_time.abs());
    let since = |t: f64| engineering(denoise(t - c.start_time, scale), "s");
    let mut section = Section::new("contact (times since first contact)");
    section.row("first contact, in the scene's time", format!("t = {}", engineering(c.start_time, "s")));
    section.row("maximum force at", since(c.max_force_time));
    section.row("maximum compression (d' = 0) at", since(c.max_compression_time));
    let separation = c.duration.map_or_else(|| "none: the bodies did not separate".into(), |d| engineering(d, "s"));
    section.row("separation at (= contact duration)", separation);
    section.row("maximum penetration", engineering(c.max_penetration, "m"));
    section.row("maximum force", engineering(c.max_force, "N"));
    section.row("common normal velocity V0", engineering(denoise(c.common_normal_velocity, scales.speed), "m/s"));
    let impulse = |value: f64| engineering(denoise(value, scales.impulse), "N s");
    section.row("deformation impulse", impulse(c.deformation_impulse));
    section.row("restitution impulse", maybe(c.restitution_impulse, impulse));
    if let Some(dent) = c.permanent_dent {
        section.row("permanent dent (force zero at)", engineering(dent, "m"));
    }
    section
}

/// e three ways.
fn restitution(report: &Report) -> Section {
    let c = &report.contact;
    let mut section = Section::new("coefficient of restitution e");
    // Before separation there is no e ("—"); after it, a ratio the report could not form is "n/a" (a note says why).
    let e = |value: Option<f64>| match value {
        None if c.separated => "n/a (see the notes)".into(),
        value => maybe(value, plain),
    };
    section.row("impulse ratio (Poisson)", e(c.restitution_impulse_ratio));
    section.row("velocity ratio (Newton)", e(c.restitution_velocity_ratio));
    section.row("energy ratio (Stronge)", e(c.restitution_energy));
    if let Some(dt) = report.solver.dt {
        // A fixed-step scheme's e beside the accurate path's: what a peer code gives at its step.
        let continuous = report.solver.restitution_continuous;
        let value = match (c.restitution_velocity_ratio, continuous) {
            (Some(e), Some(accurate)) => format!(
                "{} (continuous: {}, difference {})",
                plain(e),
                plain(accurate),
                plain_digits(e - accurate, ERROR_DIGITS)
            ),
            (Some(e), None) => format!("{} (continuous: the bodies did not part)", plain(e)),
            (None, Some(accurate)) => format!("— (continuous: {})", plain(accurate)),
            (None, None) => "—".into(),
        };
        section.row(format!("e at dt = {}", engineering_digits(dt, "s", 3)), value);
    }
    section
}

/// Kinetic energies, the work of the damping (and friction) forces, what an immovable body put in and what the
/// contact still holds when it ends — and how well the balance of these separately integrated terms closes.
fn energy(report: &Report, scales: &Scales) -> Section {
    let e = &report.energy;
    let joules = |value: f64| engineering(denoise(value, scales.energy), "J");
    // What the contact itself takes or leaves is measured against the impact's own energy m* v0², not against a
    // kinetic energy that a heavy body's motion may make far larger.
    let impact_energy = scales.contact_energy;
    let contact_joules = |value: f64| engineering(denoise(value, impact_energy), "J");
    let mut section = Section::new("energy");
    section.row("kinetic energy before", joules(e.kinetic_before));
    if let Some(work) = e.work_of_immovable_bodies.filter(|w| denoise(*w, scales.energy) != 0.0) {
        section.row("work done by the immovable body", joules(work));
    }
    section.row("kinetic energy after", maybe(e.kinetic_after, joules));
    let frictional = report.oblique.as_ref().is_some_and(|o| o.friction_work.is_some_and(|w| w != 0.0));
    if family(report) != Some(Family::Elastic) || frictional {
        let what = match (frictional, family(report) == Some(Family::Plastic)) {
            (true, true) => "dissipated (plastic dent and friction)",
            (true, false) => "dissipated (damping and friction)",
            (false, true) => "dissipated in the plastic dent",
            (false, false) => "dissipated by damping",
        };
        section.row(what, maybe(e.dissipated, contact_joules));
    }
    if let Some(left) = e.elastic_left_at_separation.filter(|l| denoise(*l, impact_energy) != 0.0) {
        section.row("elastic energy left at separation", contact_joules(left));
    }
    if let (Some(after), Some(dissipated), Some(left), Some(work)) =
        (e.kinetic_after, e.dissipated, e.elastic_left_at_separation, e.work_of_immovable_bodies)
    {
        let imbalance = (e.kinetic_before + work - after - dissipated - left) / scales.energy;
        section.row(
            "balance (in - out) / m* v0²",
            if imbalance == 0.0 { "0".into() } else { plain_digits(imbalance, ERROR_DIGITS) },
        );
    }
    section
}

/// Oblique impact, friction and spin: angles, tangential restitution, friction work, and rigid-body theory.
fn oblique(report: &Report, scales: &Scales) -> Option<Section> {
    let o = report.oblique.as_ref()?;
    let degrees = |value: f64| format!("{} deg", plain_digits(value, DIGITS));
    let mut section = Section::new("oblique impact");
    section.row("incidence from the normal", degrees(o.incidence_from_normal_deg));
    section.row("rebound from the normal", maybe(o.rebound_from_normal_deg, degrees));
    section.row("tangential restitution, centres", maybe(o.tangential_restitution_centre, plain));
    section.row("tangential restitution, contact points", maybe(o.tangential_restitution_contact, plain));
    let regime = match (o.regime.as_str(), o.slip_rest_time) {
        ("sliding", _) => "sliding (the contact points slipped throughout)".to_string(),
        ("sticking", Some(0.0)) => "sticking (no slip at first contact)".to_string(),
        ("sticking", Some(rest)) => format!("sticking (the slip came to rest at {})", engineering(rest, "s")),
        _ => o.regime.clone(),
    };
    section.row("regime", regime);
    if let Some(below) = o.below_friction_limit_duration.filter(|&below| below > 0.0) {
        section.row("friction below the Coulomb limit for", engineering(below, "s"));
    }
    // The simulators' tangential options, when a frictional contact names one other than the default.
    if o.regime != "smooth" && o.friction_cap != "compressive" {
        section.row("Coulomb limit", "mu |Fn|, also while the normal force pulls (friction_cap = \"magnitude\")");
    }
    if o.regime != "smooth" && o.tangential_unloading != "none" {
        section.row(
            "tangential spring",
            "rescaled with the stiffness while unloading (tangential_unloading = \"rescale\")",
        );
    }
    if let Some(work) = o.friction_work.filter(|_| o.regime != "smooth") {
        section.row("work of friction", engineering(denoise(work, scales.energy), "J"));
    }
    if let Some(pull) = o.tensile_impulse.filter(|&pull| pull > 0.0) {
        section.row("impulse while the normal force pulled", engineering(pull, "N s"));
    }
    if let Some(turn) = o.normal_turn_deg {
        section.row("line of centres turned by", degrees(turn));
    }
    if o.slid_off {
        section.row("the bodies slid off each other", "yes: a graze (see the note)");
    }
    if let Some(rigid) = &o.rigid_body {
        section.heading(format!("rigid-body theory with the simulated e ({})", rigid.regime));
        for (i, body) in report.bodies.iter().enumerate().filter(|(_, body)| body.mass.is_finite()) {
            section.row(format!("  velocity after, {}", body.name), velocity(&rigid.velocity_after[i], scales));
            if body.inertia.is_finite() {
                section.row(format!("  spin after, {}", body.name), spin(&rigid.angular_velocity_after[i], scales));
            }
        }
        section.row("  largest velocity difference", difference(rigid.max_velocity_difference, "m/s"));
        section.row("  largest spin difference", difference(rigid.max_angular_velocity_difference, "rad/s"));
    }
    Some(section)
}

/// Each body: mass, radius and its velocity before, at maximum compression and after, all in one unit.
fn bodies(report: &Report, scales: &Scales) -> Section {
    let mut section = Section::new("bodies");
    for body in &report.bodies {
        let mass = if body.mass.is_infinite() { "immovable".into() } else { engineering(body.mass, "kg") };
        let radius =
            if body.radius.is_infinite() { "flat".into() } else { format!("radius {}", engineering(body.radius, "m")) };
        section.heading(format!("{}: {mass}, {radius}", body.name));
        let velocity = |v: &Vec3| velocity(v, scales);
        if body.mass.is_infinite() {
            // Nothing moves an immovable body: one velocity throughout.
            section.row("  velocity throughout", velocity(&body.velocity_before));
            continue;
        }
        section.row("  velocity before", velocity(&body.velocity_before));
        section.row("  at maximum compression", velocity(&body.velocity_at_max_compression));
        section.row("  after", body.velocity_after.as_ref().map_or_else(|| "—".into(), velocity));
        if eccentric(report) {
            section.row("  effective mass at the contact", engineering(body.effective_mass_at_contact, "kg"));
            if body.inertia.is_finite() {
                section.row("  spin before", spin(&body.angular_velocity_before, scales));
                section.row(
                    "  spin after",
                    body.angular_velocity_after.as_ref().map_or_else(|| "—".into(), |w| spin(w, scales)),
                );
            }
            if let Some(pivot) = &body.pivot_impulse {
                section.row("  impulse from the pivot", impulse(pivot, scales));
            }
        }
        if report.oblique.is_some() {
            let degrees = |value: f64| format!("{} deg", plain_digits(value, DIGITS));
            section.row("  angle from the tangent plane, before", maybe(body.angle_from_tangent_before_deg, degrees));
            section.row("  angle from the tangent plane, after", maybe(body.angle_from_tangent_after_deg, degrees));
            // (An eccentric body's spins are given above.)
            if body.inertia.is_finite() && !eccentric(report) {
                section.row("  spin before", spin(&body.angular_velocity_before, scales));
                section.row(
                    "  spin after",
                    body.angular_velocity_after.as_ref().map_or_else(|| "—".into(), |w| spin(w, scales)),
                );
            }
        }
    }
    section
}

/// The idealised instantaneous impact with the simulated or the nominal e (`with`: which e, and its value).
fn instantaneous(with: String, ideal: &InstantaneousReport, report: &Report, scales: &Scales) -> Section {
    // With an oblique section, say which idealisation this is (rigid-body friction comes in that section).
    let kind = if report.oblique.is_some() && eccentric(report) {
        "smooth eccentric instantaneous impact"
    } else if report.oblique.is_some() {
        "smooth instantaneous impact (the four equations)"
    } else {
        "instantaneous impact"
    };
    let mut section = Section::new(format!("{kind} with {with}"));
    section.row("common normal velocity V0", engineering(denoise(ideal.common_normal_velocity, scales.speed), "m/s"));
    // (An immovable body keeps its velocity: the bodies section gives it once.)
    for (body, after) in report.bodies.iter().zip(&ideal.velocity_after).filter(|(body, _)| body.mass.is_finite()) {
        section.row(format!("velocity after, {}", body.name), velocity(after, scales));
    }
    if let Some(eccentric) = &ideal.eccentric {
        let movable = report.bodies.iter().enumerate().filter(|(_, body)| body.mass.is_finite());
        for (i, body) in movable {
            section.row(format!("effective mass, {}", body.name), engineering(eccentric.effective_masses[i], "kg"));
            section.row(format!("spin after, {}", body.name), spin(&eccentric.angular_velocity_after[i], scales));
            if body.pivot_impulse.is_some() || eccentric.pivot_impulse[i] != [0.0; 3] {
                section.row(
                    format!("impulse from the pivot, {}", body.name),
                    impulse(&eccentric.pivot_impulse[i], scales),
                );
            }
        }
    }
    section.row("kinetic energy lost", engineering(denoise(ideal.energy_lost, scales.energy), "J"));
    section.row("largest difference from simulation", maybe(ideal.max_velocity_difference, |d| difference(d, "m/s")));
    if let Some(eccentric) = &ideal.eccentric {
        let spins = eccentric.max_angular_velocity_difference;
        section.row("largest spin difference", maybe(spins, |d| difference(d, "rad/s")));
    }
    section
}

/// Whether the report is of rigid bodies struck off their centre (its instantaneous impact is the eccentric one).
fn eccentric(report: &Report) -> bool {
    [&report.instantaneous, &report.instantaneous_nominal]
        .iter()
        .any(|ideal| ideal.as_ref().is_some_and(|i| i.eccentric.is_some()))
        || report.bodies.iter().any(|body| body.effective_mass_at_contact != body.mass)
}

/// An impulse vector in N s, six digits, components below the noise at the impact's scale 0.
fn impulse(j: &Vec3, scales: &Scales) -> String {
    let parts = j.map(|c| plain_digits(denoise(c, scales.impulse), DIGITS));
    format!("[{}, {}, {}] N s", parts[0], parts[1], parts[2])
}

/// The exact values for this contact and the simulation's relative error against each.
fn reference(report: &Report, scales: &Scales) -> Option<Section> {
    let reference = report.reference.as_ref()?;
    let e = &reference.errors;
    let mut section = Section::new("exact reference (times since first contact)");
    section.row("source", &reference.source);
    section.row("", format!("{:<EXACT_WIDTH$}  relative error of the simulation", "exact"));
    let v0 = denoise(reference.common_normal_velocity, scales.speed);
    for (label, exact, error, unit, per) in [
        ("restitution e", reference.restitution, e.restitution, "", ""),
        ("maximum penetration", reference.max_penetration, e.max_penetration, "m", ""),
        ("maximum compression at", reference.max_compression_time, e.max_compression_time, "s", ""),
        ("contact duration", reference.duration, e.duration, "s", ""),
        ("maximum force", reference.max_force, e.max_force, "N", ""),
        ("common normal velocity V0", Some(v0), Some(e.common_normal_velocity), "m/s", " of v0"),
    ] {
        if let Some(exact) = exact {
            let error =
                maybe(error, |x| if x == 0.0 { "0".into() } else { format!("{}{per}", plain_digits(x, ERROR_DIGITS)) });
            section.row(label, format!("{:<EXACT_WIDTH$}  {error}", engineering(exact, unit)));
        }
    }
    Some(section)
}

/// The integrator and its work, on one line.
fn solver(report: &Report) -> Section {
    let s = &report.solver;
    if let Some(dt) = s.dt {
        return Section::new(format!(
            "solver: {} at the fixed step dt = {}: {} steps, {} force evaluations, {}",
            s.method,
            engineering_digits(dt, "s", 3),
            s.steps,
            s.force_evaluations,
            engineering_digits(s.wall_time_s, "s", 3)
        ));
    }
    Section::new(format!(
        "solver: {}, rtol {:e}, atol {:e}: {} steps ({} rejected), {} force evaluations, {}",
        s.method,
        s.rtol,
        s.atol,
        s.steps,
        s.rejected_steps,
        s.force_evaluations,
        engineering_digits(s.wall_time_s, "s", 3)
    ))
}

/// A velocity vector in the unit its scale calls for ("[-0.800000, 0, 0] m/s"), components below the noise 0.
fn velocity(v: &Vec3, scales: &Scales) -> String {
    let (factor, prefix) = prefix_for(scales.speed);
    let parts = v.map(|c| plain_digits(denoise(c, scales.speed) / factor, DIGITS));
    format!("[{}, {}, {}] {prefix}m/s", parts[0], parts[1], parts[2])
}

/// An angular velocity vector in rad/s, six digits, components below the noise at the impact's scale 0.
fn spin(w: &Vec3, scales: &Scales) -> String {
    let parts = w.map(|c| plain_digits(denoise(c, scales.spin), DIGITS));
    format!("[{}, {}, {}] rad/s", parts[0], parts[1], parts[2])
}

/// A difference between two results: its order is what matters (two significant digits).
fn difference(value: f64, unit: &str) -> String {
    format!("{} {unit}", plain_digits(value, ERROR_DIGITS))
}

fn maybe(value: Option<f64>, show: impl Fn(f64) -> String) -> String {
    value.map_or_else(|| "—".into(), show)
}

fn family(report: &Report) -> Option<Family> {
    LawKind::from_name(report.law.name).map(LawKind::family)
}
