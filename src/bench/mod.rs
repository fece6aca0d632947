//! The work–precision study (`impact bench`, docs/numerics.md#the-work-precision-study): every method on
//! reference impacts with exact answers, the largest relative error over the measured quantities against the time
//! per impact.
//!
//! * Cases ([`cases`]): exact Hunt–Crossley at several `alpha v0` and exponents, elastic Hertz, Tsuji and
//!   Kelvin–Voigt under both separation criteria, each in the scaled units `m* = K = v0 = 1` (so `L = T = F0 = 1`).
//! * Methods ([`Method`]): the Taylor fast path ([`crate::fast`]) and the general path with `ode_solvers`' Dop853 or
//!   Dopri5 (the simulator's own adapter and event location) over a sweep of tolerances; the fixed-step baselines
//!   ([`baselines`]): RK4 with events located on Hermite interpolants, and velocity Verlet as DEM codes run it, at N
//!   steps per contact.
//! * Error ([`Measured::errors`]): relative, over e, the maximum penetration, the time of maximum compression, the
//!   duration, the peak force and both impulses; the deformation impulse's error is V0's relative to the approach
//!   speed (`V0 = v0 - Jd/m*` for the relative motion).
//! * Time ([`median_seconds`]): only the integration and the event location (the outcome), never the report or
//!   the exact references; the median over batches of the mean time of one impact, on one thread.

pub mod baselines;
pub mod cases;
pub mod oblique;
pub mod worlds;

use crate::fast::{Quantities, Request};
use crate::reference::ContactReference;
use crate::scene::Scene;
use crate::setup::Setup;
pub use cases::{Case, quick_cases, reference_cases};
use std::fmt::Write as _;
use std::hint::black_box;
use std::path::Path;
use std::time::{Duration, Instant};

/// What one impact measured, scaled (`m* = K = v0 = 1`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Measured {
    /// e: the separation speed over the approach speed.
    pub restitution: f64,
    /// Maximum penetration.
    pub max_penetration: f64,
    /// Time of maximum compression, since first contact.
    pub max_compression_time: f64,
    /// Contact duration.
    pub duration: f64,
    /// Largest compressive force.
    pub peak_force: f64,
    /// Impulse from first contact to maximum compression (exactly `m* v0`).
    pub deformation_impulse: f64,
    /// Impulse from maximum compression to separation (exactly `e m* v0`).
    pub restitution_impulse: f64,
}

/// The measured quantities, in the order of [`Measured::errors`] (and of the CSV's `error_*` columns).
pub const QUANTITIES: [&str; 7] = ["e", "dmax", "t0", "tc", "fmax", "jd", "jr"];

impl Measured {
    /// The relative error of each of [`QUANTITIES`] against the exact values. `Jd`'s is V0's relative to the
    /// approach speed: the relative velocity at maximum compression is `v0 - Jd/m*`, exactly zero.
    pub fn errors(&self, exact: &ContactReference) -> [f64; 7] {
        let relative = |got: f64, want: f64| ((got - want) / want).abs();
        let e = exact.restitution;
        [
            relative(self.restitution, e),
            relative(self.max_penetration, exact.max_penetration),
            relative(self.max_compression_time, exact.max_compression_time),
            relative(self.duration, exact.duration),
            relative(self.peak_force, exact.max_force),
            relative(self.deformation_impulse, 1.0),
            relative(self.restitution_impulse, e),
        ]
    }

    /// The largest of [`Measured::errors`] (infinite if any is not a number).
    pub fn error(&self, exact: &ContactReference) -> f64 {
        largest(&self.errors(exact))
    }
}

/// The largest of some errors; infinite if one is not a number.
fn largest(errors: &[f64]) -> f64 {
    errors.iter().fold(0.0, |worst, &e| if e.is_nan() { f64::INFINITY } else { worst.max(e) })
}

