//! A GameController simulator: real control packets over UDP following a script of game events,
//! so demos and tests need no outside program. The encoder is the one the decoder is tested
//! against.
//!
//! Script: one event a line, `TIME EVENT [key=value …]`, `#` comments:
//!
//! ```text
//! 0s    initial
//! 1s    ready kick=18
//! 2s    set
//! 3s    playing
//! 4s    penalty team=18 player=2 secs=2 reason=2
//! 6s    unpenalise team=18 player=2
//! 8s    finished
//! ```

use proclaim_gamecontroller::{
    encode, Colour, ControlPacket, GamePhase, GameState, RobotInfo, SetPlay, TeamInfo,
};
use proclaim_syntax::{code_lines, parse_duration, LineError, LineErrors};
use std::io;
use std::net::SocketAddr;
use std::time::Duration;
use tokio::net::UdpSocket;

#[derive(Clone, Debug, PartialEq, Eq)]
pub enum GameEvent {
    State(GameState),
    /// The team of the next kick-off or set play.
    Kick(u8),
    SetPlay(SetPlay),
    Penalise {
        team: u8,
        player: u8,
        secs: u16,
        penalty: u8,
    },
    Unpenalise {
        team: u8,
        player: u8,
    },
    Goal {
        team: u8,
    },
}

#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct GameScript {
    pub events: Vec<(Duration, GameEvent)>,
}

impl GameScript {
    /// When the last event happens.
    pub fn length(&self) -> Duration {
        self.events
            .iter()
            .map(|(t, _)| *t)
            .max()
            .unwrap_or_default()
    }
}

/// A short game between `home` and `away`: INITIAL → READY → SET → PLAYING, a penalty on the
/// home team's player 2 and its end, → FINISHED, in eight seconds.
pub fn default_game(home: u8, away: u8) -> GameScript {
    let s = Duration::from_secs;
    GameScript {
        events: vec![
            (s(0), GameEvent::State(GameState::Initial)),
            (s(0), GameEvent::Kick(home)),
            (s(1), GameEvent::State(GameState::Ready)),
            (s(2), GameEvent::State(GameState::Set)),
            (s(3), GameEvent::State(GameState::Playing)),
            (
                s(4),
                GameEvent::Penalise {
                    team: home,
                    player: 2,
                    secs: 2,
                    penalty: 2,
                },
            ),
            (
                s(6),
                GameEvent::Unpenalise {
                    team: home,
                    player: 2,
                },
            ),
            (Duration::from_millis(6500), GameEvent::Goal { team: away }),
            (Duration::from_millis(6500), GameEvent::Kick(home)),
            (s(8), GameEvent::State(GameState::Finished)),
        ],
    }
}

/// Parses a game script; every bad line is reported.
pub fn parse_game(text: &str) -> Result<GameScript, LineErrors> {
    let mut events = Vec::new();
    let mut errors = Vec::new();
    for (line, code) in code_lines(text) {
        let mut words = code.split_whitespace();
        let (Some(time), Some(event)) = (words.next(), words.next()) else {
            errors.push(LineError {
                line,
                message: "expected `TIME EVENT`, as in `3s playing`".into(),
            });
            continue;
        };
        let Some(time) = parse_duration(time) else {
            errors.push(LineError {
                line,
                message: format!("`{time}` is not a time"),
            });
            continue;
        };
        let args: Vec<(&str, &str)> = words.filter_map(|w| w.split_once('=')).collect();
        let arg = |key: &str| -> Result<u16, String> {
            let v = args
                .iter()
                .find(|(k, _)| *k == key)
                .map(|(_, v)| *v)
                .ok_or_else(|| format!("`{event}` needs {key}=N"))?;
            v.parse().map_err(|_| format!("{key}={v} is not a number"))
        };
        let small = |key: &str| {
            arg(key).and_then(|v| u8::try_from(v).map_err(|_| format!("{key} is at most 255")))
        };
        let parsed = match event.to_ascii_lowercase().as_str() {
            "initial" => Ok(GameEvent::State(GameState::Initial)),
            "ready" => Ok(GameEvent::State(GameState::Ready)),
            "set" => Ok(GameEvent::State(GameState::Set)),
            "playing" => Ok(GameEvent::State(GameState::Playing)),
            "finished" => Ok(GameEvent::State(GameState::Finished)),
            "standby" => Ok(GameEvent::State(GameState::Standby)),
            "kick" => small("team").map(GameEvent::Kick),
            "penalty" => (|| {
                Ok(GameEvent::Penalise {
                    team: small("team")?,
                    player: small("player")?,
                    secs: arg("secs")?,
                    penalty: if args.iter().any(|(k, _)| *k == "reason") { small("reason")? } else { 2 },
                })
            })(),
            "unpenalise" => (|| Ok(GameEvent::Unpenalise { team: small("team")?, player: small("player")? }))(),
            "goal" => small("team").map(|team| GameEvent::Goal { team }),
            other => Err(format!(
                "unknown event `{other}`; events are initial, ready, set, playing, finished, standby, kick, penalty, unpenalise, goal"
            )),
        };
        match parsed {
            Ok(e) => {
                // `ready kick=18` is shorthand for a state and the kicking team.
                if let (GameEvent::State(_), Some(k)) =
                    (&e, args.iter().find(|(k, _)| *k == "kick"))
                {
                    match k.1.parse::<u8>() {
                        Ok(team) => events.push((time, GameEvent::Kick(team))),
                        Err(_) => errors.push(LineError {
                            line,
                            message: format!("kick={} is not a team number", k.1),
                        }),
                    }
                }
                events.push((time, e));
            }
            Err(message) => errors.push(LineError { line, message }),
        }
    }
    events.sort_by_key(|(t, _)| *t);
    if errors.is_empty() {
        Ok(GameScript { events })
    } else {
        Err(LineErrors(errors))
    }
}

