//! Which whiteboard a command uses: the in-process one, or one shared over Zenoh when the
//! command is told to `--listen` (for the others to connect to, and with `--peer` to dial its
//! teammates), `--connect` (to one that listens) or `--scout` (to find the others by
//! multicast); no process holds a shared board. A
//! behaviour whose manifest has a `[team]` joins its team there too. Without the `zenoh` cargo
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
    /// With --listen ADDRESS (the robot's own, not 0.0.0.0): a teammate's endpoint (repeat for
    /// each; the robot's own is skipped, so every robot can be given the same list). Each pair
    /// dials the other, and again every 100 ms while it is away, so a link that comes back
    /// after a cut is used within about a second
    #[arg(long, value_name = "ENDPOINT", requires = "listen")]
    pub peer: Vec<String>,
    /// With --peer: how long one dial of a teammate may take before it is made again (three
    /// round trips must fit: give more on a network of long round trips) [default: 500ms]
    #[arg(long, value_name = "DURATION", value_parser = parse_dial, requires = "peer")]
    pub dial: Option<Duration>,
    /// Share the whiteboard with the processes this one finds on the local network by Zenoh's
    /// multicast scouting, with no endpoint given (each listens on a free port of every
    /// interface)
    #[arg(long, conflicts_with_all = ["listen", "connect"])]
    pub scout: bool,
    /// Zenoh's own JSON5 configuration (TLS, access control), read before the endpoints
    #[arg(long, value_name = "FILE")]
    pub zenoh_config: Option<PathBuf>,
    /// The whiteboard's name, when several share a network (`proclaim` unless given; a robot of a
    /// team: its member name)
    #[arg(long = "board", value_name = "NAME")]
    pub board: Option<String>,
    /// Zenoh's low-latency transport (every process of the board must say so): faster round
    /// trips, fewer messages per second, no message over 60 KiB
    #[arg(long)]
    pub low_latency: bool,
    /// How long a process may go unheard before the others count it gone: its types turn
    /// stale and a teammate drops out of its team (every process of the board should say the
    /// same) [default: 1.5s]
    #[arg(long, value_name = "DURATION", value_parser = parse_lease)]
    pub lease: Option<Duration>,
}

/// The shortest and longest `--lease` taken.
const LEASES: (Duration, Duration) = (Duration::from_millis(200), Duration::from_secs(600));

fn parse_lease(text: &str) -> Result<Duration, String> {
    duration_within(
        text,
        LEASES,
        "a lease",
        " (shorter, a busy robot's keep-alives come late and working links are closed)",
    )
}

/// The shortest and longest `--dial` taken.
const DIALS: (Duration, Duration) = (Duration::from_millis(100), Duration::from_secs(10));

fn parse_dial(text: &str) -> Result<Duration, String> {
    duration_within(text, DIALS, "a dial", "")
}

/// `text` as a duration within `(shortest, longest)`, or what is wrong with it: `what` named,
/// `why` the bounds are what they are.
fn duration_within(
    text: &str,
    (shortest, longest): (Duration, Duration),
    what: &str,
    why: &str,
) -> Result<Duration, String> {
    let duration = proclaim_experts::parse_duration(text)
        .ok_or_else(|| format!("`{text}` is not a duration (write 1s, 500ms or 2.5s)"))?;
    if duration < shortest || duration > longest {
        return Err(format!(
            "{text}: {what} is from {}ms to {}s{why}",
            shortest.as_millis(),
            longest.as_secs()
        ));
    }
    Ok(duration)
}

impl Network {
    pub fn is_local(&self) -> bool {
        self.listen.is_none() && self.connect.is_none() && !self.scout
    }

    /// The network for a robot of `team`: its whiteboard named after its member name unless
    /// `--board` names it, so the robots of a team each have their own.
    pub fn for_team(&self, team: Option<&TeamPlace>) -> Network {
        let mut network = self.clone();
        if let (None, Some(team)) = (&network.board, team) {
            network.board = Some(team.member.clone());
        }
        network
    }

    /// The whiteboard's name.
    pub fn board_name(&self) -> &str {
        self.board.as_deref().unwrap_or(DEFAULT_BOARD)
    }

    /// Where this process is on the network, for messages to people.
    pub fn describe(&self) -> String {
        let board = self.board_name();
        match (&self.listen, &self.connect) {
            (Some(e), _) if !self.peer.is_empty() => {
                let others: Vec<&str> = (self.peer.iter())
                    .filter(|p| *p != e)
                    .map(String::as_str)
                    .collect();
                format!(
                    "on whiteboard `{board}`, listening on {e}, linking to {} as they come",
                    others.join(", ")
                )
            }
            (Some(e), _) => format!("on whiteboard `{board}`, listening on {e}"),
            (_, Some(e)) => format!("on whiteboard `{board}`, connected to {e}"),
            _ if self.scout => format!("on whiteboard `{board}`, found by multicast scouting"),
            _ => "in-process whiteboard".into(),
        }
    }
}

/// The board's name when none is given.
const DEFAULT_BOARD: &str = "proclaim";

