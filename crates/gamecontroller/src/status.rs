//! The robot's status packet (`RGrt` version 4, robot to GameController, UDP port 3939).

pub const STATUS_HEADER: [u8; 4] = *b"RGrt";
pub const STATUS_VERSION: u8 = 4;
pub const STATUS_LEN: usize = 32;

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StatusPacket {
    pub player_number: u8,
    pub team_number: u8,
    pub fallen: bool,
    /// x mm, y mm, rotation rad.
    pub pose: [f32; 3],
    /// Seconds since the ball was seen; −1 when never.
    pub ball_age: f32,
    /// Ball position relative to the robot, mm.
    pub ball: [f32; 2],
}

impl StatusPacket {
    pub fn encode(&self) -> [u8; STATUS_LEN] {
        let mut out = [0u8; STATUS_LEN];
        out[..4].copy_from_slice(&STATUS_HEADER);
        out[4] = STATUS_VERSION;
        out[5] = self.player_number;
        out[6] = self.team_number;
        out[7] = self.fallen as u8;
        let floats = [
            self.pose[0],
            self.pose[1],
            self.pose[2],
            self.ball_age,
            self.ball[0],
            self.ball[1],
        ];
        for (i, f) in floats.iter().enumerate() {
            out[8 + 4 * i..12 + 4 * i].copy_from_slice(&f.to_le_bytes());
        }
        out
    }

    pub fn decode(bytes: &[u8]) -> Option<StatusPacket> {
        if bytes.len() != STATUS_LEN || bytes[..4] != STATUS_HEADER || bytes[4] != STATUS_VERSION {
            return None;
        }
        let f = |i: usize| {
            f32::from_le_bytes([
                bytes[8 + 4 * i],
                bytes[9 + 4 * i],
                bytes[10 + 4 * i],
                bytes[11 + 4 * i],
            ])
        };
        Some(StatusPacket {
            player_number: bytes[5],
            team_number: bytes[6],
            fallen: bytes[7] != 0,
            pose: [f(0), f(1), f(2)],
            ball_age: f(3),
            ball: [f(4), f(5)],
        })
    }
}
