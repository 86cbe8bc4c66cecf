//! The in-process transport: one lock around the message table, a `Notify` per type for waiters
//! and a bounded queue per subscriber. The default, and what every test runs against.

use crate::image::{nanos, BoardImage};
use crate::message::{Kind, Message};
use crate::pattern::Pattern;
use crate::registry::{ModuleDecl, Registry};
use crate::snapshot::{Slot, Snapshot, Table};
use crate::stats::Stats;
use crate::subscribers::Subscribers;
use crate::transport::{BoxFuture, Restored, Subscription, Transport};
use crate::value::Value;
use parking_lot::{Mutex, MutexGuard};
use rustc_hash::FxHashMap;
use std::cmp::Ordering;
use std::sync::atomic::{AtomicU64, Ordering as AtomicOrdering};
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::{mpsc, Notify};
use tokio::time::Instant;

/// How much history a data type keeps, and how many unread signals may wait.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Retention {
    pub count: usize,
    pub age: Duration,
    /// Unread signals of one type kept before the oldest is dropped (and counted).
    pub signals: usize,
    /// A subscriber's queue; a full queue drops (and counts) what it cannot take.
    pub subscriber_queue: usize,
}

impl Default for Retention {
    fn default() -> Retention {
        Retention {
            count: 256,
            age: Duration::from_secs(60),
            signals: 1024,
            subscriber_queue: 4096,
        }
    }
}

#[derive(Default)]
struct Inner {
    seq: u64,
    /// Persistent, so a snapshot is a reference count (`snapshot.rs`).
    table: Table,
    /// Waiters of each type, woken by every posting of it.
    notifies: FxHashMap<Arc<str>, Arc<Notify>>,
    modules: FxHashMap<String, Arc<str>>,
    subscribers: Subscribers,
    registry: Registry,
    stats: Stats,
}

impl Inner {
    /// The module's name, shared by all its messages.
    fn module_name(&mut self, module: &str) -> Arc<str> {
        match self.modules.get(module) {
            Some(m) => m.clone(),
            None => {
                let m: Arc<str> = Arc::from(module);
                self.modules.insert(module.to_string(), m.clone());
                m
            }
        }
    }

    /// The type's slot, made a state if it is new.
    fn slot(&mut self, ty: &str) -> &mut Slot {
        if !self.table.contains_key(ty) {
            self.table.insert(Arc::from(ty), Slot::new(Kind::State));
        }
        self.table.get_mut(ty).expect("inserted above")
    }

    /// The type's name as the table shares it.
    fn name(&mut self, ty: &str) -> Arc<str> {
        self.slot(ty);
        let (name, _) = self.table.get_key_value(ty).expect("made above");
        name.clone()
    }

    fn notify(&mut self, ty: &Arc<str>) -> Arc<Notify> {
        self.notifies.entry(ty.clone()).or_default().clone()
    }
}

pub struct LocalBoard {
    inner: Mutex<Inner>,
    start: Instant,
    /// Nanoseconds added to the time since `start`: a board restored from a checkpoint goes on
    /// with the clock it had.
    shift: AtomicU64,
    retention: Retention,
}

impl LocalBoard {
    /// Numbers what comes next after `seq` (a replica of a shared board taken up from a
    /// checkpoint, whose machines tell news by the numbers they saw).
    pub fn number_after(&self, seq: u64) {
        let mut inner = self.lock();
        inner.seq = inner.seq.max(seq);
    }

    pub fn new() -> LocalBoard {
        LocalBoard::with_retention(Retention::default())
    }

    pub fn with_retention(retention: Retention) -> LocalBoard {
        LocalBoard {
            inner: Mutex::new(Inner::default()),
            start: Instant::now(),
            shift: AtomicU64::new(0),
            retention,
        }
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        // parking_lot's lock does not poison: a panic elsewhere leaves the table usable, and
        // every update is a whole assignment, so it is also consistent.
        self.inner.lock()
    }

    /// Posts with a new sequence number. `consumable`: whether a signal may be taken here (a
    /// networked board keeps a signal consumable only in the process that owns its type; the
    /// others observe it).
    pub fn post_as(
        &self,
        module: &str,
        ty: &str,
        value: Value,
        priority: u32,
        consumable: bool,
    ) -> Message {
        self.post_at(module, ty, value, priority, self.now(), consumable)
    }

