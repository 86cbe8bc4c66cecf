//! Control packets (GameController to robots, UDP port 3838): version 18, 118 bytes, and
//! version 7, 116 bytes, both little-endian without padding.

use std::fmt;

pub const HEADER: [u8; 4] = *b"RGme";
pub const V18_LEN: usize = 118;
pub const V7_LEN: usize = 116;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum GameState {
    Initial,
    Ready,
    Set,
    Playing,
    Finished,
    Standby,
}

impl GameState {
    fn from_code(code: u8) -> Option<GameState> {
        Some(match code {
            0 => GameState::Initial,
            1 => GameState::Ready,
            2 => GameState::Set,
            3 => GameState::Playing,
            4 => GameState::Finished,
            5 => GameState::Standby,
            _ => return None,
        })
    }

    pub fn code(self) -> u8 {
        self as u8
    }

    /// `INITIAL`, `READY`, … as the GameController names them.
    pub fn name(self) -> &'static str {
        match self {
            GameState::Initial => "INITIAL",
            GameState::Ready => "READY",
            GameState::Set => "SET",
            GameState::Playing => "PLAYING",
            GameState::Finished => "FINISHED",
            GameState::Standby => "STANDBY",
        }
    }
}

impl fmt::Display for GameState {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum GamePhase {
    Normal,
    PenaltyShootOut,
    Overtime,
    Timeout,
    Other(u8),
}

impl GamePhase {
    fn from_code(code: u8) -> GamePhase {
        match code {
            0 => GamePhase::Normal,
            1 => GamePhase::PenaltyShootOut,
            2 => GamePhase::Overtime,
            3 => GamePhase::Timeout,
            other => GamePhase::Other(other),
        }
    }

    fn code(self) -> u8 {
        match self {
            GamePhase::Normal => 0,
            GamePhase::PenaltyShootOut => 1,
            GamePhase::Overtime => 2,
            GamePhase::Timeout => 3,
            GamePhase::Other(c) => c,
        }
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SetPlay {
    None,
    GoalKick,
    PushingFreeKick,
    CornerKick,
    KickIn,
    PenaltyKick,
    Other(u8),
}

impl SetPlay {
    fn from_code(code: u8) -> SetPlay {
        match code {
            0 => SetPlay::None,
            1 => SetPlay::GoalKick,
            2 => SetPlay::PushingFreeKick,
            3 => SetPlay::CornerKick,
            4 => SetPlay::KickIn,
            5 => SetPlay::PenaltyKick,
            other => SetPlay::Other(other),
        }
    }

    fn code(self) -> u8 {
        match self {
            SetPlay::None => 0,
            SetPlay::GoalKick => 1,
            SetPlay::PushingFreeKick => 2,
            SetPlay::CornerKick => 3,
            SetPlay::KickIn => 4,
            SetPlay::PenaltyKick => 5,
            SetPlay::Other(c) => c,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            SetPlay::None => "none",
            SetPlay::GoalKick => "goal kick",
            SetPlay::PushingFreeKick => "pushing free kick",
            SetPlay::CornerKick => "corner kick",
            SetPlay::KickIn => "kick-in",
            SetPlay::PenaltyKick => "penalty kick",
            SetPlay::Other(_) => "other",
        }
    }
}

/// Team colours (version 18 jersey colours; version 7 uses 0 blue and 1 red).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Colour {
    Blue,
    Red,
    Yellow,
    Black,
    White,
    Green,
    Orange,
    Purple,
    Brown,
    Grey,
    Other(u8),
}

impl Colour {
    pub fn from_code(code: u8) -> Colour {
        use Colour::*;
        match code {
            0 => Blue,
            1 => Red,
            2 => Yellow,
            3 => Black,
            4 => White,
            5 => Green,
            6 => Orange,
            7 => Purple,
            8 => Brown,
            9 => Grey,
            other => Other(other),
        }
    }

    pub fn code(self) -> u8 {
        use Colour::*;
        match self {
            Blue => 0,
            Red => 1,
            Yellow => 2,
            Black => 3,
            White => 4,
            Green => 5,
            Orange => 6,
            Purple => 7,
            Brown => 8,
            Grey => 9,
            Other(c) => c,
        }
    }
}

/// One player slot: its penalty code (0 none, 14 substitute, …) and the seconds left of it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct RobotInfo {
    pub penalty: u8,
    pub secs_till_unpenalised: u16,
}

/// Substitutes carry this penalty code.
pub const PENALTY_SUBSTITUTE: u8 = 14;

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct TeamInfo {
    pub team_number: u8,
    pub field_player_colour: Colour,
    /// Version 18 only (version 7 has a goal colour here).
    pub goalkeeper_colour: Colour,
    /// Player number of the goalkeeper (version 18 only).
    pub goalkeeper: u8,
    pub score: u8,
    pub penalty_shot: u8,
    pub single_shots: u16,
    pub message_budget: u16,
    /// Player slots, player number `i + 1` at index `i` (20 in version 18, 11 in version 7).
    pub players: Vec<RobotInfo>,
}

/// A decoded control packet of either version.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ControlPacket {
    pub version: u8,
    /// Version 18 only; 0 in version 7.
    pub packet_number: u8,
    pub players_per_team: u8,
    pub competition_phase: u8,
    pub competition_type: u8,
    pub game_phase: GamePhase,
    pub state: GameState,
    pub set_play: SetPlay,
    pub first_half: bool,
    /// Version 18: team number of the next kick-off or set play (`None` for 255).
    pub kicking_team: Option<u8>,
    /// Version 7: the colour kicking off (`None` for a drop ball).
    pub kick_off_colour: Option<Colour>,
    pub secs_remaining: i32,
    pub secondary_time: i16,
    pub teams: [TeamInfo; 2],
}

