//! Contact geometry: effective mass, radius and modulus, the Hertz stiffness, the contact normal and the
//! free flight up to first contact (docs/scene.md), and how two bodies of a world meet ([`Meeting`]).

use crate::body::Body;
use nalgebra::Vector3;

/// Effective mass m* = m1 m2 / (m1 + m2) in kg, written as 1/(1/m1 + 1/m2) so that a wall (m = inf) gives m* = m1.
/// `None` when both bodies are immovable.
pub fn effective_mass(a: &Body, b: &Body) -> Option<f64> {
    let inverse = a.inverse_mass() + b.inverse_mass();
    (inverse > 0.0).then(|| 1.0 / inverse)
}

/// Effective radius R*, 1/R* = 1/r1 + 1/r2, in m; `None` for two flat bodies.
pub fn effective_radius(a: &Body, b: &Body) -> Option<f64> {
    let curvature = 1.0 / a.radius + 1.0 / b.radius;
    (curvature > 0.0).then(|| 1.0 / curvature)
}

/// Effective modulus E*, 1/E* = (1-nu1²)/E1 + (1-nu2²)/E2, in Pa. `None` when a material constant is missing
/// or both bodies are rigid.
pub fn effective_modulus(a: &Body, b: &Body) -> Option<f64> {
    let compliance = a.compliance()? + b.compliance()?;
    (compliance > 0.0).then(|| 1.0 / compliance)
}

/// Hertz stiffness K = (4/3) E* sqrt(R*) in N/m^(3/2) (docs/scene.md).
pub fn hertz_stiffness(effective_modulus: f64, effective_radius: f64) -> f64 {
    4.0 / 3.0 * effective_modulus * effective_radius.sqrt()
}

/// Where and when two bodies first touch, found in closed form from their straight-line flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FirstContact {
    /// Time of first contact, s (>= 0).
    pub time: f64,
    /// Unit normal at the contact, from body 1 to body 2.
    pub normal: Vector3<f64>,
}

/// Why two placed bodies do not give a usable first contact.
#[derive(Debug, Clone, PartialEq)]
pub enum PlacementProblem {
    /// They start overlapped by more than the tolerance; the overlap in m.
    Overlapping(f64),
    /// Their straight-line paths never bring them into contact.
    NeverMeet,
    /// Two sphere centres coincide, so no line of centres exists.
    CoincidentCentres,
}

/// How two bodies `i` and `j` meet: across the line of their centres, or a sphere against a flat face.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Meeting {
    /// Two spheres; `reach` = r_i + r_j, m.
    Spheres { reach: f64 },
    /// A sphere against a flat body's face; `face` is the unit face normal pointing into the sphere's side, `sign`
    /// +1 when the flat body is body `i` of the pair (the normal from i to j is the face's), -1 when it is `j`.
    Face { face: Vector3<f64>, radius: f64, sign: f64 },
}

impl Meeting {
    /// How bodies `a` (body `i`) and `b` (body `j`) meet, with their faces: a flat body's unit face normal, `None`
    /// for a sphere (a world scene's `faces`).
    pub fn between(a: &Body, face_a: Option<Vector3<f64>>, b: &Body, face_b: Option<Vector3<f64>>) -> Meeting {
        Meeting::of_radii(a.radius, face_a, b.radius, face_b)
    }

    /// How two contact spheres of radii `a` and `b` (m) meet, with their bodies' faces (`None` for a sphere).
    pub fn of_radii(a: f64, face_a: Option<Vector3<f64>>, b: f64, face_b: Option<Vector3<f64>>) -> Meeting {
        match (face_a, face_b) {
            (Some(face), _) => Meeting::Face { face, radius: b, sign: 1.0 },
            (_, Some(face)) => Meeting::Face { face, radius: a, sign: -1.0 },
            _ => Meeting::Spheres { reach: a + b },
        }
    }

    /// The lever arms (m) from the centres of bodies i and j (radii `radii`) to their contact point, for `relative` =
    /// x_j - x_i (m): the point divides the line of centres in the ratio of the radii (the arms add up to it, so two
    /// free spheres keep their angular momentum); on a face the sphere's arm is its radius along the normal, the flat
    /// body's none.
    pub fn lever_arms(&self, relative: &Vector3<f64>, radii: [f64; 2]) -> [Vector3<f64>; 2] {
        let (_, n) = self.penetration(relative);
        match *self {
            Meeting::Spheres { reach } => [relative * (radii[0] / reach), -relative * (radii[1] / reach)],
            Meeting::Face { sign, .. } if sign > 0.0 => [Vector3::zeros(), -n * radii[1]],
            Meeting::Face { .. } => [n * radii[0], Vector3::zeros()],
        }
    }

