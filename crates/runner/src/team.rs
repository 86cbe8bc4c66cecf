//! The team's aggregates (`team.min(ballDistance)` and the rest of [`Aggregate`]) computed over
//! the `team.<type>` value on the robot's own board: the living members' latest values, in
//! member-name order, so a tie goes to the first name on every robot alike.

use proclaim_board::team::{team_members, team_type};
use proclaim_board::Value;
use proclaim_fsm::{Aggregate, Expr};
use proclaim_lower::arith::compare;
use std::cmp::Ordering;

/// The type a team aggregate call reads, when `function` is one and its argument a type name.
pub(crate) fn aggregated_type(function: &str, arguments: &[Expr]) -> Option<String> {
    Aggregate::of_function(function)?;
    Aggregate::argument(arguments).map(team_type)
}

/// Who is asking, for the aggregates that say something of this robot: its name (`me`) and the
/// team's size (`team.size`), as its board has them.
#[derive(Clone, Copy, Default)]
pub(crate) struct Asker<'a> {
    pub me: Option<&'a Value>,
    pub size: Option<&'a Value>,
}

/// The aggregate over a `team.<type>` value; `None` when no member has a value (for `count`,
/// 0; for `majority`, false) or values that do not compare (a string and a number).
pub(crate) fn aggregate(
    aggregate: Aggregate,
    team: Option<&Value>,
    asker: Asker<'_>,
) -> Option<Value> {
    let members = team.and_then(team_members).unwrap_or_default();
    match aggregate {
        Aggregate::Count => return Some(Value::Int(members.len() as i64)),
        Aggregate::Majority => return Some(Value::Bool(majority(&members, asker))),
        _ => {}
    }
    let want = match aggregate {
        Aggregate::Min | Aggregate::Argmin => Ordering::Less,
        _ => Ordering::Greater,
    };
    let mut best: Option<(&str, &Value)> = None;
    for (member, value) in members {
        best = match best {
            None => Some((member, value)),
            Some((_, held)) => match compare(value, held)? {
                o if o == want => Some((member, value)),
                _ => best,
            },
        };
    }
    let (member, value) = best?;
    Some(match aggregate {
        Aggregate::Argmin | Aggregate::Argmax => Value::from(member),
        _ => value.clone(),
    })
}

/// Whether more than half of the team's size vote for the asker: a robot that does not know its
/// name or its team's size has no majority.
fn majority(votes: &[(&str, &Value)], asker: Asker<'_>) -> bool {
    let (Some(Value::Str(me)), Some(Value::Int(size))) = (asker.me, asker.size) else {
        return false;
    };
    let for_me = votes
        .iter()
        .filter(|(_, vote)| matches!(vote, Value::Str(v) if v == me))
        .count();
    2 * for_me as i64 > *size
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_board::team::team_value;

    #[test]
    fn aggregates_over_the_living_team_break_ties_by_member_name() {
        let (near, far, also_near) = (Value::Float(0.8), Value::Int(3), Value::Float(0.8));
        let team = team_value([("robot1", &far), ("robot2", &near), ("robot3", &also_near)]);
        let of = |a| aggregate(a, Some(&team), Asker::default());
        assert_eq!(of(Aggregate::Min), Some(Value::Float(0.8)));
        assert_eq!(of(Aggregate::Max), Some(Value::Int(3)));
        assert_eq!(of(Aggregate::Count), Some(Value::Int(3)));
        assert_eq!(of(Aggregate::Argmin), Some(Value::from("robot2")));
        assert_eq!(of(Aggregate::Argmax), Some(Value::from("robot1")));
        let none = Asker::default();
        assert_eq!(aggregate(Aggregate::Argmin, None, none), None);
        assert_eq!(aggregate(Aggregate::Count, None, none), Some(Value::Int(0)));
        let mixed = team_value([("a", &near), ("b", &Value::from("far"))]);
        assert_eq!(aggregate(Aggregate::Min, Some(&mixed), none), None);
    }

    #[test]
    fn a_majority_is_more_than_half_the_teams_size_voting_for_me() {
        let (one, two) = (Value::from("robot1"), Value::from("robot2"));
        let votes = |v: &[(&str, &Value)]| team_value(v.iter().copied());
        let (me, three, four) = (Value::from("robot1"), Value::Int(3), Value::Int(4));
        let asker = |size| Asker {
            me: Some(&me),
            size: Some(size),
        };
        let won = |team: &Value, size| aggregate(Aggregate::Majority, Some(team), asker(size));
        // Robots 1 and 3 hear each other, robots 2 and 3 too, but not 1 and 2: robot 3's vote
        // makes robot 1 the only one with two of three.
        let at_robot1 = votes(&[("robot1", &one), ("robot3", &one)]);
        let at_robot2 = votes(&[("robot2", &two), ("robot3", &one)]);
        assert_eq!(won(&at_robot1, &three), Some(Value::Bool(true)));
        let robot2 = Value::from("robot2");
        let asked_by_robot2 = Asker {
            me: Some(&robot2),
            size: Some(&three),
        };
        let lost = aggregate(Aggregate::Majority, Some(&at_robot2), asked_by_robot2);
        assert_eq!(lost, Some(Value::Bool(false)));
        // Two of four is no majority; no size or no name, none either.
        assert_eq!(won(&at_robot1, &four), Some(Value::Bool(false)));
        let no_size = Asker {
            me: Some(&me),
            size: None,
        };
        let no = aggregate(Aggregate::Majority, Some(&at_robot1), no_size);
        assert_eq!(no, Some(Value::Bool(false)));
        assert_eq!(
            aggregate(Aggregate::Majority, None, asker(&three)),
            Some(Value::Bool(false))
        );
    }
}
