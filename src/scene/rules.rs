//! Every value rule of a scene, on the typed scene: number ranges, and the rules between keys (a density needs a
//! finite radius, a flat body cannot spin, each law's damping, stiffness and exponent...). One set of rules serves
//! both a scene file (after [`super::validate`] has converted it) and a sweep's point (a typed scene with values
//! set), so that both obey exactly the same rules. A broken rule names the key; the file and line are added by the
//! caller that knows them.

use super::{DampingSpec, Scene, SetupError, StiffnessSpec, TangentialStiffnessSpec};
use crate::body::Body;
use crate::law::damping::{MapError, check_restitution};
use crate::law::{Family, MAX_EXPONENT, MIN_EXPONENT};
use crate::units::{apart, brief, short, short_outside};
use nalgebra::{Matrix3, Vector3};

type Checked = Result<(), SetupError>;

fn fail(key: impl std::fmt::Display, message: impl Into<String>) -> Checked {
    Err(SetupError { key: key.to_string(), message: message.into() })
}

/// A body's key, written out only when a rule breaks (a sweep checks every point: most pass).
#[derive(Clone, Copy)]
struct BodyKey(usize, &'static str);

impl std::fmt::Display for BodyKey {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "bodies.{}.{}", self.0, self.1)
    }
}

/// What a number may be.
#[derive(Clone, Copy)]
pub(super) enum Allowed {
    /// Finite and > 0.
    Positive,
    /// > 0, `+inf` allowed (mass, radius, young).
    PositiveOrInfinite,
    /// Finite and >= 0.
    NonNegative,
    /// In [0, 1].
    Fraction,
    /// Finite.
    Any,
}

/// A value a user gave, as a message echoes it: in short form ("0.8", "1.5e-7", "inf"; six significant digits at
/// most, never three hundred), with more digits where six would read as a value that keeps the rule it breaks
/// (a restitution of 1.0000001 is "1.0000001", not "1").
fn shown_breaking(x: f64, keeps_rule: impl Fn(f64) -> bool) -> String {
    short_outside(x, keeps_rule)
}

/// A value a user gave, in short form ([`shown_breaking`] for a value whose rule is a range).
fn shown(x: f64) -> String {
    short(x)
}

/// Checks that `x` is what `range` allows; the message says what was expected and what was given.
pub(super) fn number(key: impl std::fmt::Display, x: f64, range: Allowed) -> Checked {
    if x.is_nan() {
        return fail(key, "NaN is not a valid value");
    }
    if x == f64::NEG_INFINITY {
        return fail(key, "-inf is not a valid value");
    }
    let allowed = |x: f64| match range {
        Allowed::Positive => x.is_finite() && x > 0.0,
        Allowed::PositiveOrInfinite => x > 0.0,
        Allowed::NonNegative => x.is_finite() && x >= 0.0,
        Allowed::Fraction => (0.0..=1.0).contains(&x),
        Allowed::Any => x.is_finite(),
    };
    if allowed(x) {
        return Ok(());
    }
    let expected = match range {
        Allowed::Positive => "a finite number > 0",
        Allowed::PositiveOrInfinite => "a number > 0 (or inf)",
        Allowed::NonNegative => "a finite number >= 0",
        Allowed::Fraction => "a number in [0, 1]",
        Allowed::Any => "a finite number",
    };
    fail(key, format!("expected {expected}, got {}", shown_breaking(x, allowed)))
}

/// Every component finite.
fn vector(key: impl std::fmt::Display + Copy, v: &Vector3<f64>) -> Checked {
    for (i, x) in v.iter().enumerate() {
        if !x.is_finite() {
            return fail(key, format!("component {i} must be a finite number, got {}", shown(*x)));
        }
    }
    Ok(())
}

