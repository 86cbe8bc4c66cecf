//! The ordered, blocking link one side of the board sends its messages over.

use super::*;
use crate::error::NetworkError;

/// Where one side's messages go, in order. Puts block when the link is full (Zenoh's default
/// for a put is to drop): the whiteboard loses nothing, it slows the poster down. Not express:
/// Zenoh batches only under back-pressure, and measured, express cost 5-15x the messages per
/// second for no gain in a query's latency.
pub(super) enum Outbox<T> {
    /// Put from the poster's own thread: a replica's postings (none comes from Zenoh's threads).
    Direct(Publisher<'static>, Limit, PhantomData<fn(T)>),
    /// Put by a thread of its own: the holder's, many sent from Zenoh's receiving callback,
    /// which must never wait for a link (with few threads, it is the thread that drains it).
    Queued(std::sync::mpsc::Sender<T>),
}

/// The largest message a transport carries, if it has a limit.
pub(super) type Limit = Option<usize>;

impl<T: serde::Serialize + Send + 'static> Outbox<T> {
    pub(super) async fn publisher(
        session: &zenoh::Session,
        key: &str,
    ) -> Result<Publisher<'static>, NetworkError> {
        session
            .declare_publisher(key.to_string())
            .congestion_control(CongestionControl::Block)
            .express(false)
            .await
            .map_err(|e| NetworkError::zenoh(format!("cannot publish on {key}"), e))
    }

    pub(super) async fn direct(
        session: &zenoh::Session,
        key: &str,
        limit: Limit,
    ) -> Result<Outbox<T>, NetworkError> {
        Ok(Outbox::Direct(
            Self::publisher(session, key).await?,
            limit,
            PhantomData,
        ))
    }

    pub(super) async fn queued(
        session: &zenoh::Session,
        key: &str,
        limit: Limit,
    ) -> Result<Outbox<T>, NetworkError> {
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
            .map_err(|e| {
                NetworkError::zenoh(format!("cannot start the thread sending on {key}"), e)
            })?;
        Ok(Outbox::Queued(tx))
    }

    pub(super) fn send(&self, item: T) {
        match self {
            Outbox::Direct(publisher, limit, _) => put(publisher, &item, *limit),
            Outbox::Queued(tx) => {
                let _ = tx.send(item);
            }
        }
    }
}

pub(super) fn put<T: serde::Serialize>(publisher: &Publisher<'static>, item: &T, limit: Limit) {
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
