//! Message values and the truthiness rule that turns any value into a proposition.

use std::fmt;

#[derive(Clone, Debug, PartialEq)]
pub enum Value {
    Bool(bool),
    Int(i64),
    Float(f64),
    Str(String),
    Bytes(Vec<u8>),
    List(Vec<Value>),
}

impl Value {
    /// gufsm's rule: a bool is itself; a number is true when non-zero; a string is false when
    /// empty or starting with `n`, `f`, `-`, `0` or `of` (any case: no, false, -1, 0, off).
    /// Bytes and lists are true when non-empty.
    pub fn truthy(&self) -> bool {
        match self {
            Value::Bool(b) => *b,
            Value::Int(i) => *i != 0,
            Value::Float(f) => *f != 0.0,
            Value::Str(s) => {
                let lower = s.trim().to_ascii_lowercase();
                !(lower.is_empty()
                    || lower.starts_with(['n', 'f', '-', '0'])
                    || lower.starts_with("of"))
            }
            Value::Bytes(b) => !b.is_empty(),
            Value::List(l) => !l.is_empty(),
        }
    }

    /// A number, when the value is one (bools count as 0 and 1).
    pub fn as_f64(&self) -> Option<f64> {
        match self {
            Value::Bool(b) => Some(*b as i64 as f64),
            Value::Int(i) => Some(*i as f64),
            Value::Float(f) => Some(*f),
            Value::Str(s) => s.trim().parse().ok(),
            _ => None,
        }
    }

    /// Reads a value as typed at a terminal or in a script: `true`/`false`, an integer, a
    /// float, or else a string (quotes optional).
    pub fn parse(text: &str) -> Value {
        let t = text.trim();
        match t {
            "true" => Value::Bool(true),
            "false" => Value::Bool(false),
            _ => {
                if let Ok(i) = t.parse::<i64>() {
                    Value::Int(i)
                } else if let Ok(f) = t.parse::<f64>() {
                    Value::Float(f)
                } else {
                    Value::Str(t.trim_matches('"').to_string())
                }
            }
        }
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Value::Bool(b) => write!(f, "{b}"),
            Value::Int(i) => write!(f, "{i}"),
            Value::Float(x) => write!(f, "{x}"),
            Value::Str(s) => write!(f, "{s:?}"),
            Value::Bytes(b) => write!(f, "<{} bytes>", b.len()),
            Value::List(l) => {
                f.write_str("[")?;
                for (i, v) in l.iter().enumerate() {
                    if i > 0 {
                        f.write_str(", ")?;
                    }
                    write!(f, "{v}")?;
                }
                f.write_str("]")
            }
        }
    }
}

impl From<bool> for Value {
    fn from(b: bool) -> Value {
        Value::Bool(b)
    }
}

impl From<i64> for Value {
    fn from(i: i64) -> Value {
        Value::Int(i)
    }
}

impl From<f64> for Value {
    fn from(f: f64) -> Value {
        Value::Float(f)
    }
}

impl From<&str> for Value {
    fn from(s: &str) -> Value {
        Value::Str(s.to_string())
    }
}

impl From<String> for Value {
    fn from(s: String) -> Value {
        Value::Str(s)
    }
}

#[cfg(test)]
mod tests {
    use super::Value;

    /// `check(typed, truth)`: a value as typed at a terminal, and its truth by gufsm's rule.
    fn check(typed: &str, truth: bool) {
        assert_eq!(Value::parse(typed).truthy(), truth, "{typed:?}");
    }

    #[test]
    fn truthiness_as_gufsm_had_it() {
        for (typed, truth) in [
            ("true", true),
            ("false", false),
            ("1", true),
            ("0", false),
            ("-1", true),
            ("0.0", false),
            ("2.5", true),
            ("yes", true),
            ("on", true),
            ("no", false),
            ("No", false),
            ("off", false),
            ("OFF", false),
            ("-x", false),
            ("", false),
            ("\"ball\"", true),
        ] {
            check(typed, truth);
        }
        assert!(!Value::List(Vec::new()).truthy());
        assert!(Value::Bytes(vec![0]).truthy());
    }

    #[test]
    fn typed_values_read_as_their_kind() {
        assert_eq!(Value::parse(" 12 "), Value::Int(12));
        assert_eq!(Value::parse("1.5"), Value::Float(1.5));
        assert_eq!(Value::parse("\"kick 2\""), Value::Str("kick 2".into()));
        assert_eq!(Value::parse("true").as_f64(), Some(1.0));
        assert_eq!(Value::Str("3".into()).as_f64(), Some(3.0));
    }
}
