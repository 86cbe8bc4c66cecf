//! `proclaim`: the command line of the clausal defeasible logic reasoner (prove, table, explain,
//! check, gen, bench). Exit codes: 0 done (whatever the answers), 1 `check` found errors, 2 bad
//! input or usage.

mod cli;
mod commands;
mod embedded;
mod failure;
mod load;
mod machines;

use clap::Parser;
use std::process::ExitCode;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    match commands::run(cli) {
        Ok(code) => code,
        Err(failure) => {
            failure.report();
            ExitCode::from(2)
        }
    }
}