    /// The penetration (m, positive overlapping) and the unit normal from body i to body j, for `relative` =
    /// x_j - x_i (m).
    pub fn penetration(&self, relative: &Vector3<f64>) -> (f64, Vector3<f64>) {
        match *self {
            Meeting::Spheres { reach } => {
                let distance = relative.norm();
                (reach - distance, relative / distance)
            }
            // The sphere's height above the face: f·(x_sphere - x_face), which is sign · f·(x_j - x_i).
            Meeting::Face { face, radius, sign } => (radius - sign * face.dot(relative), face * sign),
        }
    }
}

impl Meeting {
    /// [`Meeting::penetration`] for `relative` = `start + moved` (m), where `start` is the relative position at some
    /// earlier instant and `moved` the small change since, without the rounding of their sum: the penetration as a
    /// smooth function of `moved`, and the distance of the centres (infinite on a face).
    ///
    /// The penetration of touching bodies is the small difference of two lengths of the size of their radii. Formed
    /// from the sum `start + moved`, it is rounded to a unit in the last place of the radii: about 1e-11 of a steel
    /// ball's resting overlap, in steps, as `moved` varies. An integrator's error estimate and an event's location
    /// read those steps as a rough force (docs/numerics.md#the-penetration-without-rounding). Here the large
    /// cancelling parts depend on `start` alone, so they are rounded the same way at every call; what varies with
    /// `moved` is formed from small numbers: for a face `(r - f·start) - f·moved`; for two spheres
    /// `(R² - |s|²  - (2 s·m + |m|²)) / (R + |s + m|)`, with `R² - |s|² = (R - |s|)(R + |s|)`.
    pub fn penetration_moved(&self, start: &Vector3<f64>, moved: &Vector3<f64>) -> (f64, Vector3<f64>, f64) {
        match *self {
            Meeting::Spheres { reach } => {
                let relative = start + moved;
                let distance = relative.norm();
                let from_start = start.norm();
                let change = moved.dot(&(start * 2.0 + moved));
                let penetration = ((reach - from_start) * (reach + from_start) - change) / (reach + distance);
                (penetration, relative / distance, distance)
            }
            Meeting::Face { face, radius, sign } => {
                let penetration = (radius - sign * face.dot(start)) - sign * face.dot(moved);
                (penetration, face * sign, f64::INFINITY)
            }
        }
    }
}

/// The slip of two bodies' contact points (m/s): the velocity of body i's point relative to body j's, across the unit
/// normal `normal`, for their `velocities`, angular velocities `spins` and lever arms `arms` (m, from each centre to
/// the contact point).
pub fn slip(
    normal: &Vector3<f64>,
    velocities: [Vector3<f64>; 2],
    spins: [Vector3<f64>; 2],
    arms: [Vector3<f64>; 2],
) -> Vector3<f64> {
    let point = velocities[0] + spins[0].cross(&arms[0]) - velocities[1] - spins[1].cross(&arms[1]);
    point - normal * point.dot(normal)
}

/// The lever arms of two bodies at first touch along the unit normal `normal` (body i to body j): each radius along
/// the normal towards the other, none for a flat body — rigid-body theory's arms.
pub fn touch_arms(a: &Body, b: &Body, normal: &Vector3<f64>) -> [Vector3<f64>; 2] {
    let arm = |body: &Body, sign: f64| if body.is_flat() { Vector3::zeros() } else { normal * (sign * body.radius) };
    [arm(a, 1.0), arm(b, -1.0)]
}

/// Relative tolerance (of the smaller radius) within which bodies count as just touching.
pub const TOUCH_TOLERANCE: f64 = 1e-12;

/// The gap or overlap (m) within which bodies `a` and `b` of a world, their centres (a flat body: a point of its face)
/// at `xa` and `xb`, count as touching: the rounding of their absolute coordinates — 64 units in the last place of
/// each body's radius plus its largest coordinate — and no less than the overlap a scene may start with
/// ([`TOUCH_TOLERANCE`] of the smaller radius). Below it a world cannot tell touching from apart.
pub fn touching_tolerance(a: &Body, xa: &Vector3<f64>, b: &Body, xb: &Vector3<f64>) -> f64 {
    let size = |body: &Body, x: &Vector3<f64>| (if body.is_flat() { 0.0 } else { body.radius }) + x.abs().max();
    (64.0 * f64::EPSILON * (size(a, xa) + size(b, xb))).max(TOUCH_TOLERANCE * a.radius.min(b.radius))
}

