//! The `impact` command: parse arguments, dispatch to a verb, turn errors into messages and exit codes
//! (2 for a bad scene or bad arguments, 1 for anything else; 130 after Ctrl-C, which removes any half-written file).

use clap::Parser;
use impact::cli::{self, Cli};
use std::process::ExitCode;

// A sweep formats its rows on several threads and frees them on the writer's: mimalloc's per-thread heaps keep
// that from growing and trimming the system allocator's arenas (a tenth of a million-row sweep's time).
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    if let Err(error) = impact::files::remove_temporaries_on_signal() {
        // Outputs are still complete or absent; only an interrupted run could leave a temporary file behind.
        eprintln!("impact: warning: cannot watch for Ctrl-C ({error})");
    }
    let arguments = match Cli::try_parse() {
        Ok(arguments) => arguments,
        Err(error) => {
            let code = if error.use_stderr() { 2 } else { 0 };
            let _ = error.print();
            return ExitCode::from(code);
        }
    };
    match cli::dispatch(arguments) {
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("impact: {error:#}");
            ExitCode::from(cli::exit_code(&error))
        }
    }
}
