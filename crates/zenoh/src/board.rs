//! The whiteboard across processes. One process holds the board (it listens); the others join
//! it (they connect) and keep a replica. Every posting goes to the holder, which numbers it and
//! sends it, in order, to every replica, so sequence numbers, states and data histories are the
//! same everywhere. A signal type is consumed in one process only, the first that declared it a
//! signal (a machine, for its own name); the others observe its signals. Reads, waits and
//! subscriptions are served from the local replica, so they cost what they cost in process.

use crate::session::{open, Role, Settings};
use crate::wire::{Down, Snapshot, Up, WireDecl, WireKind, WireMessage, WireValue};
use proclaim_board::{
    BoxFuture, Kind, LocalBoard, Message, ModuleDecl, Pattern, Registry, Stats, Subscription,
    Transport, Value, Whiteboard,
};
use rustc_hash::FxHashMap;
use std::marker::PhantomData;
use std::sync::{Arc, Mutex, MutexGuard, OnceLock};
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
) -> Result<Whiteboard, String> {
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

fn lock<T>(mutex: &Mutex<T>) -> MutexGuard<'_, T> {
    mutex.lock().unwrap_or_else(|e| e.into_inner())
}

/// Where one side's messages go, in order. Puts block when the link is full (Zenoh's default
/// for a put is to drop): the whiteboard loses nothing, it slows the poster down. Not express:
/// Zenoh batches only under back-pressure, and measured, express cost 5-15x the messages per
/// second for no gain in a query's latency.
enum Outbox<T> {
    /// Put from the poster's own thread: a replica's postings (none comes from Zenoh's threads).
    Direct(Publisher<'static>, Limit, PhantomData<fn(T)>),
    /// Put by a thread of its own: the holder's, many sent from Zenoh's receiving callback,
    /// which must never wait for a link (with few threads, it is the thread that drains it).
    Queued(std::sync::mpsc::Sender<T>),
}

/// The largest message a transport carries, if it has a limit.
type Limit = Option<usize>;

impl<T: serde::Serialize + Send + 'static> Outbox<T> {
    async fn publisher(session: &zenoh::Session, key: &str) -> Result<Publisher<'static>, String> {
        session
            .declare_publisher(key.to_string())
            .congestion_control(CongestionControl::Block)
            .express(false)
            .await
            .map_err(|e| format!("cannot publish on {key}: {e}"))
    }

    async fn direct(
        session: &zenoh::Session,
        key: &str,
        limit: Limit,
    ) -> Result<Outbox<T>, String> {
        Ok(Outbox::Direct(
            Self::publisher(session, key).await?,
            limit,
            PhantomData,
        ))
    }

    async fn queued(
        session: &zenoh::Session,
        key: &str,
        limit: Limit,
    ) -> Result<Outbox<T>, String> {
        let publisher = Self::publisher(session, key).await?;
        let (tx, rx) = std::sync::mpsc::channel::<T>();
        std::thread::Builder::new()
            .name("proclaim-zenoh-out".into())
            .spawn(move || {
                // Ends when the board's last handle (and with it the sender) is dropped.
                for item in rx {
                    put(&publisher, &item, limit);
                }
            })
            .map_err(|e| format!("cannot start the thread sending on {key}: {e}"))?;
        Ok(Outbox::Queued(tx))
    }

    fn send(&self, item: T) {
        match self {
            Outbox::Direct(publisher, limit, _) => put(publisher, &item, *limit),
            Outbox::Queued(tx) => {
                let _ = tx.send(item);
            }
        }
    }
}

fn put<T: serde::Serialize>(publisher: &Publisher<'static>, item: &T, limit: Limit) {
    let bytes = encode(item);
    if let Some(limit) = limit.filter(|l| bytes.len() > *l) {
        tracing::error!(
            key = %publisher.key_expr(),
            bytes = bytes.len(),
            limit,
            "whiteboard message too large for the low-latency transport, not sent (run every process without --low-latency)"
        );
        return;
    }
    if let Err(e) = publisher.put(bytes).wait() {
        tracing::warn!(key = %publisher.key_expr(), error = %e, "whiteboard message not sent");
    }
}

