//! The whiteboard written down (`docs/spec/behaviour.md` §3.4, checkpoints): every type with its
//! kind and what it holds, each message with its sequence number, time and priority, the
//! board's sequence number, clock and counts, as a value a checkpoint file keeps and a fresh
//! in-process board is restored from. Values are in the one JSON form recordings use.

use crate::message::{Kind, Message};
use crate::snapshot::{Slot, Snapshot, Table};
use crate::stats::Stats;
use crate::value::Value;
use serde::{Deserialize, Serialize};
use std::sync::Arc;
use std::time::Duration;

/// A whole board at one moment.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct BoardImage {
    /// The highest sequence number given.
    pub seq: u64,
    /// The board's clock (nanoseconds since it was made).
    pub time_ns: u64,
    pub posts: u64,
    pub queries: u64,
    pub timeouts: u64,
    pub unanswerable: u64,
    pub drops: u64,
    /// Every type, by name.
    pub types: Vec<TypeImage>,
}

/// One type: how its messages are kept and what it holds.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct TypeImage {
    #[serde(rename = "type")]
    pub ty: String,
    pub kind: KindName,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub latest: Option<MessageImage>,
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub history: Vec<MessageImage>,
    /// Unread signals, oldest first.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub signals: Vec<MessageImage>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub last_signal: Option<MessageImage>,
    pub posts: u64,
}

/// [`Kind`] as a checkpoint names it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum KindName {
    State,
    Signal,
    Data,
}

/// One message of a type (the type is its [`TypeImage`]'s).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct MessageImage {
    pub seq: u64,
    pub module: String,
    pub value: serde_json::Value,
    pub time_ns: u64,
    #[serde(default, skip_serializing_if = "is_zero")]
    pub priority: u32,
}

fn is_zero(p: &u32) -> bool {
    *p == 0
}

/// A duration in whole nanoseconds (saturating: 584 years).
pub fn nanos(d: Duration) -> u64 {
    u64::try_from(d.as_nanos()).unwrap_or(u64::MAX)
}

impl From<Kind> for KindName {
    fn from(kind: Kind) -> KindName {
        match kind {
            Kind::State => KindName::State,
            Kind::Signal => KindName::Signal,
            Kind::Data => KindName::Data,
        }
    }
}

impl From<KindName> for Kind {
    fn from(kind: KindName) -> Kind {
        match kind {
            KindName::State => Kind::State,
            KindName::Signal => Kind::Signal,
            KindName::Data => Kind::Data,
        }
    }
}

impl MessageImage {
    pub fn of(message: &Message) -> MessageImage {
        MessageImage {
            seq: message.seq,
            module: message.module.to_string(),
            value: message.value.to_json(),
            time_ns: nanos(message.time),
            priority: message.priority,
        }
    }

    /// The message, of type `ty`.
    pub fn message(&self, ty: &Arc<str>) -> Message {
        Message {
            ty: ty.clone(),
            value: Value::from_json(&self.value),
            module: Arc::from(self.module.as_str()),
            seq: self.seq,
            time: Duration::from_nanos(self.time_ns),
            priority: self.priority,
        }
    }
}

impl Snapshot {
    /// The board as this snapshot holds it, with the counts given.
    pub fn image(&self, stats: Stats) -> BoardImage {
        let mut types: Vec<TypeImage> = self
            .table
            .iter()
            .map(|(ty, slot)| TypeImage {
                ty: ty.to_string(),
                kind: slot.kind.into(),
                latest: slot.latest.as_ref().map(MessageImage::of),
                history: slot.history.iter().map(MessageImage::of).collect(),
                signals: slot.signals.iter().map(MessageImage::of).collect(),
                last_signal: slot.last_signal.as_ref().map(MessageImage::of),
                posts: slot.posts,
            })
            .collect();
        types.sort_by(|a, b| a.ty.cmp(&b.ty));
        BoardImage {
            seq: self.seq,
            time_ns: nanos(self.time),
            posts: stats.posts,
            queries: stats.queries,
            timeouts: stats.timeouts,
            unanswerable: stats.unanswerable,
            drops: stats.drops,
            types,
        }
    }
}

impl BoardImage {
    /// The board as a snapshot holds it (what a restored board starts from, and what a
    /// machine restored from a checkpoint last saw).
    pub fn snapshot(&self) -> Snapshot {
        let mut table = Table::default();
        for image in &self.types {
            let ty: Arc<str> = Arc::from(image.ty.as_str());
            let read = |m: &MessageImage| m.message(&ty);
            let slot = Slot {
                kind: image.kind.into(),
                latest: image.latest.as_ref().map(read),
                history: image.history.iter().map(read).collect(),
                signals: image.signals.iter().map(read).collect(),
                last_signal: image.last_signal.as_ref().map(read),
                posts: image.posts,
            };
            table.insert(ty.clone(), slot);
        }
        Snapshot {
            table,
            seq: self.seq,
            time: Duration::from_nanos(self.time_ns),
        }
    }

    /// The counts the board had.
    pub fn stats(&self) -> Stats {
        Stats {
            posts: self.posts,
            drops: self.drops,
            queries: self.queries,
            timeouts: self.timeouts,
            unanswerable: self.unanswerable,
            subscribers: 0,
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{Kind, LocalBoard, Whiteboard};
    use std::sync::Arc;

    #[tokio::test(start_paused = true)]
    async fn a_board_restored_from_its_image_holds_and_numbers_as_it_did() {
        let board = Whiteboard::local();
        board.declare("Placer", Kind::Signal);
        board.declare("ball", Kind::Data);
        board.post("m", "LEDS", 3);
        board.post("m", "Placer", "On");
        board.post("m", "Placer", "Off");
        assert!(board.latest("Placer").is_some(), "one signal read");
        board.post_ranked("m", "ball", 1.5, 2);
        tokio::time::sleep(std::time::Duration::from_millis(40)).await;
        board.post("m", "ball", 2.5);
        let image = board.snapshot().image(board.stats());
        let text = serde_json::to_string(&image).unwrap();
        let read: super::BoardImage = serde_json::from_str(&text).unwrap();
        assert_eq!(read, image);

        let restored = Whiteboard::new(Arc::new(LocalBoard::new()));
        restored.restore(&read).unwrap();
        assert_eq!(restored.snapshot().image(restored.stats()), image);
        assert_eq!(
            restored.now(),
            board.now(),
            "the clock goes on from where it was"
        );
        let next = restored.post("m", "LEDS", 4);
        assert_eq!(next.seq, image.seq + 1);
        assert_eq!(restored.latest("Placer").unwrap().value, "Off".into());
        assert_eq!(restored.kind("ball"), Kind::Data);
        assert_eq!(restored.stats().posts, board.stats().posts + 1);
    }
}
