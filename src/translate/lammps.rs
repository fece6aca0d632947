//! LAMMPS' `pair_style granular` (and `fix wall/gran/region` for a wall): the normal models `hooke` (F = k_n d) and
//! `hertz` (F = k_n sqrt(R*) d^(3/2)), each with a damping force −η_n d' whose η_n the `damping` keyword picks:
//!
//! | LAMMPS | η_n | this program's law |
//! |---|---|---|
//! | `hooke k_n η_n0 damping velocity` | η_n0 | `kelvin-voigt`, c = η_n0 |
//! | `hooke k_n e damping coeff_restitution` | sqrt(4 m* k_n / (1 + (π/ln e)²)) | `kelvin-voigt` at its exact map |
//! | `hertz k_n η_n0 damping velocity` | η_n0 | `hertz-dashpot`, c = η_n0 |
//! | `hertz k_n e damping coeff_restitution` | −2 sqrt(5/6) ln e / sqrt(π² + ln² e) sqrt(3/2 m* F/d) | `tsuji`, a = −sqrt5 ln e / sqrt(π² + ln² e) |
//! | `hertz k_n η_n0 damping viscoelastic` | η_n0 sqrt(R* d) m* | `brilliantov`, A = 2 m* η_n0 / (3 k_n) |
//! | `hertz k_n e damping tsuji` | α(e) sqrt(m* F/d), Tsuji's polynomial α | `tsuji`, a = α(e) (releases before 2 Sep 2026; √2 α since) |
//!
//! The contact lasts while the spheres overlap, so the force may pull at its end; `limit_damping` clamps it at zero,
//! which is this program's `separation = "force"`. Steps are velocity Verlet (`fix nve/sphere`).

use super::{Context, Knob, Mapping, Parameters, Peer, Plan, TranslateError, cannot_express, number, short};
use crate::law::{LawKind, Separation};
use crate::reference::{kelvin_voigt_zeta, tsuji_damping};
use crate::scene::{ContactSpec, DampingSpec, FrictionCap, TangentialUnloading};
use std::f64::consts::PI;

/// A LAMMPS normal model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Normal {
    /// `hooke k_n`, N/m.
    Hooke { k: f64 },
    /// `hertz k_n`, Pa (F = k_n sqrt(R*) d^(3/2)); `radius` is R*, m.
    Hertz { k: f64, radius: f64 },
}

/// A LAMMPS damping model (what the normal model's second argument means).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Damping {
    /// η_n = η_n0, N s/m.
    Velocity,
    /// The argument is e, mapped exactly (Tsuji's form for hertz, the linear oscillator's for hooke).
    CoeffRestitution,
    /// η_n = η_n0 a m*, with a = sqrt(R* d): η_n0 in 1/(s m).
    Viscoelastic,
}

impl Damping {
    pub fn name(self) -> &'static str {
        match self {
            Damping::Velocity => "velocity",
            Damping::CoeffRestitution => "coeff_restitution",
            Damping::Viscoelastic => "viscoelastic",
        }
    }
}

/// The tangential model of the `pair_coeff` line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Tangential {
    /// Frictionless: `linear_nohistory 0 0`.
    None,
    /// `mindlin k_t 0 mu` (F_t = −k_t a ξ, k_t in Pa; `mindlin_rescale/force` when the spring's force is rescaled
    /// as the contact unloads) or `linear_history k_t 0 mu` (N/m).
    Spring { mindlin: bool, rescale: bool, k: f64, mu: f64 },
}

/// LAMMPS' `pair_coeff` granular model of one pair of types.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Granular {
    pub normal: Normal,
    pub damping: Damping,
    pub tangential: Tangential,
    /// `limit_damping`: the normal force is clamped at zero.
    pub limit_damping: bool,
    /// m*, kg (what `coeff_restitution` and `viscoelastic` multiply by).
    pub mass: f64,
}

impl Granular {
    /// The arguments after `pair_coeff I J` (and after `wall/gran/region ... granular`), with the knob `p`.
    pub fn arguments(&self, p: f64) -> String {
        let normal = match self.normal {
            Normal::Hooke { k } => format!("hooke {} {}", number(k), number(p)),
            Normal::Hertz { k, .. } => format!("hertz {} {}", number(k), number(p)),
        };
        let tangential = match self.tangential {
            Tangential::None => "tangential linear_nohistory 0.0 0.0".to_string(),
            Tangential::Spring { mindlin, rescale, k, mu } => {
                format!("tangential {} {} 0.0 {}", spring_name(mindlin, rescale), number(k), number(mu))
            }
        };
        let limit = if self.limit_damping { " limit_damping" } else { "" };
        format!("{normal} {tangential} damping {}{limit}", self.damping.name())
    }

