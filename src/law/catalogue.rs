//! The closed set of contact laws, their names, formulas, units and sources.

/// Every contact law the simulator knows (docs/laws.md).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum LawKind {
    Hertz,
    KelvinVoigt,
    HuntCrossley,
    HerbertMcWhannell,
    LeeWang,
    LankaraniNikravesh,
    Gonthier,
    ZhiyingQishao,
    Flores,
    GharibHurmuzlu,
    HuGuo,
    CarvalhoMartins,
    Tsuji,
    Brilliantov,
    Thornton,
    HertzDashpot,
    Mujoco,
    AdamsImpact,
}

/// Laws that share one force expression and so one set of exact results.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// F = K d^n.
    Elastic,
    /// F = K d^n (1 + alpha d'): Hunt–Crossley and every law that only picks alpha differently.
    Hysteresis,
    /// F = k d + c d'.
    Linear,
    /// F = K d^(3/2) + a sqrt(m* K) d^(1/4) d'.
    Tsuji,
    /// F = K (d^(3/2) + (3/2) A d^(1/2) d').
    Viscoelastic,
    /// Hertz up to the yield penetration, then the plastic line tangent to it; unloading Hertzian from the dent
    /// with the enlarged radius of the deepest point reached (Thornton 1997). The force remembers that point.
    Plastic,
    /// F = K d^n + c d': a constant dashpot beside a power-law spring (the DEM codes' Hertz with a viscous
    /// damper). Its e depends on the approach speed unless n = 1.
    Dashpot,
    /// F = m* d(d) (k d(d) d + b d'), never pulling: MuJoCo's soft contact in its continuous-time limit, the
    /// impedance d(d) of `solimp` scaling a per-unit-mass spring and damper (k, b from `solref`).
    Impedance,
    /// F = K d^n + STEP(d, 0, 0, d_max, c_max) d', never pulling: ADAMS' IMPACT function, whose damping rises
    /// from zero as a cubic step over the first d_max of penetration.
    Ramp,
}

/// One row of the law table: what `impact models` prints.
pub struct LawInfo {
    pub kind: LawKind,
    /// Scene spelling.
    pub name: &'static str,
    pub family: Family,
    /// The force, as a formula.
    pub formula: &'static str,
    /// The damping-from-restitution map, as a formula.
    pub map: &'static str,
    /// Units of the scene's `damping` key for this law.
    pub damping_units: &'static str,
    /// Where the law (and its map) was published.
    pub source: &'static str,
}

const HYSTERESIS_FORCE: &str = "K d^n (1 + alpha d'), alpha = chi / v0";

