//! The whiteboard across processes over Zenoh (built with `--features zenoh`): a behaviour split
//! over processes runs, loses an expert that dies (its labels time out) and gets it back; the
//! commands that poke at a live board work. (Every whiteboard semantic is checked over Zenoh by
//! the whiteboard suite, `whiteboard::over_zenoh`.)
//! Everything is on 127.0.0.1, on free ports, bounded in count and time.

use proclaim_board::{Kind, Value};
use proclaim_zenoh::{whiteboard, Role, Settings};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::Duration;

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
async fn join_error(endpoint: &str, board: &str) -> String {
    whiteboard(&Role::Connect(endpoint.into()), board, &Settings::default())
        .await
        .err()
        .expect("joining fails")
        .to_string()
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn joining_a_board_nobody_holds_says_so() {
    let endpoint = free_endpoint();
    let error = join_error(&endpoint, "test").await;
    assert!(error.contains(&endpoint), "{error}");
    let error = whiteboard(
        &Role::Listen("127.0.0.1:7447".into()),
        "test",
        &Settings::default(),
    )
    .await
    .err()
    .unwrap();
    assert!(
        matches!(&error, proclaim_zenoh::NetworkError::Endpoint(e) if e == "127.0.0.1:7447"),
        "{error}"
    );
    assert!(error.to_string().contains("write it as tcp/HOST:PORT"));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_low_latency_transport_refuses_what_it_cannot_carry_and_says_why() {
    let endpoint = free_endpoint();
    let settings = Settings {
        config_file: None,
        low_latency: true,
    };
    let holder = whiteboard(&Role::Listen(endpoint.clone()), "big", &settings)
        .await
        .unwrap();
    let replica = whiteboard(&Role::Connect(endpoint.clone()), "big", &settings)
        .await
        .unwrap();
    // A posting over the limit is not sent (the log says so); the link stays up for the rest.
    replica.post("camera", "image", Value::Bytes(vec![7; 100 * 1024]));
    replica.post("camera", "seen", true);
    let seen = holder.wait_for("seen", 0, Duration::from_secs(2)).await;
    assert!(seen.is_some(), "the link survived");
    assert!(holder.latest("image").is_none());
    // A board whose snapshot is over the limit cannot be joined, and the joiner is told why.
    holder.declare("odometry", Kind::Data);
    for i in 0..100 {
        holder.post("walk", "odometry", format!("{i:01000}"));
    }
    let error = whiteboard(&Role::Connect(endpoint.clone()), "big", &settings)
        .await
        .err()
        .expect("too big to join");
    assert!(
        matches!(&error, proclaim_zenoh::NetworkError::Refused { why, .. } if why.contains("--low-latency")),
        "{error}"
    );
}

/// TLS through Zenoh's own configuration: a CA, a certificate for 127.0.0.1 signed by it, the
/// holder listening on `tls/…` with them, a replica that trusts the CA joining, one that does not
/// refused. Certificates are made with the `openssl` command; without it the test says so and
/// checks nothing.
#[cfg(feature = "zenoh-tls")]
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn tls_is_switched_on_through_zenohs_own_configuration() {
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
    let seen = holder.wait_for("ballSeen", 0, Duration::from_secs(5)).await;
    assert_eq!(seen.map(|m| m.value), Some(Value::Bool(true)));
    // Trusting nobody in particular (the system's roots), the certificate is refused.
    let error = join_error(&endpoint, "tls").await;
    assert!(error.contains(&endpoint), "{error}");
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
    let (tx, rx) = std::sync::mpsc::channel();
    let out = child.0.stdout.take().unwrap();
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
    wait_line(&trace, "holding whiteboard", Duration::from_secs(10));
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
    wait_line(
        &trace,
        "cook: no expert answers it",
        Duration::from_secs(10),
    );

    let expert = proclaim(&["expert", "microwave", "--connect", &endpoint]);
    let post = |ty: &str, value: &str| {
        let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args(["post", ty, value, "--connect", &endpoint])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    };
    wait_line(&trace, "cook = false  (microwave)", Duration::from_secs(10));
    post("doorOpen", "false");
    post("timeLeft", "true");
    wait_line(&trace, "Oven  → COOKING", Duration::from_secs(10));

    // The expert dies: its label times out and the machine goes on.
    drop(expert);
    wait_line(
        &trace,
        "cook: no answer in time, counted false",
        Duration::from_secs(10),
    );
    wait_line(&trace, "Oven  → IDLE", Duration::from_secs(10));
    // It comes back, and is answered again without restarting the machine.
    let _expert = proclaim(&["expert", "microwave", "--connect", &endpoint]);
    wait_line(&trace, "cook = true  (microwave)", Duration::from_secs(10));
    wait_line(&trace, "Oven  → COOKING", Duration::from_secs(10));
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
    let seen = wait_line(&watched, "go = true", Duration::from_secs(10));
    assert!(seen.last().unwrap().contains("tester"), "{seen:?}");
    wait_line(&trace, "M  → B", Duration::from_secs(10));

    let o = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["ping", "--count", "20", "--connect", &endpoint])
        .output()
        .unwrap();
    let out = String::from_utf8_lossy(&o.stdout);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    assert!(
        out.starts_with("20 round trips to the holder of `proclaim`: p50 "),
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
