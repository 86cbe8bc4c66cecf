//! Sensor wrappers for buttons and falls: debounced propositions from raw postings, with the
//! timing a robot needs (contacts bounce; a stumble is not a fall; a short press is a command).

use proclaim_board::{ModuleDecl, Pattern, Whiteboard};
use std::time::Duration;
use tokio::time::Instant;
use tracing::Instrument;

/// A raw boolean posting, debounced: a change counts once it has held for `rise` (to true) or
/// `fall` (to false). Returns the next settled value, or `None` when the board is gone.
struct Debounced {
    sub: proclaim_board::Subscription,
    settled: bool,
    rise: Duration,
    fall: Duration,
}

impl Debounced {
    /// Subscribes to `raw` and to queries for the label, registers the wrapper, and posts the
    /// label's first value (false). The second result answers queries; run it beside the wrapper.
    fn start(
        board: &Whiteboard,
        decl: ModuleDecl,
        raw: &str,
        label: &str,
        rise: Duration,
        fall: Duration,
    ) -> (Debounced, impl std::future::Future<Output = ()>) {
        let sub = board.subscribe_pattern(Pattern::Type(raw.to_string()));
        let answering =
            crate::answers::answer_from_latest(board, &decl.name, vec![label.to_string()]);
        board.post(&decl.name, label, false);
        board.register(decl);
        (
            Debounced {
                sub,
                settled: false,
                rise,
                fall,
            },
            answering,
        )
    }

    async fn next(&mut self) -> Option<(bool, Instant)> {
        let mut pending: Option<(bool, Instant)> = None;
        loop {
            let deadline = pending.map(|(v, since)| since + if v { self.rise } else { self.fall });
            let message = match deadline {
                Some(at) => tokio::select! {
                    m = self.sub.next() => m,
                    _ = tokio::time::sleep_until(at) => {
                        let (v, since) = pending.take().expect("pending");
                        self.settled = v;
                        return Some((v, since));
                    }
                },
                None => self.sub.next().await,
            };
            let value = message?.value.truthy();
            if value == self.settled {
                pending = None; // bounced back
            } else if pending.is_none_or(|(v, _)| v != value) {
                pending = Some((value, Instant::now()));
            }
        }
    }
}

/// A button: `raw` is the contact's posting (truthy while pressed).
pub struct ButtonWrapper {
    pub name: String,
    pub raw: String,
    pub label: String,
    pub debounce: Duration,
    /// `Some(max)`: the label is a *short press* (pressed and released within `max`), true for
    /// `hold` after the release. `None`: the label is true while the button is held.
    pub short_press: Option<Duration>,
    pub hold: Duration,
}

impl ButtonWrapper {
    /// `shortChestButtonPressed` from `ChestButton`: a press shorter than a second.
    pub fn chest() -> ButtonWrapper {
        ButtonWrapper {
            name: "chestButton".into(),
            raw: "ChestButton".into(),
            label: "shortChestButtonPressed".into(),
            debounce: Duration::from_millis(30),
            short_press: Some(Duration::from_secs(1)),
            hold: Duration::from_secs(1),
        }
    }

    /// `leftFootBumpPressed` / `rightFootBumpPressed` from `LeftFootBump` / `RightFootBump`.
    pub fn foot(left: bool) -> ButtonWrapper {
        let side = if left { "left" } else { "right" };
        let capitalised = if left { "Left" } else { "Right" };
        ButtonWrapper {
            name: format!("{side}FootBump"),
            raw: format!("{capitalised}FootBump"),
            label: format!("{side}FootBumpPressed"),
            debounce: Duration::from_millis(30),
            short_press: None,
            hold: Duration::ZERO,
        }
    }

    pub fn declaration(&self) -> ModuleDecl {
        wrapper_declaration(&self.name, &self.raw, &self.label)
    }

    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("button", name = %self.name);
        self.serve(board).instrument(span).await
    }

    async fn serve(self, board: Whiteboard) {
        let (contact, answering) = Debounced::start(
            &board,
            self.declaration(),
            &self.raw,
            &self.label,
            self.debounce,
            self.debounce,
        );
        tokio::select! {
            () = self.follow(&board, contact) => {}
            () = answering => {}
        }
    }

    async fn follow(&self, board: &Whiteboard, mut contact: Debounced) {
        let mut pressed_at: Option<Instant> = None;
        let mut clear_at: Option<Instant> = None;
        loop {
            let settled = match clear_at {
                Some(at) => tokio::select! {
                    s = contact.next() => s,
                    _ = tokio::time::sleep_until(at) => {
                        clear_at = None;
                        board.post(&self.name, &self.label, false);
                        continue;
                    }
                },
                None => contact.next().await,
            };
            let Some((down, since)) = settled else { return };
            match self.short_press {
                None => {
                    board.post(&self.name, &self.label, down);
                }
                Some(max) => {
                    if down {
                        pressed_at = Some(since);
                    } else if let Some(at) = pressed_at.take() {
                        if since.duration_since(at) <= max {
                            board.post(&self.name, &self.label, true);
                            clear_at = Some(Instant::now() + self.hold);
                        }
                    }
                }
            }
        }
    }
}

/// `fallen` from a raw fall detector posting (`FallDetected`): true once the detector has said
/// so for `confirm`, false again once it has been clear for `recover` (getting up takes time).
pub struct FallWrapper {
    pub name: String,
    pub raw: String,
    pub label: String,
    pub confirm: Duration,
    pub recover: Duration,
}

impl Default for FallWrapper {
    fn default() -> FallWrapper {
        FallWrapper {
            name: "fallDetector".into(),
            raw: "FallDetected".into(),
            label: "fallen".into(),
            confirm: Duration::from_millis(100),
            recover: Duration::from_millis(500),
        }
    }
}

impl FallWrapper {
    pub fn declaration(&self) -> ModuleDecl {
        wrapper_declaration(&self.name, &self.raw, &self.label)
    }

    pub async fn run(self, board: Whiteboard) {
        let span = tracing::info_span!("fall_detector", name = %self.name);
        self.serve(board).instrument(span).await
    }

    async fn serve(self, board: Whiteboard) {
        let (mut detector, answering) = Debounced::start(
            &board,
            self.declaration(),
            &self.raw,
            &self.label,
            self.confirm,
            self.recover,
        );
        let follow = async {
            while let Some((fallen, _)) = detector.next().await {
                board.post(&self.name, &self.label, fallen);
            }
        };
        tokio::select! {
            () = follow => {}
            () = answering => {}
        }
    }
}

/// A wrapper reads its raw posting and answers its label.
fn wrapper_declaration(name: &str, raw: &str, label: &str) -> ModuleDecl {
    ModuleDecl::new(name)
        .reads([raw])
        .posts([label])
        .answers([label])
}
