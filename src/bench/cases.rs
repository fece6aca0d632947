//! The reference impacts of the study and their exact values, in the scaled units `m* = K = v0 = 1` (so that
//! `L = T = F0 = 1` and the exact references of [`crate::reference`] need no conversion).

use crate::fast::{Quantities, Request};
use crate::law::{ContactLaw, LawKind, Separation};
use crate::reference::{self, ContactReference};
use crate::scales::Scales;

/// One reference impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Case {
    /// `F = d^n (1 + x d')`: Hunt–Crossley with `alpha v0 = x`.
    HuntCrossley { x: f64, n: f64 },
    /// `F = d^n`: elastic Hertz.
    Hertz { n: f64 },
    /// `F = d + 2 zeta d'`.
    KelvinVoigt { zeta: f64, separation: Separation },
    /// `F = d^(3/2) + a d^(1/4) d'`, with the map's `a` for the nominal restitution `e`.
    Tsuji { e: f64, separation: Separation },
}

/// The reference impacts with an exact answer: Hunt–Crossley at `alpha v0` = 0.01, 0.5, 2, 10 and n = 1, 1.5, 2.2;
/// elastic Hertz at n = 1.5, 1, 2.2; Tsuji at e = 0.9, 0.5, 0.2 and Kelvin–Voigt at zeta = 0.1, 0.3 under both
/// separation criteria, and overdamped Kelvin–Voigt (zeta = 2) separating at zero force (at zero penetration it
/// never separates: no duration to measure).
pub fn reference_cases() -> Vec<Case> {
    let mut cases = Vec::new();
    for x in [0.01, 0.5, 2.0, 10.0] {
        for n in [1.0, 1.5, 2.2] {
            cases.push(Case::HuntCrossley { x, n });
        }
    }
    for n in [1.5, 1.0, 2.2] {
        cases.push(Case::Hertz { n });
    }
    for separation in [Separation::Penetration, Separation::Force] {
        for e in [0.9, 0.5, 0.2] {
            cases.push(Case::Tsuji { e, separation });
        }
        for zeta in [0.1, 0.3, 2.0] {
            if zeta < 1.0 || separation == Separation::Force {
                cases.push(Case::KelvinVoigt { zeta, separation });
            }
        }
    }
    cases
}

/// The cases of a quick study: one of each family, damped and elastic, both separation criteria.
pub fn quick_cases() -> Vec<Case> {
    vec![
        Case::HuntCrossley { x: 0.5, n: 1.5 },
        Case::Hertz { n: 1.5 },
        Case::KelvinVoigt { zeta: 0.3, separation: Separation::Force },
        Case::Tsuji { e: 0.5, separation: Separation::Penetration },
    ]
}

impl Case {
    /// A short name, e.g. `hunt-crossley x=0.5 n=1.5`, `kelvin-voigt zeta=0.3 F=0` (separation at zero force).
    pub fn name(&self) -> String {
        let end = |s: &Separation| if *s == Separation::Force { "F=0" } else { "d=0" };
        match self {
            Case::HuntCrossley { x, n } => format!("hunt-crossley x={x} n={n}"),
            Case::Hertz { n } => format!("hertz n={n}"),
            Case::KelvinVoigt { zeta, separation } => format!("kelvin-voigt zeta={zeta} {}", end(separation)),
            Case::Tsuji { e, separation } => format!("tsuji e={e} {}", end(separation)),
        }
    }

    /// The contact law in scaled units, and the separation criterion.
    pub fn law(&self) -> (ContactLaw, Separation) {
        let (kind, n, damping, separation) = match *self {
            Case::HuntCrossley { x, n } => (LawKind::HuntCrossley, n, x, Separation::Penetration),
            Case::Hertz { n } => (LawKind::Hertz, n, 0.0, Separation::Penetration),
            Case::KelvinVoigt { zeta, separation } => (LawKind::KelvinVoigt, 1.0, 2.0 * zeta, separation),
            Case::Tsuji { e, separation } => (LawKind::Tsuji, 1.5, reference::tsuji_damping(e), separation),
        };
        let tsuji_scale = if kind == LawKind::Tsuji { 1.0 } else { 0.0 };
        (
            ContactLaw {
                kind,
                stiffness: 1.0,
                exponent: n,
                damping,
                tsuji_scale,
                yield_penetration: f64::INFINITY,
                solimp: crate::law::NO_SOLIMP,
                ramp: f64::INFINITY,
            },
            separation,
        )
    }

