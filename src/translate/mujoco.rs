//! MuJoCo's soft contact: `solref` and `solimp` on the contact's geoms, read per unit mass (of the constraint's
//! effective mass, m* for two free bodies) and scaled by the impedance d(r) of `solimp`. Its force never pulls.
//! Steps are the semi-implicit Euler of `integrator="Euler"` (the default). This program's `mujoco` law is that
//! contact in its continuous-time limit (docs/laws.md); a Kelvin–Voigt contact is MuJoCo's with `solref`'s direct
//! form and a constant impedance (`solimp` with d_min = d_max), k and c per unit mass.

use super::{Context, Knob, Mapping, Parameters, Peer, Plan, TranslateError, cannot_express, number, short};
use crate::law::{LawKind, Separation};
use crate::scene::{ContactSpec, DampingSpec};

/// MuJoCo's default `solimp`.
pub const DEFAULT_SOLIMP: [f64; 5] = [0.9, 0.95, 0.001, 0.5, 2.0];
/// The constant impedance a translated spring–dashpot takes (MuJoCo's default d_max).
pub const CONSTANT_SOLIMP: [f64; 5] = [0.95, 0.95, 0.001, 0.5, 2.0];

/// Where the knob enters `solref`.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Form {
    /// The scene's own `solref` and `solimp`, unchanged (the knob is unused).
    Given { solref: [f64; 2], solimp: [f64; 5] },
    /// A spring–dashpot K (N/m), the knob its c (N s/m): solref = [−K/m*, −c/m*], constant impedance.
    Dashpot { stiffness: f64, mass: f64 },
}

struct Soft {
    form: Form,
    context: Context,
    friction: f64,
}

impl Soft {
    fn solref_solimp(&self, p: f64) -> ([f64; 2], [f64; 5]) {
        match self.form {
            Form::Given { solref, solimp } => (solref, solimp),
            Form::Dashpot { stiffness, mass } => ([-stiffness / mass, -p / mass], CONSTANT_SOLIMP),
        }
    }
}

/// The `mujoco` law's contact spec with these `solref` and `solimp`.
pub fn spec(context: &Context, solref: [f64; 2], solimp: [f64; 5]) -> ContactSpec {
    let mut spec = context.spec(LawKind::Mujoco, Separation::Force);
    spec.stiffness = crate::scene::StiffnessSpec::Hertz;
    spec.exponent = 1.0;
    spec.exponent_given = None;
    spec.damping = DampingSpec::None;
    spec.solref = Some(solref);
    spec.solimp = Some(solimp);
    spec
}

fn list(values: &[f64]) -> String {
    values.iter().map(|v| number(*v)).collect::<Vec<_>>().join(" ")
}

impl Mapping for Soft {
    fn contact(&self, p: f64) -> ContactSpec {
        let (solref, solimp) = self.solref_solimp(p);
        spec(&self.context, solref, solimp)
    }

    fn parameters(&self, p: f64) -> Parameters {
        let (solref, solimp) = self.solref_solimp(p);
        let mut parameters = Parameters::default().with("solref", solref.to_vec()).with("solimp", solimp.to_vec());
        parameters = parameters.with("condim", if self.friction > 0.0 { 3 } else { 1 });
        if self.friction > 0.0 {
            parameters = parameters.with("friction", self.friction);
        }
        parameters
    }

    fn snippet(&self, p: f64, dt: Option<f64>) -> String {
        let (solref, solimp) = self.solref_solimp(p);
        let friction = if self.friction > 0.0 {
            format!(" condim=\"3\" friction=\"{} 0 0\"", number(self.friction))
        } else {
            " condim=\"1\"".into()
        };
        let option = match dt {
            Some(dt) => format!("<option timestep=\"{}\" integrator=\"Euler\"/>\n", number(dt)),
            None => "<option integrator=\"Euler\"/>\n".into(),
        };
        format!(
            "<!-- {} in MuJoCo (impact translate): give both geoms of the contact these attributes (MuJoCo mixes \
             two geoms' solref and solimp) -->\n{option}<geom{friction} margin=\"0\" solref=\"{}\" solimp=\"{}\"/>\n",
            self.context.title(),
            list(&solref),
            list(&solimp)
        )
    }
}