/// The law table. Order is the order of docs/laws.md.
pub const LAWS: [LawInfo; 18] = [
    LawInfo {
        kind: LawKind::Hertz,
        name: "hertz",
        family: Family::Elastic,
        formula: "K d^n",
        map: "none (elastic, e = 1)",
        damping_units: "-",
        source: "Hertz (1882)",
    },
    LawInfo {
        kind: LawKind::KelvinVoigt,
        name: "kelvin-voigt",
        family: Family::Linear,
        formula: "k d + c d'",
        map: "zeta = -ln e / sqrt(pi^2 + ln^2 e), c = 2 zeta sqrt(k m*)",
        damping_units: "c in N s/m",
        source: "linear spring-dashpot; map exact for penetration separation",
    },
    LawInfo {
        kind: LawKind::HuntCrossley,
        name: "hunt-crossley",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = 3(1-e)/2",
        damping_units: "alpha in s/m",
        source: "Hunt & Crossley, J. Appl. Mech. 42 (1975)",
    },
    LawInfo {
        kind: LawKind::HerbertMcWhannell,
        name: "herbert-mcwhannell",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = 6(1-e)/((2e-1)^2 + 3)",
        damping_units: "alpha in s/m",
        source: "Herbert & McWhannell, J. Eng. Ind. 99 (1977)",
    },
    LawInfo {
        kind: LawKind::LeeWang,
        name: "lee-wang",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = 3(1-e)/4",
        damping_units: "alpha in s/m",
        source: "Lee & Wang, J. Mech. Transm. Autom. Des. 105 (1983)",
    },
    LawInfo {
        kind: LawKind::LankaraniNikravesh,
        name: "lankarani-nikravesh",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = 3(1-e^2)/4",
        damping_units: "alpha in s/m",
        source: "Lankarani & Nikravesh, J. Mech. Des. 112 (1990)",
    },
    LawInfo {
        kind: LawKind::Gonthier,
        name: "gonthier",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = (1-e^2)/e",
        damping_units: "alpha in s/m",
        source: "Gonthier et al., Multibody Syst. Dyn. 11 (2004)",
    },
    LawInfo {
        kind: LawKind::ZhiyingQishao,
        name: "zhiying-qishao",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = 3(1-e^2) exp(2(1-e))/4",
        damping_units: "alpha in s/m",
        source: "Zhiying & Qishao, Acta Mech. Sin. (2006)",
    },
    LawInfo {
        kind: LawKind::Flores,
        name: "flores",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = 8(1-e)/(5e)",
        damping_units: "alpha in s/m",
        source: "Flores et al., Mech. Mach. Theory 46 (2011)",
    },
    LawInfo {
        kind: LawKind::GharibHurmuzlu,
        name: "gharib-hurmuzlu",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = (1-e)/e",
        damping_units: "alpha in s/m",
        source: "Gharib & Hurmuzlu, J. Comput. Nonlinear Dyn. 7 (2012)",
    },
    LawInfo {
        kind: LawKind::HuGuo,
        name: "hu-guo",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi = 3(1-e)/(2e)",
        damping_units: "alpha in s/m",
        source: "Hu & Guo, Mech. Mach. Theory 85 (2015)",
    },
    LawInfo {
        kind: LawKind::CarvalhoMartins,
        name: "carvalho-martins",
        family: Family::Hysteresis,
        formula: HYSTERESIS_FORCE,
        map: "chi: root of ln((1+chi)/(1-e chi)) = chi (1+e) (exact)",
        damping_units: "alpha in s/m",
        source: "Carvalho & Martins, Mech. Mach. Theory 134 (2019)",
    },
    LawInfo {
        kind: LawKind::Tsuji,
        name: "tsuji",
        family: Family::Tsuji,
        formula: "K d^(3/2) + a sqrt(m* K) d^(1/4) d'",
        map: "a = -sqrt(5) ln e / sqrt(pi^2 + ln^2 e)",
        damping_units: "a, dimensionless",
        source: "Tsuji, Tanaka & Ishida, Powder Technol. 71 (1992)",
    },
    LawInfo {
        kind: LawKind::Brilliantov,
        name: "brilliantov",
        family: Family::Viscoelastic,
        formula: "K (d^(3/2) + (3/2) A d^(1/2) d')",
        map: "none (e depends on impact speed)",
        damping_units: "A in s",
        source: "Brilliantov et al., Phys. Rev. E 53 (1996); Kuwabara & Kono (1987)",
    },
    LawInfo {
        kind: LawKind::Thornton,
        name: "thornton",
        family: Family::Plastic,
        formula: "K d^(3/2) to d_y, then K d_y^(3/2) + (3/2) K d_y^(1/2) (d - d_y); unloading K_p (d - d_p)^(3/2)",
        map: "none (e = 1 below the yield speed, then falls with speed)",
        damping_units: "none: give yield_pressure p_y in Pa",
        source: "Thornton, J. Appl. Mech. 64 (1997)",
    },
    LawInfo {
        kind: LawKind::HertzDashpot,
        name: "hertz-dashpot",
        family: Family::Dashpot,
        formula: "K d^n + c d'",
        map: "n = 1: the Kelvin–Voigt map; otherwise the c for e at this contact's speed, found by simulation",
        damping_units: "c in N s/m",
        source: "the DEM codes' Hertz with a viscous dashpot (LAMMPS damping velocity / mass_velocity)",
    },
    LawInfo {
        kind: LawKind::Mujoco,
        name: "mujoco",
        family: Family::Impedance,
        formula: "m* d(d) (k d(d) d + b d'), never pulling; k, b from solref, d(d) from solimp",
        map: "none: give solref = [timeconst, dampratio] or [-stiffness, -damping] (per unit mass)",
        damping_units: "b m* in N s/m (from solref)",
        source: "MuJoCo (Todorov 2014; the solref/solimp reference of its documentation)",
    },
    LawInfo {
        kind: LawKind::AdamsImpact,
        name: "adams-impact",
        family: Family::Ramp,
        formula: "K d^n + STEP(d, 0, 0, d_max, c_max) d', never pulling",
        map: "none: give cmax (N s/m) and dmax (m)",
        damping_units: "c_max in N s/m",
        source: "MSC ADAMS, the IMPACT function",
    },
];

impl LawKind {
    /// This law's row of the table (the rows are in variant order; a test checks it). Constant time: the force
    /// evaluation asks for the family at every step.
    pub fn info(self) -> &'static LawInfo {
        &LAWS[self as usize]
    }

    /// Scene spelling, e.g. `"hunt-crossley"`.
    pub fn name(self) -> &'static str {
        self.info().name
    }

    /// The force family.
    pub fn family(self) -> Family {
        self.info().family
    }

    /// The law named `name` in a scene.
    pub fn from_name(name: &str) -> Option<LawKind> {
        LAWS.iter().find(|row| row.name == name).map(|row| row.kind)
    }

    /// All scene spellings, for error messages.
    pub fn names() -> Vec<&'static str> {
        LAWS.iter().map(|row| row.name).collect()
    }

    /// Whether the force can pull at all: a damping term that can outweigh the spring and is not cut where the sum
    /// would pull (the Hunt–Crossley family's K d^n (1 + c d') too, for a heavy damping given as such), so that a
    /// Coulomb limit of mu |Fn| differs from mu max(Fn, 0).
    pub fn can_pull(self) -> bool {
        matches!(
            self.family(),
            Family::Hysteresis | Family::Linear | Family::Tsuji | Family::Viscoelastic | Family::Dashpot
        )
    }

    /// Whether the force can turn tensile before the penetration returns to zero (docs/laws.md), so that the
    /// separation criterion matters.
    pub fn can_turn_tensile(self) -> bool {
        matches!(
            self.family(),
            Family::Linear | Family::Tsuji | Family::Viscoelastic | Family::Dashpot | Family::Impedance
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_in_variant_order_and_names_are_unique() {
        for (i, row) in LAWS.iter().enumerate() {
            assert_eq!(row.kind as usize, i, "row {i} ({})", row.name);
            assert_eq!(LawKind::from_name(row.name), Some(row.kind));
        }
    }
}
