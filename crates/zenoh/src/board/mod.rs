//! The whiteboard across processes, with no process it depends on. Every process keeps its own
//! replica (a `LocalBoard`) and is the authority for what it posts: it numbers its own postings
//! of each type and puts them on the type's own key, `proclaim/<board>/<type>`, the value as
//! plain JSON and the rest in the attachment. A process joining asks the others for the values
//! they own (each answers for its own, `catchup.rs`); a process that dies is noticed through its
//! liveliness token and the types whose current value it posted turn stale (`members.rs`).
//! Reads, waits and subscriptions are served from the local replica, so they cost what they
//! cost in process, and a replica numbers what reaches it in the order it arrives.

use crate::error::NetworkError;
use crate::keys::{type_key_error, Keys};
use crate::session::{open, Role, Settings};
use crate::wire::{decode_value, encode_value, unix_now, Meta, WireDecl, WireKind, ANONYMOUS};
use parking_lot::Mutex;
use proclaim_board::{
    BoxFuture, Kind, LocalBoard, Message, ModuleDecl, Pattern, Registry, Restored, Stats,
    Subscription, Transport, Value, Whiteboard,
};
use rustc_hash::{FxHashMap, FxHashSet};
use std::collections::{BTreeSet, VecDeque};
use std::sync::{Arc, Weak};
use std::time::Duration;
use zenoh::bytes::Encoding;
use zenoh::liveliness::LivelinessToken;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::qos::CongestionControl;
use zenoh::query::Queryable;
use zenoh::sample::Locality;
use zenoh::Wait;

mod catchup;
mod members;
mod team;

pub use team::Team;

/// The largest message a transport carries, if it has a limit.
type Limit = Option<usize>;

/// How many of its own postings of a data type a process keeps to answer a late joiner with
/// (the in-process board's default history).
const OWN_HISTORY: usize = 256;

/// The module a stale mark is posted by: the gone process, as a person reads its id.
fn gone_module(process: &str) -> String {
    format!("gone {}", &process[..process.len().min(8)])
}

/// The local type saying whether `ty`'s current value came from a process that is gone.
pub fn stale_type(ty: &str) -> String {
    format!("{ty}Stale")
}

/// Joins the whiteboard named `board` (several can share a network): listening on an endpoint
/// or connecting to one, as `role` says; either way a process like every other.
pub async fn whiteboard(
    role: &Role,
    board: &str,
    settings: &Settings,
) -> Result<Whiteboard, NetworkError> {
    join(role, board, settings, None).await
}

/// Joins the whiteboard named `board` as [`whiteboard`] does, as a robot of `team`: the types
/// the team shares are also put where its teammates hear them, and theirs are kept on this
/// board (`team.rs`).
pub async fn team_whiteboard(
    role: &Role,
    board: &str,
    settings: &Settings,
    team: Team,
) -> Result<Whiteboard, NetworkError> {
    join(role, board, settings, Some(team)).await
}

async fn join(
    role: &Role,
    board: &str,
    settings: &Settings,
    team: Option<Team>,
) -> Result<Whiteboard, NetworkError> {
    let session = open(role, settings).await?;
    members::meet(&session, role).await?;
    let peer = Peer::start(session, Keys::new(board), settings.message_limit(), team).await?;
    peer.catch_up(None).await;
    Ok(Whiteboard::new(peer))
}

/// Posts one message from a process that ends right after: joins, posts, and returns once every
/// process linked to this one has answered a ping sent after the posting (on each link the
/// posting went first, so each has it), with the message and how many processes answered.
pub async fn post_once(
    role: &Role,
    board: &str,
    settings: &Settings,
    module: &str,
    ty: &str,
    value: Value,
) -> Result<(Message, usize), NetworkError> {
    let session = open(role, settings).await?;
    members::meet(&session, role).await?;
    let peer = Peer::start(session, Keys::new(board), settings.message_limit(), None).await?;
    let message = peer.post(module, ty, value);
    let heard = peer.ask(&peer.keys.ping()).await.len();
    Ok((message, heard))
}

fn nanos(time: Duration) -> u64 {
    time.as_nanos().min(u128::from(u64::MAX)) as u64
}

/// One process on the board.
pub(crate) struct Peer {
    board: LocalBoard,
    /// This process's Zenoh id, the name its liveliness token and its postings carry.
    me: String,
    keys: Keys,
    limit: Limit,
    session: zenoh::Session,
    /// Numbering a posting and putting it happen under this lock, so each type's puts leave in
    /// the order of their numbers whichever threads post at once.
    outgoing: Mutex<Outgoing>,
    net: Mutex<Net>,
    /// Kind declarations this process made, each a liveliness token (dropping one undeclares it).
    kind_tokens: Mutex<FxHashMap<String, LivelinessToken>>,
    /// What this process serves and listens to; dropping them undeclares them.
    serving: Mutex<Vec<Serving>>,
    /// The robot's team, when it is in one.
    team: Option<team::TeamPart>,
}