/// A method of the study.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Method {
    /// The Taylor-series fast path ([`crate::fast::simulate_normal`]) at a tolerance.
    Taylor,
    /// The Taylor integration asked for the motion alone ([`crate::fast::Quantities::MOTION`]): measured on e, the
    /// maximum penetration and both impulses (V0), not on the times or the peak force.
    TaylorMotion,
    /// The hysteresis family's exact first integral ([`crate::fast::simulate_normal`] asked for everything but the
    /// time: what a sweep writing e, the impulses or the peak force computes for these laws), on the Hunt–Crossley
    /// and Hertz cases alone: measured on e, the maximum penetration, the peak force and both impulses.
    FirstIntegral,
    /// The same asked for every quantity ([`crate::fast::simulate_first_integral`]): the times by quadrature over the
    /// first integral ([`crate::fast::first_integral_times`]), on the Hunt–Crossley and Hertz cases alone; measured
    /// on every quantity. (A run's own path integrates instead: this was measured slower for a damped law.)
    FirstIntegralTimed,
    /// The general path with Dop853 at `rtol` (`atol = rtol / 100`).
    Dop853,
    /// The general path with Dopri5 at `rtol` (`atol = rtol / 100`).
    Dopri5,
    /// [`baselines::rk4`] at N steps per contact.
    Rk4,
    /// [`baselines::verlet`] at N steps per contact.
    Verlet,
}

impl Method {
    pub const ALL: [Method; 8] = [
        Method::Taylor,
        Method::TaylorMotion,
        Method::FirstIntegral,
        Method::FirstIntegralTimed,
        Method::Dop853,
        Method::Dopri5,
        Method::Rk4,
        Method::Verlet,
    ];

    /// The name in the CSV.
    pub fn name(self) -> &'static str {
        match self {
            Method::Taylor => "taylor",
            Method::TaylorMotion => "taylor-motion",
            Method::FirstIntegral => "first-integral",
            Method::FirstIntegralTimed => "first-integral-timed",
            Method::Dop853 => "dop853",
            Method::Dopri5 => "dopri5",
            Method::Rk4 => "rk4",
            Method::Verlet => "verlet",
        }
    }

    /// What the method is, for the figure's legend.
    pub fn label(self) -> &'static str {
        match self {
            Method::Taylor => "Taylor series, regularised (fast path)",
            Method::TaylorMotion => "the same, the motion alone (error over e, dmax, V0, Jr)",
            Method::FirstIntegral => "first integral, Hunt-Crossley and Hertz (e, dmax, Fmax, V0, Jr)",
            Method::FirstIntegralTimed => "the same with its times by quadrature (every quantity)",
            Method::Dop853 => "Dop853 (ode_solvers), events re-stepped",
            Method::Dopri5 => "Dopri5 (ode_solvers), events re-stepped",
            Method::Rk4 => "RK4, fixed step, events located",
            Method::Verlet => "velocity Verlet (DEM), events at the step past",
        }
    }

    /// Which of [`QUANTITIES`] the method measures (the motion alone leaves out the times and the peak force).
    pub fn measures(self) -> [bool; 7] {
        match self {
            Method::TaylorMotion => [true, true, false, false, false, true, true],
            Method::FirstIntegral => [true, true, false, false, true, true, true],
            _ => [true; 7],
        }
    }

    /// Whether the method runs `case` (the first integral answers for the hysteresis family alone).
    pub fn covers(self, case: &Case) -> bool {
        !matches!(self, Method::FirstIntegral | Method::FirstIntegralTimed)
            || matches!(case, Case::HuntCrossley { .. } | Case::Hertz { .. })
    }
}

/// A method's setting: a tolerance (adaptive methods) or N steps per contact (fixed-step ones).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Setting {
    Tolerance(f64),
    Steps(u32),
}

impl Setting {
    /// The range of some settings of one kind, e.g. `tol 1e-4 to 1e-16`, `N = 30 to 10000`.
    pub fn range(settings: &[Setting]) -> String {
        match (settings.first(), settings.last()) {
            (Some(Setting::Tolerance(a)), Some(Setting::Tolerance(b))) if a != b => format!("tol {a:.0e} to {b:.0e}"),
            (Some(Setting::Steps(a)), Some(Setting::Steps(b))) if a != b => format!("N = {a} to {b}"),
            (Some(one), _) => one.to_string(),
            (None, _) => String::new(),
        }
    }
}

