//! An expert whose answers come from a function of the program that embeds the behaviour (a
//! Python callable, a closure in a test): asked an atom, it calls the function with the atom and
//! the whiteboard, at the moment of the query, and posts what it returns.

use proclaim_board::{ModuleDecl, Pattern, Value, Whiteboard, QUERY_TYPE};
use std::sync::Arc;
use tracing::Instrument;

/// What a function expert is asked: the atom and the board it may read. `None` is no answer
/// (the query times out and the label reads false, as for any silent expert).
pub type AnswerFunction = Arc<dyn Fn(&str, &Whiteboard) -> Option<bool> + Send + Sync>;

/// Answers its atoms by calling one function per query. Clones share the function.
#[derive(Clone)]
pub struct FunctionExpert {
    name: String,
    atoms: Vec<String>,
    answer: AnswerFunction,
}

impl FunctionExpert {
    /// An expert called `name` answering `atoms`, each by `answer(atom, board)`.
    pub fn new<S: Into<String>>(
        name: impl Into<String>,
        atoms: impl IntoIterator<Item = S>,
        answer: impl Fn(&str, &Whiteboard) -> Option<bool> + Send + Sync + 'static,
    ) -> FunctionExpert {
        FunctionExpert {
            name: name.into(),
            atoms: atoms.into_iter().map(Into::into).collect(),
            answer: Arc::new(answer),
        }
    }

    pub fn name(&self) -> &str {
        &self.name
    }

    pub fn declaration(&self) -> ModuleDecl {
        ModuleDecl::new(&self.name)
            .reads([QUERY_TYPE])
            .posts(self.atoms.clone())
            .answers(self.atoms.clone())
    }

    /// Registers and answers queries until the whiteboard is gone.
    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("function expert", name = %self.name);
        self.serve(board).instrument(span).await
    }

    async fn serve(self, board: Whiteboard) {
        // Subscribed before registering, so no query made once it is registered is missed.
        let mut queries = board.subscribe_pattern(Pattern::Type(QUERY_TYPE.to_string()));
        board.register(self.declaration());
        while let Some(query) = queries.next().await {
            let Value::Str(atom) = &query.value else {
                continue;
            };
            if !self.atoms.contains(atom) {
                continue;
            }
            if let Some(value) = (self.answer)(atom, &board) {
                board.post(&self.name, atom, value);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::time::Duration;

    #[tokio::test(start_paused = true)]
    async fn each_query_calls_the_function_with_the_atom_and_the_board_at_that_moment() {
        let board = Whiteboard::local();
        let expert =
            FunctionExpert::new("door", ["doorOpen", "silent"], |atom, board| match atom {
                "doorOpen" => Some(board.latest("hinge").is_some_and(|m| m.value.truthy())),
                _ => None,
            });
        tokio::spawn(expert.run(board.clone()));
        while board.registry().answerers("doorOpen").is_empty() {
            tokio::task::yield_now().await;
        }
        let ask = |atom: &'static str| {
            let board = board.clone();
            async move { board.query("test", atom, Duration::from_millis(50)).await }
        };
        assert!(!ask("doorOpen").await.truth());
        board.post("sensor", "hinge", true);
        assert!(ask("doorOpen").await.truth(), "read when asked, not before");
        let silent = ask("silent").await;
        assert!(!silent.truth(), "no answer reads false");
        assert!(
            matches!(silent, proclaim_board::QueryOutcome::TimedOut),
            "{silent:?}"
        );
    }
}
