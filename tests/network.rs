//! The whiteboard across `proclaim` processes over Zenoh (built with `--features zenoh`): a
//! behaviour split over processes runs, loses an expert that dies (its labels time out) and gets it
//! back; a board of four processes outlives each of them killed in turn; the commands that poke at
//! a live board work; TLS through Zenoh's own configuration; sessions joining at once. (Every
//! whiteboard semantic is checked over Zenoh by the whiteboard suite, `whiteboard::over_zenoh`;
//! joining, catching up, staleness and signals between sessions are crates/zenoh's own tests.)
//! Everything is on 127.0.0.1, on free ports, bounded in count and time.

use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

/// How long a test waits for a line a process must print: generous, for a loaded two-core CI
/// machine where starting a process and its Zenoh session can take seconds; a line that never
/// comes still fails.
const PATIENCE: Duration = Duration::from_secs(60);

/// An endpoint on loopback no one listens on yet.
pub fn free_endpoint() -> String {
    let port = std::net::TcpListener::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    format!("tcp/127.0.0.1:{port}")
}

/// Why joining `board` at `endpoint` with default settings fails (it must).
#[cfg(feature = "zenoh-tls")]
async fn join_error(endpoint: &str, board: &str) -> String {
    use proclaim_zenoh::{whiteboard, Role, Settings};
    whiteboard(&Role::Connect(endpoint.into()), board, &Settings::default())
        .await
        .err()
        .expect("joining fails")
        .to_string()
}

/// TLS through Zenoh's own configuration: a CA, a certificate for 127.0.0.1 signed by it, the
/// holder listening on `tls/…` with them, a replica that trusts the CA joining, one that does not
/// refused. Certificates are made with the `openssl` command; without it the test says so and
/// checks nothing.
#[cfg(feature = "zenoh-tls")]
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn tls_is_switched_on_through_zenohs_own_configuration() {
    use proclaim_board::Value;
    use proclaim_zenoh::{whiteboard, Role, Settings};
    let dir = crate::behaviour_folder(
        "tls",
        &[(
            "server.ext",
            "subjectAltName=DNS:localhost,IP:127.0.0.1\nbasicConstraints=CA:FALSE\nextendedKeyUsage=serverAuth\n",
        )],
    );
    let openssl = |args: &[&str]| {
        Command::new("openssl")
            .args(args)
            .current_dir(&dir)
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .status()
            .map(|s| s.success())
    };
    let ec = [
        "-newkey",
        "ec",
        "-pkeyopt",
        "ec_paramgen_curve:prime256v1",
        "-nodes",
    ];
    let made = [
        [
            &["req", "-x509"][..],
            &ec[..],
            &[
                "-keyout",
                "ca.key",
                "-out",
                "ca.pem",
                "-days",
                "2",
                "-subj",
                "/CN=proclaim test CA",
            ][..],
        ]
        .concat(),
        [
            &["req"][..],
            &ec[..],
            &[
                "-keyout",
                "key.pem",
                "-out",
                "server.csr",
                "-subj",
                "/CN=127.0.0.1",
            ][..],
        ]
        .concat(),
        vec![
            "x509",
            "-req",
            "-in",
            "server.csr",
            "-CA",
            "ca.pem",
            "-CAkey",
            "ca.key",
            "-CAcreateserial",
            "-out",
            "cert.pem",
            "-days",
            "2",
            "-extfile",
            "server.ext",
        ],
    ]
    .iter()
    .map(|args| openssl(args))
    .collect::<Result<Vec<bool>, _>>();
    match made {
        Err(_) => {
            eprintln!("no `openssl` command: TLS not checked");
            return;
        }
        Ok(ok) => assert!(
            ok.iter().all(|b| *b),
            "openssl could not make the certificates"
        ),
    }
    let config = |name: &str, tls: String| {
        let path = dir.join(name);
        std::fs::write(
            &path,
            format!("{{ transport: {{ link: {{ tls: {{ {tls} }} }} }} }}"),
        )
        .unwrap();
        Settings {
            config_file: Some(path),
            low_latency: false,
            ..Settings::default()
        }
    };
    let file = |f: &str| dir.join(f).display().to_string();
    let holder_settings = config(
        "holder.json5",
        format!(
            "listen_private_key: {:?}, listen_certificate: {:?}",
            file("key.pem"),
            file("cert.pem")
        ),
    );
    let trusting = config(
        "trusting.json5",
        format!("root_ca_certificate: {:?}", file("ca.pem")),
    );
    let endpoint = free_endpoint().replace("tcp/", "tls/");
    let holder = whiteboard(&Role::Listen(endpoint.clone()), "tls", &holder_settings)
        .await
        .expect("listens over TLS");
    let replica = whiteboard(&Role::Connect(endpoint.clone()), "tls", &trusting)
        .await
        .expect("a replica that trusts the CA joins");
    replica.post("vision", "ballSeen", true);
    let seen = holder.wait_for("ballSeen", 0, PATIENCE).await;
    assert_eq!(seen.map(|m| m.value), Some(Value::Bool(true)));
    // Trusting nobody in particular (the system's roots), the certificate is refused.
    let error = join_error(&endpoint, "tls").await;
    assert!(error.contains(&endpoint), "{error}");
}

