//! `--law a,b,c`: running one scene under another law, with that law's own defaults re-derived.
//!
//! The rules, applied to the scene document before the point's values are set:
//! - `contact.law` becomes the law.
//! - `hertz` takes neither `restitution` nor `damping`: both are removed (so it is the elastic reference; varying
//!   either then gives rows whose status says why `hertz` cannot take them).
//! - `thornton` takes neither either (its loss is plastic): both are removed; its `yield_pressure` (or the bodies'
//!   `yield_stress`) stays, and every other law drops `yield_pressure`.
//! - Exponent: `kelvin-voigt` (1), `tsuji`, `brilliantov` and `thornton` (3/2) fix it, so `exponent` is removed. A numeric
//!   `stiffness` is in N/m^n for the exponent it was written with (the file's `exponent`, or its law's default: 1
//!   for `kelvin-voigt`, 3/2 otherwise): a law that fixes another exponent cannot take it, and the row says so
//!   (unless `contact.stiffness` is varied, whose values then hold for every law). A law with a free exponent keeps
//!   the file's one, written out explicitly with a numeric stiffness (so `kelvin-voigt`'s k in N/m stays a K in
//!   N/m^1 for `hunt-crossley`). `stiffness = "hertz"` is kept as is; `kelvin-voigt` then cannot run (row status).
//! - Damping: a nominal `restitution` carries over (each law turns it into damping with its own map). A `damping`
//!   parameter is in the units of its law (alpha in s/m for the whole Hunt–Crossley family, c in N s/m, a
//!   dimensionless, A in s): it carries over only to a law with the same units. Otherwise it is removed, and
//!   unless `contact.damping` or `contact.restitution` is varied the row says that the law has no damping.
//!   `brilliantov` takes no `restitution` (its e depends on speed): such rows say so.

use super::key::SceneKey;
use crate::law::{Family, LawKind};
use toml::{Table, Value};

/// The exponent a law fixes, if it fixes one.
fn fixed_exponent(law: LawKind) -> Option<f64> {
    match law.family() {
        Family::Linear => Some(1.0),
        Family::Tsuji | Family::Viscoelastic | Family::Plastic => Some(1.5),
        Family::Elastic | Family::Hysteresis | Family::Dashpot | Family::Ramp => None,
        Family::Impedance => Some(1.0),
    }
}

/// The units of K in K d^n.
fn units(exponent: f64) -> String {
    if exponent == 1.0 { "N/m".into() } else { format!("N/m^{}", crate::units::short(exponent)) }
}

fn as_number(value: &Value) -> Option<f64> {
    value.as_float().or_else(|| value.as_integer().map(|i| i as f64))
}

/// Rewrites the scene document for `law` (rules in the module doc). `varied` are the keys the point sets
/// afterwards. `Err` is why this law cannot run this scene: the row's status.
pub fn apply(scene: &mut Table, law: LawKind, varied: &[SceneKey]) -> Result<(), String> {
    let contact = scene.entry("contact").or_insert_with(|| Value::Table(Table::new()));
    let Some(contact) = contact.as_table_mut() else { return Err("`contact` is not a table".into()) };
    let original = contact.get("law").and_then(Value::as_str).and_then(LawKind::from_name);
    contact.insert("law".into(), Value::String(law.name().into()));
    let varies = |field: &str| varied.iter().any(|key| key.is_contact(field));

    let stiffness = contact.get("stiffness").and_then(as_number);
    let written_exponent = contact.get("exponent").and_then(as_number);
    let exponent = written_exponent.unwrap_or(match original.map(LawKind::family) {
        Some(Family::Linear) => 1.0,
        _ => 1.5,
    });
    match fixed_exponent(law) {
        Some(fixed) => {
            contact.remove("exponent");
            if let Some(k) = stiffness
                && fixed != exponent
                && !varies("stiffness")
            {
                return Err(format!(
                    "the scene's stiffness {} is in {} (exponent {}); `{}` fixes the exponent at {}: vary \
                     contact.stiffness or write a scene for this law",
                    crate::units::short(k),
                    units(exponent),
                    crate::units::short(exponent),
                    law.name(),
                    crate::units::short(fixed)
                ));
            }
        }
        None => {
            if stiffness.is_some() && written_exponent.is_none() {
                contact.insert("exponent".into(), Value::Float(exponent));
            }
        }
    }

    if law.family() != Family::Plastic {
        contact.remove("yield_pressure");
    }
    if matches!(law.family(), Family::Elastic | Family::Plastic) {
        contact.remove("restitution");
        contact.remove("damping");
        return Ok(());
    }
    let units = law.info().damping_units;
    if let Some(original) = original
        && contact.contains_key("damping")
        && original.info().damping_units != units
    {
        contact.remove("damping");
        if !varies("damping") && !varies("restitution") {
            return Err(format!(
                "the scene's damping is for `{}` ({}), `{}` takes {}: give `restitution` in the scene or vary \
                 contact.damping",
                original.name(),
                original.info().damping_units,
                law.name(),
                units
            ));
        }
    }
    Ok(())
}
