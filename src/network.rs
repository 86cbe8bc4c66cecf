//! Which whiteboard a command uses: the in-process one, or one shared over Zenoh when the
//! command is told to `--listen` (for the others to connect to) or `--connect` (to one that
//! listens); no process holds a shared board. Without the `zenoh` cargo
//! feature the options are still understood and say how to get it.

use crate::failure::Failure;
use clap::Args;
use proclaim_board::Whiteboard;
use std::path::PathBuf;
use std::time::Duration;

/// The endpoint `--listen` uses when given none.
pub const DEFAULT_ENDPOINT: &str = "tcp/127.0.0.1:7447";

#[derive(Args, Clone, Debug, Default)]
pub struct Network {
    /// Share the whiteboard with other processes, listening on this endpoint for them
    /// (loopback by default; tcp/0.0.0.0:PORT to let other machines in)
    #[arg(long, value_name = "ENDPOINT", num_args = 0..=1, default_missing_value = DEFAULT_ENDPOINT)]
    pub listen: Option<String>,
    /// Share the whiteboard with the process listening on this endpoint (and, through it, with
    /// every other)
    #[arg(long, value_name = "ENDPOINT", conflicts_with = "listen")]
    pub connect: Option<String>,
    /// Zenoh's own JSON5 configuration (TLS, access control), read before the endpoints
    #[arg(long, value_name = "FILE")]
    pub zenoh_config: Option<PathBuf>,
    /// The whiteboard's name, when several share a network
    #[arg(long = "board", value_name = "NAME", default_value = "proclaim")]
    pub board: String,
    /// Zenoh's low-latency transport (every process of the board must say so): faster round
    /// trips, fewer messages per second, no message over 60 KiB
    #[arg(long)]
    pub low_latency: bool,
}

impl Network {
    pub fn is_local(&self) -> bool {
        self.listen.is_none() && self.connect.is_none()
    }

    /// Where this process is on the network, for messages to people.
    pub fn describe(&self) -> String {
        match (&self.listen, &self.connect) {
            (Some(e), _) => format!("on whiteboard `{}`, listening on {e}", self.board),
            (_, Some(e)) => format!("on whiteboard `{}`, connected to {e}", self.board),
            _ => "in-process whiteboard".into(),
        }
    }
}

/// The whiteboard `network` asks for (call inside a tokio runtime).
pub async fn whiteboard(network: &Network) -> Result<Whiteboard, Failure> {
    if network.is_local() {
        return Ok(Whiteboard::local());
    }
    shared(network).await
}

#[cfg(feature = "zenoh")]
async fn shared(network: &Network) -> Result<Whiteboard, Failure> {
    proclaim_zenoh::whiteboard(&role(network), &network.board, &settings(network))
        .await
        .map_err(|e| Failure::Network(e.to_string()))
}

/// Posts one message on the whiteboard `network` shares and returns it once every process
/// linked to this one has it, with how many did.
#[cfg(feature = "zenoh")]
pub async fn post_once(
    network: &Network,
    module: &str,
    ty: &str,
    value: proclaim_board::Value,
) -> Result<(proclaim_board::Message, usize), Failure> {
    proclaim_zenoh::post_once(
        &role(network),
        &network.board,
        &settings(network),
        module,
        ty,
        value,
    )
    .await
    .map_err(|e| Failure::Network(e.to_string()))
}

#[cfg(feature = "zenoh")]
fn role(network: &Network) -> proclaim_zenoh::Role {
    match (&network.listen, &network.connect) {
        (Some(e), _) => proclaim_zenoh::Role::Listen(e.clone()),
        (_, Some(e)) => proclaim_zenoh::Role::Connect(e.clone()),
        _ => unreachable!("a local board is handled by the caller"),
    }
}

#[cfg(feature = "zenoh")]
fn settings(network: &Network) -> proclaim_zenoh::Settings {
    proclaim_zenoh::Settings {
        config_file: network.zenoh_config.clone(),
        low_latency: network.low_latency,
    }
}

/// `count` round trips to a process of the whiteboard `network` joins.
#[cfg(feature = "zenoh")]
pub async fn round_trips(network: &Network, count: usize) -> Result<Vec<Duration>, Failure> {
    let Some(endpoint) = &network.connect else {
        return Err(Failure::Argument(
            "ping needs --connect ENDPOINT: a process of the whiteboard".into(),
        ));
    };
    proclaim_zenoh::ping(endpoint, &network.board, &settings(network), count)
        .await
        .map_err(|e| Failure::Network(e.to_string()))
}

#[cfg(not(feature = "zenoh"))]
async fn shared(_: &Network) -> Result<Whiteboard, Failure> {
    Err(without_zenoh())
}

#[cfg(not(feature = "zenoh"))]
pub async fn post_once(
    _: &Network,
    _: &str,
    _: &str,
    _: proclaim_board::Value,
) -> Result<(proclaim_board::Message, usize), Failure> {
    Err(without_zenoh())
}

#[cfg(not(feature = "zenoh"))]
pub async fn round_trips(_: &Network, _: usize) -> Result<Vec<Duration>, Failure> {
    Err(without_zenoh())
}

#[cfg(not(feature = "zenoh"))]
fn without_zenoh() -> Failure {
    Failure::Network(
        "this proclaim was built without the whiteboard across processes; build it with `cargo build --release --features zenoh`".into(),
    )
}