/// Waits until `done` holds, at most [`PATIENCE`]: on a loaded two-core CI machine Zenoh's
/// gossip and links can take seconds; a pair that never hears the other still fails.
async fn until(what: &str, done: impl Fn() -> bool) {
    let deadline = std::time::Instant::now() + PATIENCE;
    while !done() {
        assert!(
            std::time::Instant::now() < deadline,
            "not within {PATIENCE:?}: {what}"
        );
        tokio::time::sleep(Duration::from_millis(10)).await;
    }
}

/// Processes that join at once are told of each other by gossip at once; every pair must end up
/// linked (over the low-latency transport, a pair that both dialled lost its link for good, and
/// neither heard the other again).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn processes_joining_at_once_all_hear_each_other() {
    use proclaim_zenoh::{whiteboard, Role, Settings};
    let endpoint = free_endpoint();
    let settings = Settings {
        config_file: None,
        low_latency: true,
        ..Settings::default()
    };
    let first = whiteboard(&Role::Listen(endpoint.clone()), "crowd", &settings)
        .await
        .unwrap();
    let role = Role::Connect(endpoint);
    let joiner = || whiteboard(&role, "crowd", &settings);
    let (b, c, d, e) = tokio::join!(joiner(), joiner(), joiner(), joiner());
    let boards = [first, b.unwrap(), c.unwrap(), d.unwrap(), e.unwrap()];
    for (i, board) in boards.iter().enumerate() {
        board.post("crowd", &format!("hello{i}"), i as i64);
    }
    for (i, board) in boards.iter().enumerate() {
        for j in (0..boards.len()).filter(|j| *j != i) {
            until(&format!("process {i} hears process {j}"), || {
                board.latest(&format!("hello{j}")).is_some()
            })
            .await;
        }
    }
}

/// A child process, killed when dropped.
struct Process(Child);

impl Drop for Process {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn proclaim(args: &[&str]) -> Process {
    Process(
        Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(args)
            .env("NO_COLOR", "1")
            .stdin(Stdio::null())
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .expect("the binary runs"),
    )
}

/// Lines of a child's output, read on a thread so the test can wait with a bound.
fn lines(child: &mut Process) -> std::sync::mpsc::Receiver<String> {
    lines_of(child.0.stdout.take().unwrap())
}

/// Lines of `out`, read on a thread.
fn lines_of(out: impl std::io::Read + Send + 'static) -> std::sync::mpsc::Receiver<String> {
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            if tx.send(line).is_err() {
                return;
            }
        }
    });
    rx
}

/// Waits (at most `limit`) for a line containing `text`; returns the lines read until then.
fn wait_line(rx: &std::sync::mpsc::Receiver<String>, text: &str, limit: Duration) -> Vec<String> {
    let deadline = std::time::Instant::now() + limit;
    let mut seen = Vec::new();
    while let Some(left) = deadline.checked_duration_since(std::time::Instant::now()) {
        match rx.recv_timeout(left) {
            Ok(line) => {
                let found = line.contains(text);
                seen.push(line);
                if found {
                    return seen;
                }
            }
            Err(_) => break,
        }
    }
    panic!(
        "no line with `{text}` within {limit:?}; read:\n{}",
        seen.join("\n")
    );
}

/// `proclaim run` of a one-machine behaviour (its manifest and the machine the manifest's
/// `file` names) holding the board on a free loopback port: the process, its output, the
/// endpoint.
fn listening(
    tag: &str,
    manifest: &str,
    machine: &str,
) -> (Process, std::sync::mpsc::Receiver<String>, String) {
    let file = manifest
        .split('"')
        .find(|p| p.ends_with(".machine"))
        .expect("the manifest names a .machine file");
    let dir = crate::behaviour_folder(tag, &[("behaviour.toml", manifest), (file, machine)]);
    let endpoint = free_endpoint();
    let mut run = proclaim(&[
        "run",
        dir.to_str().unwrap(),
        "--listen",
        &endpoint,
        "--for",
        "60s",
    ]);
    let trace = lines(&mut run);
    wait_line(&trace, "listening on", PATIENCE);
    (run, trace, endpoint)
}

