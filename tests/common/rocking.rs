//! Housner's rocking block (docs/world.md#the-rocking-block) as the tests pose it: a steel box, h/b = 4, on two
//! 1 mm corner spheres, released at rest on its -x corner tilted 10° on a steel floor.

/// Half-width b, half-height h (m): h/b = 4.
pub const B: f64 = 0.05;
pub const H: f64 = 0.2;
/// The corner spheres' radius, m.
pub const R_CORNER: f64 = 0.001;
/// The block's depth across the rocking plane (m) and its density (steel, kg/m³).
pub const DEPTH: f64 = 0.05;
pub const DENSITY: f64 = 7850.0;
/// The release tilt, degrees.
pub const TILT: f64 = 10.0;
pub const G: f64 = 9.81;

/// The block's mass, kg.
pub fn mass() -> f64 {
    DENSITY * 2.0 * B * 2.0 * H * DEPTH
}

/// The box's principal inertias about its mass centre (x, y, z as the block stands level), kg m².
pub fn principal() -> [f64; 3] {
    let m = mass();
    [
        m * ((2.0 * H).powi(2) + DEPTH * DEPTH) / 12.0,
        m * ((2.0 * B).powi(2) + (2.0 * H).powi(2)) / 12.0,
        m * ((2.0 * B).powi(2) + DEPTH * DEPTH) / 12.0,
    ]
}

/// The mass centre's height at release, standing on the -x corner sphere tilted φ0: `r + b sin φ0 + (h - r) cos φ0`.
pub fn release_height() -> f64 {
    let phi = TILT.to_radians();
    R_CORNER + B * phi.sin() + (H - R_CORNER) * phi.cos()
}

fn exact(x: f64) -> String {
    format!("{x:?}")
}

/// The block's scene: its mass and inertia (a uniform box, turned by the tilt about y), its corner spheres, a floor
/// of the same `young`, and the `[contact]` lines given.
pub fn scene(young: f64, contact: &str, max_contacts: usize) -> String {
    let (mass, principal) = (mass(), principal());
    // Turned by -φ0 about y: the body's +x axis goes to (cos φ0, 0, sin φ0), its +x side up.
    let (c, s) = (TILT.to_radians().cos(), TILT.to_radians().sin());
    let turn = [[c, 0.0, -s], [0.0, 1.0, 0.0], [s, 0.0, c]];
    let entry = |i: usize, j: usize| (0..3).map(|k| turn[i][k] * principal[k] * turn[j][k]).sum::<f64>();
    let row = |i: usize| format!("[{}, {}, {}]", exact(entry(i, 0)), exact(entry(i, 1)), exact(entry(i, 2)));
    // A corner sphere's centre in the body, (±b, 0, -(h - r)), turned.
    let corner = |side: f64| [side * B * c + (H - R_CORNER) * s, 0.0, side * B * s - (H - R_CORNER) * c];
    let (plus, minus) = (corner(1.0), corner(-1.0));
    let centre = R_CORNER - minus[2];
    let sphere = |o: [f64; 3]| {
        format!(
            "[[bodies.spheres]]\noffset = [{}, 0.0, {}]\nradius = {}\n\n",
            exact(o[0]),
            exact(o[2]),
            exact(R_CORNER)
        )
    };
    format!(
        "title = \"rocking block\"\n[world]\ngravity = [0.0, 0.0, {}]\nmax_contacts = {max_contacts}\n\n\
         [[bodies]]\nname = \"block\"\nmass = {}\ninertia = [{}, {}, {}]\nposition = [0.0, 0.0, {}]\n\
         velocity = [0.0, 0.0, 0.0]\nyoung = {}\npoisson = 0.3\n\n{}{}\
         [[bodies]]\nname = \"floor\"\nmass = inf\nradius = inf\nposition = [0.0, 0.0, 0.0]\n\
         normal = [0.0, 0.0, 1.0]\nvelocity = [0.0, 0.0, 0.0]\nyoung = {}\npoisson = 0.3\n\n[contact]\n{contact}\n",
        exact(-G),
        exact(mass),
        row(0),
        row(1),
        row(2),
        exact(centre),
        exact(young),
        sphere(plus),
        sphere(minus),
        exact(young)
    )
}
