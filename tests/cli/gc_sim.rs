//! `gc-sim` and `sensor gamecontroller`: a scripted GameController over UDP; script errors.

use super::{stderr, stdout, temp_file};
use crate::proclaim;
use std::process::Command;

#[test]
fn gc_sim_plays_to_the_sensor_command_over_udp() {
    let port = std::net::UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let sensor = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args([
            "sensor",
            "gamecontroller",
            "--bind",
            "127.0.0.1",
            "--port",
            &port.to_string(),
        ])
        .args(["--team", "18", "--player", "2", "--for", "4s"])
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    let script = temp_file(
        "game.txt",
        b"# a quick game\n0s initial\n200ms ready kick=5\n400ms set\n600ms playing\n700ms penalty team=18 player=2 secs=5\n1s finished\n",
    );
    let sim = std::thread::spawn(move || {
        std::thread::sleep(std::time::Duration::from_millis(800));
        let to = format!("127.0.0.1:{port}");
        proclaim(&[
            "gc-sim",
            "--script",
            script.to_str().unwrap(),
            "--to",
            &to,
            "--interval",
            "50",
        ])
    });
    let sim = sim.join().unwrap();
    let sensor = sensor.wait_with_output().unwrap();
    assert_eq!(sim.status.code(), Some(0), "{}", stderr(&sim));
    assert!(
        stdout(&sim).contains("PLAYING (kicking team 5"),
        "{}",
        stdout(&sim)
    );
    let out = stdout(&sensor);
    let states: Vec<&str> = out
        .lines()
        .filter(|l| l.contains("gameState"))
        .map(|l| l.rsplit(' ').next().unwrap())
        .collect();
    assert_eq!(
        states,
        [
            "\"INITIAL\"",
            "\"READY\"",
            "\"SET\"",
            "\"PLAYING\"",
            "\"FINISHED\""
        ],
        "{out}"
    );
    assert!(out.contains("penaltyReceived = true"), "{out}");
    assert!(out.contains("weKickOff = false"), "{out}");
    assert!(stderr(&sensor).contains("0 ignored"), "{}", stderr(&sensor));
}

#[test]
fn gc_sim_reports_script_errors_by_line() {
    let script = temp_file("bad-game.txt", b"0s initial\n1s dance\nsoon playing\n");
    let o = proclaim(&["gc-sim", "--script", script.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(2));
    let err = stderr(&o);
    assert!(
        err.contains("bad-game.txt:2: error: unknown event `dance`"),
        "{err}"
    );
    assert!(
        err.contains("bad-game.txt:3: error: `soon` is not a time"),
        "{err}"
    );
}
