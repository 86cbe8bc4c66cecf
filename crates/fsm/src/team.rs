//! The team's words in labels (`docs/spec/behaviour.md` §1, "A team"): a teammate's value of a
//! shared type (`robot2.ballDistance`), an aggregate over the living team
//! (`team.min(ballDistance)`, `team.max`, `team.count`, `team.argmin`, `team.argmax`, the vote
//! `team.majority(vote)`), whether the robot hears a majority (`team.quorum`) and the robot's
//! own name, `me`. What they read is kept on the robot's own board; this is only how a
//! label spells them.

use crate::code::Expr;

/// What a `team.…(type)` call computes over the living members' latest values of the type.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Aggregate {
    Min,
    Max,
    /// How many living members have posted the type.
    Count,
    /// The member with the smallest value; of equal values, the first member name.
    Argmin,
    /// The member with the largest value; of equal values, the first member name.
    Argmax,
    /// Whether more than half of the team's `size` living members' values name this robot
    /// (`me`): a vote, so that of robots that do not all hear each other at most one wins.
    Majority,
}

impl Aggregate {
    pub const ALL: [Aggregate; 6] = [
        Aggregate::Min,
        Aggregate::Max,
        Aggregate::Count,
        Aggregate::Argmin,
        Aggregate::Argmax,
        Aggregate::Majority,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Aggregate::Min => "min",
            Aggregate::Max => "max",
            Aggregate::Count => "count",
            Aggregate::Argmin => "argmin",
            Aggregate::Argmax => "argmax",
            Aggregate::Majority => "majority",
        }
    }

    /// The aggregate a called function names (`team.min`), if it names one.
    pub fn of_function(function: &str) -> Option<Aggregate> {
        let name = function.strip_prefix("team.")?;
        Aggregate::ALL.into_iter().find(|a| a.name() == name)
    }

    /// The type a call of this aggregate reads: its one argument, a plain type name.
    pub fn argument(arguments: &[Expr]) -> Option<&str> {
        match arguments {
            [Expr::Name(ty)] if !ty.contains('.') => Some(ty),
            _ => None,
        }
    }
}

/// A place where a label reads the team.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TeamWord<'a> {
    /// `team.f(type)`; `aggregate` is `None` for a function `team.f` that is no aggregate, and
    /// `ty` is `None` when the argument is not one plain type name.
    Aggregate {
        function: &'a str,
        aggregate: Option<Aggregate>,
        ty: Option<&'a str>,
    },
    /// `robot2.ballDistance` (and `team.ballDistance`, the whole team's pairs).
    Member { member: &'a str, ty: &'a str },
    /// `team.quorum`: whether the robot hears a majority of its team.
    Quorum,
}

/// The name a label reads for whether the robot hears a majority of its team.
const QUORUM: &str = "team.quorum";

/// Every place `expr` reads the team, left to right.
pub fn team_words(expr: &Expr) -> Vec<TeamWord<'_>> {
    let mut out = Vec::new();
    expr.visit_names(&mut |name, _| {
        if name == QUORUM {
            out.push(TeamWord::Quorum);
        } else if let Some((member, ty)) = name.split_once('.') {
            out.push(TeamWord::Member { member, ty });
        }
    });
    for (function, arguments) in expr.calls() {
        if function.starts_with("team.") {
            out.push(TeamWord::Aggregate {
                function,
                aggregate: Aggregate::of_function(function),
                ty: Aggregate::argument(arguments),
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::parse_label;

    #[test]
    fn a_label_reads_teammates_and_aggregates() {
        let label = parse_label("team.argmin(ballDistance) == me && robot2.role != \"striker\" || team.median(x) > 1 || team.min(a + b) || team.quorum").unwrap();
        assert_eq!(
            team_words(&label),
            vec![
                TeamWord::Member {
                    member: "robot2",
                    ty: "role"
                },
                TeamWord::Quorum,
                TeamWord::Aggregate {
                    function: "team.argmin",
                    aggregate: Some(Aggregate::Argmin),
                    ty: Some("ballDistance")
                },
                TeamWord::Aggregate {
                    function: "team.median",
                    aggregate: None,
                    ty: Some("x")
                },
                TeamWord::Aggregate {
                    function: "team.min",
                    aggregate: Some(Aggregate::Min),
                    ty: None
                },
            ]
        );
        assert_eq!(
            team_words(&parse_label("ballSeen && abs(x) > 1").unwrap()),
            vec![]
        );
    }
}
