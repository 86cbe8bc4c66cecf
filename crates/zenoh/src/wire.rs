//! What travels between processes, as JSON: a module's request to the process that holds the
//! board (`Up`), and what that process tells every other (`Down`), plus the snapshot a joining
//! process starts from.

use proclaim_board::{Kind, Message, ModuleDecl, Value};
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::time::Duration;

#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub enum WireValue {
    Bool(bool),
    Int(i64),
    Float(f64),
    Str(String),
    Bytes(Vec<u8>),
    List(Vec<WireValue>),
}

impl From<&Value> for WireValue {
    fn from(v: &Value) -> WireValue {
        match v {
            Value::Bool(b) => WireValue::Bool(*b),
            Value::Int(i) => WireValue::Int(*i),
            Value::Float(f) => WireValue::Float(*f),
            Value::Str(s) => WireValue::Str(s.clone()),
            Value::Bytes(b) => WireValue::Bytes(b.clone()),
            Value::List(l) => WireValue::List(l.iter().map(WireValue::from).collect()),
        }
    }
}

impl From<WireValue> for Value {
    fn from(v: WireValue) -> Value {
        match v {
            WireValue::Bool(b) => Value::Bool(b),
            WireValue::Int(i) => Value::Int(i),
            WireValue::Float(f) => Value::Float(f),
            WireValue::Str(s) => Value::Str(s),
            WireValue::Bytes(b) => Value::Bytes(b),
            WireValue::List(l) => Value::List(l.into_iter().map(Value::from).collect()),
        }
    }
}

#[derive(Serialize, Deserialize, Clone, Copy, Debug, PartialEq, Eq)]
pub enum WireKind {
    State,
    Signal,
    Data,
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

#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub struct WireMessage {
    pub ty: String,
    pub value: WireValue,
    pub module: String,
    pub seq: u64,
    pub time_ns: u64,
    /// The poster's subsumption priority; left out when 0 (every message of a process that
    /// knows nothing of priorities reads as 0).
    #[serde(default, skip_serializing_if = "is_zero")]
    pub priority: u32,
}

fn is_zero(priority: &u32) -> bool {
    *priority == 0
}

impl From<&Message> for WireMessage {
    fn from(m: &Message) -> WireMessage {
        WireMessage {
            ty: m.ty.to_string(),
            value: WireValue::from(&m.value),
            module: m.module.to_string(),
            seq: m.seq,
            time_ns: m.time.as_nanos().min(u128::from(u64::MAX)) as u64,
            priority: m.priority,
        }
    }
}

impl From<WireMessage> for Message {
    fn from(m: WireMessage) -> Message {
        Message {
            ty: Arc::from(m.ty),
            value: m.value.into(),
            module: Arc::from(m.module),
            seq: m.seq,
            time: Duration::from_nanos(m.time_ns),
            priority: m.priority,
        }
    }
}

#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Eq, Default)]
pub struct WireDecl {
    pub name: String,
    pub posts: Vec<String>,
    pub reads: Vec<String>,
    pub waits_on: Vec<String>,
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

/// From a process to the one that holds the board.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub enum Up {
    Post {
        module: String,
        ty: String,
        value: WireValue,
        /// As `WireMessage::priority`.
        #[serde(default, skip_serializing_if = "is_zero")]
        priority: u32,
    },
    /// `process` declared `ty`; a signal type is consumed in the first process to declare it.
    Declare {
        ty: String,
        kind: WireKind,
        process: String,
    },
    Register(WireDecl),
}

/// From the process that holds the board to every other, in order.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq)]
pub enum Down {
    /// A message and, for a signal, the process that may consume it.
    Posted {
        message: WireMessage,
        owner: Option<String>,
    },
    Declared {
        ty: String,
        kind: WireKind,
    },
    Registered(WireDecl),
}

/// Where a joining process starts: every type's kind, what the board holds, who owns which
/// signal type, and the registry.
#[derive(Serialize, Deserialize, Clone, Debug, PartialEq, Default)]
pub struct Snapshot {
    pub kinds: Vec<(String, WireKind)>,
    pub messages: Vec<WireMessage>,
    pub owners: Vec<(String, String)>,
    pub registry: Vec<WireDecl>,
    /// The holder's clock when the snapshot was taken.
    pub now_us: u64,
}