#[test]
fn a_behaviour_split_over_processes_loses_a_dead_expert_and_gets_it_back() {
    let (_run, trace, endpoint) = listening(
        "net",
        "answer_timeout = \"300ms\"\n[[machine]]\nfile = \"Oven.machine\"\n",
        "machine Oven\nstate IDLE {\n  when cook -> COOKING\n}\nstate COOKING {\n  when ~cook -> IDLE\n}\n",
    );
    // Nobody answers `cook` yet.
    wait_line(&trace, "cook: no expert answers it", PATIENCE);

    let expert = proclaim(&["expert", "microwave", "--connect", &endpoint]);
    let post = |ty: &str, value: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(["post", ty, value, "--connect", &endpoint])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    wait_line(&trace, "cook = false  (microwave)", PATIENCE);
    post("doorOpen", "false");
    post("timeLeft", "true");
    wait_line(&trace, "Oven  → COOKING", PATIENCE);

    // The expert dies: its label times out and the machine goes on.
    drop(expert);
    wait_line(&trace, "cook: no answer in time, counted false", PATIENCE);
    wait_line(&trace, "Oven  → IDLE", PATIENCE);
    // It comes back, and is answered again without restarting the machine.
    let _expert = proclaim(&["expert", "microwave", "--connect", &endpoint]);
    wait_line(&trace, "cook = true  (microwave)", PATIENCE);
    wait_line(&trace, "Oven  → COOKING", PATIENCE);
}

#[test]
fn post_watch_and_ping_poke_at_a_live_whiteboard() {
    let (_run, trace, endpoint) = listening(
        "watch-net",
        "[[machine]]\nfile = \"M.machine\"\n",
        // B is not final, or the run (and the board) would end there.
        "machine M\nstate A {\n  when go -> B\n}\nstate B {\n  when stop -> A\n}\n",
    );
    let mut watch = proclaim(&["watch", "go*", "--connect", &endpoint, "--for", "20s"]);
    let watched = lines(&mut watch);
    std::thread::sleep(Duration::from_millis(500));
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args([
            "post",
            "go",
            "true",
            "--connect",
            &endpoint,
            "--module",
            "tester",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(String::from_utf8_lossy(&o.stdout).starts_with("posted go = true (#"));
    let seen = wait_line(&watched, "go = true", PATIENCE);
    assert!(seen.last().unwrap().contains("tester"), "{seen:?}");
    wait_line(&trace, "M  → B", PATIENCE);

    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["ping", "--count", "20", "--connect", &endpoint])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        out.starts_with("20 round trips to a process of `proclaim`: p50 "),
        "{out}"
    );
    // Asked of nobody, it says so.
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["ping", "--count", "1", "--connect", &free_endpoint()])
        .output()
        .unwrap();
    assert!(!o.status.success());
    assert!(String::from_utf8_lossy(&o.stderr).contains("tcp/127.0.0.1:"));
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["ping", "--count", "0", "--connect", &endpoint])
        .output()
        .unwrap();
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--count 0"));
}

/// A folder holding a one-machine behaviour: the machine `name` in `name.machine`.
fn behaviour(tag: &str, name: &str, machine: &str) -> String {
    let file = format!("{name}.machine");
    let manifest = format!("[[machine]]\nfile = \"{file}\"\n");
    crate::behaviour_folder(
        tag,
        &[
            ("behaviour.toml", manifest.as_str()),
            (file.as_str(), machine),
        ],
    )
    .display()
    .to_string()
}

/// A machine that goes to SEEN while `ballSeen` is true and back while it is not.
fn follower(name: &str) -> String {
    format!(
        "machine {name}\nstate WAIT {{\n  when ballSeen -> SEEN\n}}\nstate SEEN {{\n  when ~ballSeen -> WAIT\n}}\n"
    )
}

/// A machine that follows `ballSeen` and, while the sensor that posted it is gone, is blind.
const STRIKER: &str = "machine Striker\nstate WAIT {\n  when ballSeen -> SEEN\n}\nstate SEEN {\n  when ballSeenStale -> BLIND\n  when ~ballSeen -> WAIT\n}\nstate BLIND {\n  when ~ballSeenStale -> WAIT\n}\n";

