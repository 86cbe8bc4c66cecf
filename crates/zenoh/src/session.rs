//! Opening a Zenoh session the safe way: the endpoints given (a listening process on loopback
//! unless told otherwise), no multicast scouting unless asked ([`Role::Scout`]), TCP (and TLS,
//! with the `tls` feature) only; the
//! rest (certificates, access control) from Zenoh's own configuration file when one is given.
//! A process that connects also listens, on a port of its own beside it, so that the others,
//! told of it by Zenoh's gossip, link to it directly: postings go straight from poster to reader.
//! The robots of a team given each other's endpoints ([`Role::Mesh`]) dial each other and dial
//! again for as long as one is away, so a pair cut apart links again soon after its link works.

use crate::error::NetworkError;
use std::path::PathBuf;
use std::time::Duration;

/// How a process meets the others of a whiteboard (none holds it).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Role {
    /// Listens on this endpoint (`tcp/127.0.0.1:7447`) for the others to connect to.
    Listen(String),
    /// Connects to the process listening on this endpoint, and through it meets the rest.
    Connect(String),
    /// Listens on `listen` and links to every process of `peers` (the team's endpoints; this
    /// process's own, `listen` itself, is skipped, so every robot can be given one list). Each
    /// pair is dialled from both ends, and a link that closes is dialled again every
    /// [`MESH_RETRY`] with a fresh connection, however long the other is away. A process that
    /// starts before the others goes on alone.
    Mesh { listen: String, peers: Vec<String> },
    /// Finds the others on the local network by Zenoh's multicast scouting (UDP to
    /// 224.0.0.224:7446 unless Zenoh's configuration file says otherwise), and listens on a free
    /// port of every interface for them to link to.
    Scout,
}

/// How a session is set up beyond its endpoint. Every process of one board must agree.
#[derive(Clone, Debug, Default)]
pub struct Settings {
    /// Zenoh's own JSON5 configuration (TLS, access control), read first.
    pub config_file: Option<PathBuf>,
    /// Zenoh's low-latency transport: a message goes straight to the socket, with no queue,
    /// batching, fragmentation or priorities: shorter round trips, fewer messages a second
    /// (`cargo bench --features zenoh --bench network` compares them). No message may exceed
    /// 60 KiB: a larger posting is not sent (logged as an error).
    pub low_latency: bool,
    /// How long a process may go unheard before the others count it gone: its types turn
    /// stale, its claims pass on, its team values drop out ([`DEFAULT_LEASE`] unless given).
    /// Zenoh's link lease: a keep-alive goes every quarter of it, and a link that hears
    /// nothing for the whole of it is closed (docs/spec/behaviour.md §1.1, "Partitions").
    pub lease: Option<Duration>,
    /// How long one dial of a [`Role::Mesh`] may take before it is made again
    /// ([`DEFAULT_DIAL`] unless given): longer on a network of long round trips, whose dials
    /// would otherwise never finish.
    pub dial: Option<Duration>,
}

/// The lease when none is given: a robot cut off its team's Wi-Fi is seen gone within it, while
/// a link that works but loses 10% of its packets is not closed: TCP sends a lost segment again
/// after 0.2, 0.6 and 1.4 s, so only four losses in a row stall it past 1.5 s (at 1 s, three
/// do). Zenoh's own default, 10 s, leaves a cut robot striking beside its successor that long.
pub const DEFAULT_LEASE: Duration = Duration::from_millis(1500);

/// How often a process of a [`Role::Mesh`] dials a peer it is not linked to. A dial whose SYN
/// was lost is given up after [`Settings::dial`] and made again, rather than left to TCP, which
/// sends a lost SYN again only after 1, 2 and 4 s: a pair that was cut apart is linked again
/// within about one dial and one wait of its link working.
pub const MESH_RETRY: Duration = Duration::from_millis(100);

