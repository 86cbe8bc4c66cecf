//! The whiteboard across processes. One process holds the board (it listens); the others join
//! it (they connect) and keep a replica. Every posting goes to the holder, which numbers it and
//! sends it, in order, to every replica, so sequence numbers, states and data histories are the
//! same everywhere. A signal type is consumed in one process only, the first that declared it a
//! signal (a machine, for its own name); the others observe its signals. Reads, waits and
//! subscriptions are served from the local replica, so they cost what they cost in process.

use crate::session::{open, Role};
use crate::wire::{Down, Snapshot, Up, WireDecl, WireKind, WireMessage, WireValue};
use proclaim_board::{
    BoxFuture, Kind, LocalBoard, Message, ModuleDecl, Pattern, Registry, Stats, Subscription,
    Transport, Value, Whiteboard,
};
use rustc_hash::FxHashMap;
use std::path::Path;
use std::sync::{Arc, Mutex};
use std::time::Duration;
use tokio::sync::mpsc;

/// Key expressions of one board, under its name.
#[derive(Clone)]
struct Keys {
    up: String,
    down: String,
    snapshot: String,
}

impl Keys {
    fn new(board: &str) -> Keys {
        Keys {
            up: format!("proclaim/{board}/up"),
            down: format!("proclaim/{board}/down"),
            snapshot: format!("proclaim/{board}/snapshot"),
        }
    }
}

