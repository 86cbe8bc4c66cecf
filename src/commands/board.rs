//! Commands that work on a whiteboard, usually one shared by other processes: `expert` (a
//! theory answering labels), `post` (one message), `watch` (every message, as it comes) and
//! `ping` (what a round trip to another process of it costs).

use super::runtime::{runtime, Shape};
use crate::cli::ExpertArgs;
use crate::failure::Failure;
use crate::load;
use crate::network::{post_once, round_trips, whiteboard, Network};
use proclaim_board::{Message, Pattern, Value, Whiteboard};
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

/// `proclaim expert`.
pub fn expert_command(args: ExpertArgs) -> Result<ExitCode, Failure> {
    expert(
        &args.theory,
        args.name.as_deref(),
        args.mapping.as_deref(),
        &args.network,
        args.duration.as_deref(),
    )
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
        if !network.is_local() {
            let (m, heard) = post_once(network, module, ty, Value::parse(value)).await?;
            let processes = if heard == 1 { "process" } else { "processes" };
            println!(
                "posted {} = {} (#{}, heard by {heard} {processes})",
                m.ty, m.value, m.seq
            );
            return Ok(ExitCode::SUCCESS);
        }
        let board = whiteboard(network).await?;
        let m = board.post(module, ty, Value::parse(value));
        println!("posted {} = {} (#{})", m.ty, m.value, m.seq);
        Ok(ExitCode::SUCCESS)
    })
}

pub fn watch(pattern: &str, network: &Network, limit: Option<&str>) -> Result<ExitCode, Failure> {
    let limit = duration(limit)?;
    runtime(Shape::TwoThreads)?.block_on(async {
        let board: Whiteboard = whiteboard(network).await?;
        let mut messages = board.subscribe(pattern);
        // Times from the watch's start: a shared board's clock is the Unix epoch's.
        let start = board.now();
        eprintln!("watching {pattern} ({})", network.describe());
        // What the board holds already (a shared board's other processes told it on joining),
        // then every posting from now on.
        let matching = Pattern::parse(pattern);
        let now = board.snapshot();
        for row in now.rows().into_iter().filter(|r| matching.matches(r.ty)) {
            print_posting(row.newest, start);
        }
        let print = async {
            while let Some(m) = messages.next().await {
                if m.seq > now.seq {
                    print_posting(&m, start);
                }
            }
        };
        tokio::select! {
            () = print => {}
            () = until_stopped(limit) => {}
        }
        Ok(ExitCode::SUCCESS)
    })
}

fn print_posting(m: &Message, start: Duration) {
    // A subsumption layer's postings say their priority; others print as before.
    let priority = match m.priority {
        0 => String::new(),
        p => format!(" @{p}"),
    };
    println!(
        "{:>9.3}s #{:<6} {:<16} {} = {}{priority}",
        m.time.saturating_sub(start).as_secs_f64(),
        m.seq,
        m.module,
        m.ty,
        m.value
    );
}

pub fn ping(count: usize, network: &Network) -> Result<ExitCode, Failure> {
    if count == 0 {
        return Err(Failure::Argument("--count 0: nothing to time".into()));
    }
    let mut samples = runtime(Shape::TwoThreads)?.block_on(round_trips(network, count))?;
    samples.sort();
    let at = |q: f64| samples[((samples.len() - 1) as f64 * q) as usize].as_secs_f64() * 1e6;
    println!(
        "{} round trips to a process of `{}`: p50 {:.1} µs, p90 {:.1} µs, p99 {:.1} µs, max {:.1} µs",
        samples.len(),
        network.board_name(),
        at(0.5),
        at(0.9),
        at(0.99),
        at(1.0)
    );
    Ok(ExitCode::SUCCESS)
}
