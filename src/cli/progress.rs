//! A world run's progress on a terminal: a line on stderr, redrawn a few times a second while the run goes on —
//! simulated time against `end_time` (or contacts against `max_contacts` without one), contacts so far, steps — and
//! cleared when it ends. Nothing at all when stderr is not a terminal (a pipe, a file, a test), as the sweep's bar.
//!
//! The driver only stores three numbers in a [`Progress`] as each segment or flight ends; this thread reads them.

use crate::scene::WorldSpec;
use crate::units::brief;
use crate::world::record::Progress;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use std::io::IsTerminal;
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

/// How often the line is redrawn; a run shorter than this shows nothing.
const TICK: Duration = Duration::from_millis(250);

/// Bar positions over `end_time`.
const PERMILLE: u64 = 1000;

/// Runs `run`, given a [`Progress`] to tell (and shown on stderr) when stderr is a terminal, `None` otherwise.
pub fn watched<T>(world: &WorldSpec, run: impl FnOnce(Option<&Progress>) -> T) -> T {
    if !std::io::stderr().is_terminal() {
        return run(None);
    }
    let progress = Progress::default();
    let (done, finished) = mpsc::channel::<()>();
    std::thread::scope(|scope| {
        let progress = &progress;
        scope.spawn(move || {
            let mut bar: Option<ProgressBar> = None;
            // (The sender dropped, or a message: the run is over.)
            while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(TICK) {
                show(bar.get_or_insert_with(|| new_bar(world)), world, progress);
            }
            if let Some(bar) = bar {
                bar.finish_and_clear();
            }
        });
        let result = run(Some(progress));
        drop(done);
        result
    })
}

/// The bar: its length the permille of `end_time`, or `max_contacts`.
fn new_bar(world: &WorldSpec) -> ProgressBar {
    let length = if world.end_time.is_some() { PERMILLE } else { world.max_contacts };
    let bar = ProgressBar::with_draw_target(Some(length), ProgressDrawTarget::stderr_with_hz(4));
    bar.set_style(
        ProgressStyle::with_template("{bar:20} {msg} {elapsed}").unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    bar
}

/// Draws what `progress` holds now.
fn show(bar: &ProgressBar, world: &WorldSpec, progress: &Progress) {
    let (time, contacts, steps) = (progress.time(), progress.contacts(), progress.steps());
    let message = match world.end_time {
        Some(end) => {
            bar.set_position(((time / end).clamp(0.0, 1.0) * PERMILLE as f64) as u64);
            format!("t = {} of {}, {contacts} contacts, {steps} steps,", brief(time, "s"), brief(end, "s"))
        }
        None => {
            bar.set_position(contacts.min(world.max_contacts));
            format!("{contacts} of {} contacts, t = {}, {steps} steps,", world.max_contacts, brief(time, "s"))
        }
    };
    bar.set_message(message);
}
