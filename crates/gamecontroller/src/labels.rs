//! What a packet means to one robot: the propositions its behaviour asks about
//! (`readyReceived`, `penaltyReceived`, `UDPsaysBlueKickOff`, `weKickOff`, …).

use crate::control::{Colour, ControlPacket, GameState};

/// Which robot is listening.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Perspective {
    pub team: u8,
    /// Player number, 1-based.
    pub player: u8,
}

/// The labels one packet proclaims for one robot, each true or false.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Labels {
    pub values: Vec<(&'static str, bool)>,
}

impl Labels {
    pub fn get(&self, label: &str) -> Option<bool> {
        self.values
            .iter()
            .find(|(l, _)| *l == label)
            .map(|(_, v)| *v)
    }
}

/// Every label name the receiver answers, in posting order.
pub const LABELS: [&str; 10] = [
    "initialReceived",
    "readyReceived",
    "setReceived",
    "playingReceived",
    "finishedReceived",
    "standbyReceived",
    "penaltyReceived",
    "UDPsaysBlueKickOff",
    "UDPsaysRedKickOff",
    "weKickOff",
];

impl ControlPacket {
    /// Whether the packet is about a game `team` plays in.
    pub fn involves(&self, team: u8) -> bool {
        self.teams.iter().any(|t| t.team_number == team)
    }

    /// The labels for one robot. A robot is penalised when its slot carries any penalty,
    /// substitutes included (a substitute must not play). Kick-off labels follow the kicking
    /// team's field-player colour (version 18) or the kick-off colour (version 7).
    pub fn labels(&self, me: Perspective) -> Labels {
        let ours = self.teams.iter().find(|t| t.team_number == me.team);
        let penalised = ours
            .and_then(|t| t.players.get(me.player.wrapping_sub(1) as usize))
            .is_some_and(|p| p.penalty != 0);
        let kicking_colour = match self.version {
            7 => self.kick_off_colour,
            _ => self
                .kicking_team
                .and_then(|k| self.teams.iter().find(|t| t.team_number == k))
                .map(|t| t.field_player_colour),
        };
        let we_kick = match self.version {
            7 => ours.is_some_and(|t| Some(t.field_player_colour) == self.kick_off_colour),
            _ => self.kicking_team == Some(me.team),
        };
        let s = self.state;
        Labels {
            values: vec![
                ("initialReceived", s == GameState::Initial),
                ("readyReceived", s == GameState::Ready),
                ("setReceived", s == GameState::Set),
                ("playingReceived", s == GameState::Playing),
                ("finishedReceived", s == GameState::Finished),
                ("standbyReceived", s == GameState::Standby),
                ("penaltyReceived", penalised),
                ("UDPsaysBlueKickOff", kicking_colour == Some(Colour::Blue)),
                ("UDPsaysRedKickOff", kicking_colour == Some(Colour::Red)),
                ("weKickOff", we_kick),
            ],
        }
    }
}
