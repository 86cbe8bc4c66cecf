//! `proclaim sensor gamecontroller` (the receiver alone, printing what it posts) and
//! `proclaim gc-sim` (the simulator, printing each state it sends).

use super::runtime::{runtime, Shape};
use crate::failure::Failure;
use crate::network::{whiteboard, Network};
use proclaim_experts::{parse_duration, GameControllerReceiver, ReceiverConfig};
use proclaim_gcsim::{self as simulator, default_game, parse_game, SimConfig};
use std::net::SocketAddr;
use std::path::Path;
use std::process::ExitCode;
use std::sync::atomic::Ordering;
use std::time::Duration;

pub fn sensor(
    bind: SocketAddr,
    team: Option<u8>,
    player: u8,
    status: bool,
    duration: Option<&str>,
    network: &Network,
) -> Result<ExitCode, Failure> {
    let duration = match duration {
        Some(text) => Some(parse_duration(text).ok_or_else(|| {
            Failure::Argument(format!("--for {text}: not a duration; write 30s or 500ms"))
        })?),
        None => None,
    };
    runtime(Shape::OneThread)?.block_on(async move {
        let config = ReceiverConfig {
            bind,
            team,
            player,
            send_status: status,
            ..ReceiverConfig::default()
        };
        let receiver = GameControllerReceiver::bind(config).await.map_err(|error| {
            Failure::Argument(format!("cannot listen on UDP {bind}: {error}"))
        })?;
        let counters = receiver.counters();
        let board = whiteboard(network).await?;
        let mut postings = board.subscribe("*");
        eprintln!(
            "listening for GameController packets on UDP {}{}",
            receiver.local_addr().map_or(bind, |a| a),
            team.map_or(String::new(), |t| format!(" as team {t} player {player}"))
        );
        let run = tokio::spawn(receiver.run(board.clone()));
        let print = async {
            while let Some(m) = postings.next().await {
                println!("{:>9.3} {} = {}", m.time.as_secs_f64(), m.ty, m.value);
            }
        };
        match duration {
            Some(d) => {
                let _ = tokio::time::timeout(d, print).await;
            }
            None => {
                tokio::select! {
                    _ = print => {}
                    _ = tokio::signal::ctrl_c() => {}
                }
            }
        }
        run.abort();
        let c = &counters;
        let n = |a: &std::sync::atomic::AtomicU64| a.load(Ordering::Relaxed);
        eprintln!(
            "packets: {} received, {} accepted, {} ignored (header {}, version {}, length {}, state {}, other team {})",
            n(&c.received),
            n(&c.accepted),
            c.ignored(),
            n(&c.wrong_header),
            n(&c.wrong_version),
            n(&c.wrong_length),
            n(&c.bad_state),
            n(&c.other_team)
        );
        Ok(ExitCode::SUCCESS)
    })
}

pub fn simulate(
    script: Option<&Path>,
    to: SocketAddr,
    interval: u64,
    home: u8,
    away: u8,
) -> Result<ExitCode, Failure> {
    let game = match script {
        Some(path) => crate::load::line_file(path, "the game script", parse_game)?,
        None => default_game(home, away),
    };
    if interval == 0 {
        return Err(Failure::Argument("--interval must be at least 1 ms".into()));
    }
    let config = SimConfig {
        to,
        interval: Duration::from_millis(interval),
        home,
        away,
        ..SimConfig::default()
    };
    runtime(Shape::OneThread)?.block_on(async move {
        let start = tokio::time::Instant::now();
        let mut last = None;
        let sent = simulator::play(&game, &config, |p| {
            let summary = (p.state, p.kicking_team, p.teams[0].score, p.teams[1].score);
            if last != Some(summary) {
                last = Some(summary);
                println!(
                    "{:>7.3} {} (kicking team {}, score {}:{})",
                    start.elapsed().as_secs_f64(),
                    p.state,
                    p.kicking_team.map_or("none".into(), |k| k.to_string()),
                    p.teams[0].score,
                    p.teams[1].score
                );
            }
        })
        .await
        .map_err(|error| Failure::Argument(format!("cannot send to {to}: {error}")))?;
        eprintln!("sent {sent} packets to {to}");
        Ok(ExitCode::SUCCESS)
    })
}