#[derive(Clone, Debug)]
pub struct SimConfig {
    pub to: SocketAddr,
    /// Between packets (the real GameController: 500 ms).
    pub interval: Duration,
    pub home: u8,
    pub away: u8,
    pub players_per_team: u8,
    pub half_secs: i16,
}

impl Default for SimConfig {
    fn default() -> SimConfig {
        SimConfig {
            to: SocketAddr::from(([127, 0, 0, 1], 3838)),
            interval: Duration::from_millis(250),
            home: 18,
            away: 5,
            players_per_team: 7,
            half_secs: 600,
        }
    }
}

/// The packet before any event.
pub fn initial_packet(config: &SimConfig) -> ControlPacket {
    let team = |number: u8, colour: Colour, keeper: Colour| TeamInfo {
        team_number: number,
        field_player_colour: colour,
        goalkeeper_colour: keeper,
        goalkeeper: 1,
        score: 0,
        penalty_shot: 0,
        single_shots: 0,
        message_budget: 1200,
        players: (0..20)
            .map(|i| RobotInfo {
                penalty: if i < config.players_per_team {
                    0
                } else {
                    proclaim_gamecontroller::PENALTY_SUBSTITUTE
                },
                secs_till_unpenalised: 0,
            })
            .collect(),
    };
    ControlPacket {
        version: 18,
        packet_number: 0,
        players_per_team: config.players_per_team,
        competition_phase: 0,
        competition_type: 0,
        game_phase: GamePhase::Normal,
        state: GameState::Initial,
        set_play: SetPlay::None,
        first_half: true,
        kicking_team: Some(config.home),
        kick_off_colour: None,
        secs_remaining: config.half_secs as i32,
        secondary_time: 0,
        teams: [
            team(config.home, Colour::Blue, Colour::Yellow),
            team(config.away, Colour::Red, Colour::Black),
        ],
    }
}

fn slot(packet: &mut ControlPacket, team: u8, player: u8) -> Option<&mut RobotInfo> {
    packet
        .teams
        .iter_mut()
        .find(|t| t.team_number == team)
        .and_then(|t| t.players.get_mut(player.wrapping_sub(1) as usize))
}

/// Applies an event; a penalty's end is kept in `penalties` as playing time.
fn apply(
    packet: &mut ControlPacket,
    event: &GameEvent,
    played: f64,
    penalties: &mut Vec<(u8, u8, f64)>,
) {
    match *event {
        GameEvent::State(s) => packet.state = s,
        GameEvent::Kick(team) => packet.kicking_team = Some(team),
        GameEvent::SetPlay(p) => packet.set_play = p,
        GameEvent::Penalise {
            team,
            player,
            secs,
            penalty,
        } => {
            if let Some(p) = slot(packet, team, player) {
                *p = RobotInfo {
                    penalty,
                    secs_till_unpenalised: secs,
                };
                penalties.retain(|&(t, n, _)| (t, n) != (team, player));
                penalties.push((team, player, played + f64::from(secs)));
            }
        }
        GameEvent::Unpenalise { team, player } => {
            if let Some(p) = slot(packet, team, player) {
                *p = RobotInfo::default();
            }
            penalties.retain(|&(t, n, _)| (t, n) != (team, player));
        }
        GameEvent::Goal { team } => {
            if let Some(t) = packet.teams.iter_mut().find(|t| t.team_number == team) {
                t.score = t.score.saturating_add(1);
            }
        }
    }
}

/// Plays the script to `config.to`: one packet each interval, events applied when due, the
/// clock and penalties counting down while PLAYING; ends two packets after the last event.
/// `on_packet` sees every packet sent. Returns how many were sent.
pub async fn play(
    script: &GameScript,
    config: &SimConfig,
    mut on_packet: impl FnMut(&ControlPacket),
) -> io::Result<u64> {
    let bind: SocketAddr = if config.to.ip().is_loopback() {
        ([127, 0, 0, 1], 0).into()
    } else {
        ([0, 0, 0, 0], 0).into()
    };
    let socket = UdpSocket::bind(bind).await?;
    if config.to.ip().is_multicast() || config.to.ip().to_string().ends_with(".255") {
        socket.set_broadcast(true)?;
    }
    let mut packet = initial_packet(config);
    let mut next = 0;
    let start = tokio::time::Instant::now();
    let end = script.length() + config.interval * 2;
    let mut ticker = tokio::time::interval(config.interval);
    let mut sent = 0u64;
    // Seconds spent PLAYING: the game clock and penalties run only then.
    let mut played_ms = 0u128;
    let mut penalties: Vec<(u8, u8, f64)> = Vec::new();
    loop {
        ticker.tick().await;
        let now = start.elapsed();
        while next < script.events.len() && script.events[next].0 <= now {
            let played = played_ms as f64 / 1000.0;
            apply(&mut packet, &script.events[next].1, played, &mut penalties);
            next += 1;
        }
        let bytes = encode(&packet);
        socket.send_to(&bytes, config.to).await?;
        sent += 1;
        on_packet(&packet);
        if now >= end {
            return Ok(sent);
        }
        packet.packet_number = packet.packet_number.wrapping_add(1);
        if packet.state == GameState::Playing {
            played_ms += config.interval.as_millis();
            let played = played_ms as f64 / 1000.0;
            packet.secs_remaining = config.half_secs as i32 - played.floor() as i32;
            for &(team, player, until) in &penalties {
                if let Some(p) = slot(&mut packet, team, player) {
                    p.secs_till_unpenalised = (until - played).max(0.0).ceil() as u16;
                }
            }
        }
    }
}