impl std::fmt::Display for Setting {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Setting::Tolerance(tolerance) => write!(f, "tol {tolerance:.0e}"),
            Setting::Steps(n) => write!(f, "N = {n}"),
        }
    }
}

/// The methods and settings of a study: tolerances 1e-4 to 1e-13 by decades for the adaptive methods (and 1e-16,
/// the rounding floor, for the fast path), N = 30 to 10000 steps per contact for the fixed-step ones; `quick`, a
/// few of them.
pub fn settings(quick: bool) -> Vec<(Method, Setting)> {
    let tolerances = |list: &[f64]| list.iter().map(|&t| Setting::Tolerance(t)).collect::<Vec<_>>();
    let steps = |list: &[u32]| list.iter().map(|&n| Setting::Steps(n)).collect::<Vec<_>>();
    let decades: Vec<f64> = (4..=13).map(|k| 10f64.powi(-k)).collect();
    let (taylor, general, fixed) = if quick {
        (tolerances(&[1e-6, 1e-10, 1e-13]), tolerances(&[1e-6, 1e-10]), steps(&[100, 1000]))
    } else {
        let mut taylor = tolerances(&decades);
        taylor.push(Setting::Tolerance(1e-16));
        (taylor, tolerances(&decades), steps(&[30, 100, 300, 1000, 3000, 10000]))
    };
    let mut all: Vec<(Method, Setting)> = taylor.iter().map(|&s| (Method::Taylor, s)).collect();
    all.extend(taylor.iter().map(|&s| (Method::TaylorMotion, s)));
    // (Exact to rounding whatever the tolerance: one setting.)
    all.push((Method::FirstIntegral, Setting::Tolerance(1e-10)));
    all.push((Method::FirstIntegralTimed, Setting::Tolerance(1e-10)));
    for method in [Method::Dop853, Method::Dopri5] {
        all.extend(general.iter().map(|&s| (method, s)));
    }
    for method in [Method::Rk4, Method::Verlet] {
        all.extend(fixed.iter().map(|&s| (method, s)));
    }
    all
}

/// One method at one setting on one case, ready to run repeatedly (everything outside the integration is done
/// once: the scene is read and resolved here).
pub enum Runner {
    Taylor(Request),
    FirstIntegral(Request),
    FirstIntegralTimed(Request),
    General(Box<(Scene, Setup)>),
    Rk4(baselines::Fixed),
    Verlet(baselines::Fixed),
}

impl Runner {
    pub fn new(case: &Case, method: Method, setting: Setting) -> Result<Runner, String> {
        match (method, setting) {
            (Method::Taylor, Setting::Tolerance(tolerance)) => Ok(Runner::Taylor(case.request(tolerance))),
            (Method::TaylorMotion, Setting::Tolerance(tolerance)) => {
                Ok(Runner::Taylor(Request { quantities: Quantities::MOTION, ..case.request(tolerance) }))
            }
            (Method::FirstIntegral, Setting::Tolerance(tolerance)) => {
                let asked = Quantities { time: false, ..Quantities::MOTION };
                Ok(Runner::FirstIntegral(Request {
                    quantities: Quantities { peak: true, ..asked },
                    ..case.request(tolerance)
                }))
            }
            (Method::FirstIntegralTimed, Setting::Tolerance(tolerance)) => {
                Ok(Runner::FirstIntegralTimed(Request { quantities: Quantities::ALL, ..case.request(tolerance) }))
            }
            (Method::Dop853 | Method::Dopri5, Setting::Tolerance(rtol)) => {
                let text = case.scene_text(method.name(), rtol);
                let scene = Scene::parse(&text, Path::new("bench.toml")).map_err(|e| e.to_string())?;
                let setup = Setup::new(&scene).map_err(|e| format!("{}: {}", e.key, e.message))?;
                Ok(Runner::General(Box::new((scene, setup))))
            }
            (Method::Rk4, Setting::Steps(n)) => Ok(Runner::Rk4(baselines::Fixed::new(case, n))),
            (Method::Verlet, Setting::Steps(n)) => Ok(Runner::Verlet(baselines::Fixed::new(case, n))),
            _ => Err(format!("{} does not take {setting}", method.name())),
        }
    }