/// A sensor: posts `ballSeen` once, then a `tick` counting up every 200 ms for ever.
const SENSOR: &str = "machine Sensor\ninitial INIT\nstate INIT {\n  entry {\n    int n;\n    ballSeen: true\n  }\n  when TRUE -> A\n}\nstate A {\n  entry {\n    n = n + 1;\n    post(\"tick\", n);\n  }\n  when timeout(200000) -> B\n}\nstate B {\n  entry {\n    n = n + 1;\n    post(\"tick\", n);\n  }\n  when timeout(200000) -> A\n}\n";

/// The `tick` values in a watcher's lines, in order.
fn ticks(lines: &[String]) -> Vec<i64> {
    lines
        .iter()
        .filter(|l| l.contains(" Sensor ") && l.contains(" tick = "))
        .filter_map(|l| l.rsplit(" = ").next()?.trim().parse().ok())
        .collect()
}

/// Every tick a watcher printed follows the one before it, except where the sensor restarted
/// (it counts from 1 again).
fn assert_no_tick_missed(ticks: &[i64]) {
    for pair in ticks.windows(2) {
        assert!(
            pair[1] == pair[0] + 1 || pair[1] <= 2,
            "a posting was missed between {} and {}: {ticks:?}",
            pair[0],
            pair[1]
        );
    }
}

/// Kills a process at once, as a crash would (SIGKILL on Unix).
fn kill(process: &mut Process) {
    let _ = process.0.kill();
    let _ = process.0.wait();
}

#[test]
fn a_board_of_four_processes_outlives_each_of_them_killed_in_turn() {
    let endpoint = free_endpoint();
    let keeper = behaviour("four-keeper", "Keeper", &follower("Keeper"));
    let striker = behaviour("four-striker", "Striker", STRIKER);
    let sensor = behaviour("four-sensor", "Sensor", SENSOR);
    let start = |which: &str| -> (Process, std::sync::mpsc::Receiver<String>) {
        let mut process = match which {
            "keeper" => proclaim(&["run", &keeper, "--listen", &endpoint, "--for", "120s"]),
            "striker" => proclaim(&["run", &striker, "--connect", &endpoint, "--for", "120s"]),
            "sensor" => proclaim(&["run", &sensor, "--connect", &endpoint, "--for", "120s"]),
            _ => proclaim(&["watch", "*", "--connect", &endpoint, "--for", "120s"]),
        };
        let out = lines(&mut process);
        (process, out)
    };
    let (mut keeper_p, mut keeper_out) = start("keeper");
    wait_line(&keeper_out, "listening on", PATIENCE);
    let (mut sensor_p, mut sensor_out) = start("sensor");
    let (mut striker_p, mut striker_out) = start("striker");
    let (mut watch_p, mut watch_out) = start("watch");
    wait_line(&keeper_out, "Keeper  → SEEN", PATIENCE);
    wait_line(&striker_out, "Striker  → SEEN", PATIENCE);
    let mut watched = wait_line(&watch_out, "tick = 3", PATIENCE);

    let mut gone = Vec::new();
    for victim in ["keeper", "sensor", "striker", "watch"] {
        kill(match victim {
            "keeper" => &mut keeper_p,
            "sensor" => &mut sensor_p,
            "striker" => &mut striker_p,
            _ => &mut watch_p,
        });
        // The others go on: the watcher hears the sensor, or says it went stale.
        match victim {
            "sensor" => {
                // Every type the sensor posted turns stale, in no particular order.
                let stale = |gone: &[String], ty: &str| {
                    gone.iter()
                        .any(|l| l.contains(&format!(" {ty}Stale = true")))
                };
                while !(stale(&gone, "tick") && stale(&gone, "ballSeen")) {
                    assert!(gone.len() < 10, "{gone:?}");
                    let lines = wait_line(&watch_out, "Stale = true", PATIENCE);
                    gone.extend(lines.iter().filter(|l| l.contains("Stale = true")).cloned());
                    watched.extend(lines);
                }
                // A label reads staleness like any value.
                wait_line(&striker_out, "Striker  → BLIND", PATIENCE);
            }
            "watch" => {}
            _ => {
                let before = ticks(&watched).last().copied().unwrap_or(0);
                watched.extend(wait_line(
                    &watch_out,
                    &format!("tick = {}", before + 3),
                    PATIENCE,
                ));
            }
        }
        let restarted = std::time::Instant::now();
        let (new_process, new_out) = start(victim);
        let (process, out) = match victim {
            "keeper" => (&mut keeper_p, &mut keeper_out),
            "sensor" => (&mut sensor_p, &mut sensor_out),
            "striker" => (&mut striker_p, &mut striker_out),
            _ => (&mut watch_p, &mut watch_out),
        };
        *process = new_process;
        *out = new_out;
        // The restarted one holds the current values: the behaviours see the ball the sensor
        // posted once, long before; a new watcher prints the current tick first.
        match victim {
            "keeper" => drop(wait_line(&keeper_out, "Keeper  → SEEN", PATIENCE)),
            "striker" => drop(wait_line(&striker_out, "Striker  → SEEN", PATIENCE)),
            "sensor" => {
                watched.extend(wait_line(&watch_out, "ballSeenStale = false", PATIENCE));
                wait_line(&striker_out, "Striker  → SEEN", PATIENCE);
            }
            _ => {
                assert_no_tick_missed(&ticks(&watched));
                watched = wait_line(&watch_out, "tick = ", PATIENCE);
            }
        }
        println!(
            "restarted {victim}: holds the current values after {} ms",
            restarted.elapsed().as_millis()
        );
    }
    let before = ticks(&watched).last().copied().unwrap_or(0);
    watched.extend(wait_line(
        &watch_out,
        &format!("tick = {}", before + 3),
        PATIENCE,
    ));
    assert_no_tick_missed(&ticks(&watched));
}

