//! `proclaim`: the command line of the clausal defeasible logic reasoner (prove, table, explain,
//! check, gen, bench) and of the behaviour interpreter (run, replay, import, draw). Exit codes:
//! 0 done (whatever the answers), 1 `check` found errors, 2 bad input or usage, 3 some answer
//! undecided within the search budget.

mod behaviours;
mod bounded;
mod cli;
mod commands;
mod embedded;
mod failure;
mod interrupt;
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
    // SIGPIPE stays ignored (Rust's default), so a child that exits before reading all we give
    // it (Graphviz refusing a long label, a program expert crashing) is an error we report,
    // never a signal that kills the robot. Output whose reader went away
    // (`proclaim replay t.jsonl | head`) still ends quietly: see `quiet_when_stdout_closes`.
    quiet_when_stdout_closes();
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

/// `print!` and `eprint!` panic when their reader has gone (`proclaim check t.dl 2>&1 | head`);
/// like other command-line tools, end then without a word, as the SIGPIPE default would, but
/// only for our own output: every other broken pipe stays an error its caller reports.
fn quiet_when_stdout_closes() {
    let report = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let message = info
            .payload()
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| info.payload().downcast_ref::<&str>().copied())
            .unwrap_or_default();
        let ours = ["failed printing to stdout", "failed printing to stderr"];
        if ours.iter().any(|o| message.starts_with(o)) && message.contains("Broken pipe") {
            // 128 + SIGPIPE, what a shell reports for a reader that left.
            std::process::exit(141);
        }
        report(info)
    }));
}
