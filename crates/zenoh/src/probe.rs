//! The link's own round trip, without the whiteboard: every process of a board answers pings,
//! and a process measures what one Zenoh request and reply cost. A query's latency is judged
//! against it.

use crate::error::NetworkError;
use crate::session::{open, Role, Settings};
use std::time::{Duration, Instant};
use zenoh::query::Queryable;
use zenoh::Wait;

/// Answers every ping with its own payload, from Zenoh's receiving thread.
pub(crate) async fn answer(
    session: &zenoh::Session,
    key: &str,
) -> Result<Queryable<()>, NetworkError> {
    session
        .declare_queryable(key.to_string())
        .callback(|query| {
            let payload = query.payload().cloned().unwrap_or_default();
            if let Err(e) = query.reply(query.key_expr().clone(), payload).wait() {
                tracing::debug!(error = %e, "ping not answered");
            }
        })
        .await
        .map_err(|e| NetworkError::zenoh(format!("cannot answer pings on {key}"), e))
}

/// Joins the whiteboard at `endpoint` and times `count` pings, one after another, each answered
/// by the first process that replies. The first answer (routes settling) is not counted.
pub async fn ping(
    endpoint: &str,
    board: &str,
    settings: &Settings,
    count: usize,
) -> Result<Vec<Duration>, NetworkError> {
    let session = open(&Role::Connect(endpoint.to_string()), settings).await?;
    let key = crate::keys::Keys::new(board).ping();
    let deadline = Instant::now() + Duration::from_secs(5);
    while once(&session, &key).await.is_none() {
        if Instant::now() >= deadline {
            return Err(NetworkError::NoBoard {
                board: Some(board.to_string()),
                endpoint: endpoint.to_string(),
            });
        }
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
    let mut samples = Vec::with_capacity(count);
    for _ in 0..count {
        let started = Instant::now();
        once(&session, &key)
            .await
            .ok_or_else(|| NetworkError::Stopped {
                endpoint: endpoint.to_string(),
            })?;
        samples.push(started.elapsed());
    }
    Ok(samples)
}

async fn once(session: &zenoh::Session, key: &str) -> Option<()> {
    let replies = session
        .get(key)
        .payload(vec![0u8; 32])
        .timeout(Duration::from_secs(1))
        .await
        .ok()?;
    let reply = replies.recv_async().await.ok()?;
    reply.result().ok().map(|_| ())
}

/// The key bare Zenoh puts go on in [`BareSender`] and [`bare_receive`]: no whiteboard, the
/// yardstick a posting to another process is judged against.
fn bare_key(board: &str) -> String {
    format!("proclaim/{board}/@bare")
}

/// Bare Zenoh puts of the sender's clock (nanoseconds since the Unix epoch), from a session of
/// its own set up as a whiteboard's is.
pub struct BareSender {
    publisher: zenoh::pubsub::Publisher<'static>,
    _session: zenoh::Session,
}

impl BareSender {
    pub async fn listen(
        endpoint: &str,
        board: &str,
        settings: &Settings,
    ) -> Result<BareSender, NetworkError> {
        let session = open(&Role::Listen(endpoint.to_string()), settings).await?;
        let key = bare_key(board);
        let publisher = session
            .declare_publisher(key.clone())
            .congestion_control(zenoh::qos::CongestionControl::Block)
            .await
            .map_err(|e| NetworkError::zenoh(format!("cannot publish on {key}"), e))?;
        Ok(BareSender {
            publisher,
            _session: session,
        })
    }

    /// Whether a receiver is subscribed yet.
    pub async fn heard(&self) -> bool {
        self.publisher
            .matching_status()
            .await
            .is_ok_and(|s| s.matching())
    }

    pub fn send_now(&self) {
        let now = crate::wire::unix_now().as_nanos() as u64;
        if let Err(e) = self.publisher.put(now.to_le_bytes().to_vec()).wait() {
            tracing::warn!(error = %e, "bare put not sent");
        }
    }
}

/// Receives `count` of a [`BareSender`]'s puts and returns how long each took to arrive (one
/// clock: sender and receiver on one machine).
pub async fn bare_receive(
    endpoint: &str,
    board: &str,
    settings: &Settings,
    count: usize,
    ready: impl FnOnce(),
) -> Result<Vec<Duration>, NetworkError> {
    let session = open(&Role::Connect(endpoint.to_string()), settings).await?;
    let key = bare_key(board);
    let subscriber = session
        .declare_subscriber(key.clone())
        .await
        .map_err(|e| NetworkError::zenoh(format!("cannot subscribe to {key}"), e))?;
    ready();
    let mut samples = Vec::with_capacity(count);
    while samples.len() < count {
        let sample = tokio::time::timeout(Duration::from_secs(10), subscriber.recv_async())
            .await
            .ok()
            .and_then(Result::ok)
            .ok_or_else(|| NetworkError::Stopped {
                endpoint: endpoint.to_string(),
            })?;
        let now = crate::wire::unix_now();
        let bytes = sample.payload().to_bytes();
        let sent = <[u8; 8]>::try_from(&bytes[..]).map_or(0, u64::from_le_bytes);
        samples.push(now.saturating_sub(Duration::from_nanos(sent)));
    }
    Ok(samples)
}