/// How long a dial of a mesh may take when not told ([`Settings::dial`]): a TCP connection and
/// Zenoh's two exchanges, three round trips, so links of round trips up to about 150 ms.
pub const DEFAULT_DIAL: Duration = Duration::from_millis(500);

/// The shortest lease taken: below it, a loaded robot's keep-alives come late and links that
/// work are closed.
pub const SHORTEST_LEASE: Duration = Duration::from_millis(200);

impl Settings {
    /// The lease this process announces and holds the others to.
    pub fn lease(&self) -> Duration {
        self.lease.unwrap_or(DEFAULT_LEASE).max(SHORTEST_LEASE)
    }

    /// How long one dial of a mesh may take.
    pub fn dial(&self) -> Duration {
        self.dial.unwrap_or(DEFAULT_DIAL)
    }

    /// The largest message this transport carries, if it has a limit. The low-latency
    /// transport frames each message alone in one batch (at most 64 KiB with Zenoh's headers).
    pub(crate) fn message_limit(&self) -> Option<usize> {
        self.low_latency.then_some(60 * 1024)
    }
}

pub(crate) async fn open(role: &Role, settings: &Settings) -> Result<zenoh::Session, NetworkError> {
    zenoh::open(config(role, settings)?)
        .await
        .map_err(|e| match role {
            Role::Listen(endpoint) => {
                NetworkError::zenoh(format!("cannot listen on {endpoint}"), e)
            }
            Role::Connect(endpoint) => {
                NetworkError::zenoh(format!("cannot reach a whiteboard at {endpoint}"), e)
            }
            Role::Mesh { listen, .. } => {
                NetworkError::zenoh(format!("cannot listen on {listen}"), e)
            }
            Role::Scout => NetworkError::zenoh("cannot scout for a whiteboard", e),
        })
}

/// Zenoh's configuration for `role` and `settings`: the file's, if given, with this crate's
/// choices written over it.
fn config(role: &Role, settings: &Settings) -> Result<zenoh::Config, NetworkError> {
    let mut config = match &settings.config_file {
        Some(path) => zenoh::Config::from_file(path).map_err(|e| NetworkError::Config {
            path: path.clone(),
            cause: e.to_string(),
        })?,
        None => zenoh::Config::default(),
    };
    let (listen, connect) = match role {
        Role::Listen(e) => (vec![e.clone()], Vec::new()),
        Role::Connect(e) => (beside(e).into_iter().collect(), vec![e.clone()]),
        Role::Mesh { listen, peers } => (vec![listen.clone()], dialled(listen, peers, settings)),
        Role::Scout => (vec!["tcp/0.0.0.0:0".to_string()], Vec::new()),
    };
    for e in listen.iter().chain(&connect) {
        if !e.contains('/') {
            return Err(NetworkError::Endpoint(e.clone()));
        }
    }
    if let Role::Mesh { listen, .. } = role {
        if every_address(listen) {
            return Err(NetworkError::MeshListen(listen.clone()));
        }
    }
    set(&mut config, "mode", "\"peer\"".into())?;
    // A process connecting over TLS listens where the configuration file says, if anywhere.
    if !listen.is_empty() || settings.config_file.is_none() {
        set(&mut config, "listen/endpoints", json_list(&listen))?;
    }
    set(&mut config, "connect/endpoints", json_list(&connect))?;
    let scouting = *role == Role::Scout;
    set(
        &mut config,
        "scouting/multicast/enabled",
        scouting.to_string(),
    )?;
    // Two processes told of each other by gossip at once must not both dial: the low-latency
    // transport cannot take the second link of a pair, tears the pair's transport down on
    // both sides, and gossip never dials again, so the two stay unlinked and each loses all
    // the other posts. Only the process with the greater id dials; every process listens.
    // Two that scout each other at once are the same case.
    for how in ["gossip", "multicast"] {
        set(
            &mut config,
            &format!("scouting/{how}/autoconnect_strategy"),
            "{peer: {to_peer: \"greater-zid\"}}".into(),
        )?;
    }
    dialling(&mut config, role, settings)?;
    // A link that hears nothing for a lease is closed, so the peer's tokens go (its types turn
    // stale) while a cut lasts, not after it heals. Dialling outside a mesh keeps Zenoh's 10 s:
    // a peer told of by gossip is dialled once, and TCP sends a lost SYN again only after 1, 2,
    // 4 s, so a shorter wait leaves pairs unlinked at a lossy link (docs/spec §1.1).
    let lease = settings.lease().as_millis().to_string();
    set(&mut config, "transport/link/tx/lease", lease)?;
    set(&mut config, "transport/link/tx/keep_alive", "4".into())?;
    if settings.low_latency {
        set(&mut config, "transport/unicast/lowlatency", "true".into())?;
        set(&mut config, "transport/unicast/qos/enabled", "false".into())?;
    }
    Ok(config)
}