    /// One impact: what it measured and the force evaluations it took.
    pub fn run(&self) -> Result<(Measured, u64), String> {
        match self {
            Runner::Taylor(request) | Runner::FirstIntegral(request) | Runner::FirstIntegralTimed(request) => {
                let out = match self {
                    Runner::FirstIntegral(_) => crate::fast::simulate_normal(request),
                    Runner::FirstIntegralTimed(_) => crate::fast::simulate_first_integral(request),
                    _ => crate::fast::simulate_taylor(request),
                }
                .map_err(|e| e.to_string())?;
                if matches!(self, Runner::FirstIntegral(_) | Runner::FirstIntegralTimed(_)) != out.first_integral {
                    return Err("the first integral does not answer for this case".into());
                }
                if !out.separated {
                    return Err(format!("the fast path did not separate ({:?})", out.ending));
                }
                let measured = Measured {
                    restitution: -out.end.rate,
                    max_penetration: out.max_compression.penetration,
                    max_compression_time: out.max_compression.time,
                    duration: out.end.time,
                    peak_force: out.peak_force,
                    deformation_impulse: out.max_compression.impulse,
                    restitution_impulse: out.restitution_impulse,
                };
                // (The first integral evaluates no force: counted as one, its closed forms.)
                Ok((measured, out.force_evaluations.max(1)))
            }
            Runner::General(prepared) => {
                let (scene, setup) = &**prepared;
                let out = crate::impact::outcome(scene, setup).map_err(|e| e.to_string())?;
                if !out.separated {
                    return Err(format!("{} did not separate", out.method));
                }
                // m* = v0 = 1 and L = T = F0 = 1: the SI values are the scaled ones.
                let deformation = out.max_compression.normal_impulse;
                let measured = Measured {
                    restitution: -out.end.rate,
                    max_penetration: out.max_compression.penetration,
                    max_compression_time: out.max_compression.time,
                    duration: out.end.time,
                    peak_force: out.peak_force.1,
                    deformation_impulse: deformation,
                    restitution_impulse: out.restitution.map_or(out.end.normal_impulse - deformation, |r| r.0),
                };
                Ok((measured, out.counters.evaluations))
            }
            Runner::Rk4(fixed) => baselines::rk4(fixed),
            Runner::Verlet(fixed) => baselines::verlet(fixed),
        }
    }
}

/// How long to time each setting: batches of at least `batch`, `batches` of them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    pub batch: Duration,
    pub batches: usize,
}

impl Timing {
    /// The full study's timing: 15 batches of 2 ms.
    pub const FULL: Timing = Timing { batch: Duration::from_millis(2), batches: 15 };
    /// `--quick`: 5 batches of 1 ms.
    pub const QUICK: Timing = Timing { batch: Duration::from_millis(1), batches: 5 };
}

/// The median and the least, over `timing.batches` batches, of the mean time of one call of `once`, in seconds.
/// The batches are sized by a warm-up of about one batch: as many calls as make a batch (at least one). (On a
/// shared machine the least is the nearer to a quiet core: other processes only ever add time.)
pub fn median_seconds<T>(mut once: impl FnMut() -> T, timing: Timing) -> (f64, f64) {
    let start = Instant::now();
    let mut calls = 0u64;
    while calls == 0 || start.elapsed() < timing.batch {
        black_box(once());
        calls += 1;
    }
    let per_batch = calls.max(1);
    let mut means: Vec<f64> = (0..timing.batches.max(1))
        .map(|_| {
            let clock = Instant::now();
            for _ in 0..per_batch {
                black_box(once());
            }
            clock.elapsed().as_secs_f64() / per_batch as f64
        })
        .collect();
    let least = means.iter().copied().fold(f64::INFINITY, f64::min);
    (median(&mut means), least)
}

