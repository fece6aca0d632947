//! Kratos' DEM `DEM_D_Hertz_viscous_Coulomb`: F = (2/3) k_n d + c d' with k_n = 2 E* sqrt(R* d) and
//! c = 2 γ sqrt(m* k_n), cut at zero (it never pulls) — this program's `tsuji` law with a = sqrt(6) γ and
//! `separation = "force"`. Kratos computes γ from the material relation's `COEFFICIENT_OF_RESTITUTION` by
//! Thornton, Cummins & Cleary's fit (`GammaForHertzThornton` of its DEM strategy), which is not the exact inverse of
//! its own contact: a nominal 0.98 gives 0.9724. Steps are its `Symplectic_Euler` translational scheme.

use super::{Context, Knob, Mapping, Parameters, Peer, Plan, TranslateError, cannot_express, number, short};
use crate::law::{LawKind, Separation};
use crate::scene::{ContactSpec, DampingSpec};

/// Kratos' γ for a nominal e (Thornton, Cummins & Cleary 2013's fit, as Kratos evaluates it: e clamped to 0.001
/// from below, γ = 0 above 0.999).
pub fn thornton_gamma(e: f64) -> f64 {
    let e = e.max(0.001);
    if e > 0.999 {
        return 0.0;
    }
    let h = [-6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18, 6276.757, -1489.915];
    let alpha = e * h.iter().rev().fold(0.0, |sum, c| sum * e + c);
    (1.0 / (1.0 - (1.0 + e) * (1.0 + e) * alpha.exp()) - 1.0).sqrt()
}

/// The nominal e whose γ is `gamma` (γ falls as e rises), by bisection; `None` beyond γ(0.001).
fn nominal_for_gamma(gamma: f64) -> Option<f64> {
    if gamma <= 0.0 {
        return Some(1.0);
    }
    let (mut low, mut high) = (0.001, 0.999);
    if thornton_gamma(low) < gamma {
        return None;
    }
    for _ in 0..100 {
        let middle = 0.5 * (low + high);
        if thornton_gamma(middle) > gamma { low = middle } else { high = middle }
    }
    Some(0.5 * (low + high))
}

struct Hertz {
    /// Each material's Young's modulus (Pa) and Poisson's ratio.
    materials: [(f64, f64); 2],
    friction: f64,
    context: Context,
}

impl Mapping for Hertz {
    fn contact(&self, p: f64) -> ContactSpec {
        let mut spec = self.context.spec(LawKind::Tsuji, Separation::Force);
        spec.damping = DampingSpec::Parameter(6f64.sqrt() * thornton_gamma(p));
        spec
    }

    fn parameters(&self, p: f64) -> Parameters {
        Parameters::default()
            .with("DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME", "DEM_D_Hertz_viscous_Coulomb")
            .with("YOUNG_MODULUS", vec![self.materials[0].0, self.materials[1].0])
            .with("POISSON_RATIO", vec![self.materials[0].1, self.materials[1].1])
            .with("COEFFICIENT_OF_RESTITUTION", p)
            .with("STATIC_FRICTION", self.friction)
            .with("DYNAMIC_FRICTION", self.friction)
            .with("TranslationalIntegrationScheme", "Symplectic_Euler")
    }

