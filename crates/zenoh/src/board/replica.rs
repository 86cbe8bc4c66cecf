//! A process that joined the board: a replica kept in step by the holder's messages, starting
//! from the holder's snapshot.

use super::*;
use crate::error::NetworkError;

/// A process that joined the board: a replica kept in step by the holder's messages.
pub(super) struct Replica {
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
    pub(super) async fn start(
        session: zenoh::Session,
        keys: Keys,
        endpoint: &str,
        limit: Limit,
    ) -> Result<Arc<Replica>, NetworkError> {
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
        let mut early = self.early.lock();
        for down in early.take().unwrap_or_default() {
            self.apply(down);
        }
    }

    fn receive(&self, down: Down) {
        let mut early = self.early.lock();
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
) -> Result<Snapshot, NetworkError> {
    let deadline = tokio::time::Instant::now() + Duration::from_secs(5);
    loop {
        if let Ok(replies) = session.get(&keys.snapshot).await {
            if let Ok(reply) = replies.recv_async().await {
                return match reply.result() {
                    Ok(sample) => {
                        serde_json::from_slice(&sample.payload().to_bytes()).map_err(|e| {
                            NetworkError::Refused {
                                endpoint: endpoint.to_string(),
                                why: format!("it sent an unreadable snapshot ({e})"),
                            }
                        })
                    }
                    Err(refused) => Err(NetworkError::Refused {
                        endpoint: endpoint.to_string(),
                        why: String::from_utf8_lossy(&refused.payload().to_bytes()).into_owned(),
                    }),
                };
            }
        }
        if tokio::time::Instant::now() >= deadline {
            return Err(NetworkError::NoBoard {
                board: None,
                endpoint: endpoint.to_string(),
            });
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
    fn post_ranked(&self, module: &str, ty: &str, value: Value, priority: u32) -> Message {
        // Read before sending: the answer to a query can be back before `send` returns.
        let seen = self.mirror.last_seq();
        self.up.send(Up::Post {
            module: module.to_string(),
            ty: ty.to_string(),
            value: WireValue::from(&value),
            priority,
        });
        Message {
            ty: Arc::from(ty),
            value,
            module: Arc::from(module),
            seq: seen,
            time: self.now(),
            priority,
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