/// The median of some numbers (the mean of the middle two for an even count); NaN for none.
pub fn median(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    values.sort_by(f64::total_cmp);
    let middle = values.len() / 2;
    if values.len() % 2 == 1 { values[middle] } else { 0.5 * (values[middle - 1] + values[middle]) }
}

/// One row of the study: a method at a setting on a case.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    pub method: Method,
    pub case: String,
    pub setting: Setting,
    /// The error of each of [`QUANTITIES`] (NaN when the run failed, or for a quantity the method does not
    /// measure: [`Method::measures`]).
    pub errors: [f64; 7],
    /// The largest of those it measures (infinite when the run failed).
    pub error: f64,
    /// Median time of one impact, s (NaN when the run failed).
    pub seconds_per_impact: f64,
    /// The least batch's mean time of one impact, s.
    pub seconds_least: f64,
    pub force_evaluations: u64,
    /// Why the run failed, if it did.
    pub failure: Option<String>,
}

/// Runs `case` by `method` at `setting`: measures its errors, then times it.
pub fn measure(case: &Case, method: Method, setting: Setting, timing: Timing) -> Row {
    let failed = |why: String| Row {
        method,
        case: case.name(),
        setting,
        errors: [f64::NAN; 7],
        error: f64::INFINITY,
        seconds_per_impact: f64::NAN,
        seconds_least: f64::NAN,
        force_evaluations: 0,
        failure: Some(why),
    };
    let Some(exact) = case.exact() else { return failed("no exact reference".into()) };
    let runner = match Runner::new(case, method, setting) {
        Ok(runner) => runner,
        Err(why) => return failed(why),
    };
    let (measured, force_evaluations) = match runner.run() {
        Ok(result) => result,
        Err(why) => return failed(why),
    };
    // What the method does not measure is NaN, not an error.
    let mut errors = measured.errors(&exact);
    for (error, measured) in errors.iter_mut().zip(method.measures()) {
        if !measured {
            *error = f64::NAN;
        }
    }
    let counted: Vec<f64> = errors.iter().zip(method.measures()).filter(|(_, m)| *m).map(|(&e, _)| e).collect();
    let (seconds_per_impact, seconds_least) = median_seconds(|| runner.run(), timing);
    Row {
        method,
        case: case.name(),
        setting,
        errors,
        error: largest(&counted),
        seconds_per_impact,
        seconds_least,
        force_evaluations,
        failure: None,
    }
}

/// The study: every case by every method at every setting, in that order (method, setting, case); `done` is
/// called after each row.
pub fn study(cases: &[Case], plan: &[(Method, Setting)], timing: Timing, mut done: impl FnMut(&Row)) -> Vec<Row> {
    let mut rows = Vec::with_capacity(cases.len() * plan.len());
    for &(method, setting) in plan {
        for case in cases.iter().filter(|case| method.covers(case)) {
            let row = measure(case, method, setting, timing);
            done(&row);
            rows.push(row);
        }
    }
    rows
}

/// The CSV header.
pub const HEADER: &str = "method,case,tolerance,steps,error,error_e,error_dmax,error_t0,error_tc,error_fmax,error_jd,\
                          error_jr,seconds_per_impact,seconds_least,force_evaluations";

