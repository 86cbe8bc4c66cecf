//! The GameController receiver: a real UDP socket (port 3838 by default) whose packets become
//! whiteboard postings: the game state, secondary values and the labels robots ask about, each
//! posted when it changes. Bad packets are counted and ignored. Optionally sends the robot's
//! `RGrt` status back to the sender once a second.

use proclaim_board::{ModuleDecl, Value, Whiteboard};
use proclaim_gamecontroller::{decode, DecodeError, Perspective, StatusPacket, LABELS};
use rustc_hash::FxHashMap;
use std::io;
use std::net::SocketAddr;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;
use tokio::net::UdpSocket;
use tracing::Instrument;

#[derive(Clone, Debug)]
pub struct ReceiverConfig {
    pub name: String,
    pub bind: SocketAddr,
    /// Our team number; `None` takes the first team of each packet.
    pub team: Option<u8>,
    /// Our player number, 1-based.
    pub player: u8,
    /// Send `RGrt` status packets to the GameController once a second.
    pub send_status: bool,
    pub status_port: u16,
}

impl Default for ReceiverConfig {
    fn default() -> ReceiverConfig {
        ReceiverConfig {
            name: "gamecontroller".into(),
            bind: SocketAddr::from(([0, 0, 0, 0], 3838)),
            team: None,
            player: 1,
            send_status: false,
            status_port: 3939,
        }
    }
}

/// Packets by fate, readable while the receiver runs.
#[derive(Debug, Default)]
pub struct ReceiverCounters {
    pub received: AtomicU64,
    pub accepted: AtomicU64,
    pub wrong_header: AtomicU64,
    pub wrong_version: AtomicU64,
    pub wrong_length: AtomicU64,
    pub bad_state: AtomicU64,
    pub other_team: AtomicU64,
    pub status_sent: AtomicU64,
}

impl ReceiverCounters {
    pub fn ignored(&self) -> u64 {
        [
            &self.wrong_header,
            &self.wrong_version,
            &self.wrong_length,
            &self.bad_state,
            &self.other_team,
        ]
        .iter()
        .map(|c| c.load(Ordering::Relaxed))
        .sum()
    }
}

/// The values posted besides the labels.
pub const VALUES: [&str; 5] = [
    "gameState",
    "kickingTeam",
    "setPlay",
    "secsRemaining",
    "ourPenalty",
];

pub struct GameControllerReceiver {
    socket: UdpSocket,
    config: ReceiverConfig,
    counters: Arc<ReceiverCounters>,
}

impl GameControllerReceiver {
    pub async fn bind(config: ReceiverConfig) -> io::Result<GameControllerReceiver> {
        let socket = UdpSocket::bind(config.bind).await?;
        Ok(GameControllerReceiver {
            socket,
            config,
            counters: Arc::default(),
        })
    }

    pub fn local_addr(&self) -> io::Result<SocketAddr> {
        self.socket.local_addr()
    }

    pub fn counters(&self) -> Arc<ReceiverCounters> {
        self.counters.clone()
    }

    pub fn declaration(&self) -> ModuleDecl {
        GameControllerReceiver::declaration_for(&self.config)
    }

    /// What a receiver with this configuration posts, reads and answers (no socket needed).
    pub fn declaration_for(config: &ReceiverConfig) -> ModuleDecl {
        ModuleDecl::new(&config.name)
            .posts(VALUES.iter().chain(&LABELS).copied())
            .answers(LABELS)
            .reads(if config.send_status {
                vec!["fallen"]
            } else {
                vec![]
            })
    }

    /// Receives until the socket fails; posts every change.
    pub async fn run(self, board: Whiteboard) -> io::Result<()> {
        let span = tracing::info_span!("gamecontroller", name = %self.config.name);
        self.serve(board).instrument(span).await
    }

    async fn serve(self, board: Whiteboard) -> io::Result<()> {
        let answering = crate::answers::answer_from_latest(
            &board,
            &self.config.name,
            LABELS.iter().map(|l| l.to_string()).collect(),
        );
        board.register(self.declaration());
        tokio::select! {
            result = self.receive(&board) => result,
            () = answering => Ok(()),
        }
    }

