//! `proclaim`: the command line of the clausal defeasible logic reasoner (prove, table, explain,
//! check, gen, bench) and of the behaviour interpreter (run, replay, import, draw). Exit codes:
//! 0 done (whatever the answers), 1 `check` found errors, 2 bad input or usage, 3 some answer
//! undecided within the search budget.

mod behaviours;
mod cli;
mod commands;
mod embedded;
mod failure;
mod load;
mod logs;
mod machines;
mod network;

use clap::Parser;
use std::process::ExitCode;

/// mimalloc rather than the system allocator: a large theory is a few hundred megabytes of
/// tables made once, and mimalloc backs them with transparent huge pages where the system
/// allows it (a fault per 2 MiB instead of per 4 KiB, and fewer TLB misses on the tables'
/// random reads), and frees the parser's small allocations cheaply across threads: parsing and
/// checking a large theory is markedly faster (`proclaim bench chain:1000000` shows it). The
/// library crates leave the choice to whoever embeds them.
#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

fn main() -> ExitCode {
    // Like other command-line tools, stop quietly when the reader of our output goes away
    // (`proclaim replay t.jsonl | head`) instead of failing to print. Sockets are unaffected:
    // tokio sends with MSG_NOSIGNAL.
    #[cfg(unix)]
    // SAFETY: called first thing, before any thread exists; SIG_DFL is a valid disposition.
    unsafe {
        libc::signal(libc::SIGPIPE, libc::SIG_DFL);
    }
    // Before any thread exists, as it requires.
    #[cfg(feature = "zenoh")]
    proclaim_zenoh::prefer_few_threads();
    let cli = cli::Cli::parse();
    logs::install(cli.verbose, cli.quiet, cli.log_format);
    match commands::run(cli) {
        Ok(code) => code,
        Err(failure) => {
            failure.report();
            ExitCode::from(2)
        }
    }
}