    fn snippet(&self, p: f64, dt: Option<f64>) -> String {
        let [(y1, n1), (y2, n2)] = self.materials;
        let (y1, y2, n1, n2) = (number(y1), number(y2), number(n1), number(n2));
        // Kratos takes a sphere's mass from its PARTICLE_DENSITY (kg/m³) and radius.
        let density = |body: &crate::body::Body| {
            if body.is_flat() || body.is_immovable() {
                String::new()
            } else {
                format!(
                    ", \"PARTICLE_DENSITY\": {}",
                    number(body.mass / (4.0 / 3.0 * std::f64::consts::PI * body.radius.powi(3)))
                )
            }
        };
        let [a, b] = &self.context.scene.bodies;
        let (d1, d2) = (density(a), density(b));
        let part = |body: &crate::body::Body| if body.is_flat() { "RigidFacePart" } else { "SpheresPart" };
        let table = format!("\"material_assignation_table\": [[\"{}\", \"a\"], [\"{}\", \"b\"]]", part(a), part(b));
        let (e, mu) = (number(p), number(self.friction));
        let step = match dt {
            Some(dt) => format!(", \"AutomaticTimestep\": false, \"MaxTimeStep\": {}", number(dt)),
            None => String::new(),
        };
        format!(
            "// {} in Kratos DEM (impact translate)\n// MaterialsDEM.json (a: body 1, b: body 2 or the wall):\n{{\n  \
             \"materials\": [{{\"material_name\": \"a\", \"material_id\": 1, \"Variables\": {{\"YOUNG_MODULUS\": {y1}, \
             \"POISSON_RATIO\": {n1}{d1}}}}}, {{\"material_name\": \"b\", \"material_id\": 2, \"Variables\": \
             {{\"YOUNG_MODULUS\": {y2}, \"POISSON_RATIO\": {n2}{d2}}}}}],\n  \
             \"material_relations\": [{{\"material_names_list\": [\"a\", \"b\"], \"material_ids_list\": [1, 2], \
             \"Variables\": {{\"COEFFICIENT_OF_RESTITUTION\": {e}, \"STATIC_FRICTION\": {mu}, \"DYNAMIC_FRICTION\": {mu}, \
             \"DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME\": \"DEM_D_Hertz_viscous_Coulomb\"}}}}],\n  {table}\n}}\n\
             // ProjectParameters.json, beside its other settings:\n\
             \"TranslationalIntegrationScheme\": \"Symplectic_Euler\"{step}\n",
            self.context.title()
        )
    }
}

/// The plan for Kratos.
pub fn plan(context: &Context) -> Result<Plan, TranslateError> {
    let law = &context.law;
    let mut notes = Vec::new();
    let knob = match law.kind {
        LawKind::Hertz => Knob::Fixed(1.0),
        LawKind::Tsuji if context.target.is_some() => Knob::Nominal,
        LawKind::Tsuji => Knob::Fixed(nominal_for_gamma(law.damping / 6f64.sqrt()).ok_or_else(|| {
            TranslateError::bad(
                "contact.damping",
                "a is beyond the damping Kratos' fit reaches (its gamma at e = 0.001)",
            )
        })?),
        _ if context.target.is_some() && context.hertzian() && law.kind != LawKind::Thornton => {
            notes.push(super::substituted(context, Peer::Kratos, "COEFFICIENT_OF_RESTITUTION (Tsuji's form)"));
            Knob::Nominal
        }
        kind => {
            return Err(cannot_express(
                Peer::Kratos,
                kind,
                "DEM_D_Hertz_viscous_Coulomb is a Hertz spring with Tsuji-form damping",
                "DEM_D_Hertz_viscous_Coulomb (this program's `tsuji` with separation = \"force\"); a scene that asks \
                 for an e with a Hertz spring is tuned to it",
            ));
        }
    };
    let Some(radius) = context.radius else {
        return Err(TranslateError::bad("bodies", "Kratos' Hertz contact needs the contact's effective radius R*"));
    };
    let materials = context.peer_materials(radius, &mut notes);
    if let (Some(nominal), Some(target)) = (context.nominal, context.target) {
        let typed = Hertz { materials, friction: 0.0, context: context.clone() }.contact(nominal);
        if let Some(e) = super::restitution(context, &typed, None)? {
            notes.push(format!(
                "Kratos maps COEFFICIENT_OF_RESTITUTION to its damping by a fit (Thornton et al. 2013) that misses \
                 its own contact near e = 1 (a nominal 0.98 gives 0.9724): typing the scene's restitution = {} would \
                 give {}; the value above is tuned to give {}.",
                crate::units::short(nominal),
                short(e),
                short(target)
            ));
        }
    }
    notes.push(
        "Kratos' contact never pulls: it is this program's `tsuji` with separation = \"force\", whatever the scene \
         separates by."
            .into(),
    );
    let friction = context.setup.friction.map_or(0.0, |f| f.coefficient);
    if friction > 0.0 {
        notes.push("Kratos' walls take the lever arm r - d for friction's torque (this program: r).".into());
    }
    let mapping = Hertz { materials, friction, context: context.clone() };
    Ok(Plan {
        law: "DEM_D_Hertz_viscous_Coulomb".into(),
        mapping: Box::new(mapping),
        knob,
        notes,
        scheme: Peer::Kratos.scheme(),
    })
}