/// Why bytes are not a control packet this receiver accepts.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum DecodeError {
    /// Fewer bytes than a header and a version.
    TooShort { len: usize },
    /// Not `RGme`: some other protocol on the port.
    Header([u8; 4]),
    /// A version this decoder does not read.
    Version(u32),
    /// The right header and version, but not that version's length.
    Length {
        version: u8,
        len: usize,
        expected: usize,
    },
    /// A state code outside 0..=5 (0..=4 in version 7).
    State(u8),
}

impl fmt::Display for DecodeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            DecodeError::TooShort { len } => {
                write!(f, "{len} bytes is too short for a GameController packet")
            }
            DecodeError::Header(h) => {
                write!(f, "header {:?} is not RGme", String::from_utf8_lossy(h))
            }
            DecodeError::Version(v) => {
                write!(f, "packet version {v} is not supported (18 and 7 are)")
            }
            DecodeError::Length {
                version,
                len,
                expected,
            } => {
                write!(
                    f,
                    "a version {version} packet has {expected} bytes, this one {len}"
                )
            }
            DecodeError::State(s) => write!(f, "game state code {s} is unknown"),
        }
    }
}

impl std::error::Error for DecodeError {}

struct Reader<'a> {
    bytes: &'a [u8],
    at: usize,
}

impl Reader<'_> {
    fn u8(&mut self) -> u8 {
        let v = self.bytes[self.at];
        self.at += 1;
        v
    }

    fn u16(&mut self) -> u16 {
        let v = u16::from_le_bytes([self.bytes[self.at], self.bytes[self.at + 1]]);
        self.at += 2;
        v
    }

    fn u32(&mut self) -> u32 {
        let b = &self.bytes[self.at..self.at + 4];
        self.at += 4;
        u32::from_le_bytes([b[0], b[1], b[2], b[3]])
    }
}

/// Decodes a control packet. Lengths are checked before any field is read, so no input panics.
pub fn decode(bytes: &[u8]) -> Result<ControlPacket, DecodeError> {
    if bytes.len() < 8 {
        return Err(DecodeError::TooShort { len: bytes.len() });
    }
    let header = [bytes[0], bytes[1], bytes[2], bytes[3]];
    if header != HEADER {
        return Err(DecodeError::Header(header));
    }
    match bytes[4] {
        18 => expect_len(bytes, 18, V18_LEN).and_then(|_| decode_v18(bytes)),
        7 if bytes[5..8] == [0, 0, 0] => {
            expect_len(bytes, 7, V7_LEN).and_then(|_| decode_v7(bytes))
        }
        _ => Err(DecodeError::Version(u32::from_le_bytes([
            bytes[4], bytes[5], bytes[6], bytes[7],
        ]))),
    }
}

fn expect_len(bytes: &[u8], version: u8, expected: usize) -> Result<(), DecodeError> {
    if bytes.len() == expected {
        Ok(())
    } else {
        Err(DecodeError::Length {
            version,
            len: bytes.len(),
            expected,
        })
    }
}

fn decode_v18(bytes: &[u8]) -> Result<ControlPacket, DecodeError> {
    let mut r = Reader { bytes, at: 5 };
    let packet_number = r.u8();
    let players_per_team = r.u8();
    let competition_phase = r.u8();
    let competition_type = r.u8();
    let game_phase = GamePhase::from_code(r.u8());
    let state_code = r.u8();
    let state = GameState::from_code(state_code).ok_or(DecodeError::State(state_code))?;
    let set_play = SetPlay::from_code(r.u8());
    let first_half = r.u8() != 0;
    let kicking_team = Some(r.u8()).filter(|&t| t != 255);
    let secs_remaining = r.u16() as i16 as i32;
    let secondary_time = r.u16() as i16;
    let team = |r: &mut Reader<'_>| TeamInfo {
        team_number: r.u8(),
        field_player_colour: Colour::from_code(r.u8()),
        goalkeeper_colour: Colour::from_code(r.u8()),
        goalkeeper: r.u8(),
        score: r.u8(),
        penalty_shot: r.u8(),
        single_shots: r.u16(),
        message_budget: r.u16(),
        players: (0..20)
            .map(|_| RobotInfo {
                penalty: r.u8(),
                secs_till_unpenalised: r.u8() as u16,
            })
            .collect(),
    };
    let teams = [team(&mut r), team(&mut r)];
    Ok(ControlPacket {
        version: 18,
        packet_number,
        players_per_team,
        competition_phase,
        competition_type,
        game_phase,
        state,
        set_play,
        first_half,
        kicking_team,
        kick_off_colour: None,
        secs_remaining,
        secondary_time,
        teams,
    })
}

