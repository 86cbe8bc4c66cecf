//! The in-process transport: one lock around the message table, a `Notify` per type for waiters
//! and a bounded queue per subscriber. The default, and what every test runs against.

use crate::message::{Kind, Message};
use crate::pattern::Pattern;
use crate::registry::{ModuleDecl, Registry};
use crate::transport::{BoxFuture, Stats, Subscription, Transport};
use crate::value::Value;
use rustc_hash::FxHashMap;
use std::cmp::Ordering;
use std::collections::VecDeque;
use std::sync::{Arc, Mutex, MutexGuard};
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

struct Entry {
    /// The type's name, shared by all its messages.
    name: Arc<str>,
    kind: Kind,
    latest: Option<Message>,
    history: VecDeque<Message>,
    signals: VecDeque<Message>,
    notify: Arc<Notify>,
}

impl Entry {
    fn new(name: Arc<str>, kind: Kind) -> Entry {
        Entry {
            name,
            kind,
            latest: None,
            history: VecDeque::new(),
            signals: VecDeque::new(),
            notify: Arc::new(Notify::new()),
        }
    }
}

struct Subscriber {
    pattern: Pattern,
    tx: mpsc::Sender<Message>,
}

#[derive(Default)]
struct Inner {
    seq: u64,
    types: FxHashMap<Arc<str>, Entry>,
    modules: FxHashMap<String, Arc<str>>,
    subscribers: Vec<Subscriber>,
    /// Subscriber count at which closed subscriptions are next pruned.
    prune_at: usize,
    registry: Registry,
    stats: Stats,
}

impl Inner {
    fn entry(&mut self, ty: &str) -> &mut Entry {
        if !self.types.contains_key(ty) {
            let name: Arc<str> = Arc::from(ty);
            self.types
                .insert(name.clone(), Entry::new(name, Kind::State));
        }
        self.types.get_mut(ty).expect("inserted above")
    }
}

pub struct LocalBoard {
    inner: Mutex<Inner>,
    start: Instant,
    retention: Retention,
}

impl LocalBoard {
    pub fn new() -> LocalBoard {
        LocalBoard::with_retention(Retention::default())
    }

    pub fn with_retention(retention: Retention) -> LocalBoard {
        LocalBoard {
            inner: Mutex::new(Inner::default()),
            start: Instant::now(),
            retention,
        }
    }

    fn lock(&self) -> MutexGuard<'_, Inner> {
        // A panic while holding the lock leaves the table consistent (every update is a whole
        // assignment), so a poisoned lock is still usable.
        self.inner.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The first message of `ty` after `after`, taking it if a signal.
    fn find_after(inner: &mut Inner, ty: &str, after: u64) -> Option<Message> {
        let entry = inner.types.get_mut(ty)?;
        match entry.kind {
            Kind::State => entry.latest.clone().filter(|m| m.seq > after),
            Kind::Data => entry.history.iter().find(|m| m.seq > after).cloned(),
            Kind::Signal => {
                let at = entry.signals.iter().position(|m| m.seq > after)?;
                entry.signals.remove(at)
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
        let entry = inner.entry(ty);
        // A command posted before its reader declared the type a signal (a parent starting a
        // sub-machine that is still loading) is kept as one unread signal, not lost.
        if kind == Kind::Signal && entry.kind != Kind::Signal {
            if let Some(pending) = entry.latest.take() {
                entry.signals.push_back(pending);
            }
        }
        entry.kind = kind;
    }

    fn kind(&self, ty: &str) -> Kind {
        self.lock().types.get(ty).map_or(Kind::State, |e| e.kind)
    }

    fn post(&self, module: &str, ty: &str, value: Value) -> Message {
        let time = self.now();
        let retention = self.retention;
        let mut inner = self.lock();
        inner.seq += 1;
        inner.stats.posts += 1;
        let module = match inner.modules.get(module) {
            Some(m) => m.clone(),
            None => {
                let m: Arc<str> = Arc::from(module);
                inner.modules.insert(module.to_string(), m.clone());
                m
            }
        };
        let seq = inner.seq;
        let mut dropped = 0;
        let entry = inner.entry(ty);
        let message = Message {
            ty: entry.name.clone(),
            value,
            module,
            seq,
            time,
        };
        match entry.kind {
            Kind::State => entry.latest = Some(message.clone()),
            Kind::Signal => {
                entry.signals.push_back(message.clone());
                if entry.signals.len() > retention.signals {
                    entry.signals.pop_front();
                    dropped += 1;
                }
            }
            Kind::Data => {
                entry.history.push_back(message.clone());
                while entry.history.len() > retention.count
                    || entry
                        .history
                        .front()
                        .is_some_and(|m| time.saturating_sub(m.time) > retention.age)
                {
                    entry.history.pop_front();
                }
            }
        }
        let notify = entry.notify.clone();
        inner.subscribers.retain(|s| {
            if !s.pattern.matches(ty) {
                return true;
            }
            match s.tx.try_send(message.clone()) {
                Ok(()) => true,
                Err(mpsc::error::TrySendError::Full(_)) => {
                    dropped += 1;
                    true
                }
                Err(mpsc::error::TrySendError::Closed(_)) => false,
            }
        });
        inner.stats.drops += dropped;
        drop(inner);
        notify.notify_waiters();
        tracing::trace!(ty, seq, "post");
        if dropped > 0 {
            tracing::debug!(ty, dropped, "messages dropped");
        }
        message
    }

    fn latest(&self, ty: &str) -> Option<Message> {
        let mut inner = self.lock();
        let entry = inner.types.get_mut(ty)?;
        match entry.kind {
            Kind::State => entry.latest.clone(),
            Kind::Data => entry.history.back().cloned(),
            Kind::Signal => entry.signals.pop_front(),
        }
    }

    fn wait_for(&self, ty: &str, after: u64, timeout: Duration) -> BoxFuture<'_, Option<Message>> {
        let ty = ty.to_string();
        Box::pin(async move {
            let deadline = Instant::now() + timeout;
            loop {
                let notify = self.lock().entry(&ty).notify.clone();
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
        let entry = inner.types.get(ty)?;
        let candidates: Box<dyn Iterator<Item = &Message>> = match entry.kind {
            Kind::Data => Box::new(entry.history.iter()),
            Kind::State => Box::new(entry.latest.iter()),
            Kind::Signal => Box::new(entry.signals.iter()),
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
        let mut inner = self.lock();
        // Dropped subscriptions are otherwise removed only when a message for them is posted;
        // pruning whenever the list doubles keeps it bounded at amortised constant cost.
        if inner.subscribers.len() >= inner.prune_at {
            inner.subscribers.retain(|s| !s.tx.is_closed());
            inner.prune_at = (inner.subscribers.len() * 2).max(64);
        }
        inner.subscribers.push(Subscriber { pattern, tx });
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
    }
}
