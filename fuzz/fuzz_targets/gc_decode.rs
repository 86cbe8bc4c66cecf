//! Fuzz target: any datagram through the GameController decoders must not panic, and whatever
//! decodes must re-encode to a packet that decodes the same.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|data: &[u8]| {
    if let Ok(packet) = proclaim_gamecontroller::decode(data) {
        let again = proclaim_gamecontroller::decode(&proclaim_gamecontroller::encode(&packet)).expect("re-encoded packets decode");
        assert_eq!(again, packet);
        let _ = packet.labels(proclaim_gamecontroller::Perspective { team: data.first().copied().unwrap_or(0), player: 2 });
    }
    let _ = proclaim_gamecontroller::StatusPacket::decode(data);
});
