//! `impact stress --count N --seed S [--json]`: random scenes over the whole accepted range, each checked against
//! the invariants and exact results it must meet (see [`crate::stress`]). Exit 0 when no case failed, 1 otherwise.

use super::BadInput;
use crate::stress::{self, Summary};
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::fmt::Write as _;
use std::time::Instant;

#[derive(Debug, Args)]
pub struct StressArgs {
    /// How many random scenes to run.
    #[arg(long, default_value_t = 1000)]
    pub count: u64,
    /// The seed: the same seed gives the same scenes (and results) on every machine, with any thread count.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
    /// Index of the first case (to rerun one case of a larger run: `--start I --count 1`).
    #[arg(long, default_value_t = 0)]
    pub start: u64,
    /// Narrower ranges that run fast (damping ratios up to 10, e >= 0.1, no friction): what the test suite runs. With
    /// --worlds: each world runs up to 0.05 s and 12 contacts instead of 1 s and 60 (half of them rough, as without it).
    #[arg(long)]
    pub quick: bool,
    /// Print the JSON summary on stdout instead of the readable one.
    #[arg(long)]
    pub json: bool,
    /// Print the scene text of every case run (for a few cases) instead of running them.
    #[arg(long)]
    pub scenes: bool,
    /// Worker threads (default: all cores).
    #[arg(long, value_name = "N")]
    pub threads: Option<usize>,
    /// Random worlds of 3 to 8 bodies instead of single impacts (docs/world.md#what-is-tested): the energy balance,
    /// momentum and angular momentum where they are kept, and no overlap left when a run stops.
    #[arg(long)]
    pub worlds: bool,
}

/// Most cases one run may take.
const MAX_COUNT: u64 = 1 << 40;

pub fn run(args: &StressArgs) -> anyhow::Result<()> {
    if args.count == 0 || args.count > MAX_COUNT {
        return Err(BadInput(format!("--count must be between 1 and {MAX_COUNT}, got {}", args.count)).into());
    }
    if args.start.checked_add(args.count).is_none() {
        return Err(BadInput("--start + --count is beyond the last case index".into()).into());
    }
    if args.scenes {
        for index in args.start..args.start + args.count {
            let text = if args.worlds {
                stress::world::scene_text(args.seed, index, args.quick)
            } else {
                stress::scene_text(args.seed, index, args.quick)
            };
            println!("# case {index}\n{text}");
        }
        return Ok(());
    }
    let threads = match args.threads {
        Some(0) => return Err(BadInput("--threads must be at least 1".into()).into()),
        Some(n) if n > 1024 => return Err(BadInput(format!("--threads must be at most 1024, got {n}")).into()),
        Some(n) => n,
        None => 0,
    };
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build()?;
    let bar = ProgressBar::with_draw_target(Some(args.count), ProgressDrawTarget::stderr_with_hz(4));
    bar.set_style(
        ProgressStyle::with_template("{bar:40} {pos}/{len} cases, {per_sec}, eta {eta}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let clock = Instant::now();
    // A panicking case is caught and reported as a failure with its scene: keep the default hook's message off the
    // terminal while the run lasts.
    let hook = std::panic::take_hook();
    std::panic::set_hook(Box::new(|_| {}));
    let summary = pool.install(|| {
        if args.worlds {
            stress::run_worlds(args.seed, args.start, args.count, args.quick, &|| bar.inc(1))
        } else {
            stress::run(args.seed, args.start, args.count, args.quick, &|| bar.inc(1))
        }
    });
    std::panic::set_hook(hook);
    bar.finish_and_clear();
    let seconds = clock.elapsed().as_secs_f64();
    if args.json {
        let mut value = serde_json::to_value(&summary)?;
        value["seconds"] = serde_json::json!(seconds);
        println!("{}", serde_json::to_string_pretty(&value)?);
    } else {
        print!("{}", readable(&summary, seconds));
    }
    if summary.failures > 0 {
        anyhow::bail!("{} of {} cases failed", summary.failures, summary.cases);
    }
    Ok(())
}

/// The readable summary.
fn readable(summary: &Summary, seconds: f64) -> String {
    let mut text = String::new();
    for scene in &summary.failed {
        let _ = writeln!(text, "{scene}");
    }
    let _ = writeln!(
        text,
        "stress run: seed {}, cases {}..{}: {} cases, {} failures, {:.1} s",
        summary.seed,
        summary.start,
        summary.start + summary.cases,
        summary.cases,
        summary.failures,
        seconds
    );
    let _ = writeln!(text, "\noutcomes:");
    for (class, count) in &summary.outcomes {
        let examples: Vec<String> = summary.examples.get(class).into_iter().flatten().map(|i| i.to_string()).collect();
        let _ = writeln!(text, "  {count:>10}  {class}  (cases {})", examples.join(", "));
    }
    let _ = writeln!(text, "\nworst errors (tolerance, case):");
    for (quantity, error) in &summary.worst {
        let limit = summary.tolerances.get(quantity).copied().unwrap_or(0.0);
        let case = summary.worst_case.get(quantity).copied().unwrap_or(0);
        let flag = if *error <= limit { "" } else { "  FAILED" };
        let _ = writeln!(text, "  {quantity:<36} {error:>10.3e}  ({limit:.0e}, case {case}){flag}");
    }
    text
}
