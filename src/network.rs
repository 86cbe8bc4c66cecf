//! Which whiteboard a command uses: the in-process one, or one shared over Zenoh when the
//! command is told to `--listen` (hold it) or `--connect` (join it). Without the `zenoh` cargo
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
    /// Hold a whiteboard other processes can join, listening on this endpoint (loopback by
    /// default; tcp/0.0.0.0:PORT to let other machines in)
    #[arg(long, value_name = "ENDPOINT", num_args = 0..=1, default_missing_value = DEFAULT_ENDPOINT)]
    pub listen: Option<String>,
    /// Join the whiteboard held by the process listening on this endpoint
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
            (Some(e), _) => format!("holding whiteboard `{}` on {e}", self.board),
            (_, Some(e)) => format!("joined whiteboard `{}` at {e}", self.board),
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
    let role = match (&network.listen, &network.connect) {
        (Some(e), _) => proclaim_zenoh::Role::Listen(e.clone()),
        (_, Some(e)) => proclaim_zenoh::Role::Connect(e.clone()),
        _ => unreachable!("a local board is handled by the caller"),
    };
    proclaim_zenoh::whiteboard(&role, &network.board, &settings(network))
        .await
        .map_err(|e| Failure::Network(e.to_string()))
}

#[cfg(feature = "zenoh")]
fn settings(network: &Network) -> proclaim_zenoh::Settings {
    proclaim_zenoh::Settings {
        config_file: network.zenoh_config.clone(),
        low_latency: network.low_latency,
    }
}

/// `count` round trips to the process holding the whiteboard `network` joins.
#[cfg(feature = "zenoh")]
pub async fn round_trips(network: &Network, count: usize) -> Result<Vec<Duration>, Failure> {
    let Some(endpoint) = &network.connect else {
        return Err(Failure::Argument(
            "ping needs --connect ENDPOINT: the process holding the whiteboard".into(),
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
pub async fn round_trips(_: &Network, _: usize) -> Result<Vec<Duration>, Failure> {
    Err(without_zenoh())
}

#[cfg(not(feature = "zenoh"))]
fn without_zenoh() -> Failure {
    Failure::Network(
        "this proclaim was built without the whiteboard across processes; build it with `cargo build --release --features zenoh`".into(),
    )
}
