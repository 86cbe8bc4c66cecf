//! The local types a team's values are kept under on each robot's own board, the contract
//! between whoever hears the team (`proclaim-zenoh`) and whoever reads it (labels): a teammate's
//! value of a shared type as `robot2.ballDistance`, every living member's as one list
//! `team.ballDistance` of `[member, value]` pairs in member-name order, the robot's own name
//! as `me`, and whether it hears a majority of its team as `team.quorum`.

use crate::Value;

/// The type holding this robot's own name in its team.
pub const ME: &str = "me";

/// The type saying whether this robot hears a majority of its team (itself among them), for a
/// team whose manifest says its `size`: what a role that must be held by one robot at a time
/// waits for, since only one side of a split team can hold it.
pub const QUORUM: &str = "team.quorum";

/// The type holding the team's size, for a team whose manifest says it (`team.majority` counts
/// votes against it).
pub const SIZE: &str = "team.size";

/// The prefix of the types holding a shared type's values over the living team.
pub const TEAM: &str = "team";

/// The type holding `member`'s latest value of the shared type `ty`.
pub fn member_type(member: &str, ty: &str) -> String {
    format!("{member}.{ty}")
}

/// The type holding every living member's latest value of the shared type `ty`.
pub fn team_type(ty: &str) -> String {
    format!("{TEAM}.{ty}")
}

/// The value of a `team.<type>` posting: `[member, value]` pairs, in the order given.
pub fn team_value<'a>(members: impl IntoIterator<Item = (&'a str, &'a Value)>) -> Value {
    Value::List(
        members
            .into_iter()
            .map(|(member, value)| Value::List(vec![Value::from(member), value.clone()]))
            .collect(),
    )
}

/// The `[member, value]` pairs of a `team.<type>` value; `None` for a value of another shape.
pub fn team_members(value: &Value) -> Option<Vec<(&str, &Value)>> {
    let Value::List(pairs) = value else {
        return None;
    };
    pairs
        .iter()
        .map(|pair| match pair {
            Value::List(p) => match p.as_slice() {
                [Value::Str(member), value] => Some((member.as_str(), value)),
                _ => None,
            },
            _ => None,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_team_value_reads_back_as_its_pairs() {
        let (one, two) = (Value::Float(0.8), Value::Int(2));
        let value = team_value([("robot1", &one), ("robot2", &two)]);
        assert_eq!(
            team_members(&value),
            Some(vec![("robot1", &one), ("robot2", &two)])
        );
        assert_eq!(team_members(&Value::Int(3)), None);
        assert_eq!(member_type("robot2", "role"), "robot2.role");
        assert_eq!(team_type("role"), "team.role");
    }
}
