//! GameController packets: the real capture decodes to the game its README describes, encoding
//! round-trips, and malformed packets are refused with a reason, never a panic.

use proclaim_gamecontroller::{
    decode, encode, Colour, DecodeError, GameState, Perspective, StatusPacket, V18_LEN, V7_LEN,
};
use proptest::prelude::*;

fn hex(text: &str) -> Vec<u8> {
    (0..text.len())
        .step_by(2)
        .map(|i| u8::from_str_radix(&text[i..i + 2], 16).unwrap())
        .collect()
}

/// The capture's packets, or `None` (the test then skips) when the shared corpus is absent.
fn capture() -> Option<Vec<(f64, Vec<u8>)>> {
    let path = corpus_dir()?.join("gamecontroller/gc3-capture.hex");
    let text = std::fs::read_to_string(path).ok()?;
    Some(
        text.lines()
            .filter(|l| !l.trim().is_empty())
            .map(|l| {
                let (t, bytes) = l.split_once(' ').unwrap();
                (t.parse().unwrap(), hex(bytes.trim()))
            })
            .collect(),
    )
}

#[test]
fn the_real_capture_decodes_to_the_game_described() {
    let Some(packets) = capture() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    assert_eq!(packets.len(), 49);
    let decoded: Vec<_> = packets.iter().map(|(_, b)| decode(b).unwrap()).collect();
    // State codes in order of appearance: 0, 5, 2, 3, 4 (READY is hidden by the GameController).
    let mut states: Vec<GameState> = decoded.iter().map(|p| p.state).collect();
    states.dedup();
    use GameState::*;
    assert_eq!(states, [Initial, Standby, Set, Playing, Finished]);
    let first = &decoded[0];
    assert_eq!(
        (first.version, first.players_per_team, first.secs_remaining),
        (18, 7, 600)
    );
    assert_eq!(first.kicking_team, Some(18));
    assert_eq!(first.teams[0].team_number, 18);
    assert_eq!(first.teams[0].field_player_colour, Colour::Yellow);
    assert_eq!(first.teams[0].goalkeeper_colour, Colour::Green);
    assert_eq!(first.teams[1].team_number, 5);
    assert_eq!(first.teams[1].field_player_colour, Colour::Black);
    assert_eq!(
        first.teams[1].players[8].penalty,
        proclaim_gamecontroller::PENALTY_SUBSTITUTE
    );
    // Packet numbers count up by one.
    for pair in decoded.windows(2) {
        assert_eq!(pair[1].packet_number, pair[0].packet_number.wrapping_add(1));
    }
    // Team 5's player 2 is penalised for pushing (45 s), counting down while PLAYING.
    let penalised: Vec<_> = decoded
        .iter()
        .filter(|p| p.teams[1].players[1].penalty == 2)
        .map(|p| (p.state, p.teams[1].players[1].secs_till_unpenalised))
        .collect();
    assert!(penalised.iter().any(|&(_, s)| s == 45), "{penalised:?}");
    let playing: Vec<u16> = penalised
        .iter()
        .filter(|(s, _)| *s == Playing)
        .map(|(_, t)| *t)
        .collect();
    assert!(
        playing.windows(2).all(|w| w[1] <= w[0]) && playing.first() > playing.last(),
        "{playing:?}"
    );
    // Scores stay 0:0.
    assert!(decoded
        .iter()
        .all(|p| p.teams[0].score == 0 && p.teams[1].score == 0));
    // Labels from the point of view of team 5's player 2 and team 18's player 1.
    let them = Perspective { team: 5, player: 2 };
    let us = Perspective {
        team: 18,
        player: 1,
    };
    let set = decoded.iter().find(|p| p.state == Set).unwrap();
    assert_eq!(set.labels(us).get("setReceived"), Some(true));
    assert_eq!(set.labels(us).get("weKickOff"), Some(true));
    assert_eq!(set.labels(them).get("weKickOff"), Some(false));
    assert_eq!(
        set.labels(us).get("UDPsaysBlueKickOff"),
        Some(false),
        "team 18 wears yellow"
    );
    let during_penalty = decoded
        .iter()
        .find(|p| p.teams[1].players[1].penalty == 2)
        .unwrap();
    assert_eq!(
        during_penalty.labels(them).get("penaltyReceived"),
        Some(true)
    );
    assert_eq!(
        during_penalty.labels(us).get("penaltyReceived"),
        Some(false)
    );
    // Re-encoding every real packet gives its bytes back.
    for (_, bytes) in &packets {
        assert_eq!(&encode(&decode(bytes).unwrap()), bytes);
    }
}

