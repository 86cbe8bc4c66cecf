//! One module per subcommand; `run` dispatches.

mod bench;
mod bench_all;
mod board;
mod check;
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

use crate::cli::{AlgArg, Cli, Command, Sensor};
use crate::failure::Failure;
use proclaim_cdl::Algorithm;
use std::process::ExitCode;

/// Runs one subcommand. Long by design: one arm a subcommand, each only unpacking its
/// arguments for the command's own file, so the whole command line reads in one place.
pub fn run(cli: Cli) -> Result<ExitCode, Failure> {
    match cli.command {
        Command::Prove {
            theory,
            queries,
            alg,
            set,
            json,
            format,
            budget,
        } => match format {
            crate::cli::ProveFormat::Spindle => prove::spindle(&theory, &queries, &set, budget),
            crate::cli::ProveFormat::Text => prove::run(&theory, &queries, alg, &set, json, budget),
        },
        Command::Table { theory, format } => table::run(&theory, format),
        Command::Compile {
            theory,
            target,
            out,
            unknown_inputs,
            budget,
        } => compile::run(&theory, target, &out, unknown_inputs, budget),
        Command::Explain {
            theory,
            query,
            alg,
            set,
            depth,
            json,
        } => explain::run(&theory, &query, alg, &set, depth, json),
        Command::Check { theories, json } => check::run(&theories, json),
        Command::Verify {
            behaviour,
            never,
            always,
            reachable,
            eventually,
            leads_to,
            always_eventually,
            fair,
            max_states,
            max_memory: _,
            without: _,
            engine: _,
            json: _,
            counterexample: _,
            emit: Some(language),
            output,
        } => verify::emit(
            &behaviour,
            &verify::Asked {
                never,
                always,
                reachable,
                eventually,
                leads_to,
                always_eventually,
                fair,
            },
            max_states,
            language,
            output.as_deref(),
        ),
        Command::Verify {
            behaviour,
            never,
            always,
            reachable,
            eventually,
            leads_to,
            always_eventually,
            fair,
            max_states,
            max_memory,
            without,
            engine,
            json,
            counterexample,
            emit: None,
            output: _,
        } => verify::run(
            &behaviour,
            &verify::Asked {
                never,
                always,
                reachable,
                eventually,
                leads_to,
                always_eventually,
                fair,
            },
            verify::options(max_states, max_memory, &without, engine),
            json,
            counterexample.as_deref(),
        ),
        Command::Draw {
            machine,
            output,
            name,
        } => draw::run(&machine, output.as_deref(), name.as_deref()),
        Command::Edit {
            behaviour,
            addr,
            read_only,
        } => edit::run(&behaviour, &addr, read_only),
        Command::Run(args) => run::run(args),
        Command::Expert {
            theory,
            name,
            mapping,
            duration,
            network,
        } => board::expert(
            &theory,
            name.as_deref(),
            mapping.as_deref(),
            &network,
            duration.as_deref(),
        ),
        Command::Post {
            ty,
            value,
            module,
            network,
        } => board::post(&ty, &value, &module, &network),
        Command::Watch {
            pattern,
            duration,
            network,
        } => board::watch(&pattern, &network, duration.as_deref()),
        Command::Ping { count, network } => board::ping(count, &network),
        Command::Test {
            behaviour,
            recordings,
        } => test::run(&behaviour, &recordings),
        Command::Replay {
            trace,
            speed,
            monitor: None,
            ..
        } => run::replay(&trace, speed),
        Command::Replay {
            trace,
            monitor: Some(addr),
            behaviour,
            ..
        } => monitor::replay(&trace, &addr, behaviour.as_deref()),
        Command::Deps {
            behaviour,
            module,
            launch,
            output,
        } => deps::run(
            &behaviour,
            module.as_deref(),
            launch.as_deref(),
            output.as_deref(),
        ),
        Command::Liveness { file, output } => liveness::run(&file, &output),
        Command::Import { files, output } => import::run(&files, &output),
        Command::Gen {
            family,
            sizes,
            format,
            output,
        } => gen::run(&family, &sizes, format, output.as_deref()),
        Command::Bench {
            cases,
            quick,
            repeat,
            json,
            all,
        } => bench::run(
            &cases,
            bench::BenchOptions {
                quick,
                repeat,
                json,
                all,
            },
        ),
        Command::BenchRun { file, expect } => bench::run_one(&file, &expect),
        Command::Sensor {
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
        Command::GcSim {
            script,
            to,
            interval,
            home,
            away,
        } => gamecontroller::simulate(script.as_deref(), to, interval, home, away),
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