    /// Posts with a new sequence number of this board and the time the poster gave it (a
    /// networked board's posting from another process, on the clock every process shares).
    pub fn post_at(
        &self,
        module: &str,
        ty: &str,
        value: Value,
        priority: u32,
        time: Duration,
        consumable: bool,
    ) -> Message {
        let mut inner = self.lock();
        inner.seq += 1;
        let seq = inner.seq;
        let module = inner.module_name(module);
        let ty_name = inner.name(ty);
        let message = Message {
            ty: ty_name,
            value,
            module,
            seq,
            time,
            priority,
        };
        self.insert(inner, message.clone(), consumable);
        message
    }

    /// Takes a message sequenced elsewhere (a recording played back): kept with its own
    /// sequence number and time. One already seen (by sequence number) is ignored, except that a
    /// signal handed over to this board as its consumer becomes consumable.
    pub fn apply(&self, message: Message, consumable: bool) {
        let mut inner = self.lock();
        if message.seq <= inner.seq {
            let ty = inner.name(&message.ty);
            let slot = inner.slot(&ty);
            if consumable
                && slot.kind == Kind::Signal
                && !slot.signals.iter().any(|m| m.seq == message.seq)
            {
                slot.signals.push_back(message);
                let notify = inner.notify(&ty);
                drop(inner);
                notify.notify_waiters();
            }
            return;
        }
        inner.seq = message.seq;
        self.insert(inner, message, consumable);
    }

    /// Declares a type's kind as another process did, without taking a pending state value as
    /// a signal of this process.
    pub fn declare_observed(&self, ty: &str, kind: Kind) {
        self.lock().slot(ty).kind = kind;
    }

    /// Stores a message and tells waiters and subscribers; takes the lock and releases it.
    fn insert(&self, mut inner: MutexGuard<'_, Inner>, message: Message, consumable: bool) {
        let retention = self.retention;
        inner.stats.posts += 1;
        let (ty, seq, time) = (message.ty.clone(), message.seq, message.time);
        let mut dropped = 0;
        let slot = inner.slot(&ty);
        slot.posts += 1;
        match slot.kind {
            Kind::State => slot.latest = Some(message.clone()),
            Kind::Signal => {
                slot.last_signal = Some(message.clone());
                if consumable {
                    slot.signals.push_back(message.clone());
                    if slot.signals.len() > retention.signals {
                        slot.signals.pop_front();
                        dropped += 1;
                    }
                }
            }
            Kind::Data => {
                slot.history.push_back(message.clone());
                while slot.history.len() > retention.count
                    || slot
                        .history
                        .front()
                        .is_some_and(|m| time.saturating_sub(m.time) > retention.age)
                {
                    slot.history.pop_front();
                }
            }
        }
        let notify = inner.notify(&ty);
        dropped += inner.subscribers.deliver(&message);
        inner.stats.drops += dropped;
        drop(inner);
        notify.notify_waiters();
        tracing::trace!(ty = &*ty, seq, "post");
        if dropped > 0 {
            tracing::debug!(ty = &*ty, dropped, "messages dropped");
        }
    }

    /// The first message of `ty` after `after`, taking it if a signal.
    fn find_after(inner: &mut Inner, ty: &str, after: u64) -> Option<Message> {
        let slot = inner.table.get_mut(ty)?;
        match slot.kind {
            Kind::State => slot.latest.clone().filter(|m| m.seq > after),
            Kind::Data => slot.history.iter().find(|m| m.seq > after).cloned(),
            Kind::Signal => {
                let at = slot.signals.iter().position(|m| m.seq > after)?;
                Some(slot.signals.remove(at))
            }
        }
    }
}

impl Default for LocalBoard {
    fn default() -> LocalBoard {
        LocalBoard::new()
    }
}

impl Transport for LocalBoard {
    fn declare(&self, ty: &str, kind: Kind) {
        let mut inner = self.lock();
        let slot = inner.slot(ty);
        // A command posted before its reader declared the type a signal (a parent starting a
        // sub-machine that is still loading) is kept as one unread signal, not lost.
        if kind == Kind::Signal && slot.kind != Kind::Signal {
            if let Some(pending) = slot.latest.take() {
                slot.last_signal = Some(pending.clone());
                slot.signals.push_back(pending);
            }
        }
        slot.kind = kind;
    }

