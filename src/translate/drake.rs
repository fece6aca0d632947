//! Drake's point contact (`MultibodyPlant` with `contact_model = "point"`). Continuous (`time_step = 0`): the
//! Hunt–Crossley force k d (1 + d_hc d') with exponent 1, k the two geometries' `point_contact_stiffness` in series
//! and d_hc their `hunt_crossley_dissipation` (s/m) weighted by the other's stiffness. Discrete with the SAP solver:
//! a Kelvin–Voigt force k (d + τ d'), cut at zero, where τ = τ_A + τ_B adds the geometries' `relaxation_time`s
//! (c = k (τ_A + τ_B)). Both geometries carry the same values here, so k is half of each one's and τ twice each
//! one's.

use super::{Context, Knob, Mapping, Parameters, Peer, Plan, TranslateError, cannot_express, number};
use crate::law::{Family, LawKind, Separation};
use crate::scene::{ContactSpec, DampingSpec};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Model {
    /// Continuous Hunt–Crossley: the knob is d_hc, s/m.
    HuntCrossley,
    /// Discrete SAP: the knob is c = k τ, N s/m.
    Sap,
}

struct Point {
    model: Model,
    /// k, N/m.
    stiffness: f64,
    context: Context,
}

impl Point {
    /// Each geometry's stiffness (N/m) and dissipation (s/m) or relaxation time (s) for the knob `p`.
    fn each(&self, p: f64) -> (f64, f64) {
        match self.model {
            Model::HuntCrossley => (2.0 * self.stiffness, p),
            Model::Sap => (2.0 * self.stiffness, p / (2.0 * self.stiffness)),
        }
    }
}

impl Mapping for Point {
    fn contact(&self, p: f64) -> ContactSpec {
        let (law, separation) = match self.model {
            Model::HuntCrossley => (LawKind::HuntCrossley, Separation::Penetration),
            Model::Sap => (LawKind::KelvinVoigt, Separation::Force),
        };
        let mut spec = self.context.spec(law, separation);
        spec.exponent = 1.0;
        spec.exponent_given = Some(1.0);
        spec.damping = DampingSpec::Parameter(p);
        spec
    }

    fn parameters(&self, p: f64) -> Parameters {
        let (k, second) = self.each(p);
        let parameters = Parameters::default().with("point_contact_stiffness", k);
        match self.model {
            Model::HuntCrossley => parameters.with("hunt_crossley_dissipation", second),
            Model::Sap => parameters.with("relaxation_time", second),
        }
    }

    fn snippet(&self, p: f64, dt: Option<f64>) -> String {
        let (k, second) = self.each(p);
        let (setting, solver) = match self.model {
            Model::HuntCrossley => (
                format!(
                    "AddContactMaterial(dissipation={}, point_stiffness={}, friction=CoulombFriction(0.0, 0.0), \
                         properties=props)\n",
                    number(second),
                    number(k)
                ),
                "MultibodyPlantConfig(time_step=0.0, contact_model=\"point\")".to_string(),
            ),
            Model::Sap => (
                format!(
                    "AddContactMaterial(point_stiffness={}, friction=CoulombFriction(0.0, 0.0), properties=props)\n\
                         props.AddProperty(\"material\", \"relaxation_time\", {})\n",
                    number(k),
                    number(second)
                ),
                format!(
                    "MultibodyPlantConfig(time_step={}, contact_model=\"point\", \
                     discrete_contact_approximation=\"sap\")",
                    number(dt.unwrap_or(1e-3))
                ),
            ),
        };
        format!(
            "# {} in Drake (impact translate): both geometries of the contact get these properties\n\
             from pydrake.geometry import ProximityProperties, AddContactMaterial\n\
             from pydrake.multibody.plant import CoulombFriction, MultibodyPlantConfig\n\
             props = ProximityProperties()\n\
             {setting}config = {solver}\n",
            self.context.title(),
        )
    }
}

/// The plan for Drake.
pub fn plan(context: &Context) -> Result<Plan, TranslateError> {
    let law = &context.law;
    let mut notes = Vec::new();
    let (model, knob) = match law.kind.family() {
        Family::Hysteresis | Family::Elastic if law.exponent == 1.0 => {
            let knob = match context.target {
                Some(_) => Knob::Damping { scale: 1.0 / context.speed },
                None => Knob::Fixed(law.damping),
            };
            (Model::HuntCrossley, knob)
        }
        Family::Linear => {
            notes.push(
                "Drake's continuous point contact is Hunt–Crossley: a spring–dashpot is its discrete SAP contact \
                 (time_step > 0), with c = k (tau_A + tau_B). SAP's force never pulls, so its e is that of the \
                 force falling to zero; its step is an implicit Euler, whose e falls below the continuous one at \
                 first order in dt."
                    .into(),
            );
            let knob = match context.target {
                Some(_) => Knob::Damping { scale: 2.0 * (law.stiffness * context.mass).sqrt() },
                None => Knob::Fixed(law.damping),
            };
            (Model::Sap, knob)
        }
        _ => {
            return Err(cannot_express(
                Peer::Drake,
                law.kind,
                "its point contact's spring is linear (exponent 1)",
                "Hunt–Crossley with exponent 1 (this program's `hunt-crossley` with exponent = 1), or a \
                 spring–dashpot in its discrete SAP solver (`kelvin-voigt`)",
            ));
        }
    };
    notes.push(
        "Drake combines two geometries' point_contact_stiffness in series and weights their dissipations by the \
         other's stiffness: with equal values on both, the contact's k is half of each one's."
            .into(),
    );
    if context.setup.friction.is_some() {
        notes.push("Friction is not carried over: set CoulombFriction to the scene's coefficient yourself.".into());
    }
    let law_name = match model {
        Model::HuntCrossley => "point contact, continuous (Hunt–Crossley, exponent 1)",
        Model::Sap => "point contact, discrete SAP (Kelvin–Voigt with relaxation time)",
    };
    let mapping = Point { model, stiffness: law.stiffness, context: context.clone() };
    // (Drake's discrete SAP steps the contact with an implicit Euler, which this program runs; its continuous plant
    // integrates with error control.)
    let scheme = (model == Model::Sap).then_some(crate::fixed_step::Scheme::ImplicitEuler);
    Ok(Plan { law: law_name.into(), mapping: Box::new(mapping), knob, notes, scheme })
}
