//! Commands that work on a whiteboard, usually one shared by other processes: `expert` (a
//! theory answering labels), `post` (one message), `watch` (every message, as it comes) and
//! `ping` (what the link to its holder costs).

use super::runtime::{runtime, Shape};
use crate::failure::Failure;
use crate::load;
use crate::network::{round_trips, whiteboard, Network};
use proclaim_board::{Value, Whiteboard};
use proclaim_experts::{parse_duration, parse_mapping, ReasonerExpert};
use std::path::Path;
use std::process::ExitCode;
use std::time::Duration;

fn duration(text: Option<&str>) -> Result<Option<Duration>, Failure> {
    text.map(|t| {
        parse_duration(t).ok_or_else(|| {
            Failure::Argument(format!(
                "--for {t}: not a duration (write 30s, 500ms or 1.5s)"
            ))
        })
    })
    .transpose()
}

/// Runs until Ctrl-C or `limit`.
async fn until_stopped(limit: Option<Duration>) {
    match limit {
        Some(d) => tokio::time::sleep(d).await,
        None => {
            let _ = tokio::signal::ctrl_c().await;
        }
    }
}

pub fn expert(
    theory: &str,
    name: Option<&str>,
    mapping: Option<&Path>,
    network: &Network,
    limit: Option<&str>,
) -> Result<ExitCode, Failure> {
    let (_, checked) = load::theory(theory)?;
    let mapping = match mapping {
        None => Default::default(),
        Some(path) => load::line_file(path, "the mapping file", parse_mapping)?,
    };
    let limit = duration(limit)?;
    let name = name
        .map(str::to_string)
        .or_else(|| checked.name().map(str::to_string))
        .unwrap_or_else(|| "expert".into());
    runtime(Shape::TwoThreads)?.block_on(async {
        let board = whiteboard(network).await?;
        let expert = ReasonerExpert::new(&name, checked, &mapping);
        let decl = expert.declaration();
        println!(
            "expert {name} answers {} ({})",
            decl.answers.join(", "),
            network.describe()
        );
        tokio::select! {
            () = expert.run(board.clone()) => {}
            () = until_stopped(limit) => {}
        }
        Ok(ExitCode::SUCCESS)
    })
}

pub fn post(ty: &str, value: &str, module: &str, network: &Network) -> Result<ExitCode, Failure> {
    runtime(Shape::TwoThreads)?.block_on(async {
        let board = whiteboard(network).await?;
        // Seen coming back through the whiteboard: then it has been delivered.
        let mut echo = board.subscribe(ty);
        board.post(module, ty, Value::parse(value));
        match tokio::time::timeout(Duration::from_secs(5), echo.next()).await {
            Ok(Some(m)) => {
                println!("posted {} = {} (#{})", m.ty, m.value, m.seq);
                Ok(ExitCode::SUCCESS)
            }
            _ => Err(Failure::Network(format!(
                "the posting of {ty} was not seen on the whiteboard within 5 s"
            ))),
        }
    })
}

pub fn watch(pattern: &str, network: &Network, limit: Option<&str>) -> Result<ExitCode, Failure> {
    let limit = duration(limit)?;
    runtime(Shape::TwoThreads)?.block_on(async {
        let board: Whiteboard = whiteboard(network).await?;
        let mut messages = board.subscribe(pattern);
        eprintln!("watching {pattern} ({})", network.describe());
        let print = async {
            while let Some(m) = messages.next().await {
                // A subsumption layer's postings say their priority; others print as before.
                let priority = match m.priority {
                    0 => String::new(),
                    p => format!(" @{p}"),
                };
                println!(
                    "{:>9.3}s #{:<6} {:<16} {} = {}{priority}",
                    m.time.as_secs_f64(),
                    m.seq,
                    m.module,
                    m.ty,
                    m.value
                );
            }
        };
        tokio::select! {
            () = print => {}
            () = until_stopped(limit) => {}
        }
        Ok(ExitCode::SUCCESS)
    })
}

pub fn ping(count: usize, network: &Network) -> Result<ExitCode, Failure> {
    if count == 0 {
        return Err(Failure::Argument("--count 0: nothing to time".into()));
    }
    let mut samples = runtime(Shape::TwoThreads)?.block_on(round_trips(network, count))?;
    samples.sort();
    let at = |q: f64| samples[((samples.len() - 1) as f64 * q) as usize].as_secs_f64() * 1e6;
    println!(
        "{} round trips to the holder of `{}`: p50 {:.1} µs, p90 {:.1} µs, p99 {:.1} µs, max {:.1} µs",
        samples.len(),
        network.board,
        at(0.5),
        at(0.9),
        at(0.99),
        at(1.0)
    );
    Ok(ExitCode::SUCCESS)
}