/// How `role` dials: a mesh again and again with short dials, a joiner until it finds the board.
fn dialling(
    config: &mut zenoh::Config,
    role: &Role,
    settings: &Settings,
) -> Result<(), NetworkError> {
    if let Role::Mesh { .. } = role {
        // A robot up before its teammates goes on alone, and dials them until they come. Each
        // dial is short and made again soon: Zenoh's connector does so for the endpoints
        // configured, for as long as a peer is away, and gossip never dials those. The one-off
        // dial of a process told of by gossip (a watcher's laptop) gets the same short wait,
        // with no TCP resend inside it, so a lost SYN leaves that pair unlinked until the mesh
        // changes; the watcher's own dial, if its id is the greater, waits the usual 10 s.
        set(config, "connect/exit_on_failure", "false".into())?;
        let retry = MESH_RETRY.as_millis();
        set(
            config,
            "connect/retry",
            format!(
                "{{period_init_ms: {retry}, period_max_ms: {retry}, period_increase_factor: 1}}"
            ),
        )?;
        let dial = settings.dial().as_millis().to_string();
        set(config, "transport/unicast/open_timeout", dial)?;
        // Nor does opening wait for the teammates: the members' meeting (`members.rs`) waits
        // for them itself, and Zenoh's own wait only warns that they were not up.
        set(
            config,
            "open/return_conditions/connect_scouted",
            "false".into(),
        )?;
    } else {
        // A process joining must find the board, or say so, not wait for ever.
        set(config, "connect/exit_on_failure", "true".into())?;
        set(config, "connect/timeout_ms", "5000".into())?;
        // A process that was away (the listening one restarted) is linked again within a second.
        set(
            config,
            "connect/retry",
            "{period_init_ms: 100, period_max_ms: 500, period_increase_factor: 2}".into(),
        )?;
    }
    Ok(())
}

/// Writes one of Zenoh's settings, or says which Zenoh refused.
fn set(config: &mut zenoh::Config, key: &str, value: String) -> Result<(), NetworkError> {
    config
        .insert_json5(key, &value)
        .map_err(|e| NetworkError::zenoh(format!("Zenoh refused {key} = {value}"), e))
}

/// The peers of a mesh that a process listening on `listen` dials: every one but itself. The
/// universal transport takes a link from each end of a pair (one inbound and one outbound
/// link), so both ends dial and whichever gets through first links the pair. The low-latency
/// transport takes one link a pair and tears the pair down at a second, so there only the end
/// whose endpoint sorts greater dials.
fn dialled(listen: &str, peers: &[String], settings: &Settings) -> Vec<String> {
    let mut dialled: Vec<String> = peers
        .iter()
        .filter(|p| p.as_str() != listen)
        .filter(|p| !settings.low_latency || p.as_str() < listen)
        .cloned()
        .collect();
    dialled.sort();
    dialled.dedup();
    dialled
}