/// An inertia tensor a rigid body can have: finite, symmetric, positive definite, and its principal moments each at
/// most the sum of the other two (a mass distribution's: I_xx = ∫(y² + z²) dm ≤ I_yy + I_zz).
fn inertia_tensor(key: impl std::fmt::Display + Copy, tensor: &Matrix3<f64>) -> Checked {
    if let Some(x) = tensor.iter().find(|x| !x.is_finite()) {
        return fail(key, format!("every entry must be a finite number (kg m²), got {}", shown(*x)));
    }
    let size = tensor.abs().max();
    for (i, j) in [(0, 1), (0, 2), (1, 2)] {
        if (tensor[(i, j)] - tensor[(j, i)]).abs() > 1e-12 * size {
            let (upper, lower) = apart(tensor[(i, j)], tensor[(j, i)], "kg m²");
            return fail(
                key,
                format!("an inertia tensor is symmetric: entry [{i}][{j}] = {upper} but [{j}][{i}] = {lower}"),
            );
        }
    }
    let moments = tensor.symmetric_eigenvalues();
    let smallest = moments.min();
    if smallest.is_nan() || smallest <= 0.0 || tensor.cholesky().is_none() {
        return fail(
            key,
            format!(
                "an inertia tensor is positive definite: its principal moments are {}, {}, {} kg m² (each must be > 0)",
                brief(moments[0], ""),
                brief(moments[1], ""),
                brief(moments[2], "")
            ),
        );
    }
    let sum = moments.sum();
    if let Some(m) = moments.iter().find(|&&m| m > (sum - m) * (1.0 + 1e-12)) {
        let (moment, others) = apart(*m, sum - m, "kg m²");
        return fail(
            key,
            format!(
                "no mass distribution has the principal moment {moment} larger than the other two together \
                 ({others}): each principal moment is at most the sum of the other two"
            ),
        );
    }
    Ok(())
}

/// The keys of the simulators' laws: `solref` and `solimp` for `mujoco` (in MuJoCo's own ranges), `cmax` and `dmax`
/// for `adams-impact`; each refused for another law.
fn check_simulator_keys(contact: &super::ContactSpec) -> Checked {
    let family = contact.law.family();
    let name = contact.law.name();
    let foreign = |key: &str, owner: &str| {
        fail(format!("contact.{key}"), format!("`{name}` does not take `{key}`: it belongs to law = \"{owner}\""))
    };
    match contact.solref {
        Some(_) if family != Family::Impedance => foreign("solref", "mujoco")?,
        None if family == Family::Impedance => fail(
            "contact.solref",
            "missing: `mujoco` needs solref = [timeconst, dampratio] (s, both > 0) or [-stiffness, -damping] (per unit \
             mass: 1/s², 1/s)",
        )?,
        Some([a, b]) => {
            for (i, x) in [a, b].into_iter().enumerate() {
                if !x.is_finite() {
                    return fail("contact.solref", format!("entry {i} must be a finite number, got {}", shown(x)));
                }
            }
            let standard = a > 0.0 && b > 0.0;
            let direct = a < 0.0 && b <= 0.0;
            if !standard && !direct {
                return fail(
                    "contact.solref",
                    format!(
                        "expected both entries > 0 ([timeconst, dampratio]) or the first < 0 and the second <= 0 \
                         ([-stiffness, -damping]), got [{}, {}]",
                        shown(a),
                        shown(b)
                    ),
                );
            }
        }
        None => {}
    }
    match contact.solimp {
        Some(_) if family != Family::Impedance => foreign("solimp", "mujoco")?,
        Some([low, high, width, middle, power]) => {
            let ranges: [(&str, f64, bool, &str); 5] = [
                ("dmin", low, (1e-4..=0.9999).contains(&low), "in [0.0001, 0.9999]"),
                ("dmax", high, (1e-4..=0.9999).contains(&high), "in [0.0001, 0.9999]"),
                ("width", width, width > 0.0 && width.is_finite(), "a finite width > 0 in m"),
                ("midpoint", middle, middle > 0.0 && middle < 1.0, "in (0, 1)"),
                ("power", power, (1.0..1e6).contains(&power), "at least 1"),
            ];
            if let Some((what, value, _, range)) = ranges.iter().find(|(_, _, ok, _)| !ok) {
                return fail(
                    "contact.solimp",
                    format!(
                        "{what} (entry {}) must be {range} (MuJoCo's range), got {}",
                        ranges.iter().position(|r| r.0 == *what).unwrap_or(0),
                        shown_breaking(*value, |x| match *what {
                            "dmin" | "dmax" => (1e-4..=0.9999).contains(&x),
                            "width" => x > 0.0 && x.is_finite(),
                            "midpoint" => x > 0.0 && x < 1.0,
                            _ => (1.0..1e6).contains(&x),
                        })
                    ),
                );
            }
        }
        None => {}
    }
    for (key, value, rule) in [("cmax", contact.cmax, Allowed::NonNegative), ("dmax", contact.dmax, Allowed::Positive)]
    {
        match value {
            Some(_) if family != Family::Ramp => foreign(key, "adams-impact")?,
            Some(x) => number(format!("contact.{key}"), x, rule)?,
            None if family == Family::Ramp => fail(
                format!("contact.{key}"),
                "missing: `adams-impact` needs `cmax` (full damping, N s/m) and `dmax` (the penetration at which it is \
                 reached, m)",
            )?,
            None => {}
        }
    }
    Ok(())
}

