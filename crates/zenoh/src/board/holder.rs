//! The process that holds the board: it numbers every posting and sends it to every replica,
//! serves requests, snapshots for joining processes, and pings.

use super::*;
use crate::error::NetworkError;

/// The process that holds the board.
pub(super) struct Holder {
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
    pub(super) async fn start(
        session: zenoh::Session,
        keys: Keys,
        limit: Limit,
    ) -> Result<Arc<Holder>, NetworkError> {
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
            .map_err(|e| NetworkError::zenoh(format!("cannot serve {}", keys.snapshot), e))?;
        let pings = crate::probe::answer(&session, &keys.ping).await?;
        let _ = holder.serving.set((requests, snapshots, pings));
        Ok(holder)
    }

    pub(super) fn handle(&self, up: Up) {
        match up {
            Up::Post {
                module,
                ty,
                value,
                priority,
            } => {
                self.post_here(&module, &ty, value.into(), priority);
            }
            Up::Declare { ty, kind, process } => self.declare_for(&ty, kind.into(), &process),
            Up::Register(decl) => self.register(decl.into()),
        }
    }

    pub(super) fn owner(&self, ty: &str) -> Option<String> {
        self.owners.lock().get(ty).cloned()
    }

    pub(super) fn post_here(&self, module: &str, ty: &str, value: Value, priority: u32) -> Message {
        let signal = self.core.kind(ty) == Kind::Signal;
        let owner = if signal { self.owner(ty) } else { None };
        // Unowned signals wait here until a process declares the type.
        let consumable = owner.as_ref().is_none_or(|o| *o == self.id);
        let down = self.down.lock();
        let message = self.core.post_as(module, ty, value, priority, consumable);
        down.send(Down::Posted {
            message: WireMessage::from(&message),
            owner,
        });
        message
    }

    pub(super) fn declare_for(&self, ty: &str, kind: Kind, process: &str) {
        let down = self.down.lock();
        let was = self.core.kind(ty);
        if kind == Kind::Signal {
            let owner = {
                self.owners
                    .lock()
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

    pub(super) fn snapshot(&self) -> Snapshot {
        let (kinds, messages) = self.core.snapshot().contents();
        let owners = self.owners.lock();
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

    fn post_ranked(&self, module: &str, ty: &str, value: Value, priority: u32) -> Message {
        self.post_here(module, ty, value, priority)
    }

    fn register(&self, decl: ModuleDecl) {
        let wire = WireDecl::from(&decl);
        let down = self.down.lock();
        self.core.register(decl);
        down.send(Down::Registered(wire));
    }

    fn now(&self) -> Duration {
        self.core.now()
    }
}
