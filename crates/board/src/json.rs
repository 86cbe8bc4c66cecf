//! A whiteboard value as plain JSON, the one form recordings, traces and the Zenoh wire
//! (`docs/whiteboard-wire.md`) write and read back: a truth value, a whole number, a fraction, a
//! string, `{"bytes": [...]}` or a list.

use crate::Value;

impl Value {
    pub fn to_json(&self) -> serde_json::Value {
        match self {
            Value::Bool(b) => serde_json::Value::Bool(*b),
            Value::Int(i) => serde_json::Value::from(*i),
            // A fraction JSON cannot hold (NaN, ±∞) is `null`.
            Value::Float(x) => serde_json::Value::from(*x),
            Value::Str(s) => serde_json::Value::String(s.clone()),
            Value::Bytes(b) => serde_json::json!({ "bytes": b }),
            Value::List(items) => {
                serde_json::Value::Array(items.iter().map(Value::to_json).collect())
            }
        }
    }

    /// The value [`Value::to_json`] wrote; anything else JSON holds is read as near as it
    /// goes: `null` as the empty string, another object as its text.
    pub fn from_json(json: &serde_json::Value) -> Value {
        match json {
            serde_json::Value::Bool(b) => Value::Bool(*b),
            serde_json::Value::Number(n) => match n.as_i64() {
                Some(i) => Value::Int(i),
                None => Value::Float(n.as_f64().unwrap_or(0.0)),
            },
            serde_json::Value::String(s) => Value::Str(s.clone()),
            serde_json::Value::Array(items) => {
                Value::List(items.iter().map(Value::from_json).collect())
            }
            serde_json::Value::Object(o) => match o.get("bytes").and_then(|b| b.as_array()) {
                Some(bytes) => Value::Bytes(
                    bytes
                        .iter()
                        .filter_map(|b| b.as_u64().and_then(|b| u8::try_from(b).ok()))
                        .collect(),
                ),
                None => Value::Str(json.to_string()),
            },
            serde_json::Value::Null => Value::Str(String::new()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_kind_of_value_reads_back_as_written() {
        let values = [
            Value::Bool(true),
            Value::Int(-7),
            Value::Float(2.0),
            Value::Float(0.25),
            Value::Str("kick 2".into()),
            Value::Bytes(vec![0, 255, 3]),
            Value::List(vec![
                Value::Int(1),
                Value::Float(-35.5),
                Value::Str("x".into()),
            ]),
            Value::List(Vec::new()),
        ];
        for value in values {
            let text = value.to_json().to_string();
            let back = Value::from_json(&serde_json::from_str(&text).unwrap());
            assert_eq!(back, value, "{text}");
        }
    }

    #[test]
    fn the_json_is_plain() {
        let list = Value::List(vec![Value::Bool(false), Value::Int(3)]);
        assert_eq!(list.to_json().to_string(), "[false,3]");
        assert_eq!(
            Value::Bytes(vec![1]).to_json().to_string(),
            r#"{"bytes":[1]}"#
        );
        assert_eq!(
            Value::from_json(&serde_json::Value::Null),
            Value::Str(String::new())
        );
    }
}