    /// The same contact as a law of this program.
    pub fn contact(&self, context: &Context, p: f64) -> ContactSpec {
        let separation = if self.limit_damping { Separation::Force } else { Separation::Penetration };
        let (law, damping) = match (self.normal, self.damping) {
            (Normal::Hooke { .. }, Damping::Velocity) => (LawKind::KelvinVoigt, p),
            (Normal::Hooke { k }, Damping::CoeffRestitution) => {
                (LawKind::KelvinVoigt, 2.0 * (k * self.mass).sqrt() * kelvin_voigt_zeta(p))
            }
            // (hooke with viscoelastic is not offered: its damping grows as sqrt(d), a law this program lacks.)
            (Normal::Hooke { .. }, Damping::Viscoelastic) => (LawKind::KelvinVoigt, f64::NAN),
            (Normal::Hertz { .. }, Damping::Velocity) => (LawKind::HertzDashpot, p),
            (Normal::Hertz { .. }, Damping::CoeffRestitution) => (LawKind::Tsuji, tsuji_damping(p)),
            (Normal::Hertz { k, .. }, Damping::Viscoelastic) => (LawKind::Brilliantov, 2.0 * self.mass * p / (3.0 * k)),
        };
        let mut spec = context.spec(law, separation);
        spec.damping = DampingSpec::Parameter(damping);
        if law == LawKind::KelvinVoigt {
            spec.exponent = 1.0;
            spec.exponent_given = None;
        }
        spec
    }
}

/// The tangential model's name: Mindlin's spring (its force rescaled as the contact unloads, or not) or a linear one.
fn spring_name(mindlin: bool, rescale: bool) -> &'static str {
    match (mindlin, rescale) {
        (true, true) => "mindlin_rescale/force",
        (true, false) => "mindlin",
        (false, _) => "linear_history",
    }
}

/// Tsuji's polynomial α(e), as LAMMPS' `damping tsuji` evaluates it (without the factor √2 of releases from 2 Sep
/// 2026 on).
pub fn tsuji_alpha(e: f64) -> f64 {
    let coefficients = [1.2728, -4.2783, 11.087, -22.348, 27.467, -18.022, 4.8218];
    coefficients.iter().rev().fold(0.0, |sum, c| sum * e + c)
}

/// The e of the exact Tsuji map at damping `a` (a < sqrt 5): the e a `coeff_restitution` contact is typed with.
pub fn nominal_for_tsuji(a: f64) -> Option<f64> {
    let beta = -a / 5f64.sqrt();
    (beta > -1.0 && beta <= 0.0).then(|| (beta * PI / (1.0 - beta * beta).sqrt()).exp())
}

struct Pair {
    granular: Granular,
    context: Context,
}

impl Mapping for Pair {
    fn contact(&self, p: f64) -> ContactSpec {
        self.granular.contact(&self.context, p)
    }

    fn parameters(&self, p: f64) -> Parameters {
        let g = &self.granular;
        let (model, k) = match g.normal {
            Normal::Hooke { k } => ("hooke", k),
            Normal::Hertz { k, .. } => ("hertz", k),
        };
        let damp = if g.damping == Damping::CoeffRestitution { "e" } else { "eta_n0" };
        let mut parameters = Parameters::default().with("normal", model).with("k_n", k).with(damp, p);
        parameters = parameters.with("damping", g.damping.name()).with("limit_damping", g.limit_damping);
        if let Tangential::Spring { mindlin, rescale, k, mu } = g.tangential {
            parameters = parameters.with("tangential", spring_name(mindlin, rescale)).with("k_t", k).with("mu", mu);
        }
        parameters.with("pair_coeff", format!("* * {}", g.arguments(p)))
    }

