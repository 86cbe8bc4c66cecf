//! The program expert's protocol: JSON lines between proclaim and the process that answers
//! labels (the guide, "Any program as an expert"). proclaim writes [`Request`]s to the process's
//! stdin, one a line; the process writes [`Reply`]s to its stdout, one a line.

use proclaim_board::Value;
use serde::{Deserialize, Serialize};
use serde_json::Value as Json;

/// A line to the process.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum Request {
    /// The first line: who it is, the labels it answers, the whiteboard inputs it follows.
    Hello {
        expert: String,
        answers: Vec<String>,
        inputs: Vec<String>,
    },
    /// A Prolog knowledge base to load (the Prolog expert's driver only).
    Load {
        file: String,
        text: String,
        /// Seconds a proof may take.
        time_limit: f64,
    },
    /// An input's current value: at the start for each one already posted, then at each
    /// posting; `seq` counts the inputs sent (1, 2, …), so an answer given unasked can say
    /// which it followed.
    Input { name: String, value: Json, seq: u64 },
    /// A machine asks for this label: answer it, echoing `id`.
    Query { label: String, id: u64 },
}

impl Request {
    /// The request as one line, newline included.
    pub fn line(&self) -> String {
        // Strings, numbers and bools only: serialising cannot fail.
        let mut line = serde_json::to_string(self).unwrap_or_default();
        line.push('\n');
        line
    }
}

/// A line from the process: an answer (`label` with `value` or `error`, and the query's `id`
/// when it answers one), a warning about its
/// own files (`warning`, with `file` and `line` when it knows them), or `ready` once it has
/// loaded what it needs. Unknown fields are ignored, so a program can say more.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
pub struct Reply {
    #[serde(default)]
    pub label: Option<String>,
    #[serde(default)]
    pub value: Option<Json>,
    /// Why the label could not be answered: it counts as false, with a warning.
    #[serde(default)]
    pub error: Option<String>,
    /// The query it answers; none for an answer it gives unasked (its value changed).
    #[serde(default)]
    pub id: Option<u64>,
    /// For an answer given unasked: the `seq` of the last input it took into account. One that
    /// an input sent since has overtaken is dropped, so a query never takes an answer about
    /// inputs that have already changed. Optional.
    #[serde(default)]
    pub after: Option<u64>,
    #[serde(default)]
    pub warning: Option<String>,
    #[serde(default)]
    pub file: Option<String>,
    #[serde(default)]
    pub line: Option<usize>,
    #[serde(default)]
    pub column: Option<usize>,
    #[serde(default)]
    pub ready: Option<bool>,
}

/// What one line from the process means.
#[derive(Clone, Debug, PartialEq)]
pub enum Said {
    Answer {
        label: String,
        value: bool,
        id: Option<u64>,
        after: Option<u64>,
    },
    /// No answer: false, with a warning and a count.
    Failed {
        label: String,
        why: String,
        id: Option<u64>,
        after: Option<u64>,
    },
    Warning(Located),
    Ready,
    /// A line that is not the protocol (said why).
    Garbled(String),
}

/// A warning, placed in a file when the process says where.
#[derive(Clone, Debug, PartialEq)]
pub struct Located {
    pub message: String,
    pub file: Option<String>,
    pub line: usize,
    pub column: usize,
}

/// Reads one line of the process's stdout.
pub fn read_reply(line: &str) -> Said {
    let reply: Reply = match serde_json::from_str(line) {
        Ok(r) => r,
        Err(e) => return Said::Garbled(format!("not a JSON object ({e}): {}", shorten(line))),
    };
    if let Some(label) = reply.label {
        return match (reply.value, reply.error) {
            (_, Some(why)) => Said::Failed {
                label,
                why,
                id: reply.id,
                after: reply.after,
            },
            (Some(Json::Bool(value)), None) => Said::Answer {
                label,
                value,
                id: reply.id,
                after: reply.after,
            },
            (other, None) => Said::Garbled(format!(
                "the answer for `{label}` needs \"value\": true or false, or \"error\" (found {})",
                other.map_or("neither".to_string(), |v| v.to_string())
            )),
        };
    }
    if let Some(message) = reply.warning {
        return Said::Warning(Located {
            message,
            file: reply.file,
            line: reply.line.unwrap_or(1).max(1),
            column: reply.column.unwrap_or(0),
        });
    }
    if reply.ready == Some(true) {
        return Said::Ready;
    }
    Said::Garbled(format!(
        "a line with no \"label\", \"warning\" or \"ready\": {}",
        shorten(line)
    ))
}

fn shorten(line: &str) -> String {
    const MOST: usize = 120;
    match line.char_indices().nth(MOST) {
        Some((at, _)) => format!("{}…", &line[..at]),
        None => line.to_string(),
    }
}

/// A whiteboard value as JSON: bools, numbers, strings and lists as themselves; bytes as a
/// list of numbers.
pub fn to_json(value: &Value) -> Json {
    match value {
        Value::Bool(b) => Json::Bool(*b),
        Value::Int(i) => Json::from(*i),
        Value::Float(f) => serde_json::Number::from_f64(*f).map_or(Json::Null, Json::Number),
        Value::Str(s) => Json::String(s.clone()),
        Value::Bytes(b) => Json::Array(b.iter().map(|&x| Json::from(x)).collect()),
        Value::List(l) => Json::Array(l.iter().map(to_json).collect()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `(line, what it means)`.
    #[test]
    fn replies_as_data() {
        let cases: Vec<(&str, Said)> = vec![
            (
                r#"{"label":"ballNear","value":true}"#,
                Said::Answer {
                    label: "ballNear".into(),
                    value: true,
                    id: None,
                    after: None,
                },
            ),
            (
                r#"{"label":"ballNear","value":false,"id":7}"#,
                Said::Answer {
                    label: "ballNear".into(),
                    value: false,
                    id: Some(7),
                    after: None,
                },
            ),
            (
                r#"{"label":"x","error":"boom","value":true}"#,
                Said::Failed {
                    label: "x".into(),
                    why: "boom".into(),
                    id: None,
                    after: None,
                },
            ),
            (
                r#"{"warning":"Syntax error","file":"a.pl","line":3,"column":7}"#,
                Said::Warning(Located {
                    message: "Syntax error".into(),
                    file: Some("a.pl".into()),
                    line: 3,
                    column: 7,
                }),
            ),
            (r#"{"ready":true,"extra":1}"#, Said::Ready),
        ];
        for (line, said) in cases {
            assert_eq!(read_reply(line), said, "{line}");
        }
        for garbled in [
            "hello",
            r#"{"label":"x","value":"yes"}"#,
            r#"{"label":"x"}"#,
            "{}",
            "[1]",
        ] {
            assert!(matches!(read_reply(garbled), Said::Garbled(_)), "{garbled}");
        }
    }

    #[test]
    fn requests_are_one_line_each() {
        let hello = Request::Hello {
            expert: "ball".into(),
            answers: vec!["ballNear".into()],
            inputs: vec!["ballDistance".into()],
        };
        assert_eq!(
            hello.line(),
            "{\"type\":\"hello\",\"expert\":\"ball\",\"answers\":[\"ballNear\"],\"inputs\":[\"ballDistance\"]}\n"
        );
        let input = Request::Input {
            name: "note".into(),
            value: to_json(&Value::Str("two\nlines".into())),
            seq: 1,
        };
        assert_eq!(input.line().matches('\n').count(), 1);
        assert_eq!(
            Request::Query {
                label: "ballNear".into(),
                id: 3
            }
            .line(),
            "{\"type\":\"query\",\"label\":\"ballNear\",\"id\":3}\n"
        );
    }
}