/// Whether `endpoint` listens on every address of the machine (`tcp/0.0.0.0:7447`,
/// `tcp/[::]:7447`).
fn every_address(endpoint: &str) -> bool {
    let address = endpoint.split_once('/').map_or(endpoint, |(_, a)| a);
    let host = address.rsplit_once(':').map_or(address, |(h, _)| h);
    let host = host.trim_start_matches('[').trim_end_matches(']');
    host.parse::<std::net::IpAddr>()
        .is_ok_and(|ip| ip.is_unspecified())
}

/// Where a process connecting to `endpoint` listens for the others: a free port on loopback when
/// the endpoint is on loopback, on every interface otherwise. Over TLS a process listens only
/// where Zenoh's configuration file says (it needs its own certificate to).
fn beside(endpoint: &str) -> Option<String> {
    let address = endpoint.strip_prefix("tcp/")?;
    let loopback = address.starts_with("127.") || address.starts_with("localhost:");
    Some(
        if loopback {
            "tcp/127.0.0.1:0"
        } else {
            "tcp/0.0.0.0:0"
        }
        .to_string(),
    )
}

fn json_list(items: &[String]) -> String {
    let quoted: Vec<String> = items.iter().map(|i| format!("{i:?}")).collect();
    format!("[{}]", quoted.join(","))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn setting(config: &zenoh::Config, key: &str) -> String {
        config.get_json(key).unwrap().replace(' ', "")
    }

    #[test]
    fn a_listening_process_listens_where_told_and_dials_nobody() {
        let role = Role::Listen("tcp/127.0.0.1:7447".into());
        let config = config(&role, &Settings::default()).unwrap();
        assert_eq!(setting(&config, "mode"), "\"peer\"");
        assert_eq!(
            setting(&config, "listen/endpoints"),
            r#"["tcp/127.0.0.1:7447"]"#
        );
        assert_eq!(setting(&config, "connect/endpoints"), "[]");
        assert_eq!(setting(&config, "scouting/multicast/enabled"), "false");
        assert_eq!(setting(&config, "transport/unicast/lowlatency"), "false");
        assert_eq!(setting(&config, "transport/link/tx/lease"), "1500");
    }

    #[test]
    fn the_lease_is_the_one_given_and_never_below_the_shortest() {
        let lease = |ms| {
            let settings = Settings {
                lease: Some(Duration::from_millis(ms)),
                ..Settings::default()
            };
            let config = config(&Role::Listen("tcp/127.0.0.1:7447".into()), &settings).unwrap();
            setting(&config, "transport/link/tx/lease")
        };
        assert_eq!(lease(2500), "2500");
        assert_eq!(lease(5), SHORTEST_LEASE.as_millis().to_string());
    }

    #[test]
    fn a_connecting_process_also_listens_beside_on_the_same_side_of_loopback() {
        let role = Role::Connect("tcp/127.0.0.1:7447".into());
        let config = config(&role, &Settings::default()).unwrap();
        assert!(setting(&config, "listen/endpoints").contains("\"tcp/127.0.0.1:0\""));
        assert!(setting(&config, "connect/endpoints").contains("\"tcp/127.0.0.1:7447\""));
        assert_eq!(
            beside("tcp/10.0.0.2:7447").as_deref(),
            Some("tcp/0.0.0.0:0")
        );
        assert_eq!(
            beside("tcp/localhost:7447").as_deref(),
            Some("tcp/127.0.0.1:0")
        );
        assert_eq!(beside("tls/10.0.0.2:7447"), None);
    }

    #[test]
    fn a_mesh_dials_every_peer_but_itself_again_and_again_with_short_dials() {
        let peers: Vec<String> = [
            "tcp/10.0.0.3:7447",
            "tcp/10.0.0.1:7447",
            "tcp/10.0.0.2:7447",
        ]
        .map(String::from)
        .into();
        let role = |settings: &Settings| {
            let role = Role::Mesh {
                listen: "tcp/10.0.0.2:7447".into(),
                peers: peers.clone(),
            };
            config(&role, settings).unwrap()
        };
        let config = role(&Settings::default());
        assert_eq!(
            setting(&config, "listen/endpoints"),
            r#"["tcp/10.0.0.2:7447"]"#
        );
        assert_eq!(
            setting(&config, "connect/endpoints"),
            r#"["tcp/10.0.0.1:7447","tcp/10.0.0.3:7447"]"#
        );
        // The first robot up goes on alone and keeps dialling, a dial at a time.
        assert_eq!(setting(&config, "connect/exit_on_failure"), "false");
        assert!(setting(&config, "connect/retry").contains("\"period_max_ms\":100"));
        assert_eq!(setting(&config, "transport/unicast/open_timeout"), "500");
        // Low latency takes one link a pair: only the greater endpoint dials.
        let low = role(&Settings {
            low_latency: true,
            ..Settings::default()
        });
        assert_eq!(
            setting(&low, "connect/endpoints"),
            r#"["tcp/10.0.0.1:7447"]"#
        );
        // A robot listening on every address cannot tell itself in the list.
        let everywhere = Role::Mesh {
            listen: "tcp/0.0.0.0:7447".into(),
            peers: peers.clone(),
        };
        let error = super::config(&everywhere, &Settings::default()).unwrap_err();
        assert!(matches!(&error, NetworkError::MeshListen(_)), "{error}");
        assert!(every_address("tcp/[::]:7447"));
        assert!(!every_address("tcp/10.0.0.2:7447"));
        // A network of long round trips is given longer dials.
        let slow = role(&Settings {
            dial: Some(Duration::from_secs(2)),
            ..Settings::default()
        });
        assert_eq!(setting(&slow, "transport/unicast/open_timeout"), "2000");
        // Outside a mesh, a joiner must find the board and each dial waits out TCP's resends.
        let joiner = config_of(&Role::Connect("tcp/10.0.0.1:7447".into()));
        assert_eq!(setting(&joiner, "connect/exit_on_failure"), "true");
        assert_eq!(setting(&joiner, "transport/unicast/open_timeout"), "10000");
    }

    fn config_of(role: &Role) -> zenoh::Config {
        config(role, &Settings::default()).unwrap()
    }

    #[test]
    fn low_latency_switches_the_queues_off() {
        let settings = Settings {
            low_latency: true,
            ..Settings::default()
        };
        let config = config(&Role::Listen("tcp/127.0.0.1:7447".into()), &settings).unwrap();
        assert_eq!(setting(&config, "transport/unicast/lowlatency"), "true");
        assert_eq!(setting(&config, "transport/unicast/qos/enabled"), "false");
        assert_eq!(settings.message_limit(), Some(60 * 1024));
        assert_eq!(Settings::default().message_limit(), None);
    }

    #[test]
    fn an_endpoint_without_its_protocol_is_refused_by_name() {
        let error = config(
            &Role::Connect("127.0.0.1:7447".into()),
            &Settings::default(),
        )
        .unwrap_err();
        assert!(matches!(&error, NetworkError::Endpoint(e) if e == "127.0.0.1:7447"));
        assert!(error.to_string().contains("tcp/HOST:PORT"), "{error}");
    }

    #[test]
    fn a_missing_configuration_file_is_named() {
        let settings = Settings {
            config_file: Some(PathBuf::from("no/such/zenoh.json5")),
            ..Settings::default()
        };
        let error = config(&Role::Listen("tcp/127.0.0.1:7447".into()), &settings).unwrap_err();
        assert!(
            matches!(&error, NetworkError::Config { path, .. } if path.ends_with("zenoh.json5")),
            "{error}"
        );
        assert!(error.to_string().contains("no/such/zenoh.json5"), "{error}");
    }

    #[test]
    fn endpoints_are_written_as_a_json_list() {
        assert_eq!(json_list(&[]), "[]");
        assert_eq!(
            json_list(&["tcp/127.0.0.1:1".into(), "tcp/[::1]:2".into()]),
            r#"["tcp/127.0.0.1:1","tcp/[::1]:2"]"#
        );
    }
}