    fn snippet(&self, p: f64, dt: Option<f64>) -> String {
        let arguments = self.granular.arguments(p);
        let mut text = format!(
            "# {} in LAMMPS (impact translate); SI units\nunits si\natom_style sphere\ncomm_modify vel yes\n\
             pair_style granular\npair_coeff * * {arguments}\n",
            self.context.title()
        );
        if self.context.wall {
            let s = &self.context.setup;
            // The wall is body 2 (or 1); the region's inside is the sphere's side, against the normal from the sphere.
            let (point, normal) = if self.context.scene.bodies[1].is_immovable() {
                (s.positions[1], -s.normal)
            } else {
                (s.positions[0], s.normal)
            };
            let sphere = if self.context.scene.bodies[1].is_immovable() { s.positions[0] } else { s.positions[1] };
            text += &format!(
                "# the sphere touches the wall with its centre at ({}, {}, {}) (the scene's coordinates)\n",
                number(sphere.x + 0.0),
                number(sphere.y + 0.0),
                number(sphere.z + 0.0)
            );
            text += &format!(
                "region wall plane {} {} {} {} {} {} side in\nfix wall all wall/gran/region granular {arguments} \
                 region wall\n",
                number(point.x + 0.0),
                number(point.y + 0.0),
                number(point.z + 0.0),
                number(normal.x + 0.0),
                number(normal.y + 0.0),
                number(normal.z + 0.0)
            );
        }
        text += "fix integrate all nve/sphere\n";
        if let Some(dt) = dt {
            text += &format!("timestep {}\n", number(dt));
        }
        text
    }
}