#[test]
fn malformed_packets_are_refused_with_a_reason() {
    let good = {
        let mut p = decode(&hex(&format!("52476d6512{}", "00".repeat(V18_LEN - 5)))).unwrap();
        p.state = GameState::Ready;
        encode(&p)
    };
    assert_eq!(decode(&good).unwrap().state, GameState::Ready);
    assert_eq!(decode(&good[..3]), Err(DecodeError::TooShort { len: 3 }));
    assert_eq!(
        decode(&good[..100]),
        Err(DecodeError::Length {
            version: 18,
            len: 100,
            expected: 118
        })
    );
    let mut long = good.clone();
    long.push(0);
    assert!(matches!(decode(&long), Err(DecodeError::Length { .. })));
    let mut header = good.clone();
    header[..4].copy_from_slice(b"RGrt");
    assert!(matches!(decode(&header), Err(DecodeError::Header(_))));
    let mut version = good.clone();
    version[4] = 17;
    assert_eq!(decode(&version), Err(DecodeError::Version(17)));
    let mut state = good;
    state[10] = 9;
    assert_eq!(decode(&state), Err(DecodeError::State(9)));
}

#[test]
fn version_7_round_trips_and_speaks_of_colours() {
    let mut bytes = Vec::new();
    bytes.extend_from_slice(b"RGme");
    bytes.extend_from_slice(&7u32.to_le_bytes());
    bytes.extend_from_slice(&[5, 1, 1, 0, 0, 0, 0, 0]); // 5 a side, READY, first half, blue kicks
    bytes.extend_from_slice(&600u32.to_le_bytes());
    for (number, colour) in [(9u8, 0u8), (12, 1)] {
        bytes.extend_from_slice(&[number, colour, colour, 0]);
        bytes.extend_from_slice(&[0; 44]);
    }
    assert_eq!(bytes.len(), V7_LEN);
    let packet = decode(&bytes).unwrap();
    assert_eq!(
        (packet.version, packet.state, packet.secs_remaining),
        (7, GameState::Ready, 600)
    );
    assert_eq!(encode(&packet), bytes);
    let labels = packet.labels(Perspective { team: 9, player: 1 });
    assert_eq!(labels.get("UDPsaysBlueKickOff"), Some(true));
    assert_eq!(labels.get("UDPsaysRedKickOff"), Some(false));
    assert_eq!(labels.get("weKickOff"), Some(true));
    assert_eq!(labels.get("readyReceived"), Some(true));
}

#[test]
fn status_packets_round_trip() {
    let status = StatusPacket {
        player_number: 3,
        team_number: 18,
        fallen: true,
        pose: [1000.0, -250.5, 1.5],
        ball_age: -1.0,
        ball: [0.0, 0.0],
    };
    let bytes = status.encode();
    assert_eq!(&bytes[..5], b"RGrt\x04");
    assert_eq!(StatusPacket::decode(&bytes), Some(status));
    assert_eq!(StatusPacket::decode(&bytes[..31]), None);
}

proptest! {
    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        let _ = decode(&bytes);
        let _ = StatusPacket::decode(&bytes);
    }

    #[test]
    fn random_packets_with_a_valid_header_never_panic(mut body in prop::collection::vec(any::<u8>(), 118..=118), v7 in any::<bool>()) {
        body[..4].copy_from_slice(b"RGme");
        if v7 {
            body.truncate(V7_LEN);
            body[4..8].copy_from_slice(&7u32.to_le_bytes());
        } else {
            body[4] = 18;
        }
        if let Ok(packet) = decode(&body) {
            prop_assert_eq!(decode(&encode(&packet)).unwrap(), packet);
        }
    }
}

/// The shared corpus (`../shared/corpus` from the repository's root), when present beside it.
fn corpus_dir() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    dir.is_dir().then_some(dir)
}
