//! ADAMS' `IMPACT(x, x', x1, k, e, cmax, d)`: k (x1 − x)^e + STEP(x, x1 − d, cmax, x1, 0) (−x'), never pulling —
//! this program's `adams-impact` law (penetration x1 − x, exponent e, damping ramping up to c_max over d_max = d).
//! ADAMS integrates with variable-step stiff integrators (GSTIFF, WSTIFF, HHT): no fixed step to predict.

use super::{Context, Knob, Mapping, Parameters, Peer, Plan, TranslateError, cannot_express, number};
use crate::law::{Family, LawKind, Separation};
use crate::scene::{ContactSpec, DampingSpec};

/// The fraction of the penetration scale a translated contact takes as d_max, when the scene has none.
const RAMP_FRACTION: f64 = 0.01;

struct Impact {
    /// K, N/m^n.
    stiffness: f64,
    exponent: f64,
    /// d_max, m.
    ramp: f64,
    context: Context,
}

impl Mapping for Impact {
    fn contact(&self, p: f64) -> ContactSpec {
        let mut spec = self.context.spec(LawKind::AdamsImpact, Separation::Force);
        spec.damping = DampingSpec::None;
        spec.cmax = Some(p);
        spec.dmax = Some(self.ramp);
        spec
    }

    fn parameters(&self, p: f64) -> Parameters {
        Parameters::default().with("k", self.stiffness).with("e", self.exponent).with("cmax", p).with("d", self.ramp)
    }

    fn snippet(&self, p: f64, _dt: Option<f64>) -> String {
        let bodies = &self.context.scene.bodies;
        let reach = bodies.iter().map(|b| if b.radius.is_finite() { b.radius } else { 0.0 }).sum::<f64>();
        format!(
            "! {} in ADAMS (impact translate): a single-component force along the line of centres,\n\
             ! x the distance between the centres (DM), x' its rate (VR), x1 = r1 + r2 (a wall: the distance from \
             its plane, DZ, and x1 = r)\n\
             FUNCTION = IMPACT(DM(I,J), VR(I,J), {}, {}, {}, {}, {})\n",
            self.context.title(),
            number(reach),
            number(self.stiffness),
            number(self.exponent),
            number(p),
            number(self.ramp)
        )
    }
}

/// The plan for ADAMS.
pub fn plan(context: &Context) -> Result<Plan, TranslateError> {
    let law = &context.law;
    let mut notes = Vec::new();
    let length = context.setup.scales.length;
    let critical = 2.0 * context.mass * context.speed / length;
    let (ramp, knob) = match law.kind.family() {
        Family::Ramp => (law.ramp, Knob::Fixed(law.damping)),
        Family::Elastic => (RAMP_FRACTION * length, Knob::Fixed(0.0)),
        family if context.target.is_some() && family != Family::Plastic && family != Family::Impedance => {
            let ramp = RAMP_FRACTION * length;
            notes.push(super::substituted(context, Peer::Adams, "IMPACT's c_max"));
            notes.push(format!(
                "IMPACT's d is taken as {}, a hundredth of the penetration scale.",
                crate::units::brief(ramp, "m")
            ));
            (ramp, Knob::Damping { scale: critical })
        }
        _ => {
            return Err(cannot_express(
                Peer::Adams,
                law.kind,
                "IMPACT is a power-law spring with a damping that ramps up over its first d of penetration",
                "`adams-impact`; a scene that asks for an e with a power-law spring is tuned to it",
            ));
        }
    };
    notes.push(format!(
        "IMPACT's damping vanishes at first touch and rises as a cubic STEP to c_max at d = {}: a d comparable with \
         the deepest penetration ({} is its scale here) changes e; ADAMS' integrator must resolve d (HMAX well below \
         the contact time).",
        crate::units::brief(ramp, "m"),
        crate::units::brief(length, "m")
    ));
    let mapping = Impact { stiffness: law.stiffness, exponent: law.exponent, ramp, context: context.clone() };
    Ok(Plan { law: "IMPACT function".into(), mapping: Box::new(mapping), knob, notes, scheme: Peer::Adams.scheme() })
}
