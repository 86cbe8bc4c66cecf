//! The RoboCup SPL GameController protocol (`docs/spec/gamecontroller.md`): control packets
//! of version 18 (GameController3) and 7 (the Griffith era), the robot's `RGrt` status packet,
//! and the labels a robot's behaviour asks about. Pure: bytes in, values out; sockets live
//! elsewhere.

mod control;
mod labels;
mod status;

pub use control::PENALTY_SUBSTITUTE;
pub use control::{
    decode, encode, Colour, ControlPacket, DecodeError, GamePhase, GameState, RobotInfo, SetPlay,
    TeamInfo, HEADER, V18_LEN, V7_LEN,
};
pub use labels::{Labels, Perspective, LABELS};
pub use status::{StatusPacket, STATUS_HEADER, STATUS_LEN, STATUS_VERSION};
