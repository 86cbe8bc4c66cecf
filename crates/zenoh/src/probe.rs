//! The link's own round trip, without the whiteboard: the holder answers pings, and a process
//! measures what one Zenoh request and reply to it cost. A query's latency is judged against it.

use crate::error::NetworkError;
use crate::session::{open, Role, Settings};
use std::time::{Duration, Instant};
use zenoh::query::Queryable;
use zenoh::Wait;

/// The key the holder of `board` answers pings on.
pub(crate) fn key(board: &str) -> String {
    format!("proclaim/{board}/ping")
}

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

/// Joins the whiteboard held at `endpoint` and times `count` pings to its holder, one after
/// another. The first answer (routes settling) is not counted.
pub async fn ping(
    endpoint: &str,
    board: &str,
    settings: &Settings,
    count: usize,
) -> Result<Vec<Duration>, NetworkError> {
    let session = open(&Role::Connect(endpoint.to_string()), settings).await?;
    let key = key(board);
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