/// The study's CSV: [`HEADER`], then one line per row. Numbers are shortest round-trip (`1e-10`, `2.3456e-6`);
/// `tolerance` is empty for the fixed-step methods, `steps` for the adaptive ones; a failed run has error `inf`
/// and empty times.
pub fn csv(rows: &[Row]) -> String {
    let mut text = String::with_capacity(256 * (rows.len() + 1));
    text.push_str(HEADER);
    text.push('\n');
    let number = |x: f64| if x.is_nan() { String::new() } else { format!("{x:e}") };
    for row in rows {
        let (tolerance, steps) = match row.setting {
            Setting::Tolerance(t) => (format!("{t:e}"), String::new()),
            Setting::Steps(n) => (String::new(), n.to_string()),
        };
        let errors: Vec<String> = row.errors.iter().map(|&e| number(e)).collect();
        let _ = writeln!(
            text,
            "{},{},{tolerance},{steps},{},{},{},{},{}",
            row.method.name(),
            row.case,
            number(row.error),
            errors.join(","),
            number(row.seconds_per_impact),
            number(row.seconds_least),
            row.force_evaluations
        );
    }
    text
}

/// A method at a setting over all the cases.
#[derive(Debug, Clone, PartialEq)]
pub struct Summary {
    pub method: Method,
    pub setting: Setting,
    pub cases: usize,
    /// The largest error over the cases.
    pub error: f64,
    /// The largest error of e alone over the cases.
    pub error_e: f64,
    /// The median over the cases of the time per impact, s.
    pub median_seconds: f64,
    /// The slowest case's time per impact, s.
    pub largest_seconds: f64,
    /// The median over the cases of the force evaluations.
    pub evaluations: f64,
}

/// The rows summarised per method and setting, in the study's order.
pub fn summarise(rows: &[Row]) -> Vec<Summary> {
    let mut groups: Vec<(Method, Setting, Vec<&Row>)> = Vec::new();
    for row in rows {
        match groups.iter_mut().find(|(m, s, _)| *m == row.method && *s == row.setting) {
            Some(group) => group.2.push(row),
            None => groups.push((row.method, row.setting, vec![row])),
        }
    }
    groups
        .into_iter()
        .map(|(method, setting, rows)| {
            // Times of the runs that finished (a failed case has none; its infinite error marks the setting).
            let mut seconds: Vec<f64> =
                rows.iter().filter(|r| r.failure.is_none()).map(|r| r.seconds_per_impact).collect();
            let mut evaluations: Vec<f64> = rows.iter().map(|r| r.force_evaluations as f64).collect();
            Summary {
                method,
                setting,
                cases: rows.len(),
                error: largest(&rows.iter().map(|r| r.error).collect::<Vec<_>>()),
                error_e: largest(&rows.iter().map(|r| r.errors[0]).collect::<Vec<_>>()),
                median_seconds: median(&mut seconds),
                largest_seconds: seconds.iter().copied().fold(0.0, f64::max),
                evaluations: median(&mut evaluations),
            }
        })
        .collect()
}

/// The cheapest setting of `method` whose largest error over the cases is at most `error` (by its slowest case).
pub fn cheapest(summaries: &[Summary], method: Method, error: f64) -> Option<&Summary> {
    summaries
        .iter()
        .filter(|s| s.method == method && s.error <= error)
        .min_by(|a, b| a.largest_seconds.total_cmp(&b.largest_seconds))
}

/// The summary as a text table: per method and setting, the largest error (all quantities, and e alone), the
/// median and largest time per impact, the median force evaluations.
pub fn summary_table(summaries: &[Summary]) -> String {
    let mut text = String::new();
    let _ = writeln!(
        text,
        "{:<13} {:<11} {:>9} {:>9} {:>12} {:>12} {:>11}",
        "method", "setting", "error", "error e", "median µs", "slowest µs", "evaluations"
    );
    for s in summaries {
        let _ = writeln!(
            text,
            "{:<13} {:<11} {:>9.1e} {:>9.1e} {:>12.3} {:>12.3} {:>11.0}",
            s.method.name(),
            s.setting.to_string(),
            s.error,
            s.error_e,
            s.median_seconds * 1e6,
            s.largest_seconds * 1e6,
            s.evaluations
        );
    }
    text
}