/// The scene's value rules, in the order a reader meets the keys (body 1, body 2, contact, solver).
pub fn check(scene: &Scene) -> Checked {
    check_groups(scene, RuleGroups::NONE)
}

/// The groups of [`check`]'s rules, in its order: each body's, the contact's, the solver's. The rules of a group read
/// only its own table, so a scene that differs from one passing a group only outside that table passes it too.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RuleGroups {
    pub bodies: [bool; 2],
    pub contact: bool,
    pub solver: bool,
    /// The contact's rules other than those that read its damping (`damping` or `restitution`, one value of the
    /// scene): a scene that differs from one passing the contact's rules only in its damping needs only
    /// [`check_damping`]'s. (Meaningful among groups to skip; `contact` covers it.)
    pub contact_but_damping: bool,
}

impl RuleGroups {
    pub const NONE: RuleGroups =
        RuleGroups { bodies: [false; 2], contact: false, solver: false, contact_but_damping: false };

    /// The groups whose rules `scene` passes.
    pub fn passed_by(scene: &Scene) -> RuleGroups {
        let contact = check_contact(&scene.contact).is_ok();
        RuleGroups {
            bodies: [0, 1].map(|i| check_body(i, &scene.bodies[i]).is_ok()),
            contact,
            solver: check_solver(&scene.solver).is_ok(),
            contact_but_damping: contact,
        }
    }
}

/// [`check`] without the groups in `skip`: for a scene known to pass them (a sweep's point, whose varied keys lie
/// outside the tables its base scene passed). The first broken rule, and so the error, is [`check`]'s.
pub fn check_groups(scene: &Scene, skip: RuleGroups) -> Checked {
    for (i, body) in scene.bodies.iter().enumerate() {
        if !skip.bodies[i] {
            check_body(i, body)?;
        }
    }
    if skip.contact_but_damping && !skip.contact {
        check_damping(&scene.contact)?;
    } else if !skip.contact {
        check_contact(&scene.contact)?;
    }
    if skip.solver { Ok(()) } else { check_solver(&scene.solver) }
}

fn check_solver(solver: &super::SolverSpec) -> Checked {
    for (key, x) in [("solver.rtol", solver.tolerances.rtol), ("solver.atol", solver.tolerances.atol)] {
        number(key, x, Allowed::Positive)?;
        let tolerance = |x: f64| (1e-14..=1e-2).contains(&x);
        if !tolerance(x) {
            return fail(key, format!("expected a tolerance in [1e-14, 0.01], got {}", shown_breaking(x, tolerance)));
        }
    }
    let method = solver.method.name();
    match (solver.method.is_fixed_step(), solver.dt) {
        (true, None) => fail(
            "solver.dt",
            format!(
                "method = \"{method}\" is a fixed-step scheme: give its time step `dt` (s), the step of the code \
                 whose e you want to see"
            ),
        ),
        (true, Some(dt)) => number("solver.dt", dt, Allowed::Positive),
        (false, Some(_)) => fail(
            "solver.dt",
            format!(
                "`dt` is the step of the fixed-step methods (\"verlet\", \"symplectic-euler\"); method = \
                 \"{method}\" chooses its own steps (set its tolerances with rtol and atol)"
            ),
        ),
        (false, None) => Ok(()),
    }
}

