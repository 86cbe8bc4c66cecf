//! Answering queries for experts whose answers are their latest postings (sensor wrappers): a
//! query for one of their atoms re-posts its current value, so the asking machine, which waits
//! for a posting after its query, is answered at once.

use proclaim_board::{Pattern, Value, Whiteboard, QUERY_TYPE};
use std::future::Future;

/// Subscribes now (call it before registering, so no query is missed) and returns the loop that
/// answers. An atom never posted is not answered: the query times out, which is the truth.
pub(crate) fn answer_from_latest(
    board: &Whiteboard,
    module: &str,
    atoms: Vec<String>,
) -> impl Future<Output = ()> {
    let mut queries = board.subscribe_pattern(Pattern::Type(QUERY_TYPE.to_string()));
    let (board, module) = (board.clone(), module.to_string());
    async move {
        while let Some(query) = queries.next().await {
            let Value::Str(atom) = &query.value else {
                continue;
            };
            if atoms.contains(atom) {
                if let Some(current) = board.latest(atom) {
                    board.post(&module, atom, current.value);
                }
            }
        }
    }
}
