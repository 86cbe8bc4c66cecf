//! What reaches a compiled run from outside while it waits: other modules' postings on its
//! whiteboard (not its own, not queries) and Ctrl-C (or the page's Stop), in the order they come.

use proclaim_board::{Pattern, Value, Whiteboard, QUERY_TYPE};
use proclaim_runtime::host::Heard;
use std::sync::{mpsc, Arc};

/// Starts listening on `runtime`; what is heard comes out of the receiver. `stop` (the page's
/// Stop button) ends the run as Ctrl-C does.
pub(crate) fn hear(
    runtime: &tokio::runtime::Runtime,
    board: &Whiteboard,
    ours: Vec<&'static str>,
    stop: Arc<tokio::sync::Notify>,
) -> mpsc::Receiver<Heard> {
    let (tell, heard) = mpsc::channel();
    let mut all = board.subscribe_pattern(Pattern::All);
    let posting = tell.clone();
    runtime.spawn(async move {
        while let Some(m) = all.next().await {
            if &*m.ty == QUERY_TYPE || ours.contains(&&*m.module) {
                continue;
            }
            let content = match &m.value {
                Value::Str(text) => text.clone(),
                other => other.to_string(),
            };
            let heard = Heard::Posting(
                m.module.to_string(),
                m.ty.to_string(),
                content,
                m.value.to_json(),
            );
            if posting.send(heard).is_err() {
                return;
            }
        }
    });
    runtime.spawn(async move {
        tokio::select! {
            interrupted = tokio::signal::ctrl_c() => {
                if interrupted.is_err() {
                    return;
                }
            }
            () = stop.notified() => {}
        }
        let _ = tell.send(Heard::Interrupted);
    });
    heard
}