/// A world scene's rules (docs/scene.md#worlds): every body's, each contact table's (the keys renamed to where the
/// pair writes them), the `[world]` table's, and the rules between bodies that hold before anything moves — flat
/// bodies immovable with a face, Hertz and Mindlin stiffnesses available for every pair that can touch, and no two
/// bodies overlapping at the start by more than 1e-12 of the smaller radius.
pub fn check_world(scene: &super::WorldScene) -> Checked {
    for (i, body) in scene.bodies.iter().enumerate() {
        check_body(i, body)?;
        check_turning(i, body)?;
        if let Some(face) = scene.faces[i] {
            vector(BodyKey(i, "normal"), &face)?;
            if face.norm() == 0.0 {
                return fail(BodyKey(i, "normal"), "the face normal must be a non-zero vector");
            }
        }
        if body.is_flat() && !body.is_immovable() {
            return fail(BodyKey(i, "mass"), "a flat body (radius = inf) of a world run is immovable: give mass = inf");
        }
    }
    check_contact(&scene.contact)?;
    for (k, pair) in scene.pairs.iter().enumerate() {
        let (i, j) = (pair.bodies[0], pair.bodies[1]);
        check_contact(&pair.contact).map_err(|error| scene.rename(i, j, error))?;
        if !scene.interacts(i, j) {
            return fail(format!("pair.{k}.bodies"), "these two bodies never touch (both immovable, or both flat)");
        }
    }
    let world = &scene.world;
    vector("world.gravity", &world.gravity)?;
    if let Some(end) = world.end_time {
        number("world.end_time", end, Allowed::Positive)?;
    }
    if let Some(skin) = world.skin {
        number("world.skin", skin, Allowed::PositiveOrInfinite)?;
    }
    check_solver(&scene.solver)?;
    if scene.solver.method.is_fixed_step() {
        return fail(
            "solver.method",
            format!(
                "method = \"{}\" runs one normal contact (a scene of two bodies) at a fixed step; a world run \
                 (more bodies, [world] or [[pair]]) takes the accurate path: use \"auto\" or \"dop853\"",
                scene.solver.method.name()
            ),
        );
    }
    let n = scene.bodies.len();
    for i in 0..n {
        for j in i + 1..n {
            if scene.interacts(i, j) {
                check_pair_at_start(scene, i, j)?;
            }
        }
    }
    Ok(())
}

/// A rigid body of a world (docs/world.md#rigid-bodies): a clump gives its inertia (its spheres are not its mass
/// distribution), and a pivoted body moves as it turns about its pivot, `velocity = angular_velocity × (position -
/// pivot)`.
fn check_turning(i: usize, body: &Body) -> Checked {
    if !body.spheres.is_empty() && !body.is_immovable() && body.inertia_given.is_none() && body.inertia_tensor.is_none()
    {
        return fail(
            BodyKey(i, "inertia"),
            "missing: a body of [[bodies.spheres]] gives its `inertia` (kg m²: a number, three principal moments or a \
             3×3 tensor about its mass centre), since its contact spheres are not its mass distribution",
        );
    }
    if let (Some(pivot), Some(position)) = (body.pivot, body.position) {
        let turning = body.angular_velocity.cross(&(position - pivot));
        let size = body.velocity.norm().max(turning.norm());
        if (body.velocity - turning).norm() > 1e-9 * size {
            let (turning, velocity) = crate::units::apart_vectors(turning.as_slice(), body.velocity.as_slice(), "m/s");
            return fail(
                BodyKey(i, "velocity"),
                format!(
                    "a body turning about its pivot moves with angular_velocity × (position - pivot) = {turning}, \
                     not {velocity}"
                ),
            );
        }
    }
    Ok(())
}