/// Joins or holds the whiteboard named `board` (several can share a network) as `role` says.
/// `config_file` is Zenoh's own JSON5 configuration (TLS, access control), read first.
pub async fn whiteboard(
    role: &Role,
    board: &str,
    config_file: Option<&Path>,
) -> Result<Whiteboard, String> {
    let session = open(role, config_file).await?;
    let keys = Keys::new(board);
    let transport: Arc<dyn Transport> = match role {
        Role::Listen(_) => Holder::start(session, keys).await?,
        Role::Connect(endpoint) => Replica::start(session, keys, endpoint).await?,
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

/// Sends each item, in order, as one Zenoh put on `key`.
fn publisher<T: serde::Serialize + Send + 'static>(
    session: zenoh::Session,
    key: String,
) -> mpsc::UnboundedSender<T> {
    let (tx, mut rx) = mpsc::unbounded_channel::<T>();
    tokio::spawn(async move {
        while let Some(item) = rx.recv().await {
            if let Err(e) = session.put(&key, encode(&item)).await {
                tracing::warn!(%key, error = %e, "whiteboard message not sent");
            }
        }
    });
    tx
}

/// The process that holds the board.
struct Holder {
    core: LocalBoard,
    id: String,
    /// Signal type → the process that consumes it.
    owners: Mutex<FxHashMap<String, String>>,
    down: mpsc::UnboundedSender<Down>,
    _session: zenoh::Session,
}

impl Holder {
    async fn start(session: zenoh::Session, keys: Keys) -> Result<Arc<Holder>, String> {
        let holder = Arc::new(Holder {
            core: LocalBoard::new(),
            id: process_id(),
            owners: Mutex::default(),
            down: publisher(session.clone(), keys.down.clone()),
            _session: session.clone(),
        });
        let requests = session
            .declare_subscriber(&keys.up)
            .await
            .map_err(|e| format!("cannot subscribe to {}: {e}", keys.up))?;
        let snapshots = session
            .declare_queryable(&keys.snapshot)
            .await
            .map_err(|e| format!("cannot serve {}: {e}", keys.snapshot))?;
        // The tasks hold the holder weakly: the board ends when its last handle is dropped.
        let weak = Arc::downgrade(&holder);
        tokio::spawn(async move {
            while let Ok(sample) = requests.recv_async().await {
                let Some(holder) = weak.upgrade() else { return };
                match serde_json::from_slice::<Up>(&sample.payload().to_bytes()) {
                    Ok(up) => holder.handle(up),
                    Err(e) => tracing::warn!(error = %e, "unreadable whiteboard request ignored"),
                }
            }
        });
        let weak = Arc::downgrade(&holder);
        tokio::spawn(async move {
            while let Ok(query) = snapshots.recv_async().await {
                let Some(holder) = weak.upgrade() else { return };
                let snapshot = holder.snapshot();
                if let Err(e) = query
                    .reply(query.key_expr().clone(), encode(&snapshot))
                    .await
                {
                    tracing::warn!(error = %e, "snapshot not sent");
                }
            }
        });
        Ok(holder)
    }

    fn handle(&self, up: Up) {
        match up {
            Up::Post { module, ty, value } => {
                self.post_here(&module, &ty, value.into());
            }
            Up::Declare { ty, kind, process } => self.declare_for(&ty, kind.into(), &process),
            Up::Register(decl) => self.register(decl.into()),
        }
    }

    fn owner(&self, ty: &str) -> Option<String> {
        self.owners
            .lock()
            .unwrap_or_else(|e| e.into_inner())
            .get(ty)
            .cloned()
    }

    fn post_here(&self, module: &str, ty: &str, value: Value) -> Message {
        let signal = self.core.kind(ty) == Kind::Signal;
        let owner = if signal { self.owner(ty) } else { None };
        // Unowned signals wait here until a process declares the type.
        let consumable = owner.as_ref().is_none_or(|o| *o == self.id);
        let message = self.core.post_as(module, ty, value, consumable);
        let _ = self.down.send(Down::Posted {
            message: WireMessage::from(&message),
            owner,
        });
        message
    }

    fn declare_for(&self, ty: &str, kind: Kind, process: &str) {
        let was = self.core.kind(ty);
        if kind == Kind::Signal {
            let owner = {
                let mut owners = self.owners.lock().unwrap_or_else(|e| e.into_inner());
                owners
                    .entry(ty.to_string())
                    .or_insert_with(|| process.to_string())
                    .clone()
            };
            if owner != process {
                tracing::warn!(
                    ty,
                    owner,
                    process,
                    "signal type already consumed by another process; this one observes it"
                );
            }
            if owner == self.id {
                self.core.declare(ty, kind);
            } else {
                // What was posted before its consumer declared the type goes to it now: unread
                // signals, or the command posted while the type was still a state.
                let mut pending = Vec::new();
                match was {
                    Kind::Signal => pending.extend(std::iter::from_fn(|| self.core.latest(ty))),
                    _ => pending.extend(self.core.take_latest(ty)),
                }
                self.core.declare_observed(ty, kind);
                for message in pending {
                    let _ = self.down.send(Down::Posted {
                        message: WireMessage::from(&message),
                        owner: Some(owner.clone()),
                    });
                }
            }
        } else {
            self.core.declare(ty, kind);
        }
        let _ = self.down.send(Down::Declared {
            ty: ty.to_string(),
            kind: kind.into(),
        });
    }

    fn snapshot(&self) -> Snapshot {
        let (kinds, messages) = self.core.snapshot();
        let owners = self.owners.lock().unwrap_or_else(|e| e.into_inner());
        Snapshot {
            kinds: kinds.into_iter().map(|(t, k)| (t, k.into())).collect(),
            messages: messages.iter().map(WireMessage::from).collect(),
            owners: owners.iter().map(|(t, o)| (t.clone(), o.clone())).collect(),
            registry: self
                .core
                .registry()
                .modules()
                .into_iter()
                .map(WireDecl::from)
                .collect(),
            now_us: self.core.now().as_micros() as u64,
        }
    }
}

impl Transport for Holder {
    fn declare(&self, ty: &str, kind: Kind) {
        let id = self.id.clone();
        self.declare_for(ty, kind, &id);
    }

    fn kind(&self, ty: &str) -> Kind {
        self.core.kind(ty)
    }

    fn post(&self, module: &str, ty: &str, value: Value) -> Message {
        self.post_here(module, ty, value)
    }

    fn latest(&self, ty: &str) -> Option<Message> {
        self.core.latest(ty)
    }

    fn wait_for(&self, ty: &str, after: u64, timeout: Duration) -> BoxFuture<'_, Option<Message>> {
        self.core.wait_for(ty, after, timeout)
    }

    fn nearest(&self, ty: &str, time: Duration, side: std::cmp::Ordering) -> Option<Message> {
        self.core.nearest(ty, time, side)
    }

    fn subscribe(&self, pattern: Pattern) -> Subscription {
        self.core.subscribe(pattern)
    }

    fn register(&self, decl: ModuleDecl) {
        let wire = WireDecl::from(&decl);
        self.core.register(decl);
        let _ = self.down.send(Down::Registered(wire));
    }

    fn registry(&self) -> Registry {
        self.core.registry()
    }

    fn is_answered(&self, atom: &str) -> bool {
        self.core.is_answered(atom)
    }

    fn stats(&self) -> Stats {
        self.core.stats()
    }

    fn count_query(&self, timed_out: bool, unanswerable: bool) {
        self.core.count_query(timed_out, unanswerable)
    }

    fn now(&self) -> Duration {
        self.core.now()
    }
}

/// A process that joined the board: a replica kept in step by the holder's messages.
struct Replica {
    mirror: LocalBoard,
    id: String,
    up: mpsc::UnboundedSender<Up>,
    /// The holder's clock when the replica's began, so times compare across processes.
    clock_offset: Duration,
    _session: zenoh::Session,
}

