//! A late joiner's catch-up: every process answers a get on `proclaim/<board>/*` (or one type's
//! key) with the values it owns (a state whose current value it posted, its recent postings of
//! a data type; never a signal, which its consumer took or holds) and, as stale, the states
//! whose poster is gone; and a get on `@registry` with the modules registered in it. The joiner
//! applies the answers oldest first, each poster's numbers still deciding what is new. Also the
//! ping every process answers.

use super::*;
use zenoh::query::{ConsolidationMode, QueryTarget};

/// How long a catch-up waits for the processes' answers.
const ANSWER_PATIENCE: Duration = Duration::from_secs(5);

pub(super) async fn serve(peer: &Arc<Peer>, weak: &PeerRef) -> Result<Vec<Serving>, NetworkError> {
    let session = &peer.session;
    let values = {
        let weak = weak.clone();
        let key = peer.keys.every_type();
        session
            .declare_queryable(key.clone())
            .complete(false)
            .allowed_origin(Locality::Remote)
            .callback(move |query| {
                if let Some(peer) = weak.upgrade() {
                    peer.answer_values(query);
                }
            })
            .await
            .map_err(|e| NetworkError::zenoh(format!("cannot answer on {key}"), e))?
    };
    let registry = {
        let weak = weak.clone();
        let key = peer.keys.registry();
        session
            .declare_queryable(key.clone())
            .allowed_origin(Locality::Remote)
            .callback(move |query| {
                let Some(peer) = weak.upgrade() else { return };
                let registered = peer.net.lock().registered.clone();
                for decl in registered {
                    let bytes = serde_json::to_vec(&decl).unwrap_or_default();
                    if let Err(e) = query.reply(query.key_expr().clone(), bytes).wait() {
                        tracing::debug!(error = %e, "module declaration not sent to a joiner");
                    }
                }
            })
            .await
            .map_err(|e| NetworkError::zenoh(format!("cannot answer on {key}"), e))?
    };
    let ping = crate::probe::answer(session, &peer.keys.ping()).await?;
    Ok(vec![
        Serving::Queryable(values),
        Serving::Queryable(registry),
        Serving::Queryable(ping),
    ])
}

impl Peer {
    /// Answers a get with what this process owns of the types it asks for. `?from=PROCESS`
    /// asks one process only.
    fn answer_values(&self, query: zenoh::query::Query) {
        if let Some(from) = query.parameters().get("from") {
            if from != self.me {
                return;
            }
        }
        let asked = query.key_expr();
        let owned: Vec<(String, Meta, Value)> = {
            let net = self.net.lock();
            // A state is answered by the process that posted its current value; when that one
            // is gone, by every process that holds it, as stale (the joiner sees one: same
            // poster, same number).
            let states = net.current.iter().filter_map(|(ty, (meta, value))| {
                if self.board.kind(ty) != Kind::State {
                    return None;
                }
                let mut meta = meta.clone();
                match meta.process.as_deref() {
                    Some(p) if p == self.me => {}
                    Some(p) if net.alive.contains(p) => return None,
                    Some(_) => meta.stale = true,
                    None => {}
                }
                Some((ty.clone(), meta, value.clone()))
            });
            let histories = net.own_history.iter().flat_map(|(ty, postings)| {
                postings
                    .iter()
                    .map(move |(meta, value)| (ty.clone(), meta.clone(), value.clone()))
            });
            states.chain(histories).collect()
        };
        let answers: Vec<(zenoh::key_expr::KeyExpr<'static>, Meta, Value)> = owned
            .into_iter()
            .filter_map(|(ty, meta, value)| {
                let key = zenoh::key_expr::KeyExpr::try_from(self.keys.ty(&ty)).ok()?;
                asked.intersects(&key).then_some((key, meta, value))
            })
            .collect();
        // Replies wait when the link is full, and this is Zenoh's receiving thread, the one
        // that drains it: answer from a thread of its own.
        let answering = std::thread::Builder::new()
            .name("proclaim-zenoh-answer".into())
            .spawn(move || {
                for (key, meta, value) in answers {
                    let sent = query
                        .reply(key, encode_value(&value))
                        .encoding(Encoding::APPLICATION_JSON)
                        .attachment(meta.encode())
                        .wait();
                    if let Err(e) = sent {
                        tracing::debug!(error = %e, "value not sent to a joiner");
                    }
                }
            });
        if let Err(e) = answering {
            tracing::warn!(error = %e, "cannot answer a joiner");
        }
    }

    /// Asks every process (or the one named) for the values it owns and the modules registered
    /// in it, and applies the answers.
    pub(super) async fn catch_up(&self, from: Option<&str>) {
        let values = self.ask(&self.values_selector(from)).await;
        self.apply_values(values);
        if from.is_none() {
            for reply in self.ask(&self.keys.registry()).await {
                self.on_registration(&reply.payload().to_bytes());
            }
        }
    }

    /// [`Peer::catch_up`] with one process, from a thread of its own (Zenoh's runtime cannot
    /// be driven from a callback's or a single-threaded one).
    pub(super) fn catch_up_with(&self, process: &str) {
        let mut values = Vec::new();
        if let Some(replies) = self.replies(&self.values_selector(Some(process))) {
            while let Ok(reply) = replies.recv() {
                values.extend(reply.into_result().ok());
            }
        }
        self.apply_values(values);
    }

    fn values_selector(&self, from: Option<&str>) -> String {
        match from {
            Some(process) => format!("{}?from={process}", self.keys.every_type()),
            None => self.keys.every_type(),
        }
    }

    /// Applies the answers to a catch-up, oldest first.
    fn apply_values(&self, samples: Vec<zenoh::sample::Sample>) {
        let mut answers: Vec<(String, Meta, Value)> = Vec::new();
        for sample in samples {
            let Some(ty) = self.keys.type_of(sample.key_expr().as_str()) else {
                continue;
            };
            let meta = sample
                .attachment()
                .and_then(|a| Meta::decode(&a.to_bytes()).ok())
                .unwrap_or_default();
            answers.push((
                ty.to_string(),
                meta,
                decode_value(&sample.payload().to_bytes()),
            ));
        }
        answers.sort_by_key(|(_, meta, _)| meta.time_ns);
        for (ty, meta, value) in answers {
            self.receive(&ty, value, meta);
        }
    }

    /// Every answer to a get on `selector` from the other processes.
    pub(super) async fn ask(&self, selector: &str) -> Vec<zenoh::sample::Sample> {
        let mut samples = Vec::new();
        if let Some(replies) = self.replies(selector) {
            while let Ok(reply) = replies.recv_async().await {
                samples.extend(reply.into_result().ok());
            }
        }
        samples
    }

    fn replies(
        &self,
        selector: &str,
    ) -> Option<zenoh::handlers::FifoChannelHandler<zenoh::query::Reply>> {
        let sent = self
            .session
            .get(selector)
            .consolidation(ConsolidationMode::None)
            .target(QueryTarget::All)
            .allowed_destination(Locality::Remote)
            .timeout(ANSWER_PATIENCE)
            .wait();
        match sent {
            Ok(replies) => Some(replies),
            Err(e) => {
                tracing::warn!(selector, error = %e, "cannot ask the other processes");
                None
            }
        }
    }
}