/// The rules of one pair that hold before anything moves: a Hertz stiffness and (with friction) a Mindlin tangential
/// stiffness can be formed, and no two of their contact spheres start overlapped.
fn check_pair_at_start(scene: &super::WorldScene, i: usize, j: usize) -> Checked {
    let (a, b) = (&scene.bodies[i], &scene.bodies[j]);
    let (contact, _) = scene.contact_of(i, j);
    if contact.stiffness == StiffnessSpec::Hertz {
        for (k, body) in [(i, a), (j, b)] {
            match (body.young, body.poisson) {
                (None, _) => {
                    return fail(BodyKey(k, "young"), "stiffness = \"hertz\" needs `young` (Pa) for every body");
                }
                (Some(e), None) if e.is_finite() => {
                    return fail(BodyKey(k, "poisson"), "stiffness = \"hertz\" needs `poisson` for an elastic body");
                }
                _ => {}
            }
        }
        if a.young.is_some_and(f64::is_infinite) && b.young.is_some_and(f64::is_infinite) {
            return fail(
                BodyKey(j, "young"),
                format!("bodies {i} and {j} are both rigid (young = inf): their Hertz stiffness would be infinite"),
            );
        }
    }
    if contact.friction > 0.0 && contact.tangential_stiffness == super::TangentialStiffnessSpec::Mindlin {
        let key = |leaf: &str| {
            scene.rename(i, j, super::SetupError { key: format!("contact.{leaf}"), message: String::new() }).key
        };
        for (k, body) in [(i, a), (j, b)] {
            if body.young.is_some_and(f64::is_infinite) {
                continue;
            }
            if body.young.is_none() || body.poisson.is_none() {
                return fail(
                    key("tangential_stiffness"),
                    format!(
                        "the Mindlin tangential stiffness (the default with friction) needs `young` and `poisson` of \
                         every elastic body (bodies.{k} lacks them): give them, or a numeric `tangential_stiffness` in N/m"
                    ),
                );
            }
        }
        if a.young.is_some_and(f64::is_infinite) && b.young.is_some_and(f64::is_infinite) {
            return fail(
                key("tangential_stiffness"),
                format!("bodies {i} and {j} are both rigid (young = inf): their Mindlin stiffness would be infinite"),
            );
        }
    }
    for p in scene.sites_of(i) {
        for q in scene.sites_of(j) {
            let (first, second) = (scene.site(i, p), scene.site(j, q));
            let overlap = scene.site_meeting(&first, &second).penetration(&(second.centre - first.centre)).0;
            let smallest = first.radius.min(second.radius);
            if overlap > crate::geometry::TOUCH_TOLERANCE * smallest {
                let spheres = |k: usize, s: usize| {
                    if scene.bodies[k].spheres.is_empty() { String::new() } else { format!(" (sphere {s})") }
                };
                return fail(
                    BodyKey(j, "position"),
                    format!(
                        "bodies {i}{} and {j}{} start overlapped by {} (more than {} of the smaller radius)",
                        spheres(i, p),
                        spheres(j, q),
                        brief(overlap, "m"),
                        brief(crate::geometry::TOUCH_TOLERANCE, "")
                    ),
                );
            }
        }
    }
    Ok(())
}

fn check_body(i: usize, body: &Body) -> Checked {
    let key = |leaf: &'static str| BodyKey(i, leaf);
    for (s, sphere) in body.spheres.iter().enumerate() {
        vector(format_args!("bodies.{i}.spheres.{s}.offset"), &sphere.offset)?;
        number(format_args!("bodies.{i}.spheres.{s}.radius"), sphere.radius, Allowed::Positive)?;
    }
    number(key("radius"), body.radius, Allowed::PositiveOrInfinite)?;
    match body.density {
        Some(density) => {
            number(key("density"), density, Allowed::Positive)?;
            if body.radius.is_infinite() {
                return fail(
                    key("density"),
                    "`density` needs a finite radius: a flat body's mass would be infinite (give `mass`)",
                );
            }
            if !(body.mass.is_finite() && body.mass > 0.0) {
                return fail(
                    key("density"),
                    format!(
                        "the mass (4/3) pi r^3 density = {} of this radius and density is outside double precision: \
                         give `mass` or check the radius",
                        brief(body.mass, "kg")
                    ),
                );
            }
        }
        None => number(key("mass"), body.mass, Allowed::PositiveOrInfinite)?,
    }
    vector(key("velocity"), &body.velocity)?;
    if let Some(position) = &body.position {
        vector(key("position"), position)?;
    }
    vector(key("angular_velocity"), &body.angular_velocity)?;
    if body.angular_velocity != Vector3::zeros() && body.radius.is_infinite() {
        return fail(key("angular_velocity"), "a flat body (radius = inf) cannot spin: use [0, 0, 0] or leave it out");
    }
    if let Some(inertia) = body.inertia_given {
        number(key("inertia"), inertia, Allowed::Positive)?;
        let why = if body.mass.is_infinite() {
            Some("an immovable body (mass = inf) does not rotate")
        } else if body.radius.is_infinite() {
            Some("a flat body (radius = inf) does not rotate")
        } else {
            None
        };
        if let Some(why) = why {
            return fail(key("inertia"), format!("{why}: leave `inertia` out"));
        }
    }
    if let Some(tensor) = &body.inertia_tensor {
        inertia_tensor(key("inertia"), tensor)?;
        if body.mass.is_infinite() || body.radius.is_infinite() {
            let why =
                if body.mass.is_infinite() { "an immovable body (mass = inf)" } else { "a flat body (radius = inf)" };
            return fail(key("inertia"), format!("{why} does not rotate: leave `inertia` out"));
        }
    }
    if body.contact_offset != Vector3::zeros() {
        vector(key("contact_offset"), &body.contact_offset)?;
        if body.radius.is_infinite() {
            return fail(
                key("contact_offset"),
                "a flat body (radius = inf) has no contact sphere to offset: leave `contact_offset` out",
            );
        }
    }
    if let Some(pivot) = &body.pivot {
        vector(key("pivot"), pivot)?;
        if body.mass.is_infinite() {
            return fail(key("pivot"), "an immovable body (mass = inf) is fixed already: leave `pivot` out");
        }
        if body.radius.is_infinite() {
            return fail(key("pivot"), "a flat body (radius = inf) does not rotate: leave `pivot` out");
        }
    }
    if let Some(young) = body.young {
        number(key("young"), young, Allowed::PositiveOrInfinite)?;
    }
    if let Some(stress) = body.yield_stress {
        number(key("yield_stress"), stress, Allowed::PositiveOrInfinite)?;
    }
    if let Some(nu) = body.poisson {
        number(key("poisson"), nu, Allowed::Any)?;
        let poisson = |nu: f64| nu > -1.0 && nu <= 0.5;
        if !poisson(nu) {
            return fail(
                key("poisson"),
                format!("expected a number in (-1, 0.5], got {}", shown_breaking(nu, poisson)),
            );
        }
    }
    Ok(())
}