/// The checkpoint of the latest round among `dir`'s `cp.rROUND.json` files.
fn latest_checkpoint(dir: &std::path::Path) -> std::path::PathBuf {
    let round = |p: &std::path::Path| -> Option<u64> {
        let name = p.file_name()?.to_str()?;
        name.strip_prefix("cp.r")?
            .strip_suffix(".json")?
            .parse()
            .ok()
    };
    std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| round(p).is_some())
        .max_by_key(|p| round(p))
        .expect("a checkpoint was written")
}

/// Issue 49's crash recovery on a team's board: a process killed and taken up from its last
/// checkpoint goes on where it was, and the others see its values come back and its count go
/// on, not a process starting over.
#[test]
fn a_process_killed_and_taken_up_from_its_checkpoint_goes_on_on_the_shared_board() {
    let endpoint = free_endpoint();
    let sensor = behaviour("resume-sensor", "Sensor", SENSOR);
    let dir = std::path::PathBuf::from(&sensor);
    let file = dir.join("cp.json");
    // A teammate holds the endpoint; a watcher sees what the others see.
    let keeper = behaviour("resume-keeper", "Keeper", &follower("Keeper"));
    let mut keeper = proclaim(&["run", &keeper, "--listen", &endpoint, "--for", "120s"]);
    let keeper_out = lines(&mut keeper);
    wait_line(&keeper_out, "listening on", PATIENCE);
    // Read on, so a full pipe never holds up the process the others connect through.
    std::thread::spawn(move || keeper_out.iter().for_each(drop));
    let mut watch = proclaim(&["watch", "*", "--connect", &endpoint, "--for", "120s"]);
    let watch_out = lines(&mut watch);
    let every = |extra: &[&str]| {
        let mut args = vec!["run", &sensor, "--connect", &endpoint, "--for", "120s"];
        args.extend_from_slice(extra);
        args.iter().map(|a| a.to_string()).collect::<Vec<_>>()
    };
    let first = every(&[
        "--checkpoint-every",
        "2",
        "--checkpoint-file",
        file.to_str().unwrap(),
    ]);
    let mut run = proclaim(&first.iter().map(String::as_str).collect::<Vec<_>>());
    let mut watched = wait_line(&watch_out, "tick = 12", PATIENCE);
    kill(&mut run);
    watched.extend(wait_line(&watch_out, "tickStale = true", PATIENCE));
    let before = ticks(&watched).last().copied().unwrap();
    let checkpoint = latest_checkpoint(&dir);
    let taken_up = every(&["--resume", checkpoint.to_str().unwrap()]);
    let _run = proclaim(&taken_up.iter().map(String::as_str).collect::<Vec<_>>());
    // Its values are its own again, and it counts on from its checkpoint, not from 1.
    let after = wait_line(&watch_out, &format!("tick = {}", before + 3), PATIENCE);
    assert!(
        after.iter().any(|l| l.contains("ballSeenStale = false")),
        "{after:?}"
    );
    assert!(
        after.iter().any(|l| l.contains("tickStale = false")),
        "{after:?}"
    );
    let counted = ticks(&after);
    assert!(
        counted.iter().all(|t| *t + 3 > before),
        "it went back only as far as its checkpoint, at most a round or two: {before} then {counted:?}"
    );
    assert!(
        counted.windows(2).all(|w| w[1] == w[0] + 1 || w[1] <= w[0]),
        "{counted:?}"
    );
}