#[allow(dead_code)] // held only to keep the declarations alive
enum Serving {
    Subscriber(Subscriber<()>),
    Queryable(Queryable<()>),
    Token(LivelinessToken),
}

#[derive(Default)]
struct Outgoing {
    seq: FxHashMap<String, u64>,
    publishers: FxHashMap<String, Publisher<'static>>,
}

/// What this process knows of the others.
#[derive(Default)]
struct Net {
    /// Processes whose liveliness token is seen.
    alive: FxHashSet<String>,
    /// Each type's current posting, with the process that posted it (none for a bare Zenoh
    /// put): whom it turns stale with, and what a late joiner is answered.
    current: FxHashMap<String, (Meta, Value)>,
    /// The last number seen from each (process, type).
    last: FxHashMap<(String, String), u64>,
    /// Each signal type's claims to consume it: (since when, by which process). The earliest
    /// living claim consumes.
    claims: FxHashMap<String, BTreeSet<(u64, String)>>,
    /// Kinds declared in this process, which a declaration elsewhere does not override.
    declared_here: FxHashMap<String, Kind>,
    /// Types whose current value's poster is gone.
    stale: FxHashSet<String>,
    /// This process's own recent postings of each data type, what it answers a late joiner
    /// with.
    own_history: FxHashMap<String, VecDeque<(Meta, Value)>>,
    /// Modules registered in this process.
    registered: Vec<WireDecl>,
}

impl Net {
    fn consumer(&self, ty: &str) -> Option<&str> {
        self.claims
            .get(ty)
            .and_then(|c| c.first())
            .map(|(_, p)| p.as_str())
    }
}

impl Peer {
    async fn start(
        session: zenoh::Session,
        keys: Keys,
        limit: Limit,
        team: Option<Team>,
    ) -> Result<Arc<Peer>, NetworkError> {
        let peer = Arc::new(Peer {
            board: LocalBoard::new(),
            me: session.zid().to_string(),
            keys,
            limit,
            session: session.clone(),
            outgoing: Mutex::default(),
            net: Mutex::default(),
            kind_tokens: Mutex::default(),
            serving: Mutex::default(),
            team: team.map(team::TeamPart::new),
        });
        let weak = Arc::downgrade(&peer);
        let postings = {
            let weak = weak.clone();
            session
                .declare_subscriber(peer.keys.every_type())
                .allowed_origin(Locality::Remote)
                .callback(move |sample| {
                    if let Some(peer) = weak.upgrade() {
                        peer.on_sample(&sample);
                    }
                })
                .await
                .map_err(|e| {
                    NetworkError::zenoh(
                        format!("cannot subscribe to {}", peer.keys.every_type()),
                        e,
                    )
                })?
        };
        let registrations = {
            let weak = weak.clone();
            session
                .declare_subscriber(peer.keys.registry())
                .allowed_origin(Locality::Remote)
                .callback(move |sample| {
                    if let Some(peer) = weak.upgrade() {
                        peer.on_registration(&sample.payload().to_bytes());
                    }
                })
                .await
                .map_err(|e| {
                    NetworkError::zenoh(format!("cannot subscribe to {}", peer.keys.registry()), e)
                })?
        };
        let mut serving = vec![
            Serving::Subscriber(postings),
            Serving::Subscriber(registrations),
        ];
        serving.extend(catchup::serve(&peer, &weak).await?);
        serving.extend(members::watch(&peer, &weak).await?);
        serving.extend(team::serve(&peer, &weak).await?);
        *peer.serving.lock() = serving;
        Ok(peer)
    }

    /// A posting from another process (or a bare Zenoh put).
    fn on_sample(&self, sample: &zenoh::sample::Sample) {
        let Some(ty) = self.keys.type_of(sample.key_expr().as_str()) else {
            return;
        };
        let meta = match sample.attachment().map(|a| Meta::decode(&a.to_bytes())) {
            None => Meta::default(),
            Some(Ok(meta)) => meta,
            Some(Err(why)) => {
                tracing::warn!(key = %sample.key_expr(), "{why}; the posting is taken without it");
                Meta::default()
            }
        };
        self.receive(ty, decode_value(&sample.payload().to_bytes()), meta);
    }

    fn on_registration(&self, bytes: &[u8]) {
        match serde_json::from_slice::<WireDecl>(bytes) {
            Ok(decl) => self.board.register(decl.into()),
            Err(e) => tracing::warn!(error = %e, "unreadable module declaration ignored"),
        }
    }