    async fn receive(&self, board: &Whiteboard) -> io::Result<()> {
        let mut last: FxHashMap<&'static str, Value> = FxHashMap::default();
        let mut buffer = [0u8; 2048];
        let mut status = tokio::time::interval(Duration::from_secs(1));
        status.set_missed_tick_behavior(tokio::time::MissedTickBehavior::Delay);
        let mut controller: Option<SocketAddr> = None;
        let mut team_seen: Option<u8> = None;
        loop {
            tokio::select! {
                received = self.socket.recv_from(&mut buffer) => {
                    let (len, from) = received?;
                    if let Some(team) = self.accept(&buffer[..len]).and_then(|p| self.post_changes(board, &p, &mut last)) {
                        controller = Some(from);
                        team_seen = Some(team);
                    }
                }
                _ = status.tick(), if self.config.send_status => {
                    if let (Some(to), Some(team)) = (controller, team_seen) {
                        let packet = StatusPacket {
                            player_number: self.config.player,
                            team_number: team,
                            fallen: board.truth("fallen").unwrap_or(false),
                            pose: [0.0; 3],
                            ball_age: -1.0,
                            ball: [0.0; 2],
                        };
                        let to = SocketAddr::new(to.ip(), self.config.status_port);
                        if self.socket.send_to(&packet.encode(), to).await.is_ok() {
                            self.counters.status_sent.fetch_add(1, Ordering::Relaxed);
                        }
                    }
                }
            }
        }
    }

    /// Decodes and filters one datagram, counting what it ignores.
    fn accept(&self, bytes: &[u8]) -> Option<proclaim_gamecontroller::ControlPacket> {
        let c = &self.counters;
        c.received.fetch_add(1, Ordering::Relaxed);
        let packet = match decode(bytes) {
            Ok(p) => p,
            Err(e) => {
                let counter = match e {
                    DecodeError::TooShort { .. } | DecodeError::Length { .. } => &c.wrong_length,
                    DecodeError::Header(_) => &c.wrong_header,
                    DecodeError::Version(_) => &c.wrong_version,
                    DecodeError::State(_) => &c.bad_state,
                };
                counter.fetch_add(1, Ordering::Relaxed);
                tracing::debug!(error = %e, "GameController packet ignored");
                return None;
            }
        };
        if let Some(team) = self.config.team {
            if !packet.involves(team) {
                c.other_team.fetch_add(1, Ordering::Relaxed);
                return None;
            }
        }
        c.accepted.fetch_add(1, Ordering::Relaxed);
        Some(packet)
    }

    /// Posts what changed; returns the team number whose perspective was taken.
    fn post_changes(
        &self,
        board: &Whiteboard,
        packet: &proclaim_gamecontroller::ControlPacket,
        last: &mut FxHashMap<&'static str, Value>,
    ) -> Option<u8> {
        let team = self.config.team.unwrap_or(packet.teams[0].team_number);
        let me = Perspective {
            team,
            player: self.config.player,
        };
        let ours = packet.teams.iter().find(|t| t.team_number == team)?;
        let penalty = ours
            .players
            .get(self.config.player.wrapping_sub(1) as usize)
            .map_or(0, |p| p.penalty);
        let values: [(&'static str, Value); 5] = [
            ("gameState", packet.state.name().into()),
            (
                "kickingTeam",
                packet.kicking_team.map_or(-1, i64::from).into(),
            ),
            ("setPlay", packet.set_play.name().into()),
            ("secsRemaining", i64::from(packet.secs_remaining).into()),
            ("ourPenalty", i64::from(penalty).into()),
        ];
        let labels = packet
            .labels(me)
            .values
            .into_iter()
            .map(|(l, v)| (l, Value::Bool(v)));
        for (ty, value) in values.into_iter().chain(labels) {
            if last.get(ty) != Some(&value) {
                board.post(&self.config.name, ty, value.clone());
                last.insert(ty, value);
            }
        }
        Some(team)
    }
}