/// Reads a robot's lines until none comes for half a second (ten seconds at most): the state
/// its `Player` machine is in then, `state` if it did not move.
fn settled_player(rx: &std::sync::mpsc::Receiver<String>, mut state: String) -> String {
    let deadline = std::time::Instant::now() + Duration::from_secs(10);
    while std::time::Instant::now() < deadline {
        match rx.recv_timeout(Duration::from_millis(500)) {
            Ok(line) => {
                if let Some((_, to)) = line.split_once("Player  → ") {
                    state = to.trim().to_string();
                }
            }
            Err(_) => return state,
        }
    }
    panic!("the robot's Player never settled (last in {state})");
}

#[test]
fn a_team_elects_the_closest_robot_striker_and_the_next_closest_when_it_dies() {
    let endpoint = free_endpoint();
    let striker = concat!(env!("CARGO_MANIFEST_DIR"), "/machines/striker");
    // One behaviour, three robots: the manifest's member (robot1), then two named here.
    let mut robot1 = proclaim(&["run", striker, "--listen", &endpoint, "--for", "120s"]);
    let robot1_out = lines(&mut robot1);
    wait_line(&robot1_out, "robot1 of team `blue`", PATIENCE);
    let mut robots = Vec::new();
    for member in ["robot2", "robot3"] {
        let mut robot = proclaim(&[
            "run",
            striker,
            "--member",
            member,
            "--connect",
            &endpoint,
            "--for",
            "120s",
        ]);
        let out = lines(&mut robot);
        wait_line(&out, &format!("{member} of team `blue`"), PATIENCE);
        robots.push((robot, out));
    }
    // Each robot's vision says how far the ball is, on the robot's own board.
    for (member, distance) in [("robot1", "0.8"), ("robot2", "1.5"), ("robot3", "2.5")] {
        let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(["post", "ballDistance", distance, "--board", member])
            .args(["--connect", &endpoint])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    }
    wait_line(&robot1_out, "Player  → STRIKER", PATIENCE);
    let [(_, robot2_out), (_, robot3_out)] = &robots[..] else {
        unreachable!()
    };
    assert_eq!(settled_player(robot2_out, "SUPPORTER".into()), "SUPPORTER");
    assert_eq!(settled_player(robot3_out, "SUPPORTER".into()), "SUPPORTER");

    // The striker dies: the next closest takes the role, the farthest stays a supporter.
    kill(&mut robot1);
    let killed = std::time::Instant::now();
    wait_line(robot2_out, "Player  → STRIKER", PATIENCE);
    println!(
        "robot2 took the striker's role {} ms after robot1 was killed",
        killed.elapsed().as_millis()
    );
    assert_eq!(settled_player(robot3_out, "SUPPORTER".into()), "SUPPORTER");
}

/// Robots given each other's endpoints (`--peer`, the same list for all) link in whatever order
/// they start, the first going on alone, and a robot that dies and starts again is dialled
/// back by the others: the striker is elected, handed over, and taken back.
#[test]
fn a_team_given_each_others_endpoints_links_in_any_order_and_takes_a_restarted_robot_back() {
    let striker = concat!(env!("CARGO_MANIFEST_DIR"), "/machines/striker");
    let endpoints: Vec<String> = (0..3).map(|_| free_endpoint()).collect();
    let robot_with = |i: usize, peers: &[String]| {
        let member = format!("robot{}", i + 1);
        let mut args = vec!["run", striker, "--member", &member, "--for", "120s"];
        args.extend(["--listen", &endpoints[i]]);
        for e in peers {
            args.extend(["--peer", e.as_str()]);
        }
        let mut process = proclaim(&args);
        let out = lines(&mut process);
        let said = wait_line(&out, &format!("{member} of team `blue`"), PATIENCE);
        let listed = said.iter().any(|l| l.contains("linking to"));
        assert_eq!(listed, !peers.is_empty(), "{said:?}");
        (process, out)
    };
    let robot = |i: usize| robot_with(i, &endpoints);
    // robot3 first, alone: it goes on, and dials the others until they come.
    let mut robots = [robot(2), robot(0), robot(1)];
    robots.rotate_right(2);
    let vision = |i: usize, distance: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(["post", "ballDistance", distance])
            .args(["--board", &format!("robot{}", i + 1)])
            .args(["--connect", &endpoints[i]])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    for (i, distance) in ["0.8", "1.5", "2.5"].into_iter().enumerate() {
        vision(i, distance);
    }
    wait_line(&robots[0].1, "Player  → STRIKER", PATIENCE);
    assert_eq!(
        settled_player(&robots[1].1, "SUPPORTER".into()),
        "SUPPORTER"
    );
    assert_eq!(
        settled_player(&robots[2].1, "SUPPORTER".into()),
        "SUPPORTER"
    );

    // robot1 dies: robot2 strikes. robot1 starts again on its endpoint, given no peers this
    // time, so only the others' dials bring it back; it says its distance anew and takes the
    // role again.
    kill(&mut robots[0].0);
    wait_line(&robots[1].1, "Player  → STRIKER", PATIENCE);
    robots[0] = robot_with(0, &[]);
    vision(0, "0.8");
    wait_line(&robots[0].1, "Player  → STRIKER", PATIENCE);
    wait_line(&robots[1].1, "Player  → SUPPORTER", PATIENCE);
}

