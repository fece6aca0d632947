//! A sweep's row builds a light report: only the parts its columns read (`report::Sections`), on a worker's copy of
//! the typed scene without its names (only the tables its keys set copied back from row to row), checking only the
//! groups of value rules its varied keys reach. Its CSV line must be byte for
//! byte the line of the same point run the long way: the point written into the scene's TOML, read back, checked by
//! every rule, simulated with the whole report (every section filled), and its cells picked from that report. Here
//! over random scenes (central and oblique, sphere on wall and two spheres, with and without friction), random laws,
//! random points of random keys, and random sets of columns.

use impact::history::Recording;
use impact::impact::{Options, simulate_with};
use impact::law::LawKind;
use impact::report::Sections;
use impact::scene::Scene;
use impact::sweep::grid::{Axis, Grid, Spacing};
use impact::sweep::table::{Cell, Columns, RESULT_COLUMNS, Row, Status, VERDICT_COLUMNS, line};
use impact::sweep::{Scratch, Sweep};
use std::path::Path;

/// xorshift64: the draws of this test, the same on every run.
struct Draw(u64);

impl Draw {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
    fn below(&mut self, n: usize) -> usize {
        (self.next() % n as u64) as usize
    }
    /// Uniform in [low, high).
    fn between(&mut self, low: f64, high: f64) -> f64 {
        low + (high - low) * (self.next() >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// A random two-body scene: a sphere on a wall or two spheres, head-on or oblique, with or without friction.
fn scene(draw: &mut Draw, law: &str) -> String {
    let speed = draw.between(0.1, 3.0);
    let across = if draw.below(3) == 0 { draw.between(0.1, 1.0) } else { 0.0 };
    let friction = if across > 0.0 && draw.below(2) == 0 { "friction = 0.2\n" } else { "" };
    let radius = draw.between(0.003, 0.02);
    let first = format!(
        "title = \"a random scene\"\n[[bodies]]\nname = \"ball\"\nradius = {radius}\ndensity = 7850\nvelocity = \
         [{speed}, {across}, 0.0]\nyoung = 2e11\npoisson = 0.3\n\n"
    );
    let second = if draw.below(2) == 0 {
        "[[bodies]]\nname = \"wall\"\nradius = inf\nmass = inf\nvelocity = [0.0, 0.0, 0.0]\nyoung = inf\n\n".to_string()
    } else {
        format!(
            "[[bodies]]\nname = \"other\"\nradius = {}\nmass = {}\nvelocity = [-0.5, 0.0, 0.0]\nyoung = 7e10\npoisson \
             = 0.33\nposition = [{}, 0.0, 0.0]\n\n",
            radius,
            draw.between(0.01, 1.0),
            // Just touching the first, which is at the origin by default.
            2.0 * radius
        )
    };
    let position = if second.contains("position") { "position = [0.0, 0.0, 0.0]\n" } else { "" };
    let first = first.replace("poisson = 0.3\n", &format!("poisson = 0.3\n{position}"));
    format!("{first}{second}[contact]\nlaw = \"{law}\"\nrestitution = 0.7\n{friction}")
}

/// A random varied key with a few values, some of which break a rule.
fn axis(draw: &mut Draw) -> String {
    let keys = [
        "contact.restitution=0.05,0.5,0.95,1.5",
        "contact.damping=0.01,0.3,-1",
        "bodies.0.velocity.0=0.05,1,4",
        "bodies.0.radius=0.004,0.01,-0.01",
        "bodies.0.density=1000,7850",
        "solver.rtol=1e-8,1e-11",
        "contact.exponent=1.5,2",
    ];
    keys[draw.below(keys.len())].to_string()
}

/// A random set of columns: the defaults (empty), or a few result and verdict columns in a random order.
fn columns(draw: &mut Draw) -> Vec<String> {
    match draw.below(5) {
        0 => return Vec::new(),
        // The columns read from the report's optional sections (the bodies', the instantaneous impact's).
        1 => return ["spin_after_1", "max_velocity_difference", "spin_after_2"].map(String::from).to_vec(),
        _ => {}
    }
    let mut names: Vec<String> = Vec::new();
    for _ in 0..1 + draw.below(4) {
        let name = if draw.below(6) == 0 {
            VERDICT_COLUMNS[draw.below(VERDICT_COLUMNS.len())]
        } else {
            RESULT_COLUMNS[draw.below(RESULT_COLUMNS.len())]
        };
        if !names.iter().any(|n| n == name) {
            names.push(name.to_string());
        }
    }
    names
}

/// Row `index` the long way: written, read back, checked, simulated with every section of the report.
fn long_way(sweep: &Sweep, index: usize) -> Row {
    let mut row = sweep.evaluate_written(index);
    if matches!(row.status, Status::Error(_)) {
        return row;
    }
    let text = sweep.scene_text(index).unwrap();
    let scene = Scene::parse(&text, Path::new("light.toml")).unwrap();
    let columns = sweep.columns();
    let options = Options {
        recording: Recording::Off,
        reference: columns.reference(),
        quantities: columns.quantities(),
        idealisation: columns.verdicts(),
        sections: Sections::ALL,
    };
    let report = simulate_with(&scene, options).unwrap().report;
    // The whole report has its title and names.
    assert_eq!(report.title, "a random scene");
    assert_eq!(report.bodies[0].name, "ball");
    row.results = columns.pick(&report);
    row
}

#[test]
fn a_light_rows_line_is_the_full_reports_line_byte_for_byte() {
    let mut draw = Draw(0x5eed_1e55_c0ff_ee11);
    let laws = ["hunt-crossley", "hertz", "kelvin-voigt", "tsuji", "gonthier", "flores", "lankarani-nikravesh"];
    let (mut rows, mut errors, mut ran) = (0, 0, 0);
    for _ in 0..30 {
        let law = laws[draw.below(laws.len())];
        let text = scene(&mut draw, law);
        let axes = (0..1 + draw.below(2)).map(|_| axis(&mut draw)).collect::<Vec<_>>();
        let axes = if axes.len() == 2 && axes[0].split('=').next() == axes[1].split('=').next() {
            vec![axes[0].clone()]
        } else {
            axes
        };
        let grid = Grid::new(axes.iter().map(|spec| Axis::parse(spec, Spacing::Linear).unwrap()).collect()).unwrap();
        let listed = if draw.below(3) == 0 { vec![LawKind::Hertz, LawKind::Tsuji] } else { Vec::new() };
        let mut sweep = Sweep::new(Path::new("light.toml"), text.clone(), grid, listed).unwrap();
        let chosen = columns(&mut draw);
        if !chosen.is_empty() {
            sweep.select(Columns::parse(&chosen).unwrap());
        }
        // One worker's copies of the scene, kept from row to row as a sweep's worker keeps them, the rows taken
        // forwards and backwards (a row starts from what the previous one left).
        let mut scratch = Scratch::default();
        let forwards = 0..sweep.rows();
        for index in forwards.clone().chain(forwards.rev()) {
            let (light, long) = (sweep.evaluate_in(index, &mut scratch), long_way(&sweep, index));
            assert_eq!(line(&light), line(&long), "row {index} of {axes:?}, columns {chosen:?}\n{text}");
            rows += 1;
            errors += usize::from(matches!(light.status, Status::Error(_)));
            ran += usize::from(light.results.iter().any(|c| *c != Cell::Empty));
        }
    }
    // The draws reach rows that run and rows that break a rule.
    assert!(rows > 100 && errors > 5 && ran > 50, "{rows} rows, {errors} errors, {ran} run");
}

/// `impact sweep`'s own path: each worker writes its rows' lines straight into a block's text
/// (`Sweep::line_in`, `Sweep::stream_lines`). Its text must be byte for byte the lines of the rows run the long way,
/// in order, on two threads and on one, and the counts of how the rows ended those of the rows' statuses.
#[test]
fn the_streamed_lines_are_the_full_reports_lines() {
    let mut draw = Draw(0x0ddb_10c5_11e5);
    let laws = ["hunt-crossley", "hertz", "kelvin-voigt", "tsuji", "gonthier"];
    for case in 0..12 {
        let law = laws[draw.below(laws.len())];
        let text = scene(&mut draw, law);
        // The sweep of the damping alone (the setup's approach found once, the damping's rules alone) and others.
        let axes =
            if case % 3 == 0 { vec!["contact.damping=0.01,0.3,-1,2".to_string()] } else { vec![axis(&mut draw)] };
        let grid = Grid::new(axes.iter().map(|spec| Axis::parse(spec, Spacing::Linear).unwrap()).collect()).unwrap();
        let listed = if draw.below(3) == 0 { vec![LawKind::HuntCrossley, LawKind::Hertz] } else { Vec::new() };
        let mut sweep = Sweep::new(Path::new("light.toml"), text.clone(), grid, listed).unwrap();
        let chosen = columns(&mut draw);
        if !chosen.is_empty() {
            sweep.select(Columns::parse(&chosen).unwrap());
        }
        let rows: Vec<Row> = (0..sweep.rows()).map(|index| long_way(&sweep, index)).collect();
        let expected: String = rows.iter().map(line).collect();
        // One row at a time on one worker's scratch, backwards (a row starts from what the next one left).
        let mut scratch = Scratch::default();
        let mut backwards = Vec::new();
        for index in (0..sweep.rows()).rev() {
            let mut one = String::new();
            let status = sweep.line_in(index, &mut scratch, &mut one);
            assert_eq!(status, rows[index].status, "row {index} of {axes:?}\n{text}");
            backwards.push(one);
        }
        backwards.reverse();
        assert_eq!(backwards.concat(), expected, "{axes:?}, columns {chosen:?}\n{text}");
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let (mut streamed, mut counted, mut ok, mut stuck, mut first) = (String::new(), 0, 0, 0, None);
            sweep
                .stream_lines(
                    0..sweep.rows(),
                    &pool,
                    |_| {},
                    |lines| {
                        streamed.push_str(&lines.text);
                        counted += lines.rows;
                        ok += lines.ok;
                        stuck += lines.stuck;
                        first = first.take().or(lines.first);
                        Ok::<(), ()>(())
                    },
                )
                .unwrap();
            assert_eq!(streamed, expected, "{threads} threads, {axes:?}, columns {chosen:?}\n{text}");
            assert_eq!(counted, rows.len());
            assert_eq!(ok, rows.iter().filter(|row| row.status == Status::Ok).count());
            assert_eq!(stuck, rows.iter().filter(|row| row.status == Status::NotSeparated).count());
            assert_eq!(first, rows.first().map(|row| row.status.clone()));
        }
    }
}