/// Runs `handle` on every message arriving on `key`, on Zenoh's receiving thread: applying a
/// message to a board never blocks, and no task hop stands between the socket and the waiter.
async fn on_every<T, F>(
    session: &zenoh::Session,
    key: &str,
    handle: F,
) -> Result<Subscriber<()>, String>
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
        .map_err(|e| format!("cannot subscribe to {key}: {e}"))
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

/// The process that holds the board.
struct Holder {
    core: LocalBoard,
    id: String,
    /// Signal type → the process that consumes it.
    owners: Mutex<FxHashMap<String, String>>,
    /// Numbering a posting and queueing it happen under this lock, so replicas receive postings
    /// in sequence order whichever threads post at once.
    down: Mutex<Outbox<Down>>,
    /// The requests, snapshot queries and pings served; dropping them undeclares them.
    serving: OnceLock<(Subscriber<()>, Queryable<()>, Queryable<()>)>,
    _session: zenoh::Session,
}

impl Holder {
    async fn start(
        session: zenoh::Session,
        keys: Keys,
        limit: Limit,
    ) -> Result<Arc<Holder>, String> {
        let holder = Arc::new(Holder {
            core: LocalBoard::new(),
            id: process_id(),
            owners: Mutex::default(),
            down: Mutex::new(Outbox::queued(&session, &keys.down, limit).await?),
            serving: OnceLock::new(),
            _session: session.clone(),
        });
        let requests = on_every(&session, &keys.up, while_alive(&holder, Holder::handle)).await?;
        let weak = Arc::downgrade(&holder);
        let snapshots = session
            .declare_queryable(keys.snapshot.clone())
            .callback(move |query| {
                let Some(holder) = weak.upgrade() else { return };
                let snapshot = encode(&holder.snapshot());
                let sent = match limit.filter(|l| snapshot.len() > *l) {
                    None => query.reply(query.key_expr().clone(), snapshot).wait(),
                    Some(limit) => {
                        let why = format!(
                            "its snapshot is {} bytes, over the low-latency transport's {limit}; run every process without --low-latency",
                            snapshot.len()
                        );
                        tracing::error!("a process could not join: {why}");
                        query.reply_err(why).wait()
                    }
                };
                if let Err(e) = sent {
                    tracing::warn!(error = %e, "snapshot not sent");
                }
            })
            .await
            .map_err(|e| format!("cannot serve {}: {e}", keys.snapshot))?;
        let pings = crate::probe::answer(&session, &keys.ping).await?;
        let _ = holder.serving.set((requests, snapshots, pings));
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
        lock(&self.owners).get(ty).cloned()
    }

    fn post_here(&self, module: &str, ty: &str, value: Value) -> Message {
        let signal = self.core.kind(ty) == Kind::Signal;
        let owner = if signal { self.owner(ty) } else { None };
        // Unowned signals wait here until a process declares the type.
        let consumable = owner.as_ref().is_none_or(|o| *o == self.id);
        let down = lock(&self.down);
        let message = self.core.post_as(module, ty, value, consumable);
        down.send(Down::Posted {
            message: WireMessage::from(&message),
            owner,
        });
        message
    }

    fn declare_for(&self, ty: &str, kind: Kind, process: &str) {
        let down = lock(&self.down);
        let was = self.core.kind(ty);
        if kind == Kind::Signal {
            let owner = {
                lock(&self.owners)
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
                    down.send(Down::Posted {
                        message: WireMessage::from(&message),
                        owner: Some(owner.clone()),
                    });
                }
            }
        } else {
            self.core.declare(ty, kind);
        }
        down.send(Down::Declared {
            ty: ty.to_string(),
            kind: kind.into(),
        });
    }

    fn snapshot(&self) -> Snapshot {
        let (kinds, messages) = self.core.snapshot().contents();
        let owners = lock(&self.owners);
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
    served_locally!(core);

    fn declare(&self, ty: &str, kind: Kind) {
        let id = self.id.clone();
        self.declare_for(ty, kind, &id);
    }

    fn post(&self, module: &str, ty: &str, value: Value) -> Message {
        self.post_here(module, ty, value)
    }

    fn register(&self, decl: ModuleDecl) {
        let wire = WireDecl::from(&decl);
        let down = lock(&self.down);
        self.core.register(decl);
        down.send(Down::Registered(wire));
    }

    fn now(&self) -> Duration {
        self.core.now()
    }
}