/// The first robot of a mesh up runs alone at once and quietly: no warning that its teammates
/// were not there yet (Zenoh's own wait for them once said so on every lone start).
#[test]
fn a_robot_alone_in_its_mesh_starts_at_once_and_says_nothing_amiss() {
    let striker = concat!(env!("CARGO_MANIFEST_DIR"), "/machines/striker");
    let (own, other) = (free_endpoint(), free_endpoint());
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["run", striker, "--member", "robot1", "--for", "1s"])
        .args(["--listen", &own, "--peer", &own, "--peer", &other])
        .env("NO_COLOR", "1")
        .output()
        .unwrap();
    let (out, err) = (
        String::from_utf8_lossy(&o.stdout),
        String::from_utf8_lossy(&o.stderr),
    );
    assert!(o.status.success(), "{err}");
    assert!(
        out.contains(&format!("linking to {other} as they come")),
        "{out}"
    );
    assert!(!err.contains("WARN") && !err.contains("Scouting"), "{err}");
}

#[test]
fn a_peer_without_an_address_of_its_own_is_refused() {
    let striker = concat!(env!("CARGO_MANIFEST_DIR"), "/machines/striker");
    let refused = |args: &[&str]| {
        let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(["run", striker, "--for", "1s"])
            .args(args)
            .output()
            .unwrap();
        assert!(!o.status.success());
        String::from_utf8_lossy(&o.stderr).into_owned()
    };
    let said = refused(&["--peer", "tcp/127.0.0.1:7447"]);
    assert!(said.contains("--listen"), "{said}");
    // Listening everywhere, it would find no own address in the list and dial itself.
    let everywhere = free_endpoint().replace("127.0.0.1", "0.0.0.0");
    let said = refused(&["--listen", &everywhere, "--peer", "tcp/127.0.0.1:7447"]);
    assert!(said.contains("own address"), "{said}");
}

#[test]
fn processes_started_with_scout_find_each_other_with_no_endpoint() {
    // A board of this test's own, so other processes scouting on the network do not mix in.
    let board = format!("scout{}", std::process::id());
    let follower = behaviour("scout", "Follower", &follower("Follower"));
    let mut run = proclaim(&[
        "run", &follower, "--scout", "--board", &board, "--for", "60s",
    ]);
    let out = lines(&mut run);
    wait_line(&out, "found by multicast scouting", PATIENCE);
    wait_line(&out, "Follower  → WAIT", PATIENCE);
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["post", "ballSeen", "true", "--scout", "--board", &board])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        String::from_utf8_lossy(&o.stdout).contains("heard by 1 process"),
        "{}",
        String::from_utf8_lossy(&o.stdout)
    );
    wait_line(&out, "Follower  → SEEN", PATIENCE);
}

