//! The team's aggregates (`team.min(ballDistance)` and the rest of [`Aggregate`]) computed over
//! the `team.<type>` value on the robot's own board: the living members' latest values, in
//! member-name order, so a tie goes to the first name on every robot alike.

use crate::arith::compare;
use proclaim_board::team::{team_members, team_type};
use proclaim_board::Value;
use proclaim_fsm::{Aggregate, Expr};
use std::cmp::Ordering;

/// The type a team aggregate call reads, when `function` is one and its argument a type name.
pub(crate) fn aggregated_type(function: &str, arguments: &[Expr]) -> Option<String> {
    Aggregate::of_function(function)?;
    Aggregate::argument(arguments).map(team_type)
}

/// The aggregate over a `team.<type>` value; `None` when no member has a value (for `count`,
/// 0) or values that do not compare (a string and a number).
pub(crate) fn aggregate(aggregate: Aggregate, team: Option<&Value>) -> Option<Value> {
    let members = team.and_then(team_members).unwrap_or_default();
    if aggregate == Aggregate::Count {
        return Some(Value::Int(members.len() as i64));
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

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_board::team::team_value;

    #[test]
    fn aggregates_over_the_living_team_break_ties_by_member_name() {
        let (near, far, also_near) = (Value::Float(0.8), Value::Int(3), Value::Float(0.8));
        let team = team_value([("robot1", &far), ("robot2", &near), ("robot3", &also_near)]);
        let of = |a| aggregate(a, Some(&team));
        assert_eq!(of(Aggregate::Min), Some(Value::Float(0.8)));
        assert_eq!(of(Aggregate::Max), Some(Value::Int(3)));
        assert_eq!(of(Aggregate::Count), Some(Value::Int(3)));
        assert_eq!(of(Aggregate::Argmin), Some(Value::from("robot2")));
        assert_eq!(of(Aggregate::Argmax), Some(Value::from("robot1")));
        assert_eq!(aggregate(Aggregate::Argmin, None), None);
        assert_eq!(aggregate(Aggregate::Count, None), Some(Value::Int(0)));
        let mixed = team_value([("a", &near), ("b", &Value::from("far"))]);
        assert_eq!(aggregate(Aggregate::Min, Some(&mixed)), None);
    }
}