impl Replica {
    async fn start(
        session: zenoh::Session,
        keys: Keys,
        endpoint: &str,
    ) -> Result<Arc<Replica>, String> {
        // Subscribe first, so nothing posted between the snapshot and the stream is lost
        // (what arrives twice is recognised by its sequence number).
        let stream = session
            .declare_subscriber(&keys.down)
            .await
            .map_err(|e| format!("cannot subscribe to {}: {e}", keys.down))?;
        let snapshot = fetch_snapshot(&session, &keys, endpoint).await?;
        let mirror = LocalBoard::new();
        let local_start = mirror.now();
        let id = process_id();
        for (ty, kind) in &snapshot.kinds {
            mirror.declare_observed(ty, (*kind).into());
        }
        for m in snapshot.messages {
            mirror.apply(m.into(), false);
        }
        for d in snapshot.registry {
            mirror.register(d.into());
        }
        let replica = Arc::new(Replica {
            mirror,
            id,
            up: publisher(session.clone(), keys.up.clone()),
            clock_offset: Duration::from_micros(snapshot.now_us).saturating_sub(local_start),
            _session: session.clone(),
        });
        let weak = Arc::downgrade(&replica);
        tokio::spawn(async move {
            while let Ok(sample) = stream.recv_async().await {
                let Some(replica) = weak.upgrade() else {
                    return;
                };
                match serde_json::from_slice::<Down>(&sample.payload().to_bytes()) {
                    Ok(down) => replica.apply(down),
                    Err(e) => tracing::warn!(error = %e, "unreadable whiteboard message ignored"),
                }
            }
        });
        Ok(replica)
    }

    fn apply(&self, down: Down) {
        match down {
            Down::Posted { message, owner } => {
                let mine = owner.as_deref() == Some(self.id.as_str());
                self.mirror.apply(message.into(), mine);
            }
            Down::Declared { ty, kind } => {
                if self.mirror.kind(&ty) != Kind::from(kind) {
                    self.mirror.declare_observed(&ty, kind.into());
                }
            }
            Down::Registered(decl) => self.mirror.register(decl.into()),
        }
    }
}

/// The holder's snapshot; it may take a moment for the new link's routes to settle.
async fn fetch_snapshot(
    session: &zenoh::Session,
    keys: &Keys,
    endpoint: &str,
) -> Result<Snapshot, String> {
    let deadline = tokio::time::Instant::now() + Duration::from_secs(5);
    loop {
        if let Ok(replies) = session.get(&keys.snapshot).await {
            while let Ok(reply) = replies.recv_async().await {
                if let Ok(sample) = reply.result() {
                    return serde_json::from_slice(&sample.payload().to_bytes()).map_err(|e| {
                        format!("the whiteboard at {endpoint} sent an unreadable snapshot: {e}")
                    });
                }
            }
        }
        if tokio::time::Instant::now() >= deadline {
            return Err(format!(
                "no whiteboard answered at {endpoint} (is a `proclaim run … --listen {endpoint}` running?)"
            ));
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

impl Transport for Replica {
    fn declare(&self, ty: &str, kind: Kind) {
        // A signal type's pending command comes from the holder, which alone knows whether
        // another process consumes the type already.
        match kind {
            Kind::Signal => self.mirror.declare_observed(ty, kind),
            _ => self.mirror.declare(ty, kind),
        }
        let _ = self.up.send(Up::Declare {
            ty: ty.to_string(),
            kind: WireKind::from(kind),
            process: self.id.clone(),
        });
    }

    fn kind(&self, ty: &str) -> Kind {
        self.mirror.kind(ty)
    }

    /// Sent to the holder, which numbers it; the message comes back to this replica like any
    /// other. The one returned carries the highest sequence number seen here: the posting is
    /// numbered after it (what a query waits beyond).
    fn post(&self, module: &str, ty: &str, value: Value) -> Message {
        let _ = self.up.send(Up::Post {
            module: module.to_string(),
            ty: ty.to_string(),
            value: WireValue::from(&value),
        });
        Message {
            ty: Arc::from(ty),
            value,
            module: Arc::from(module),
            seq: self.mirror.last_seq(),
            time: self.now(),
        }
    }

    fn latest(&self, ty: &str) -> Option<Message> {
        self.mirror.latest(ty)
    }

    fn wait_for(&self, ty: &str, after: u64, timeout: Duration) -> BoxFuture<'_, Option<Message>> {
        self.mirror.wait_for(ty, after, timeout)
    }

    fn nearest(&self, ty: &str, time: Duration, side: std::cmp::Ordering) -> Option<Message> {
        self.mirror.nearest(ty, time, side)
    }

    fn subscribe(&self, pattern: Pattern) -> Subscription {
        self.mirror.subscribe(pattern)
    }

    fn register(&self, decl: ModuleDecl) {
        let _ = self.up.send(Up::Register(WireDecl::from(&decl)));
        self.mirror.register(decl);
    }

    fn registry(&self) -> Registry {
        self.mirror.registry()
    }

    fn is_answered(&self, atom: &str) -> bool {
        self.mirror.is_answered(atom)
    }

    fn stats(&self) -> Stats {
        self.mirror.stats()
    }

    fn count_query(&self, timed_out: bool, unanswerable: bool) {
        self.mirror.count_query(timed_out, unanswerable)
    }

    fn now(&self) -> Duration {
        self.mirror.now() + self.clock_offset
    }
}