/// The exponent n of K d^n inside the range the laws' physics supports, [`MIN_EXPONENT`] to [`MAX_EXPONENT`]: from a
/// flat punch's 1 through Hertz's 3/2 and a cone's 2 to the fits of soft and rough contacts (docs/laws.md#which-exponents).
fn exponent_in_range(n: f64) -> Checked {
    let range = MIN_EXPONENT..=MAX_EXPONENT;
    if range.contains(&n) {
        return Ok(());
    }
    // (3.0001 in six digits would read "3": a number just outside the range keeps the digits that put it there.)
    let got = short_outside(n, |shown| range.contains(&shown));
    fail(
        "contact.exponent",
        format!(
            "exponent must be between {MIN_EXPONENT} and {MAX_EXPONENT}, got {got} (1 is a flat punch, 3/2 Hertz's \
             sphere, 2 a cone; fits of soft and rough contacts reach 3: docs/laws.md#which-exponents)"
        ),
    )
}

/// The contact's rules that read its damping (`damping` or `restitution`), in [`check_contact`]'s order: the
/// value's range, then whether the law takes it. The other contact rules read no damping.
pub fn check_damping(contact: &super::ContactSpec) -> Checked {
    check_damping_value(contact)?;
    check_damping_for_law(contact)
}

/// The damping's (or restitution's) range.
fn check_damping_value(contact: &super::ContactSpec) -> Checked {
    match contact.damping {
        DampingSpec::Restitution(e) => number("contact.restitution", e, Allowed::Fraction),
        DampingSpec::Parameter(c) => number("contact.damping", c, Allowed::NonNegative),
        DampingSpec::None => Ok(()),
    }
}

