//! `gc-sim` and `sensor gamecontroller`: a scripted GameController over UDP; script errors.

use super::waiting::{Lines, Running};
use super::{stderr, stdout, temp_file};
use crate::proclaim;
use std::process::Command;

/// The sensor is started, the game played once it says it listens, and the sensor stopped
/// with Ctrl-C (SIGINT, after which it prints its counts) once it has posted the game's end:
/// each step waits on what the other process says, not on the clock.
#[cfg(unix)]
#[test]
fn gc_sim_plays_to_the_sensor_command_over_udp() {
    let port = std::net::UdpSocket::bind("127.0.0.1:0")
        .unwrap()
        .local_addr()
        .unwrap()
        .port();
    let mut sensor = Running(
        Command::new(env!("CARGO_BIN_EXE_proclaim"))
            .args([
                "sensor",
                "gamecontroller",
                "--bind",
                "127.0.0.1",
                "--port",
                &port.to_string(),
            ])
            .args(["--team", "18", "--player", "2"])
            .stdout(std::process::Stdio::piped())
            .stderr(std::process::Stdio::piped())
            .spawn()
            .unwrap(),
    );
    let mut posted = Lines::of(sensor.0.stdout.take().unwrap());
    let mut said = Lines::of(sensor.0.stderr.take().unwrap());
    said.wait_for("listening for GameController packets");
    let script = temp_file(
        "game.txt",
        b"# a quick game\n0s initial\n200ms ready kick=5\n400ms set\n600ms playing\n700ms penalty team=18 player=2 secs=5\n1s finished\n",
    );
    let to = format!("127.0.0.1:{port}");
    let sim = proclaim(&[
        "gc-sim",
        "--script",
        script.to_str().unwrap(),
        "--to",
        &to,
        "--interval",
        "50",
    ]);
    assert_eq!(sim.status.code(), Some(0), "{}", stderr(&sim));
    assert!(
        stdout(&sim).contains("PLAYING (kicking team 5"),
        "{}",
        stdout(&sim)
    );
    posted.wait_for("\"FINISHED\"");
    // SAFETY: kill(2) of the child this test started and has not waited for: it is alive.
    unsafe { libc::kill(sensor.0.id() as libc::pid_t, libc::SIGINT) };
    assert!(sensor.0.wait().unwrap().success(), "Ctrl-C ends the sensor");
    let out = posted.all();
    let summary = said.all();
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
    assert!(summary.contains("0 ignored"), "{summary}");
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