/// A process that joined the board: a replica kept in step by the holder's messages.
struct Replica {
    mirror: LocalBoard,
    id: String,
    up: Outbox<Up>,
    /// The holder's clock when the replica's began, so times compare across processes.
    clock_offset: OnceLock<Duration>,
    /// What arrives from the holder before the snapshot is applied waits here (`None` after).
    early: Mutex<Option<Vec<Down>>>,
    stream: OnceLock<Subscriber<()>>,
    _session: zenoh::Session,
}

impl Replica {
    async fn start(
        session: zenoh::Session,
        keys: Keys,
        endpoint: &str,
        limit: Limit,
    ) -> Result<Arc<Replica>, String> {
        let replica = Arc::new(Replica {
            mirror: LocalBoard::new(),
            id: process_id(),
            up: Outbox::direct(&session, &keys.up, limit).await?,
            clock_offset: OnceLock::new(),
            early: Mutex::new(Some(Vec::new())),
            stream: OnceLock::new(),
            _session: session.clone(),
        });
        // Subscribe first, so nothing posted between the snapshot and the stream is lost
        // (what arrives twice is recognised by its sequence number).
        let stream = on_every(
            &session,
            &keys.down,
            while_alive(&replica, Replica::receive),
        )
        .await?;
        let _ = replica.stream.set(stream);
        let snapshot = fetch_snapshot(&session, &keys, endpoint).await?;
        replica.start_from(snapshot);
        Ok(replica)
    }

    fn start_from(&self, snapshot: Snapshot) {
        let mirror = &self.mirror;
        let _ = self
            .clock_offset
            .set(Duration::from_micros(snapshot.now_us).saturating_sub(mirror.now()));
        for (ty, kind) in &snapshot.kinds {
            mirror.declare_observed(ty, (*kind).into());
        }
        for m in snapshot.messages {
            mirror.apply(m.into(), false);
        }
        for d in snapshot.registry {
            mirror.register(d.into());
        }
        let mut early = lock(&self.early);
        for down in early.take().unwrap_or_default() {
            self.apply(down);
        }
    }

    fn receive(&self, down: Down) {
        let mut early = lock(&self.early);
        match early.as_mut() {
            Some(waiting) => waiting.push(down),
            None => {
                drop(early);
                self.apply(down);
            }
        }
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
            if let Ok(reply) = replies.recv_async().await {
                return match reply.result() {
                    Ok(sample) => {
                        serde_json::from_slice(&sample.payload().to_bytes()).map_err(|e| {
                            format!("the whiteboard at {endpoint} sent an unreadable snapshot: {e}")
                        })
                    }
                    Err(refused) => Err(format!(
                        "the whiteboard at {endpoint} cannot be joined: {}",
                        String::from_utf8_lossy(&refused.payload().to_bytes())
                    )),
                };
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
    served_locally!(mirror);

    fn declare(&self, ty: &str, kind: Kind) {
        // A signal type's pending command comes from the holder, which alone knows whether
        // another process consumes the type already.
        match kind {
            Kind::Signal => self.mirror.declare_observed(ty, kind),
            _ => self.mirror.declare(ty, kind),
        }
        self.up.send(Up::Declare {
            ty: ty.to_string(),
            kind: WireKind::from(kind),
            process: self.id.clone(),
        });
    }

    /// Sent to the holder, which numbers it; the message comes back to this replica like any
    /// other. The one returned carries the highest sequence number seen here: the posting is
    /// numbered after it (what a query waits beyond).
    fn post(&self, module: &str, ty: &str, value: Value) -> Message {
        // Read before sending: the answer to a query can be back before `send` returns.
        let seen = self.mirror.last_seq();
        self.up.send(Up::Post {
            module: module.to_string(),
            ty: ty.to_string(),
            value: WireValue::from(&value),
        });
        Message {
            ty: Arc::from(ty),
            value,
            module: Arc::from(module),
            seq: seen,
            time: self.now(),
        }
    }

    fn register(&self, decl: ModuleDecl) {
        self.up.send(Up::Register(WireDecl::from(&decl)));
        self.mirror.register(decl);
    }

    fn now(&self) -> Duration {
        self.mirror.now() + self.clock_offset.get().copied().unwrap_or_default()
    }
}