/// The granular model of the scene's contact, its knob and the notes on what LAMMPS does differently.
pub fn granular(context: &Context) -> Result<(Granular, Knob, Vec<String>), TranslateError> {
    let law = &context.law;
    let mut notes = Vec::new();
    let limit_damping = context.scene.contact.separation == Separation::Force;
    let hertz = |context: &Context| -> Result<Normal, TranslateError> {
        match context.hertz_modulus() {
            Some(k) => Ok(Normal::Hertz { k, radius: context.radius.unwrap_or(f64::NAN) }),
            None => Err(TranslateError::bad(
                "bodies",
                "LAMMPS' hertz model needs the contact's effective radius R* (k_n = K / sqrt(R*)): two flat faces \
                 have none",
            )),
        }
    };
    let critical = 2.0 * context.mass * context.speed / context.setup.scales.length;
    let (normal, damping, knob) = match law.kind {
        LawKind::Hertz => (hertz(context)?, Damping::Velocity, Knob::Fixed(0.0)),
        LawKind::KelvinVoigt => match context.target {
            Some(_) => (Normal::Hooke { k: law.stiffness }, Damping::CoeffRestitution, Knob::Nominal),
            None => (Normal::Hooke { k: law.stiffness }, Damping::Velocity, Knob::Fixed(law.damping)),
        },
        LawKind::Tsuji => {
            let knob = match context.target {
                Some(_) => Knob::Nominal,
                None => Knob::Fixed(nominal_for_tsuji(law.damping).ok_or_else(|| {
                    TranslateError::bad(
                        "contact.damping",
                        format!(
                            "a = {} is at or beyond sqrt 5, where Tsuji's contact no longer rebounds at d = 0: \
                             LAMMPS' coeff_restitution has no e for it",
                            crate::units::short_outside(law.damping, |a| a < 5f64.sqrt())
                        ),
                    )
                })?),
            };
            (hertz(context)?, Damping::CoeffRestitution, knob)
        }
        LawKind::Brilliantov => {
            let normal = hertz(context)?;
            let Normal::Hertz { k, .. } = normal else { unreachable!("hertz() gives a Hertz model") };
            let eta = 3.0 * k * law.damping / (2.0 * context.mass);
            notes.push(format!(
                "damping viscoelastic is this program's brilliantov law with A = 2 m* eta_n0 / (3 k_n) (that is \
                 eta_n0 m* / (2 E*)): eta_n0 = {} 1/(s m) holds for this pair's m* = {}; another pair of a LAMMPS \
                 run, with another m*, has another A.",
                short(eta),
                crate::units::brief(context.mass, "kg")
            ));
            let knob = match context.target {
                Some(_) => Knob::Damping { scale: 3.0 * k * critical / (context.mass * context.speed) },
                None => Knob::Fixed(eta),
            };
            (normal, Damping::Viscoelastic, knob)
        }
        LawKind::HertzDashpot if law.exponent == 1.5 || law.exponent == 1.0 => {
            let normal = if law.exponent == 1.0 { Normal::Hooke { k: law.stiffness } } else { hertz(context)? };
            let knob = match context.target {
                Some(_) => Knob::Damping { scale: critical },
                None => Knob::Fixed(law.damping),
            };
            (normal, Damping::Velocity, knob)
        }
        _ if context.target.is_some() && context.hertzian() && law.kind != LawKind::Thornton => {
            notes.push(super::substituted(context, Peer::Lammps, "Tsuji's damping (coeff_restitution)"));
            (hertz(context)?, Damping::CoeffRestitution, Knob::Nominal)
        }
        kind => {
            return Err(cannot_express(
                Peer::Lammps,
                kind,
                "pair_style granular offers the hooke and hertz springs with a velocity, mass_velocity, \
                 viscoelastic, tsuji or coeff_restitution damping",
                "`hertz ... damping coeff_restitution` (this program's `tsuji`) or `damping viscoelastic` \
                 (`brilliantov`); a scene that asks for an e with a Hertz spring is tuned to it",
            ));
        }
    };
    if matches!(normal, Normal::Hertz { .. }) && damping == Damping::CoeffRestitution {
        let nominal = context.target.unwrap_or(1.0);
        if nominal < 1.0
            && let Some(old) = nominal_for_tsuji(tsuji_alpha(nominal))
        {
            notes.push(format!(
                "Use damping coeff_restitution, not damping tsuji: LAMMPS releases before 2 Sep 2026 (22 Jul 2025 \
                 among them) evaluate Tsuji's polynomial without its factor sqrt 2, so a nominal e = {} under \
                 damping tsuji gives e = {}.",
                short(nominal),
                crate::units::brief_digits(old, "", 4)
            ));
        }
    }
    let tangential = match context.setup.friction {
        None => Tangential::None,
        Some(friction) => {
            if context.scene.contact.friction_cap == FrictionCap::Compressive && law.kind.can_pull() {
                notes.push(
                    "LAMMPS caps friction at mu |F_n| even while a damped normal force pulls; the scene caps it at \
                     mu max(F_n, 0) (friction_cap = \"magnitude\" runs LAMMPS' cap here)."
                        .into(),
                );
            }
            notes.push(
                "LAMMPS' pair torque takes the lever r - d/2 while its slip takes the full radii (this program: r \
                 for both)."
                    .into(),
            );
            if friction.damping_ratio > 0.0 {
                notes.push(
                    "The scene's tangential dashpot is not carried over (LAMMPS' x_gamma,t scales the normal \
                     damping instead): the snippet sets x_gamma,t = 0."
                        .into(),
                );
            }
            let mindlin = friction.stiffness_exponent == 0.5;
            let k = match (mindlin, context.radius) {
                (true, Some(radius)) => friction.stiffness / radius.sqrt(),
                _ => friction.stiffness,
            };
            let rescale = context.scene.contact.tangential_unloading == TangentialUnloading::Rescale;
            Tangential::Spring { mindlin, rescale: mindlin && rescale, k, mu: friction.coefficient }
        }
    };
    if limit_damping {
        notes.push(
            "The scene separates where the force falls to zero: limit_damping clamps LAMMPS' normal force at zero \
             to do the same."
                .into(),
        );
    }
    if context.wall {
        notes.push(
            "fix wall/gran/region takes the wall as flat and immovable: R* is the sphere's radius and m* its mass, \
             as here."
                .into(),
        );
    }
    if context.dt.is_some() {
        notes.push(
            "LAMMPS' velocity Verlet damps with the half-step velocity: its e converges to the continuous one at \
             first order in dt."
                .into(),
        );
    }
    let granular = Granular { normal, damping, tangential, limit_damping, mass: context.mass };
    Ok((granular, knob, notes))
}

/// The plan for LAMMPS.
pub fn plan(context: &Context) -> Result<Plan, TranslateError> {
    let (granular, knob, notes) = granular(context)?;
    let law = match (granular.normal, granular.damping) {
        (Normal::Hooke { .. }, damping) => format!("pair_style granular: hooke, damping {}", damping.name()),
        (Normal::Hertz { .. }, damping) => format!("pair_style granular: hertz, damping {}", damping.name()),
    };
    Ok(Plan {
        law,
        mapping: Box::new(Pair { granular, context: context.clone() }),
        knob,
        notes,
        scheme: Peer::Lammps.scheme(),
    })
}