    /// Puts a posting from elsewhere on this replica, unless this process has seen its number
    /// from its poster already.
    fn receive(&self, ty: &str, value: Value, meta: Meta) {
        let mut net = self.net.lock();
        if let (Some(process), Some(seq)) = (&meta.process, meta.seq) {
            let last = net
                .last
                .entry((process.clone(), ty.to_string()))
                .or_insert(0);
            if seq <= *last {
                return;
            }
            *last = seq;
        }
        if let Some(kind) = meta.kind.map(Kind::from) {
            if kind != Kind::State
                && self.board.kind(ty) == Kind::State
                && !net.declared_here.contains_key(ty)
            {
                self.board.declare_observed(ty, kind);
            }
        }
        let consumable =
            self.board.kind(ty) != Kind::Signal || net.consumer(ty) == Some(self.me.as_str());
        net.current
            .insert(ty.to_string(), (meta.clone(), value.clone()));
        let was_stale = if meta.stale {
            !net.stale.insert(ty.to_string())
        } else {
            net.stale.remove(ty)
        };
        let time = meta.time().unwrap_or_else(unix_now);
        let module = meta.module.as_deref().unwrap_or(ANONYMOUS);
        // A robot's team hears what any process of its board posts (its vision, a sensor in
        // Python), as it hears the robot's own postings; not a value whose poster is gone.
        let for_the_team = (!meta.stale).then(|| value.clone());
        self.board
            .post_at(module, ty, value, meta.priority, time, consumable);
        if meta.stale != was_stale {
            let by = match (&meta.process, meta.stale) {
                (Some(process), true) => gone_module(process),
                _ => module.to_string(),
            };
            self.mark_stale(ty, meta.stale, &by);
        }
        drop(net);
        if let Some(value) = for_the_team {
            self.share(ty, &value, &meta);
        }
    }

    /// Says on this replica (only) whether `ty`'s current value's poster is gone.
    fn mark_stale(&self, ty: &str, stale: bool, module: &str) {
        self.board
            .post_at(module, &stale_type(ty), stale.into(), 0, unix_now(), true);
    }

    fn publisher<'o>(&self, out: &'o mut Outgoing, ty: &str) -> Option<&'o Publisher<'static>> {
        if !out.publishers.contains_key(ty) {
            let key = self.keys.ty(ty);
            let declared = self
                .session
                .declare_publisher(key.clone())
                .congestion_control(CongestionControl::Block)
                .express(false)
                .encoding(Encoding::APPLICATION_JSON)
                .allowed_destination(Locality::Remote)
                .wait();
            match declared {
                Ok(publisher) => {
                    out.publishers.insert(ty.to_string(), publisher);
                }
                Err(e) => {
                    tracing::error!(key, error = %e, "cannot publish this type; kept in this process");
                    return None;
                }
            }
        }
        out.publishers.get(ty)
    }

    fn put(&self, publisher: &Publisher<'static>, value: &Value, meta: &Meta) {
        let payload = encode_value(value);
        let attachment = meta.encode();
        let size = payload.len() + attachment.len();
        if let Some(limit) = self.limit.filter(|l| size > *l) {
            tracing::error!(
                key = %publisher.key_expr(),
                bytes = size,
                limit,
                "posting too large for the low-latency transport, not sent (run every process without --low-latency)"
            );
            return;
        }
        if let Err(e) = publisher.put(payload).attachment(attachment).wait() {
            tracing::warn!(key = %publisher.key_expr(), error = %e, "posting not sent");
        }
    }
}

/// What every process serves from its own replica: reads, waits, subscriptions, the registry
/// and the counters.
impl Transport for Peer {
    fn declare(&self, ty: &str, kind: Kind) {
        let since = nanos(unix_now());
        {
            let mut net = self.net.lock();
            net.declared_here.insert(ty.to_string(), kind);
            let mine = (since, self.me.clone());
            let claims = net.claims.entry(ty.to_string()).or_default();
            claims.retain(|(_, p)| *p != self.me);
            if kind == Kind::Signal {
                claims.insert(mine);
            }
            // Only the consumer takes a command posted before the type was a signal.
            if kind != Kind::Signal || net.consumer(ty) == Some(self.me.as_str()) {
                self.board.declare(ty, kind);
            } else {
                self.board.declare_observed(ty, kind);
            }
        }
        if let Some(why) = type_key_error(ty) {
            tracing::error!(ty, "cannot share this type's kind: {why}");
            return;
        }
        let key = self.keys.kind(ty, kind.into(), since, &self.me);
        match self.session.liveliness().declare_token(key.clone()).wait() {
            Ok(token) => {
                self.kind_tokens.lock().insert(ty.to_string(), token);
            }
            Err(e) => tracing::error!(key, error = %e, "cannot share this type's kind"),
        }
    }