/// First contact of two placed bodies moving at constant velocity. `wall_normal` is the scene's normal,
/// used for the plane of a flat body. At most one body may be flat.
pub fn first_contact(a: &Body, b: &Body, wall_normal: &Vector3<f64>) -> Result<FirstContact, PlacementProblem> {
    let (xa, xb) = (a.position.unwrap_or_default(), b.position.unwrap_or_default());
    let separation = xb - xa;
    let relative_velocity = b.velocity - a.velocity;
    let smallest = a.radius.min(b.radius);
    let tolerance = TOUCH_TOLERANCE * smallest;
    if a.is_flat() || b.is_flat() {
        let sphere_radius = if a.is_flat() { b.radius } else { a.radius };
        let gap = separation.dot(wall_normal) - sphere_radius;
        if gap < -tolerance {
            return Err(PlacementProblem::Overlapping(-gap));
        }
        if gap <= tolerance {
            return Ok(FirstContact { time: 0.0, normal: *wall_normal });
        }
        let closing = -relative_velocity.dot(wall_normal);
        if closing <= 0.0 {
            return Err(PlacementProblem::NeverMeet);
        }
        return Ok(FirstContact { time: gap / closing, normal: *wall_normal });
    }
    let contact_distance = a.radius + b.radius;
    let distance = separation.norm();
    if distance == 0.0 {
        return Err(PlacementProblem::CoincidentCentres);
    }
    let gap = distance - contact_distance;
    if gap < -tolerance {
        return Err(PlacementProblem::Overlapping(-gap));
    }
    if gap <= tolerance {
        return Ok(FirstContact { time: 0.0, normal: separation / distance });
    }
    // |s + w t| = D: w² t² + 2 (s·w) t + (s² - D²) = 0; the earlier root is the first touch.
    let (w2, sw) = (relative_velocity.norm_squared(), separation.dot(&relative_velocity));
    let c = (distance - contact_distance) * (distance + contact_distance);
    let discriminant = sw * sw - w2 * c;
    if w2 == 0.0 || sw >= 0.0 || discriminant < 0.0 {
        return Err(PlacementProblem::NeverMeet);
    }
    // Stable form of the smaller root: t = c / (-sw + sqrt(disc)).
    let time = c / (-sw + discriminant.sqrt());
    let at_contact = separation + relative_velocity * time;
    Ok(FirstContact { time, normal: at_contact / at_contact.norm() })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A unit in the last place of `x`.
    fn ulp(x: f64) -> f64 {
        f64::from_bits(x.abs().to_bits() + 1) - x.abs()
    }

    /// The penetration's change as the bodies move by `moved` from `start` is, to first order, `-n·moved` (n the
    /// unit normal from i to j), with a second-order part below |moved|²/R: a change of 1e-15 m in a 20 mm pair must
    /// show as that, not in steps of an ulp of the radii (1.7e-18 m) as `R - |start + moved|` would give it.
    #[test]
    fn the_penetration_changes_smoothly_with_the_displacement() {
        let meetings = [
            (Meeting::Spheres { reach: 0.02 }, Vector3::new(0.3, -0.4, 0.866).normalize() * (0.02 - 8e-8)),
            (
                Meeting::Face { face: Vector3::new(0.0, 0.0, 1.0), radius: 0.01, sign: 1.0 },
                Vector3::new(0.02, 0.0, 0.00999992396),
            ),
            (
                Meeting::Face { face: Vector3::new(0.6, 0.0, 0.8), radius: 0.01, sign: -1.0 },
                Vector3::new(-0.006, 0.3, -0.0079999),
            ),
        ];
        for (meeting, start) in meetings {
            let (d0, n, _) = meeting.penetration_moved(&start, &Vector3::zeros());
            assert!(d0 > 0.0 && d0 < 1e-6, "{meeting:?}: an overlap of a resting contact, {d0}");
            for k in 1..=200 {
                let size = 1e-17 * k as f64;
                let moved = Vector3::new(0.3, -0.5, 0.81).normalize() * size;
                let (d, _, _) = meeting.penetration_moved(&start, &moved);
                let expected = -n.dot(&moved);
                let bound = 1e-9 * size + 8.0 * ulp(d0);
                assert!(
                    ((d - d0) - expected).abs() <= bound,
                    "{meeting:?}: moved {size:e} m: the penetration changed by {:e}, expected {expected:e}",
                    d - d0
                );
            }
        }
    }
}
