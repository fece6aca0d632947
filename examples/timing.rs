use impact::impact::simulate;
use impact::scene::Scene;
use std::path::Path;
use std::time::Instant;
fn main() {
    let text = std::fs::read_to_string(std::env::args().nth(1).unwrap()).unwrap();
    let scene = Scene::parse(&text, Path::new("x.toml")).unwrap();
    let n = 2000;
    let t = Instant::now();
    let mut evals = 0;
    for _ in 0..n {
        evals = simulate(&scene, impact::history::Recording::Off).unwrap().report.solver.force_evaluations;
    }
    let per = t.elapsed().as_secs_f64() / n as f64;
    println!("{:.2} us per impact, {} evals, {:.1} ns/eval", per * 1e6, evals, per * 1e9 / evals as f64);
}