/// The targets of the fast path (issue 8) read off a study: each line says what was reached.
pub fn targets(summaries: &[Summary]) -> String {
    let mut text = String::new();
    for (error, budget) in [(1e-10, 3e-6), (1e-13, 4e-6)] {
        let line = match cheapest(summaries, Method::Taylor, error) {
            Some(s) => format!(
                "error <= {error:.0e} on every case in <= {:.0} µs: {} gives {:.1e}, slowest case {:.3} µs (median \
                 {:.3} µs): {}",
                budget * 1e6,
                s.setting,
                s.error,
                s.largest_seconds * 1e6,
                s.median_seconds * 1e6,
                if s.largest_seconds <= budget { "met" } else { "missed" }
            ),
            None => format!("error <= {error:.0e} on every case: not reached by the fast path"),
        };
        let _ = writeln!(text, "{line}");
    }
    // The floor is what the rounding-floor request (a tolerance below 1e-15) reaches, if one was run.
    let floor_runs = summaries
        .iter()
        .filter(|s| s.method == Method::Taylor && matches!(s.setting, Setting::Tolerance(t) if t < 1e-15));
    let floor = floor_runs.map(|s| s.error).fold(f64::INFINITY, f64::min);
    if floor == f64::INFINITY {
        return text;
    }
    let _ = writeln!(
        text,
        "error floor <= 1e-15: the fast path's smallest largest error is {floor:.1e}: {}",
        if floor <= 1e-15 { "met" } else { "missed" }
    );
    text
}

/// The machine, for the record: the CPU model, the cores, the load average (Linux's /proc; "unknown" elsewhere).
pub fn machine() -> String {
    let model = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|info| {
            info.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|m| m.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{model}, {cores} cores, load average {}", load_average())
}

/// The 1-, 5- and 15-minute load averages ("unknown" where /proc/loadavg is missing).
pub fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .map(|text| text.split_whitespace().take(3).collect::<Vec<_>>().join(" "))
        .unwrap_or_else(|| "unknown".into())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_error_is_the_largest_relative_error_over_the_quantities() {
        let exact = ContactReference {
            restitution: 0.5,
            max_penetration: 0.9,
            max_compression_time: 1.5,
            duration: 3.5,
            max_force: 1.1,
        };
        let perfect = Measured {
            restitution: 0.5,
            max_penetration: 0.9,
            max_compression_time: 1.5,
            duration: 3.5,
            peak_force: 1.1,
            deformation_impulse: 1.0,
            restitution_impulse: 0.5,
        };
        assert_eq!(perfect.error(&exact), 0.0);
        // V0 off by 1e-9 of v0: Jd off by 1e-9 m* v0.
        let v0 = Measured { deformation_impulse: 1.0 - 1e-9, ..perfect };
        assert!((v0.error(&exact) - 1e-9).abs() < 1e-15);
        let jr = Measured { restitution_impulse: 0.5 * (1.0 + 2e-7), ..v0 };
        assert!((jr.error(&exact) - 2e-7).abs() < 1e-15);
        assert_eq!(jr.errors(&exact)[6], jr.error(&exact));
        let broken = Measured { duration: f64::NAN, ..perfect };
        assert_eq!(broken.error(&exact), f64::INFINITY);
    }

    #[test]
    fn medians_and_the_csv() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&mut [4.0, 1.0, 2.0, 3.0]), 2.5);
        let row = Row {
            method: Method::Rk4,
            case: "hertz n=1.5".into(),
            setting: Setting::Steps(100),
            errors: [1e-9, 2e-9, 0.0, 0.0, 0.0, 0.0, 0.0],
            error: 2e-9,
            seconds_per_impact: 2.5e-6,
            seconds_least: 2e-6,
            force_evaluations: 400,
            failure: None,
        };
        let text = csv(&[row]);
        let mut lines = text.lines();
        assert_eq!(lines.next(), Some(HEADER));
        assert_eq!(lines.next(), Some("rk4,hertz n=1.5,,100,2e-9,1e-9,2e-9,0e0,0e0,0e0,0e0,0e0,2.5e-6,2e-6,400"));
    }
}