/// Whether the law takes the damping (or restitution) given, or needs one that is not.
fn check_damping_for_law(contact: &super::ContactSpec) -> Checked {
    let law = contact.law;
    let name = law.name();
    match (law.family(), contact.damping) {
        (Family::Elastic | Family::Plastic | Family::Impedance | Family::Ramp, DampingSpec::None) => {}
        (Family::Impedance, DampingSpec::Restitution(_)) => fail(
            "contact.restitution",
            "`mujoco` takes its damping from `solref`, as MuJoCo does: give solref = [timeconst, dampratio] (`impact \
             translate SCENE --to mujoco` finds the one for an e)",
        )?,
        (Family::Impedance, DampingSpec::Parameter(_)) => fail(
            "contact.damping",
            "`mujoco` takes its damping from `solref` = [timeconst, dampratio] or [-stiffness, -damping]",
        )?,
        (Family::Ramp, DampingSpec::Restitution(_)) => fail(
            "contact.restitution",
            "`adams-impact` takes its damping from `cmax` (N s/m) and `dmax` (m), as ADAMS does",
        )?,
        (Family::Ramp, DampingSpec::Parameter(_)) => fail(
            "contact.damping",
            "`adams-impact` takes its damping from `cmax` (N s/m) and `dmax` (m), as ADAMS does",
        )?,
        (Family::Plastic, DampingSpec::Parameter(_)) => fail(
            "contact.damping",
            "`thornton` takes no damping: its loss is the plastic dent, set by `yield_pressure` (or the bodies' \
             `yield_stress`)",
        )?,
        (Family::Plastic, DampingSpec::Restitution(_)) => fail(
            "contact.restitution",
            "`thornton` takes no `restitution`: its e follows from the impact speed and `yield_pressure` (or the \
             bodies' `yield_stress`)",
        )?,
        (Family::Elastic, DampingSpec::Parameter(_)) => {
            fail("contact.damping", "the elastic law `hertz` takes no damping")?
        }
        (Family::Viscoelastic, DampingSpec::Restitution(_)) => fail(
            "contact.restitution",
            "`brilliantov` takes no `restitution` (its e depends on impact speed): give `damping` A in s",
        )?,
        (_, DampingSpec::None) => fail(
            "contact.restitution",
            format!("missing: `{name}` needs `restitution` (nominal e) or `damping` ({})", law.info().damping_units),
        )?,
        (_, DampingSpec::Parameter(_)) => {}
        (_, DampingSpec::Restitution(e)) => match check_restitution(law, e) {
            Ok(()) => {}
            Err(MapError::NoMap) => fail(
                "contact.restitution",
                format!(
                    "`{name}` is elastic: restitution must be 1 (or left out), got {}",
                    shown_breaking(e, |e| e == 1.0)
                ),
            )?,
            Err(MapError::UndefinedAtZero) => {
                fail("contact.restitution", format!("the map of `{name}` ({}) is undefined at e = 0", law.info().map))?
            }
        },
    }
    Ok(())
}

fn check_contact(contact: &super::ContactSpec) -> Checked {
    let law = contact.law;
    let name = law.name();
    check_damping_value(contact)?;
    if let Some(pressure) = contact.yield_pressure {
        number("contact.yield_pressure", pressure, Allowed::PositiveOrInfinite)?;
        if law.family() != Family::Plastic {
            return fail(
                "contact.yield_pressure",
                format!("`{name}` does not yield: `yield_pressure` belongs to law = \"thornton\""),
            );
        }
    }
    check_simulator_keys(contact)?;
    check_damping_for_law(contact)?;
    if let StiffnessSpec::Value(k) = contact.stiffness {
        number("contact.stiffness", k, Allowed::Positive)?;
    }
    if let Some(n) = contact.exponent_given {
        number("contact.exponent", n, Allowed::Positive)?;
        exponent_in_range(n)?;
    }
    let exponent = contact.exponent_given;
    let family = law.family();
    if matches!(family, Family::Tsuji | Family::Viscoelastic | Family::Plastic) && exponent.is_some() {
        return fail("contact.exponent", format!("`{name}` fixes the exponent at 3/2: leave `exponent` out"));
    }
    if family == Family::Impedance {
        if exponent.is_some() {
            return fail(
                "contact.exponent",
                "`mujoco` is linear in the penetration (its `solref` spring): leave `exponent` out",
            );
        }
        if let StiffnessSpec::Value(_) = contact.stiffness {
            return fail("contact.stiffness", "`mujoco` takes its stiffness from `solref`: leave `stiffness` out");
        }
    }
    if family == Family::Linear {
        if contact.stiffness == StiffnessSpec::Hertz {
            return fail("contact.stiffness", "`kelvin-voigt` needs a numeric `stiffness` k in N/m");
        }
        if exponent.is_some_and(|n| n != 1.0) {
            return fail("contact.exponent", "`kelvin-voigt` is linear: `exponent` must be 1 (or left out)");
        }
    } else if contact.stiffness == StiffnessSpec::Hertz && exponent.is_some_and(|n| n != 1.5) {
        return fail(
            "contact.exponent",
            "stiffness = \"hertz\" fixes the exponent at 1.5: give a numeric stiffness for another",
        );
    }
    number("contact.friction", contact.friction, Allowed::NonNegative)?;
    if let TangentialStiffnessSpec::Value(k) = contact.tangential_stiffness {
        number("contact.tangential_stiffness", k, Allowed::Positive)?;
    }
    number("contact.tangential_damping", contact.tangential_damping, Allowed::NonNegative)?;
    if let Some(normal) = &contact.normal_given {
        vector("contact.normal", normal)?;
        let length = normal.norm();
        if length == 0.0 || !length.is_finite() {
            return fail("contact.normal", "the normal must be a non-zero vector");
        }
    }
    Ok(())
}
