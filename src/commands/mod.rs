//! One module per subcommand; `run` dispatches.

mod bench;
mod bench_all;
mod bench_parse;
mod board;
mod branch;
mod check;
mod checkpoint;
mod compile;
mod conclusions;
mod deps;
pub mod draw;
pub mod edit;
mod explain;
mod gamecontroller;
mod gen;
mod import;
mod inputs;
mod liveness;
pub mod monitor;
mod prove;
mod record;
mod run;
mod runtime;
mod step;
mod table;
mod test;
mod verify;

use crate::cli::{AlgArg, Cli, CliCommand, ReplayArgs, Sensor};
use crate::failure::Failure;
use proclaim_cdl::Algorithm;
use std::process::ExitCode;

/// Runs one subcommand: one arm a subcommand, each handing its arguments to the command's own
/// file, so the whole command line reads in one place.
pub fn run(cli: Cli) -> Result<ExitCode, Failure> {
    match cli.command {
        CliCommand::Prove(args) => prove::command(args),
        CliCommand::Table { theory, format } => table::run(&theory, format),
        CliCommand::Compile(args) => compile::command(args),
        CliCommand::Explain(args) => explain::command(args),
        CliCommand::Check {
            theories,
            json,
            deny_warnings,
        } => check::run(&theories, json, deny_warnings),
        CliCommand::Verify(args) => verify::command(args),
        CliCommand::Draw {
            machine,
            output,
            name,
        } => draw::run(&machine, output.as_deref(), name.as_deref()),
        CliCommand::Edit {
            behaviour,
            addr,
            read_only,
        } => edit::run(&behaviour, &addr, read_only),
        CliCommand::Run(args) => run::run(args),
        CliCommand::Expert(args) => board::expert_command(args),
        CliCommand::Post {
            ty,
            value,
            module,
            network,
        } => board::post(&ty, &value, &module, &network),
        CliCommand::Watch {
            pattern,
            duration,
            network,
        } => board::watch(&pattern, &network, duration.as_deref()),
        CliCommand::Ping { count, network } => board::ping(count, &network),
        CliCommand::Test(args) => test::command(args),
        CliCommand::Replay(args) => replay(args),
        CliCommand::Deps(args) => deps::command(args),
        CliCommand::Liveness { file, output } => liveness::run(&file, &output),
        CliCommand::Import { files, output } => import::run(&files, &output),
        CliCommand::Export {
            file,
            format: _,
            output,
        } => import::export(&file, output.as_deref()),
        CliCommand::Gen(args) => gen::command(args),
        CliCommand::Bench(args) => bench::command(args),
        CliCommand::BenchRun { file, expect } => bench::run_one(&file, &expect),
        CliCommand::Sensor {
            sensor:
                Sensor::Gamecontroller {
                    port,
                    bind,
                    team,
                    player,
                    status,
                    duration,
                    network,
                },
        } => gamecontroller::sensor(
            std::net::SocketAddr::new(bind, port),
            team,
            player,
            status,
            duration.as_deref(),
            &network,
        ),
        CliCommand::GcSim {
            script,
            to,
            interval,
            home,
            away,
        } => gamecontroller::simulate(script.as_deref(), to, interval, home, away),
    }
}

/// `proclaim replay`: printed as the live trace was, or shown in the browser with `--monitor`.
fn replay(args: ReplayArgs) -> Result<ExitCode, Failure> {
    match args.monitor {
        None => run::replay(&args.trace, args.speed),
        Some(addr) => monitor::replay(&args.trace, &addr, args.behaviour.as_deref()),
    }
}

/// The algorithms an `--alg` value names.
pub fn algorithms(alg: AlgArg) -> Vec<Algorithm> {
    match alg {
        AlgArg::Mu => vec![Algorithm::Mu],
        AlgArg::Pi => vec![Algorithm::Pi],
        AlgArg::Beta => vec![Algorithm::Beta],
        AlgArg::Alpha => vec![Algorithm::Alpha],
        AlgArg::Delta => vec![Algorithm::Delta],
        AlgArg::All => Algorithm::ALL.to_vec(),
    }
}
