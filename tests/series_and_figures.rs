//! The views of one impact: the CSV time series and the figures, written completely or not at all.

mod common;

use common::binary::{Scratch, impact};
use std::path::Path;

/// Steel sphere (1 kg) on a wall at 2 m/s, exact Hunt–Crossley map for e = 0.8: the total impulse is
/// (1 + e) m* v0 = 1.8 * 1 * 2 = 3.6 N s.
const SCENE: &str = "title = \"series test\"\n[[bodies]]\nradius = 0.02\nmass = 1.0\nvelocity = [2.0, 0, 0]\n\
                     [[bodies]]\nradius = inf\nmass = inf\nvelocity = [0, 0, 0]\n\
                     [contact]\nlaw = \"carvalho-martins\"\nrestitution = 0.8\nstiffness = 1e9\n";
const TOTAL_IMPULSE: f64 = 3.6;

struct Series {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Series {
    fn read(path: &Path) -> Series {
        let text = std::fs::read_to_string(path).unwrap();
        let mut lines = text.lines();
        let header = lines.next().unwrap().split(',').map(String::from).collect();
        let rows = lines.map(|l| l.split(',').map(String::from).collect()).collect();
        Series { header, rows }
    }

    fn column(&self, name: &str) -> Vec<f64> {
        let i = self.header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
        self.rows.iter().map(|r| r[i].parse().unwrap()).collect()
    }
}

/// ∫ F dt by the trapezoid rule.
fn trapezoid(time: &[f64], force: &[f64]) -> f64 {
    time.windows(2).zip(force.windows(2)).map(|(t, f)| 0.5 * (f[0] + f[1]) * (t[1] - t[0])).sum()
}

#[test]
fn uniform_series_integrates_to_the_total_impulse() {
    let scratch = Scratch::new("uniform");
    let folder = scratch.path();
    std::fs::write(folder.join("s.toml"), SCENE).unwrap();
    let out = impact(folder, &["run", "s.toml", "--csv", "series.csv", "--samples", "4000"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let series = Series::read(&folder.join("series.csv"));
    assert_eq!(series.rows.len(), 4000);
    let (time, force) = (series.column("time_s"), series.column("force_N"));
    let step = time[1] - time[0];
    assert!(time.windows(2).all(|t| ((t[1] - t[0]) - step).abs() < 1e-9 * step), "uniform spacing");
    // Trapezoid error for a force ~ t^(3/2) at both ends: O(h^2.5) relative; 1e-6 at 4000 samples is generous.
    let impulse = trapezoid(&time, &force);
    assert!((impulse / TOTAL_IMPULSE - 1.0).abs() < 1e-6, "impulse {impulse}");
    // The last impulse sample is the integrated state itself.
    let last = *series.column("impulse_N_s").last().unwrap();
    assert!((last / TOTAL_IMPULSE - 1.0).abs() < 1e-9, "impulse state {last}");
    // First contact at zero penetration and closing at v0; separation at zero penetration leaving at e v0.
    let (penetration, rate) = (series.column("penetration_m"), series.column("penetration_rate_m_s"));
    assert!(penetration[0].abs() < 1e-15 && penetration.last().unwrap().abs() < 1e-12);
    assert!((rate[0] - 2.0).abs() < 1e-12 && (rate.last().unwrap() + 1.6).abs() < 1e-8);
}

#[test]
fn step_series_has_named_columns_phases_and_the_events() {
    let scratch = Scratch::new("steps");
    let folder = scratch.path();
    std::fs::write(folder.join("s.toml"), SCENE).unwrap();
    let out = impact(folder, &["run", "s.toml", "--csv", "series.csv", "--json"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    let report: serde_json::Value = serde_json::from_slice(&out.stdout).expect("stdout stays pure JSON");
    let series = Series::read(&folder.join("series.csv"));
    for name in [
        "time_s",
        "phase",
        "penetration_m",
        "penetration_rate_m_s",
        "force_N",
        "v1_normal_m_s",
        "v2_normal_m_s",
        "v1_tangential_x_m_s",
        "v2_tangential_z_m_s",
    ] {
        assert!(series.header.iter().any(|h| h == name), "missing column {name}: {:?}", series.header);
    }
    let phase = series.header.iter().position(|h| h == "phase").unwrap();
    let phases: Vec<&str> = series.rows.iter().map(|r| r[phase].as_str()).collect();
    let switch = phases.iter().position(|p| *p == "restitution").expect("a restitution phase");
    assert!(
        phases[..switch].iter().all(|p| *p == "compression") && phases[switch..].iter().all(|p| *p == "restitution")
    );
    let time = series.column("time_s");
    assert!(time.windows(2).all(|t| t[1] > t[0]), "strictly increasing time");
    // The located maximum compression is a row: its time, with zero penetration rate.
    let t0 = report["contact"]["max_compression_time"].as_f64().unwrap();
    let at = time.iter().position(|t| *t == t0).expect("maximum compression is recorded");
    assert!(series.column("penetration_rate_m_s")[at].abs() < 1e-12);
    // The body velocities are the impulse seen by each body: v1 = 2 - J, the wall stays at rest.
    let (v1, impulse, v2) =
        (series.column("v1_normal_m_s"), series.column("impulse_N_s"), series.column("v2_normal_m_s"));
    for i in 0..v1.len() {
        assert!((v1[i] - (2.0 - impulse[i])).abs() < 1e-12 && v2[i] == 0.0);
    }
    // Trapezoid over the integrator's own steps: coarse, but still the total impulse to a few 1e-3.
    let integral = trapezoid(&time, &series.column("force_N"));
    assert!((integral / TOTAL_IMPULSE - 1.0).abs() < 1e-2, "impulse {integral}");
}

/// PNG signature, and a size that only a drawn figure reaches.
fn assert_png(path: &Path) {
    let bytes = std::fs::read(path).unwrap_or_else(|_| panic!("{} missing", path.display()));
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n", "{} is a PNG", path.display());
    assert!(bytes.len() > 20_000, "{} is only {} bytes", path.display(), bytes.len());
}

fn assert_svg(path: &Path) {
    let text = std::fs::read_to_string(path).unwrap();
    assert!(text.starts_with("<svg") && text.contains("polyline") && text.contains("<text"), "{}", path.display());
    assert!(text.contains("contact force") || text.contains("normal velocity"), "labelled axes in {}", path.display());
}

#[test]
fn figures_are_rendered_as_png_and_svg() {
    let scratch = Scratch::new("figures");
    let folder = scratch.path();
    std::fs::write(folder.join("s.toml"), SCENE).unwrap();
    let out = impact(folder, &["run", "s.toml", "--plot", "figs"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    for name in ["force_time", "force_penetration", "velocities"] {
        assert_png(&folder.join("figs").join(format!("{name}.png")));
        assert_svg(&folder.join("figs").join(format!("{name}.svg")));
    }
    let left: Vec<_> = std::fs::read_dir(folder.join("figs")).unwrap().filter_map(|e| e.ok()).collect();
    assert_eq!(left.len(), 6, "exactly the six figure files, no temporaries");
}

#[test]
fn the_scene_output_table_asks_for_series_and_figures() {
    let scratch = Scratch::new("output-table");
    let folder = scratch.path();
    let scene = format!("{SCENE}[output]\nseries = \"out/s.csv\"\nplots = \"out/figs\"\n");
    std::fs::write(folder.join("s.toml"), scene).unwrap();
    let out = impact(folder, &["run", "s.toml"]);
    assert!(out.status.success(), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(folder.join("out/s.csv").is_file());
    assert_png(&folder.join("out/figs/force_time.png"));
}

#[test]
fn nothing_is_written_when_an_output_cannot_be() {
    let scratch = Scratch::new("unwritable");
    let folder = scratch.path();
    std::fs::write(folder.join("s.toml"), SCENE).unwrap();
    // A file where the figure folder should be: the figures cannot be written.
    std::fs::write(folder.join("blocked"), "not a folder").unwrap();
    let out = impact(folder, &["run", "s.toml", "--plot", "blocked/figs"]);
    assert_eq!(out.status.code(), Some(1), "{}", String::from_utf8_lossy(&out.stderr));
    assert!(String::from_utf8_lossy(&out.stderr).contains("blocked"));
    // And a bad scene writes no series.
    std::fs::write(folder.join("bad.toml"), SCENE.replace("0.8", "1.8")).unwrap();
    let out = impact(folder, &["run", "bad.toml", "--csv", "bad.csv"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(!folder.join("bad.csv").exists());
}

#[test]
fn samples_below_two_are_a_usage_error() {
    let scratch = Scratch::new("samples");
    let folder = scratch.path();
    std::fs::write(folder.join("s.toml"), SCENE).unwrap();
    let out = impact(folder, &["run", "s.toml", "--csv", "x.csv", "--samples", "1"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--samples"));
}

#[test]
fn samples_without_a_series_are_a_usage_error() {
    let scratch = Scratch::new("samples-alone");
    let folder = scratch.path();
    std::fs::write(folder.join("s.toml"), SCENE).unwrap();
    let out = impact(folder, &["run", "s.toml", "--samples", "100"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--csv"));
}
