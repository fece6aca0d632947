//! LIGGGHTS' `pair_style gran model hertz`: the Hertz spring from the atom types' `youngsModulus` and
//! `poissonsRatio`, and a damping force −γ_n d' with γ_n = −2 sqrt(5/6) β sqrt(S_n m*), S_n = 2 Y* sqrt(R* d) and
//! β = ln e / sqrt(ln² e + π²) from `coefficientRestitution`: Tsuji's form at the exact map, this program's `tsuji`
//! with a = −sqrt(5) β (the same as LAMMPS' `coeff_restitution`). The force may pull at the end of the contact
//! unless `limitForce on`. Steps are velocity Verlet (`fix nve/sphere`).

use super::lammps::nominal_for_tsuji;
use super::{Context, Knob, Mapping, Parameters, Peer, Plan, TranslateError, cannot_express, number};
use crate::law::{LawKind, Separation};
use crate::reference::tsuji_damping;
use crate::scene::{ContactSpec, DampingSpec};

struct Hertz {
    /// Each type's Young's modulus (Pa) and Poisson's ratio.
    materials: [(f64, f64); 2],
    limit_force: bool,
    friction: f64,
    context: Context,
}

impl Mapping for Hertz {
    fn contact(&self, p: f64) -> ContactSpec {
        let separation = if self.limit_force { Separation::Force } else { Separation::Penetration };
        let mut spec = self.context.spec(LawKind::Tsuji, separation);
        spec.damping = DampingSpec::Parameter(tsuji_damping(p));
        spec
    }

    fn parameters(&self, p: f64) -> Parameters {
        let [(y1, n1), (y2, n2)] = self.materials;
        Parameters::default()
            .with("youngsModulus", vec![y1, y2])
            .with("poissonsRatio", vec![n1, n2])
            .with("coefficientRestitution", p)
            .with("coefficientFriction", self.friction)
            .with("limitForce", if self.limit_force { "on" } else { "off" })
    }

    fn snippet(&self, p: f64, dt: Option<f64>) -> String {
        let [(y1, n1), (y2, n2)] = self.materials;
        let (e, mu) = (number(p), number(self.friction));
        let limit = if self.limit_force { " limitForce on" } else { "" };
        let mut text = format!(
            "# {} in LIGGGHTS (impact translate); SI units; atom type 1 is body 1, type 2 body 2 (or the wall)\n\
             pair_style gran model hertz tangential history{limit}\npair_coeff * *\n\
             fix m1 all property/global youngsModulus peratomtype {} {}\n\
             fix m2 all property/global poissonsRatio peratomtype {} {}\n\
             fix m3 all property/global coefficientRestitution peratomtypepair 2 {e} {e} {e} {e}\n\
             fix m4 all property/global coefficientFriction peratomtypepair 2 {mu} {mu} {mu} {mu}\n",
            self.context.title(),
            number(y1),
            number(y2),
            number(n1),
            number(n2),
        );
        if self.context.wall {
            text += "# the wall: turn the scene so that its plane is z = 0, the sphere above it\n\
                     fix wall all wall/gran model hertz tangential history primitive type 2 zplane 0.0\n";
        }
        text += "fix integrate all nve/sphere\n";
        if let Some(dt) = dt {
            text += &format!("timestep {}\n", number(dt));
        }
        text
    }
}

/// The plan for LIGGGHTS.
pub fn plan(context: &Context) -> Result<Plan, TranslateError> {
    let law = &context.law;
    let mut notes = Vec::new();
    let knob = match law.kind {
        LawKind::Hertz => Knob::Fixed(1.0),
        LawKind::Tsuji => match context.target {
            Some(_) => Knob::Nominal,
            None => Knob::Fixed(nominal_for_tsuji(law.damping).ok_or_else(|| {
                TranslateError::bad(
                    "contact.damping",
                    "a is at or beyond sqrt 5: LIGGGHTS' coefficientRestitution has no e for it",
                )
            })?),
        },
        _ if context.target.is_some() && context.hertzian() && law.kind != LawKind::Thornton => {
            notes.push(super::substituted(context, Peer::Liggghts, "coefficientRestitution (Tsuji's form)"));
            Knob::Nominal
        }
        kind => {
            return Err(cannot_express(
                Peer::Liggghts,
                kind,
                "its granular models are Hertz and Hooke springs with Tsuji-form damping set by coefficientRestitution",
                "`model hertz` (this program's `tsuji`); a scene that asks for an e with a Hertz spring is tuned to it",
            ));
        }
    };
    let Some(radius) = context.radius else {
        return Err(TranslateError::bad("bodies", "LIGGGHTS' hertz model needs the contact's effective radius R*"));
    };
    let materials = context.peer_materials(radius, &mut notes);
    let limit_force = context.scene.contact.separation == Separation::Force;
    if context.dt.is_some() {
        notes.push(
            "LIGGGHTS' velocity Verlet damps with the half-step velocity: e converges at first order in dt.".into(),
        );
    }
    let friction = context.setup.friction.map_or(0.0, |f| f.coefficient);
    let mapping = Hertz { materials, limit_force, friction, context: context.clone() };
    Ok(Plan {
        law: "pair_style gran model hertz (coefficientRestitution)".into(),
        mapping: Box::new(mapping),
        knob,
        notes,
        scheme: Peer::Liggghts.scheme(),
    })
}