/// The plan for MuJoCo.
pub fn plan(context: &Context) -> Result<Plan, TranslateError> {
    let law = &context.law;
    let contact = &context.scene.contact;
    let mut notes = Vec::new();
    let mass = context.mass;
    let (form, knob) = match law.kind {
        LawKind::Mujoco => {
            let solref = contact.solref.unwrap_or([0.02, 1.0]);
            let solimp = contact.solimp.unwrap_or(DEFAULT_SOLIMP);
            let high = solimp[1];
            let (k, b) = (law.stiffness / mass * high * high, law.damping / mass * high);
            notes.push(format!(
                "MuJoCo reads solref per unit mass of the contact (m* = {} kg here): at full impedance d_max = {} \
                 this is a spring k = {} N/m and a dashpot c = {} N s/m, damping ratio b / (2 sqrt k) = {}. \
                 Typing a physical k and c into solref's direct form instead changes that ratio by sqrt(m*).",
                short(mass),
                short(high),
                short(k * mass),
                short(b * mass),
                crate::units::brief(b / (2.0 * k.sqrt()), "")
            ));
            if let Some(dt) = context.dt
                && solref[0] > 0.0
                && solref[0] < 2.0 * dt
            {
                let (timeconst, twice) = crate::units::apart(solref[0], 2.0 * dt, "s");
                notes.push(format!(
                    "timeconst = {timeconst} is below 2 dt = {twice}: MuJoCo raises it to 2 dt (its `refsafe`), so at \
                     this step the contact is softer than the scene's."
                ));
            }
            (Form::Given { solref, solimp }, Knob::Fixed(0.0))
        }
        LawKind::KelvinVoigt | LawKind::HertzDashpot if law.exponent == 1.0 => {
            let form = Form::Dashpot { stiffness: law.stiffness, mass };
            let physical = spec(context, [-law.stiffness, -law.damping], CONSTANT_SOLIMP);
            let wrong = super::restitution(context, &physical, None)?;
            notes.push(format!(
                "solref's direct form is per unit mass: [-k/m*, -c/m*] with m* = {} kg. Typed with the physical k \
                 and c (solref = \"{} {}\"), MuJoCo would give e = {}.",
                short(mass),
                short(-law.stiffness),
                short(-law.damping),
                wrong.map_or("no rebound".into(), |e| crate::units::brief_digits(e, "", 4))
            ));
            if contact.separation == Separation::Penetration {
                let own = super::restitution(context, &context.own_contact(), None)?;
                let same = spec(context, [-law.stiffness / mass, -law.damping / mass], CONSTANT_SOLIMP);
                let never_pulling = super::restitution(context, &same, None)?;
                let shown =
                    |e: Option<f64>| e.map_or("no rebound".to_string(), |e| crate::units::brief_digits(e, "", 4));
                notes.push(format!(
                    "The scene's spring–dashpot separates at d = 0 and pulls just before (e = {}); MuJoCo's contact \
                     never pulls, so the same k and c per unit mass give it a higher e ({}, continuous).",
                    shown(own),
                    shown(never_pulling)
                ));
            }
            let knob = match context.target {
                Some(_) => Knob::Damping { scale: 2.0 * (law.stiffness * mass).sqrt() },
                None => Knob::Fixed(law.damping),
            };
            (form, knob)
        }
        kind => {
            return Err(cannot_express(
                Peer::Mujoco,
                kind,
                "MuJoCo's contact spring is linear in the penetration (solref's stiffness, scaled by the impedance)",
                "a linear spring–dashpot (this program's `kelvin-voigt`, or `mujoco` with your solref and solimp)",
            ));
        }
    };
    if context.dt.is_some() {
        notes.push(
            "MuJoCo's Euler integrator is semi-implicit (velocity first, then position with it): e converges to \
             the continuous one at first order in dt."
                .into(),
        );
    }
    let friction = context.setup.friction.map_or(0.0, |f| f.coefficient);
    if friction > 0.0 {
        notes.push(
            "MuJoCo's friction is a soft pyramidal or elliptic cone, not a Mindlin spring: only the coefficient is \
             carried over."
                .into(),
        );
    }
    let name = match form {
        Form::Given { .. } => "soft contact (solref, solimp as given)",
        Form::Dashpot { .. } => "soft contact: solref's direct form, constant impedance",
    };
    Ok(Plan {
        law: name.into(),
        mapping: Box::new(Soft { form, context: context.clone(), friction }),
        knob,
        notes,
        scheme: Peer::Mujoco.scheme(),
    })
}
