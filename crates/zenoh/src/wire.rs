//! What travels between processes (docs/whiteboard-wire.md): a posting's value as plain JSON on
//! its type's own key, everything else about it as a JSON attachment beside it, and a module's
//! declaration for the registry.

use proclaim_board::{Kind, ModuleDecl, Value};
use serde::{Deserialize, Serialize};
use std::time::{Duration, SystemTime, UNIX_EPOCH};

/// Now, as the wire's times count it: since the Unix epoch, on this process's clock.
pub(crate) fn unix_now() -> Duration {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .unwrap_or_default()
}

/// Everything about a posting but its value: the attachment of every put and every reply.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Default)]
pub struct Meta {
    /// The module that posted it; a posting without one reads as [`ANONYMOUS`].
    #[serde(default)]
    pub module: Option<String>,
    /// The poster's own number for this type, from 1: a reader sees each poster's postings of a
    /// type in this order and ignores a number it has passed.
    #[serde(default)]
    pub seq: Option<u64>,
    /// When it was posted, in nanoseconds since the Unix epoch (the poster's clock).
    #[serde(default)]
    pub time_ns: Option<u64>,
    /// The poster's subsumption priority; left out when 0.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub priority: u32,
    /// How the poster keeps the type: `state`, `signal` or `data`.
    #[serde(default)]
    pub kind: Option<WireKind>,
    /// The Zenoh id of the posting process: its liveliness token says whether it is alive.
    #[serde(default)]
    pub process: Option<String>,
    /// In an answer to a late joiner: the poster is gone, and the value is stale.
    #[serde(default, skip_serializing_if = "is_false")]
    pub stale: bool,
}

fn is_false(stale: &bool) -> bool {
    !*stale
}

/// The module a posting without an attachment (a bare Zenoh put) is shown as.
pub const ANONYMOUS: &str = "zenoh";

fn is_zero(priority: &u32) -> bool {
    *priority == 0
}

impl Meta {
    pub fn encode(&self) -> Vec<u8> {
        serde_json::to_vec(self).unwrap_or_default()
    }

    /// The attachment as sent; `None` (and a warning by the caller) when it is not ours.
    pub fn decode(bytes: &[u8]) -> Result<Meta, String> {
        serde_json::from_slice(bytes).map_err(|e| format!("unreadable attachment ({e})"))
    }

    pub fn time(&self) -> Option<Duration> {
        self.time_ns.map(Duration::from_nanos)
    }
}

/// A value as the payload carries it: plain JSON (`true`, `3`, `0.5`, `"kick"`, `[1, 2]`,
/// `{"bytes": [1, 2]}`).
pub fn encode_value(value: &Value) -> Vec<u8> {
    value.to_json().to_string().into_bytes()
}

/// The value a payload holds. A payload that is not JSON is taken as a string (what a person
/// typing `z_put -v kick` means).
pub fn decode_value(bytes: &[u8]) -> Value {
    match serde_json::from_slice::<serde_json::Value>(bytes) {
        Ok(json) => Value::from_json(&json),
        Err(_) => Value::Str(String::from_utf8_lossy(bytes).into_owned()),
    }
}

#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
#[serde(rename_all = "lowercase")]
pub enum WireKind {
    State,
    Signal,
    Data,
}

impl WireKind {
    pub fn name(self) -> &'static str {
        match self {
            WireKind::State => "state",
            WireKind::Signal => "signal",
            WireKind::Data => "data",
        }
    }

    pub fn parse(text: &str) -> Option<WireKind> {
        match text {
            "state" => Some(WireKind::State),
            "signal" => Some(WireKind::Signal),
            "data" => Some(WireKind::Data),
            _ => None,
        }
    }
}

impl From<Kind> for WireKind {
    fn from(k: Kind) -> WireKind {
        match k {
            Kind::State => WireKind::State,
            Kind::Signal => WireKind::Signal,
            Kind::Data => WireKind::Data,
        }
    }
}

impl From<WireKind> for Kind {
    fn from(k: WireKind) -> Kind {
        match k {
            WireKind::State => Kind::State,
            WireKind::Signal => Kind::Signal,
            WireKind::Data => Kind::Data,
        }
    }
}

/// A module's declaration (the registry), as JSON.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Eq, Default)]
pub struct WireDecl {
    pub name: String,
    #[serde(default)]
    pub posts: Vec<String>,
    #[serde(default)]
    pub reads: Vec<String>,
    #[serde(default)]
    pub waits_on: Vec<String>,
    #[serde(default)]
    pub answers: Vec<String>,
}

impl From<&ModuleDecl> for WireDecl {
    fn from(d: &ModuleDecl) -> WireDecl {
        WireDecl {
            name: d.name.clone(),
            posts: d.posts.clone(),
            reads: d.reads.clone(),
            waits_on: d.waits_on.clone(),
            answers: d.answers.clone(),
        }
    }
}

impl From<WireDecl> for ModuleDecl {
    fn from(d: WireDecl) -> ModuleDecl {
        ModuleDecl::new(d.name)
            .posts(d.posts)
            .reads(d.reads)
            .waits_on(d.waits_on)
            .answers(d.answers)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_travel_as_plain_json() {
        for (value, text) in [
            (Value::Bool(true), "true"),
            (Value::Int(3), "3"),
            (Value::Float(0.5), "0.5"),
            (Value::from("kick"), "\"kick\""),
            (Value::List(vec![Value::Int(1), Value::Int(2)]), "[1,2]"),
        ] {
            assert_eq!(String::from_utf8(encode_value(&value)).unwrap(), text);
            assert_eq!(decode_value(text.as_bytes()), value);
        }
        assert_eq!(decode_value(b"kick left"), Value::from("kick left"));
    }

    #[test]
    fn an_attachment_leaves_out_what_it_need_not_say() {
        let meta = Meta {
            module: Some("vision".into()),
            seq: Some(7),
            time_ns: Some(1_500),
            priority: 0,
            kind: Some(WireKind::Data),
            process: Some("ab12".into()),
            stale: false,
        };
        let text = String::from_utf8(meta.encode()).unwrap();
        assert_eq!(
            text,
            r#"{"module":"vision","seq":7,"time_ns":1500,"kind":"data","process":"ab12"}"#
        );
        assert_eq!(Meta::decode(text.as_bytes()).unwrap(), meta);
        assert_eq!(Meta::decode(b"{}").unwrap(), Meta::default());
        assert!(Meta::decode(b"not json")
            .unwrap_err()
            .contains("unreadable"));
    }

    #[test]
    fn kinds_travel_by_name() {
        for kind in [Kind::State, Kind::Signal, Kind::Data] {
            let wire = WireKind::from(kind);
            assert_eq!(WireKind::parse(wire.name()), Some(wire));
            assert_eq!(Kind::from(wire), kind);
        }
        assert_eq!(WireKind::parse("Signal"), None);
    }

    #[test]
    fn a_declaration_survives_the_registry() {
        let decl = ModuleDecl::new("kicker")
            .posts(["kick"])
            .reads(["ballNear"])
            .waits_on(["whistle"])
            .answers(["canKick"]);
        let json = serde_json::to_string(&WireDecl::from(&decl)).unwrap();
        let back: WireDecl = serde_json::from_str(&json).unwrap();
        assert_eq!(ModuleDecl::from(back), decl);
        let bare: WireDecl = serde_json::from_str(r#"{"name":"eye"}"#).unwrap();
        assert_eq!(ModuleDecl::from(bare), ModuleDecl::new("eye"));
    }
}