    fn kind(&self, ty: &str) -> Kind {
        self.lock().table.get(ty).map_or(Kind::State, |s| s.kind)
    }

    fn post_ranked(&self, module: &str, ty: &str, value: Value, priority: u32) -> Message {
        self.post_as(module, ty, value, priority, true)
    }

    fn latest(&self, ty: &str) -> Option<Message> {
        let mut inner = self.lock();
        let slot = inner.table.get_mut(ty)?;
        match slot.kind {
            Kind::State => slot.latest.clone(),
            Kind::Data => slot.history.back().cloned(),
            Kind::Signal => slot.signals.pop_front(),
        }
    }

    fn wait_for(&self, ty: &str, after: u64, timeout: Duration) -> BoxFuture<'_, Option<Message>> {
        let ty = ty.to_string();
        Box::pin(async move {
            let deadline = Instant::now() + timeout;
            loop {
                let notify = {
                    let mut inner = self.lock();
                    let name = inner.name(&ty);
                    inner.notify(&name)
                };
                let notified = notify.notified();
                tokio::pin!(notified);
                // Registered before looking, so a post between the look and the wait still
                // wakes this waiter.
                notified.as_mut().enable();
                if let Some(m) = LocalBoard::find_after(&mut self.lock(), &ty, after) {
                    return Some(m);
                }
                if tokio::time::timeout_at(deadline, notified).await.is_err() {
                    return LocalBoard::find_after(&mut self.lock(), &ty, after);
                }
            }
        })
    }

    fn nearest(&self, ty: &str, time: Duration, side: Ordering) -> Option<Message> {
        let inner = self.lock();
        let slot = inner.table.get(ty)?;
        let candidates: Box<dyn Iterator<Item = &Message>> = match slot.kind {
            Kind::Data => Box::new(slot.history.iter()),
            Kind::State => Box::new(slot.latest.iter()),
            Kind::Signal => Box::new(slot.signals.iter()),
        };
        candidates
            .filter(|m| match side {
                Ordering::Greater => m.time >= time,
                Ordering::Less => m.time <= time,
                Ordering::Equal => true,
            })
            .min_by_key(|m| m.time.abs_diff(time))
            .cloned()
    }

    fn subscribe(&self, pattern: Pattern) -> Subscription {
        let (tx, rx) = mpsc::channel(self.retention.subscriber_queue);
        self.lock().subscribers.add(pattern, tx);
        Subscription::new(rx)
    }

    fn register(&self, decl: ModuleDecl) {
        self.lock().registry.register(decl);
    }

    fn registry(&self) -> Registry {
        self.lock().registry.clone()
    }

    fn is_answered(&self, atom: &str) -> bool {
        self.lock().registry.answers(atom)
    }

    fn stats(&self) -> Stats {
        let inner = self.lock();
        Stats {
            subscribers: inner.subscribers.len(),
            ..inner.stats
        }
    }

    fn count_query(&self, timed_out: bool, unanswerable: bool) {
        let mut inner = self.lock();
        inner.stats.queries += 1;
        inner.stats.timeouts += timed_out as u64;
        inner.stats.unanswerable += unanswerable as u64;
    }

    fn now(&self) -> Duration {
        Instant::now().saturating_duration_since(self.start)
            + Duration::from_nanos(self.shift.load(AtomicOrdering::Relaxed))
    }

    fn restore(&self, image: &BoardImage) -> Result<Restored, String> {
        let snapshot = image.snapshot();
        let mut inner = self.lock();
        if inner.seq > 0 {
            return Err(format!(
                "the board already holds {} messages: a checkpoint is restored before anything is posted",
                inner.seq
            ));
        }
        inner.seq = snapshot.seq;
        inner.table = snapshot.table;
        inner.stats = image.stats();
        let since = Instant::now().saturating_duration_since(self.start);
        let shift = Duration::from_nanos(image.time_ns).saturating_sub(since);
        self.shift.store(nanos(shift), AtomicOrdering::Relaxed);
        Ok(Restored::Whole)
    }

    /// Consistent (taken under the lock) and read without it.
    fn snapshot(&self) -> Snapshot {
        let time = self.now();
        let inner = self.lock();
        Snapshot {
            table: inner.table.clone(),
            seq: inner.seq,
            time,
        }
    }
}