    fn kind(&self, ty: &str) -> Kind {
        self.board.kind(ty)
    }

    fn post_ranked(&self, module: &str, ty: &str, value: Value, priority: u32) -> Message {
        let time = unix_now();
        let kind = self.board.kind(ty);
        let mut out = self.outgoing.lock();
        let seq = {
            let seq = out.seq.entry(ty.to_string()).or_insert(0);
            *seq += 1;
            *seq
        };
        let meta = Meta {
            module: Some(module.to_string()),
            seq: Some(seq),
            time_ns: Some(nanos(time)),
            priority,
            kind: Some(kind.into()),
            process: Some(self.me.clone()),
            stale: false,
        };
        let message = {
            let mut net = self.net.lock();
            let consumable = kind != Kind::Signal || net.consumer(ty) == Some(self.me.as_str());
            net.current
                .insert(ty.to_string(), (meta.clone(), value.clone()));
            let fresh = net.stale.remove(ty);
            if kind == Kind::Data {
                let own = net.own_history.entry(ty.to_string()).or_default();
                own.push_back((meta.clone(), value.clone()));
                while own.len() > OWN_HISTORY {
                    own.pop_front();
                }
            }
            let message = self
                .board
                .post_at(module, ty, value, priority, time, consumable);
            if fresh {
                self.mark_stale(ty, false, module);
            }
            message
        };
        match type_key_error(ty) {
            Some(why) => tracing::error!(ty, "posting kept in this process: {why}"),
            None => {
                if let Some(publisher) = self.publisher(&mut out, ty) {
                    self.put(publisher, &message.value, &meta);
                }
            }
        }
        self.share(ty, &message.value, &meta);
        message
    }

    fn latest(&self, ty: &str) -> Option<Message> {
        self.board.latest(ty)
    }

    fn wait_for(&self, ty: &str, after: u64, timeout: Duration) -> BoxFuture<'_, Option<Message>> {
        self.board.wait_for(ty, after, timeout)
    }

    fn nearest(&self, ty: &str, time: Duration, side: std::cmp::Ordering) -> Option<Message> {
        self.board.nearest(ty, time, side)
    }

    fn subscribe(&self, pattern: Pattern) -> Subscription {
        self.board.subscribe(pattern)
    }

    fn register(&self, decl: ModuleDecl) {
        let wire = WireDecl::from(&decl);
        self.board.register(decl);
        let bytes = serde_json::to_vec(&wire).unwrap_or_default();
        {
            let mut net = self.net.lock();
            net.registered.retain(|d| d.name != wire.name);
            net.registered.push(wire);
        }
        let key = self.keys.registry();
        if let Err(e) = self
            .session
            .put(key.clone(), bytes)
            .congestion_control(CongestionControl::Block)
            .allowed_destination(Locality::Remote)
            .wait()
        {
            tracing::warn!(key, error = %e, "module declaration not sent");
        }
    }

    fn registry(&self) -> Registry {
        self.board.registry()
    }

    fn is_answered(&self, atom: &str) -> bool {
        self.board.is_answered(atom)
    }

    fn stats(&self) -> Stats {
        self.board.stats()
    }

    fn count_query(&self, timed_out: bool, unanswerable: bool) {
        self.board.count_query(timed_out, unanswerable)
    }

    /// The Unix epoch's clock, which every process of the board shares (on one machine exactly;
    /// across machines as well as their clocks agree).
    fn now(&self) -> Duration {
        unix_now()
    }

    fn snapshot(&self) -> proclaim_board::Snapshot {
        self.board.snapshot()
    }

    /// A process taken up from a checkpoint joins as any process does: what is current is what
    /// the others hold (caught up as it joined). Its replica numbers on after the checkpoint's,
    /// so its machines tell news by the numbers they saw.
    fn restore(&self, image: &proclaim_board::BoardImage) -> Result<Restored, String> {
        self.board.number_after(image.seq);
        Ok(Restored::Numbering)
    }
}

/// A weak handle a Zenoh callback holds, so the board ends when its last handle is dropped.
type PeerRef = Weak<Peer>;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_marks_name_the_type_and_the_gone_process() {
        assert_eq!(stale_type("ballNear"), "ballNearStale");
        assert_eq!(gone_module("0123456789abcdef"), "gone 01234567");
        assert_eq!(gone_module("ab"), "gone ab");
    }

    #[test]
    fn nanoseconds_saturate() {
        assert_eq!(nanos(Duration::from_micros(3)), 3_000);
        assert_eq!(nanos(Duration::MAX), u64::MAX);
    }
}
