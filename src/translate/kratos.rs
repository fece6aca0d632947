//! Kratos' DEM `DEM_D_Hertz_viscous_Coulomb`: F = (2/3) k_n d + c d' with k_n = 2 E* sqrt(R* d) and
//! c = 2 γ sqrt(m* k_n), cut at zero (it never pulls) — this program's `tsuji` law with a = sqrt(6) γ and
//! `separation = "force"`. Kratos computes γ from the material relation's `COEFFICIENT_OF_RESTITUTION` by
//! Thornton, Cummins & Cleary's fit (`GammaForHertzThornton` of its DEM strategy), which is not the exact inverse of
//! its own contact: a nominal 0.98 gives 0.9724. Steps are its `Symplectic_Euler` translational scheme.

use super::{Context, Knob, Mapping, Parameters, Peer, Plan, TranslateError, cannot_express, number, short};
use crate::law::{LawKind, Separation};
use crate::scene::{ContactSpec, DampingSpec};

/// Poisson's ratio given to both materials.
const POISSON: f64 = 0.3;

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
    young: f64,
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
            .with("YOUNG_MODULUS", self.young)
            .with("POISSON_RATIO", POISSON)
            .with("COEFFICIENT_OF_RESTITUTION", p)
            .with("STATIC_FRICTION", self.friction)
            .with("DYNAMIC_FRICTION", self.friction)
            .with("TranslationalIntegrationScheme", "Symplectic_Euler")
    }

    fn snippet(&self, p: f64, dt: Option<f64>) -> String {
        let (young, e, mu) = (number(self.young), number(p), number(self.friction));
        let step = match dt {
            Some(dt) => format!(", \"AutomaticTimestep\": false, \"MaxTimeStep\": {}", number(dt)),
            None => String::new(),
        };
        format!(
            "// {} in Kratos DEM (impact translate): MaterialsDEM.json (both materials alike), and ProjectParameters.json\n\
             \"materials\": [{{\"material_name\": \"a\", \"material_id\": 1, \"Variables\": {{\"YOUNG_MODULUS\": {young}, \
             \"POISSON_RATIO\": {POISSON}}}}}, {{\"material_name\": \"b\", \"material_id\": 2, \"Variables\": \
             {{\"YOUNG_MODULUS\": {young}, \"POISSON_RATIO\": {POISSON}}}}}],\n\
             \"material_relations\": [{{\"material_names_list\": [\"a\", \"b\"], \"material_ids_list\": [1, 2], \
             \"Variables\": {{\"COEFFICIENT_OF_RESTITUTION\": {e}, \"STATIC_FRICTION\": {mu}, \"DYNAMIC_FRICTION\": {mu}, \
             \"DEM_DISCONTINUUM_CONSTITUTIVE_LAW_NAME\": \"DEM_D_Hertz_viscous_Coulomb\"}}}}]\n\
             \"TranslationalIntegrationScheme\": \"Symplectic_Euler\"{step}\n",
            self.context.scene.title
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
        kind if context.target.is_some() && context.hertzian() && kind != LawKind::Thornton => {
            notes.push(format!(
                "Kratos' Hertz contact damps in Tsuji's form: the translation keeps the Hertz spring and tunes \
                 COEFFICIENT_OF_RESTITUTION to the scene's e, so the force–time curve differs from `{}`'s.",
                kind.name()
            ));
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
    let modulus = 3.0 * law.stiffness / (4.0 * radius.sqrt());
    let young = 2.0 * (1.0 - POISSON * POISSON) * modulus;
    notes.push(format!(
        "Both materials get YOUNG_MODULUS = {} Pa and POISSON_RATIO = {POISSON}, which give the scene's E* = {} Pa.",
        short(young),
        short(modulus)
    ));
    if let Some(target) = context.target {
        let nominal = Hertz { young, friction: 0.0, context: context.clone() }.contact(target);
        if let Ok(Some(e)) = super::restitution(context, &nominal, None) {
            notes.push(format!(
                "Kratos maps COEFFICIENT_OF_RESTITUTION to its damping by a fit (Thornton et al. 2013) that misses \
                 its own contact near e = 1 (a nominal 0.98 gives 0.9724): typing the scene's e = {target} would give \
                 {e:.6}; the value above is tuned to give {target}."
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
    let mapping = Hertz { young, friction, context: context.clone() };
    Ok(Plan { law: "DEM_D_Hertz_viscous_Coulomb".into(), mapping: Box::new(mapping), knob, notes })
}
