//! The simulator as a team's robot meets it: game scripts read (every bad line said), and a game
//! played as real control packets over UDP on loopback, decoded by the codec the robot uses.

use proclaim_gamecontroller::{decode, GameState};
use proclaim_gcsim::{parse_game, play, GameEvent, SimConfig};
use std::time::Duration;
use tokio::net::UdpSocket;

#[test]
fn every_bad_line_of_a_script_is_said() {
    let errors = parse_game("0s initial\nsoon ready\n2s penalty team=18\n3s\n4s dance\n")
        .expect_err("four bad lines");
    let lines: Vec<usize> = errors.0.iter().map(|e| e.line).collect();
    assert_eq!(lines, [2, 3, 4, 5], "{errors:?}");
    assert!(
        errors.0[0].message.contains("`soon` is not a time"),
        "{errors:?}"
    );
    assert!(errors.0[1].message.contains("needs player=N"), "{errors:?}");
}

#[test]
fn a_script_reads_to_its_events_in_time_order() {
    let script =
        parse_game("# a short game\n0s initial kick=5\n500ms ready\n1.5s playing\n").unwrap();
    let times: Vec<Duration> = script.events.iter().map(|(t, _)| *t).collect();
    assert!(times.windows(2).all(|w| w[0] <= w[1]));
    assert!(script.events.contains(&(
        Duration::from_millis(500),
        GameEvent::State(GameState::Ready)
    )));
    assert_eq!(script.length(), Duration::from_millis(1500));
}

/// On tokio's paused clock (as `proclaim run --virtual-clock` plays it): the script's
/// milliseconds pass only while the simulator waits for its next packet, so a loaded machine
/// cannot stall the game past an event and merge two states into one packet. The packets are
/// real UDP on loopback all the same.
#[tokio::test(start_paused = true)]
async fn a_game_is_played_as_packets_a_robot_decodes() {
    let robot = UdpSocket::bind("127.0.0.1:0").await.unwrap();
    let config = SimConfig {
        to: robot.local_addr().unwrap(),
        interval: Duration::from_millis(10),
        ..SimConfig::default()
    };
    let script = parse_game(
        "0ms initial kick=18\n30ms ready\n60ms set\n90ms playing\n\
         120ms penalty team=18 player=2 secs=30 reason=2\n150ms finished\n",
    )
    .unwrap();
    let receiver = tokio::spawn(async move {
        let mut states = Vec::new();
        let mut penalised = false;
        let mut buffer = [0u8; 1024];
        while let Ok(Ok(len)) =
            tokio::time::timeout(Duration::from_secs(2), robot.recv(&mut buffer)).await
        {
            let packet = decode(&buffer[..len]).expect("a control packet");
            penalised |= packet
                .teams
                .iter()
                .any(|t| t.team_number == 18 && t.players.get(1).is_some_and(|p| p.penalty == 2));
            if states.last() != Some(&packet.state) {
                states.push(packet.state);
            }
            if packet.state == GameState::Finished {
                break;
            }
        }
        (states, penalised)
    });
    let sent = play(&script, &config, |_| {}).await.expect("played");
    let (states, penalised) = receiver.await.unwrap();
    assert!(
        sent >= 16,
        "one packet each interval until two after the last event: {sent}"
    );
    assert_eq!(
        states,
        [
            GameState::Initial,
            GameState::Ready,
            GameState::Set,
            GameState::Playing,
            GameState::Finished
        ]
    );
    assert!(penalised, "player 2 of team 18 penalised while playing");
}