/// `behaviour` (a folder) compiled to Rust and built with the `network` feature: its folder and
/// its program. Every such build shares one target folder, so Zenoh's stack builds once.
fn compiled_with_network(tag: &str, behaviour: &str) -> (std::path::PathBuf, std::path::PathBuf) {
    let project = crate::compiled::scratch(tag);
    let o = crate::proclaim(&[
        "compile",
        behaviour,
        "--target",
        "rust",
        "-o",
        project.to_str().unwrap(),
        "--whiteboard",
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let target = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("rust-network");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let o = Command::new(cargo)
        .args(["build", "--offline", "--quiet", "--features", "network"])
        .current_dir(&project)
        .env("CARGO_TARGET_DIR", &target)
        .env("CARGO_PROFILE_DEV_DEBUG", "0")
        .env("CARGO_INCREMENTAL", "0")
        .output()
        .expect("cargo runs");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let manifest = std::fs::read_to_string(project.join("Cargo.toml")).unwrap();
    let name = manifest
        .lines()
        .find_map(|l| l.strip_prefix("name = \""))
        .and_then(|l| l.strip_suffix('"'))
        .expect("the project names its package")
        .to_string();
    (project, target.join("debug").join(name))
}

/// A compiled program started with `args`, its standard error read on a thread.
fn compiled_program(
    program: &std::path::Path,
    args: &[&str],
) -> (Process, std::sync::mpsc::Receiver<String>) {
    let mut process = Process(
        Command::new(program)
            .args(args)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the compiled behaviour starts"),
    );
    let said = lines_of(process.0.stderr.take().unwrap());
    (process, said)
}

fn post(endpoint: &str, ty: &str, value: &str) {
    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["post", ty, value, "--connect", endpoint])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
}

/// A behaviour compiled to Rust with the `network` feature joins a board over Zenoh as
/// `proclaim run --listen` does: another process's posting comes into its run, its postings
/// reach another process, and Ctrl-C ends it with a recording that replays on the interpreter.
#[test]
fn a_compiled_behaviour_shares_its_whiteboard_with_other_processes() {
    let (project, program) = compiled_with_network("network-microwave", "machines/microwave");
    let script = project.join("idle.script");
    std::fs::write(&script, "doorOpen = false\ntimeLeft = false\n").unwrap();
    let (trace, record) = (project.join("trace.jsonl"), project.join("record.jsonl"));
    let endpoint = free_endpoint();
    let (mut compiled, said) = compiled_program(
        &program,
        &[
            "--script",
            script.to_str().unwrap(),
            "--listen",
            &endpoint,
            "--trace",
            trace.to_str().unwrap(),
            "--record",
            record.to_str().unwrap(),
        ],
    );
    wait_line(&said, "listening on", PATIENCE);
    let mut watch = proclaim(&["watch", "Magnetron", "--connect", &endpoint, "--for", "60s"]);
    let watched = lines(&mut watch);
    wait_line(&watched, "Magnetron = \"off\"", PATIENCE);
    post(&endpoint, "timeLeft", "true");
    let seen = wait_line(&watched, "Magnetron = \"on\"", PATIENCE);
    assert!(seen.last().unwrap().contains("Microwave"), "{seen:?}");
    crate::compiled_rust::interrupt(&mut compiled.0);
    let trace = std::fs::read_to_string(&trace).unwrap();
    assert!(
        trace.contains(r#""fired","machine":"Microwave","from":1,"to":3,"label":"cook""#),
        "{trace}"
    );
    let o = crate::proclaim(&["test", "machines/microwave", record.to_str().unwrap()]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stdout));
}

/// A label's atom that no module of the compiled behaviour answers is asked of an expert in
/// another process, as the runner asks it: the compiled oven cooks when `proclaim expert`
/// proves `cook` from the postings of a third process.
#[test]
fn a_compiled_behaviour_asks_an_expert_in_another_process() {
    let oven = crate::behaviour_folder(
        "network-compiled-oven",
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"Oven.machine\"\n"),
            (
                "Oven.machine",
                "machine Oven\nstate IDLE {\n  when cook -> COOKING\n}\nstate COOKING {\n  when ~cook -> IDLE\n}\n",
            ),
        ],
    );
    let (project, program) = compiled_with_network("network-oven", oven.to_str().unwrap());
    let endpoint = free_endpoint();
    let mut expert = proclaim(&["expert", "microwave", "--listen", &endpoint]);
    let said = lines(&mut expert);
    wait_line(&said, "listening on", PATIENCE);
    let trace = project.join("trace.jsonl");
    let (mut compiled, _) = compiled_program(
        &program,
        &["--connect", &endpoint, "--trace", trace.to_str().unwrap()],
    );
    post(&endpoint, "doorOpen", "false");
    post(&endpoint, "timeLeft", "true");
    let deadline = std::time::Instant::now() + PATIENCE;
    // The trace is written as the run goes; the oven's move to COOKING is in it once made.
    while !std::fs::read_to_string(&trace)
        .unwrap_or_default()
        .contains(r#""fired","machine":"Oven","from":1,"to":2,"label":"cook""#)
    {
        assert!(std::time::Instant::now() < deadline, "the oven never cooks");
        std::thread::sleep(Duration::from_millis(100));
    }
    crate::compiled_rust::interrupt(&mut compiled.0);
    let trace = std::fs::read_to_string(&trace).unwrap();
    assert!(
        trace.contains(r#""atom":"cook","value":true,"by":{"expert":"microwave"}"#),
        "{trace}"
    );
}
