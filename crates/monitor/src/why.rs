//! Why a machine read the answer it did, asked from the page (a click on an answer in the
//! events list). The monitor knows nothing of theories: the program that serves the page gives
//! it an [`Explainer`], which is handed the run's events so far and what was asked.

use proclaim_runner::Event;
use serde::Deserialize;
use std::sync::Arc;

/// An answer the page asks about: the label a machine read in a round.
#[derive(Clone, Debug, Deserialize, PartialEq, Eq)]
pub struct AnswerAsked {
    pub round: u64,
    pub machine: String,
    pub label: String,
}

/// Explains an answer from the run's events: the text to show, or why it cannot be.
pub type Explainer = Arc<dyn Fn(&[Event], &AnswerAsked) -> Result<String, String> + Send + Sync>;
