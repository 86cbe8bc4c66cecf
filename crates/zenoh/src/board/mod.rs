//! The whiteboard across processes. One process holds the board (it listens); the others join
//! it (they connect) and keep a replica. Every posting goes to the holder, which numbers it and
//! sends it, in order, to every replica, so sequence numbers, states and data histories are the
//! same everywhere. A signal type is consumed in one process only, the first that declared it a
//! signal (a machine, for its own name); the others observe its signals. Reads, waits and
//! subscriptions are served from the local replica, so they cost what they cost in process.

use crate::error::NetworkError;
use crate::session::{open, Role, Settings};
use crate::wire::{Down, Snapshot, Up, WireDecl, WireKind, WireMessage, WireValue};
use parking_lot::Mutex;
use proclaim_board::{
    BoxFuture, Kind, LocalBoard, Message, ModuleDecl, Pattern, Registry, Stats, Subscription,
    Transport, Value, Whiteboard,
};
use rustc_hash::FxHashMap;
use std::marker::PhantomData;
use std::sync::{Arc, OnceLock};
use std::time::Duration;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::qos::CongestionControl;
use zenoh::query::Queryable;
use zenoh::Wait;

/// What every process serves from its own board, holder or replica alike: reads, waits,
/// subscriptions, the registry and the counters.
macro_rules! served_locally {
    ($board:ident) => {
        fn kind(&self, ty: &str) -> Kind {
            self.$board.kind(ty)
        }

        fn latest(&self, ty: &str) -> Option<Message> {
            self.$board.latest(ty)
        }

        fn wait_for(
            &self,
            ty: &str,
            after: u64,
            timeout: Duration,
        ) -> BoxFuture<'_, Option<Message>> {
            self.$board.wait_for(ty, after, timeout)
        }

        fn nearest(&self, ty: &str, time: Duration, side: std::cmp::Ordering) -> Option<Message> {
            self.$board.nearest(ty, time, side)
        }

        fn subscribe(&self, pattern: Pattern) -> Subscription {
            self.$board.subscribe(pattern)
        }

        fn registry(&self) -> Registry {
            self.$board.registry()
        }

        fn is_answered(&self, atom: &str) -> bool {
            self.$board.is_answered(atom)
        }

        fn stats(&self) -> Stats {
            self.$board.stats()
        }

        fn count_query(&self, timed_out: bool, unanswerable: bool) {
            self.$board.count_query(timed_out, unanswerable)
        }

        fn snapshot(&self) -> proclaim_board::Snapshot {
            self.$board.snapshot()
        }
    };
}

mod holder;
mod outbox;
mod replica;

use holder::Holder;
use outbox::{Limit, Outbox};
use replica::Replica;

/// Key expressions of one board, under its name.
#[derive(Clone)]
struct Keys {
    up: String,
    down: String,
    snapshot: String,
    ping: String,
}

impl Keys {
    fn new(board: &str) -> Keys {
        Keys {
            up: format!("proclaim/{board}/up"),
            down: format!("proclaim/{board}/down"),
            snapshot: format!("proclaim/{board}/snapshot"),
            ping: crate::probe::key(board),
        }
    }
}

/// Joins or holds the whiteboard named `board` (several can share a network) as `role` says.
/// `config_file` is Zenoh's own JSON5 configuration (TLS, access control), read first.
pub async fn whiteboard(
    role: &Role,
    board: &str,
    settings: &Settings,
) -> Result<Whiteboard, NetworkError> {
    let session = open(role, settings).await?;
    let keys = Keys::new(board);
    let transport: Arc<dyn Transport> = match role {
        Role::Listen(_) => Holder::start(session, keys, settings.message_limit()).await?,
        Role::Connect(endpoint) => {
            Replica::start(session, keys, endpoint, settings.message_limit()).await?
        }
    };
    Ok(Whiteboard::new(transport))
}

fn process_id() -> String {
    let nanos = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    format!("{}-{nanos:08x}", std::process::id())
}

fn encode<T: serde::Serialize>(value: &T) -> Vec<u8> {
    serde_json::to_vec(value).unwrap_or_default()
}

/// Runs `handle` on every message arriving on `key`, on Zenoh's receiving thread: applying a
/// message to a board never blocks, and no task hop stands between the socket and the waiter.
async fn on_every<T, F>(
    session: &zenoh::Session,
    key: &str,
    handle: F,
) -> Result<Subscriber<()>, NetworkError>
where
    T: serde::de::DeserializeOwned,
    F: Fn(T) + Send + Sync + 'static,
{
    session
        .declare_subscriber(key.to_string())
        .callback(
            move |sample| match serde_json::from_slice::<T>(&sample.payload().to_bytes()) {
                Ok(item) => handle(item),
                Err(e) => tracing::warn!(error = %e, "unreadable whiteboard message ignored"),
            },
        )
        .await
        .map_err(|e| NetworkError::zenoh(format!("cannot subscribe to {key}"), e))
}

/// `handle` on `board` for as long as it lives: a callback holds its board weakly, so the board
/// ends when its last handle is dropped.
fn while_alive<B, T>(board: &Arc<B>, handle: fn(&B, T)) -> impl Fn(T) + Send + Sync + 'static
where
    B: Send + Sync + 'static,
    T: 'static,
{
    let weak = Arc::downgrade(board);
    move |item| {
        if let Some(board) = weak.upgrade() {
            handle(&board, item);
        }
    }
}
