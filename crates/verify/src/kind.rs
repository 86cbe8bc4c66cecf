//! What kind of value a slot or a property's term holds (a truth, a number, text), as far as
//! the behaviour's constants tell: what a comparison between kinds is refused by.

use proclaim_board::Value;

/// What kind of value a term has, as far as the behaviour's constants tell.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ValueKind {
    Truth,
    Number,
    Text,
    Any,
}

impl ValueKind {
    pub fn of_values<'a>(values: impl IntoIterator<Item = &'a Value>) -> ValueKind {
        let mut kind = None;
        for v in values {
            let k = match v {
                Value::Bool(_) => ValueKind::Truth,
                Value::Int(_) | Value::Float(_) => ValueKind::Number,
                Value::Str(_) => ValueKind::Text,
                _ => ValueKind::Any,
            };
            kind = match kind {
                None => Some(k),
                Some(old) if old == k => Some(k),
                Some(_) => Some(ValueKind::Any),
            };
        }
        kind.unwrap_or(ValueKind::Any)
    }

    pub(crate) fn describe(self) -> &'static str {
        match self {
            ValueKind::Truth => "a truth value",
            ValueKind::Number => "a number",
            ValueKind::Text => "text",
            ValueKind::Any => "a value",
        }
    }
}