    /// Whether the separation is on the force (for the laws that turn tensile) rather than the penetration.
    pub fn force_criterion(&self) -> bool {
        let (law, separation) = self.law();
        separation == Separation::Force && law.kind.can_turn_tensile()
    }

    /// The fast path's request at `tolerance`.
    pub fn request(&self, tolerance: f64) -> Request {
        let (law, separation) = self.law();
        Request {
            law,
            scales: Scales::new(1.0, 1.0, law.exponent, 1.0),
            separation,
            tolerance,
            quantities: Quantities::ALL,
        }
    }

    /// The scene of this impact for the general path: a unit mass at unit speed on a fixed wall, stiffness 1 (its
    /// radius, 1000, far above the unit penetration: it enters no force, only the rule that a dent stays below it),
    /// `[solver] method = "METHOD"` at `rtol` and `atol = rtol / 100` (the defaults' ratio; at least 1e-14, the
    /// smallest a scene takes).
    pub fn scene_text(&self, method: &str, rtol: f64) -> String {
        let (law, separation) = self.law();
        let contact = match self {
            Case::HuntCrossley { x, n } => {
                format!("law = \"hunt-crossley\"\nstiffness = 1\nexponent = {n}\ndamping = {x}")
            }
            Case::Hertz { n } => format!("law = \"hertz\"\nstiffness = 1\nexponent = {n}"),
            Case::KelvinVoigt { .. } => format!("law = \"kelvin-voigt\"\nstiffness = 1\ndamping = {:e}", law.damping),
            Case::Tsuji { .. } => format!("law = \"tsuji\"\nstiffness = 1\ndamping = {:e}", law.damping),
        };
        format!(
            "title = \"{}\"\n\n[[bodies]]\nradius = 1e3\nmass = 1\nvelocity = [1, 0, 0]\n\n[[bodies]]\nradius = inf\n\
             mass = inf\nvelocity = [0, 0, 0]\n\n[contact]\n{contact}\nseparation = \"{}\"\n\n[solver]\n\
             method = \"{method}\"\nrtol = {rtol:e}\natol = {:e}\n",
            self.name(),
            separation.name(),
            (rtol * 1e-2).max(1e-14)
        )
    }

    /// The exact values (scaled), from [`crate::reference`]: closed forms and quadratures independent of every
    /// integrator. `None` for a contact that never separates (none of [`reference_cases`]).
    pub fn exact(&self) -> Option<ContactReference> {
        match *self {
            Case::HuntCrossley { x, n } => Some(reference::hysteresis_contact(x, n)),
            Case::Hertz { n } => Some(reference::hertz_elastic(n)),
            Case::KelvinVoigt { zeta, separation } => reference::kelvin_voigt(zeta, separation),
            Case::Tsuji { e, separation } => reference::tsuji(reference::tsuji_damping(e), separation),
        }
    }

    /// The elastic contact time for this law's exponent, `tc` of Hertz's `F = d^n` (π for the linear spring): the
    /// DEM's time scale, which a fixed step divides into N steps per contact.
    pub fn elastic_duration(&self) -> f64 {
        reference::hertz_elastic(self.law().0.exponent).duration
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::Scene;
    use crate::setup::Setup;

    /// Every reference case's scene is the case itself: its law, in units where m* = K = v0 = 1 (L = T = F0 = 1),
    /// with an exact answer.
    #[test]
    fn the_scenes_are_the_cases_in_unit_scales() {
        let cases = reference_cases();
        assert_eq!(cases.len(), 26);
        for case in cases {
            let scene = Scene::parse(&case.scene_text("dop853", 1e-13), std::path::Path::new("case.toml")).unwrap();
            let setup = Setup::new(&scene).unwrap();
            let (law, separation) = case.law();
            assert_eq!(setup.law, law, "{}", case.name());
            assert_eq!(scene.contact.separation, separation);
            let s = setup.scales;
            for unit in [s.length, s.speed, s.time, s.force, s.impulse, s.energy] {
                assert!((unit - 1.0).abs() < 1e-15, "{}: {s:?}", case.name());
            }
            assert!(case.exact().is_some_and(|r| r.duration.is_finite()), "{}", case.name());
            assert_eq!(case.request(1e-10).law, law);
        }
    }
}