fn decode_v7(bytes: &[u8]) -> Result<ControlPacket, DecodeError> {
    let mut r = Reader { bytes, at: 8 };
    let players_per_team = r.u8();
    let state_code = r.u8();
    let state = match state_code {
        0..=4 => GameState::from_code(state_code).ok_or(DecodeError::State(state_code))?,
        _ => return Err(DecodeError::State(state_code)),
    };
    let first_half = r.u8() != 0;
    let kick_off = r.u8();
    let game_phase = GamePhase::from_code(r.u8());
    let _drop_in_team = r.u8();
    let secondary_time = r.u16() as i16;
    let secs_remaining = r.u32() as i32;
    let team = |r: &mut Reader<'_>| {
        let team_number = r.u8();
        let colour = Colour::from_code(r.u8());
        let goal_colour = Colour::from_code(r.u8());
        let score = r.u8();
        TeamInfo {
            team_number,
            field_player_colour: colour,
            goalkeeper_colour: goal_colour,
            goalkeeper: 1,
            score,
            penalty_shot: 0,
            single_shots: 0,
            message_budget: 0,
            players: (0..11)
                .map(|_| RobotInfo {
                    penalty: r.u16() as u8,
                    secs_till_unpenalised: r.u16(),
                })
                .collect(),
        }
    };
    let teams = [team(&mut r), team(&mut r)];
    Ok(ControlPacket {
        version: 7,
        packet_number: 0,
        players_per_team,
        competition_phase: 0,
        competition_type: 0,
        game_phase,
        state,
        set_play: SetPlay::None,
        first_half,
        kicking_team: None,
        kick_off_colour: (kick_off <= 1).then(|| Colour::from_code(kick_off)),
        secs_remaining,
        secondary_time,
        teams,
    })
}

/// Encodes a packet in its own version: the simulator's half of the protocol, and the decoder's
/// test partner.
pub fn encode(packet: &ControlPacket) -> Vec<u8> {
    let mut out = Vec::with_capacity(V18_LEN);
    out.extend_from_slice(&HEADER);
    if packet.version == 7 {
        out.extend_from_slice(&7u32.to_le_bytes());
        out.push(packet.players_per_team);
        out.push(packet.state.code());
        out.push(packet.first_half as u8);
        out.push(packet.kick_off_colour.map_or(2, Colour::code));
        out.push(packet.game_phase.code());
        out.push(0);
        out.extend_from_slice(&packet.secondary_time.to_le_bytes());
        out.extend_from_slice(&(packet.secs_remaining as u32).to_le_bytes());
        for team in &packet.teams {
            out.extend_from_slice(&[
                team.team_number,
                team.field_player_colour.code(),
                team.goalkeeper_colour.code(),
                team.score,
            ]);
            for i in 0..11 {
                let p = team.players.get(i).copied().unwrap_or_default();
                out.extend_from_slice(&(p.penalty as u16).to_le_bytes());
                out.extend_from_slice(&p.secs_till_unpenalised.to_le_bytes());
            }
        }
        return out;
    }
    out.extend_from_slice(&[
        18,
        packet.packet_number,
        packet.players_per_team,
        packet.competition_phase,
        packet.competition_type,
        packet.game_phase.code(),
        packet.state.code(),
        packet.set_play.code(),
        packet.first_half as u8,
        packet.kicking_team.unwrap_or(255),
    ]);
    out.extend_from_slice(&(packet.secs_remaining as i16).to_le_bytes());
    out.extend_from_slice(&packet.secondary_time.to_le_bytes());
    for team in &packet.teams {
        out.extend_from_slice(&[
            team.team_number,
            team.field_player_colour.code(),
            team.goalkeeper_colour.code(),
            team.goalkeeper,
            team.score,
            team.penalty_shot,
        ]);
        out.extend_from_slice(&team.single_shots.to_le_bytes());
        out.extend_from_slice(&team.message_budget.to_le_bytes());
        for i in 0..20 {
            let p = team.players.get(i).copied().unwrap_or_default();
            out.push(p.penalty);
            out.push(p.secs_till_unpenalised.min(255) as u8);
        }
    }
    out
}