/// A robot's place in its team: the manifest's `[team]`, its member name perhaps given on the
/// command line instead.
#[derive(Clone, Debug)]
pub struct TeamPlace {
    pub name: String,
    pub member: String,
    /// Read only where the whiteboard crosses processes (the `zenoh` feature).
    #[cfg_attr(not(feature = "zenoh"), allow(dead_code))]
    pub shared: Vec<String>,
    /// How many robots the team has, if the manifest says (checked positive by `check`).
    #[cfg_attr(not(feature = "zenoh"), allow(dead_code))]
    pub size: Option<usize>,
}

impl TeamPlace {
    /// The place a behaviour's manifest gives, with `member` (`run --member`) in place of its
    /// member name; `None` for a behaviour of no team.
    pub fn of(
        team: Option<&proclaim_behaviour::TeamEntry>,
        member: Option<&str>,
    ) -> Result<Option<TeamPlace>, Failure> {
        let Some(team) = team else {
            return match member {
                Some(m) => Err(Failure::Argument(format!(
                    "--member {m}: the behaviour's manifest has no [team] to be a member of"
                ))),
                None => Ok(None),
            };
        };
        let member = member.unwrap_or(team.member.get_ref()).to_string();
        if let Some(why) = proclaim_behaviour::team_name_error(&member) {
            return Err(Failure::Argument(format!(
                "--member {member} cannot name a team's member: {why}"
            )));
        }
        Ok(Some(TeamPlace {
            name: team.name.get_ref().clone(),
            member,
            shared: team.shared.iter().map(|s| s.get_ref().clone()).collect(),
            size: team
                .size
                .as_ref()
                .and_then(|s| usize::try_from(*s.get_ref()).ok())
                .filter(|&s| s > 0),
        }))
    }
}

/// The whiteboard `network` asks for (call inside a tokio runtime).
pub async fn whiteboard(network: &Network) -> Result<Whiteboard, Failure> {
    if network.is_local() {
        return Ok(Whiteboard::local());
    }
    shared(network, None).await
}

/// The whiteboard a behaviour runs on, as [`whiteboard`], for a robot of `team` when it is one
/// (a team needs a shared board; see [`Network::for_team`]).
pub async fn behaviour_whiteboard(
    network: &Network,
    team: Option<TeamPlace>,
) -> Result<Whiteboard, Failure> {
    match team {
        None => whiteboard(network).await,
        Some(team) if network.is_local() => Err(Failure::Argument(format!(
            "the behaviour is {} of team `{}`, whose members meet on a shared whiteboard: add --listen, --connect ENDPOINT or --scout",
            team.member, team.name
        ))),
        Some(team) => shared(network, Some(team)).await,
    }
}

#[cfg(feature = "zenoh")]
async fn shared(network: &Network, team: Option<TeamPlace>) -> Result<Whiteboard, Failure> {
    let (role, settings) = (role(network), settings(network));
    let joined = match team {
        None => proclaim_zenoh::whiteboard(&role, network.board_name(), &settings).await,
        Some(team) => {
            let team = proclaim_zenoh::Team {
                name: team.name,
                member: team.member,
                shared: team.shared,
                size: team.size,
            };
            proclaim_zenoh::team_whiteboard(&role, network.board_name(), &settings, team).await
        }
    };
    joined.map_err(|e| Failure::Network(e.to_string()))
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
        network.board_name(),
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
        (Some(e), _) if !network.peer.is_empty() => proclaim_zenoh::Role::Mesh {
            listen: e.clone(),
            peers: network.peer.clone(),
        },
        (Some(e), _) => proclaim_zenoh::Role::Listen(e.clone()),
        (_, Some(e)) => proclaim_zenoh::Role::Connect(e.clone()),
        _ if network.scout => proclaim_zenoh::Role::Scout,
        _ => unreachable!("a local board is handled by the caller"),
    }
}

#[cfg(feature = "zenoh")]
fn settings(network: &Network) -> proclaim_zenoh::Settings {
    proclaim_zenoh::Settings {
        config_file: network.zenoh_config.clone(),
        low_latency: network.low_latency,
        lease: network.lease,
        dial: network.dial,
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
    proclaim_zenoh::ping(endpoint, network.board_name(), &settings(network), count)
        .await
        .map_err(|e| Failure::Network(e.to_string()))
}

#[cfg(not(feature = "zenoh"))]
async fn shared(_: &Network, _: Option<TeamPlace>) -> Result<Whiteboard, Failure> {
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_lease_or_a_dial_out_of_its_bounds_is_refused_saying_them() {
        assert_eq!(parse_dial("2s"), Ok(Duration::from_secs(2)));
        assert_eq!(
            parse_dial("50ms").unwrap_err(),
            "50ms: a dial is from 100ms to 10s"
        );
        assert!(parse_dial("soon").unwrap_err().contains("not a duration"));
        assert_eq!(parse_lease("1s"), Ok(Duration::from_secs(1)));
        let error = parse_lease("100ms").unwrap_err();
        assert!(
            error.starts_with("100ms: a lease is from 200ms to 600s (shorter"),
            "{error}"
        );
    }
}
