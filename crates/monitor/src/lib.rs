//! A running behaviour as a picture in the browser (`proclaim run --monitor`, `proclaim replay
//! --monitor`): every machine's diagram with its current state lit and the transition that
//! just fired marked, the whiteboard as a live table, the labels' answers, pause / one ring /
//! resume, posting from the page, for a replay a slider over every moment (and a branch from
//! any round of a recording, through a [`Brancher`]), and why a machine read the answer it did
//! (a click on it, through an [`Explainer`] the program gives).
//!
//! The page costs the behaviour nothing it needs: machines never wait on it. Events are folded
//! into a bounded [`Picture`] by whoever reads the run's events; the whiteboard is read as an
//! O(1) [`proclaim_board::Snapshot`] when a frame is made; frames go to a page at most every
//! [`FRAME_GAP`], each one the state of things then, so a slow page sees fewer frames and
//! nothing queues up for it.
//!
//! The same crate serves `proclaim edit`'s page ([`Editor`]): the machines drawn the same way,
//! changed by text patches to their files, under the same access rules.

mod access;
mod branch;
mod diagram;
mod editor;
mod picture;
mod replay;
mod server;
mod why;

pub use access::{new_token, parse_address, Access, TOKEN_HEADER};
pub use branch::{Branched, Brancher};
pub use diagram::{node, Chart, ChartState, ChartTransition};
pub use editor::{BehaviourCheck, Editor, EditorFile};
pub use picture::{Frame, Picture, BOARD_ROWS, LABELS, RECENT};
pub use replay::Timeline;
pub use server::{Monitor, Uncovered, FRAME_GAP};
pub use why::{AnswerAsked, Explainer};
