//! The page's HTTP side (axum): the assets built into the binary, the machines' diagrams, a
//! stream of frames for a live run (server-sent events, at most [`FRAME_GAP`] apart whatever
//! the posting rate), a frame at any moment of a replay, and the controls.

use crate::access::{foreign, Access, TOKEN_HEADER};
use crate::branch::{round_after, BranchAsked, Brancher};
use crate::diagram::Chart;
use crate::picture::Picture;
use crate::replay::Timeline;
use crate::why::{AnswerAsked, Explainer, History};
use axum::extract::{Query, State};
use axum::http::{header, HeaderMap, StatusCode};
use axum::response::sse::{Event as SseEvent, KeepAlive, Sse};
use axum::response::{IntoResponse, Response};
use axum::routing::{get, post};
use axum::{Json, Router};
use parking_lot::{Mutex, MutexGuard, RwLock};
use proclaim_board::{Value, Whiteboard};
use proclaim_runner::{Event, Stepper};
use serde::{Deserialize, Serialize};
use std::net::SocketAddr;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::watch;

/// The least time between two frames sent to one page: the page keeps up with any posting
/// rate by seeing the board as it is at each frame.
pub const FRAME_GAP: Duration = Duration::from_millis(100);
/// With nothing new from the machines, the board is still looked at this often.
const IDLE_LOOK: Duration = Duration::from_millis(250);

const INDEX_HTML: &str = include_str!("../assets/index.html");
const MONITOR_JS: &str = include_str!("../assets/monitor.js");
const MONITOR_CSS: &str = include_str!("../assets/monitor.css");

/// A behaviour as the page shows it. Clones share it.
#[derive(Clone)]
pub struct Monitor {
    shared: Arc<Shared>,
}

struct Shared {
    name: String,
    /// Replaced whole when a machine is read again (`--watch`); the page asks for the model
    /// again when `charts_version` moves.
    charts: Mutex<Arc<Vec<Chart>>>,
    charts_version: std::sync::atomic::AtomicU64,
    picture: Mutex<Picture>,
    /// Bumped by every event folded in; frame streams wait on it.
    version: watch::Sender<u64>,
    source: Source,
    access: RwLock<Access>,
    /// Why a machine read an answer, when the program can say ([`Monitor::set_explainer`]).
    explainer: RwLock<Option<Explainer>>,
    /// A live run's events, kept once there is an explainer to hand them to.
    history: Mutex<History>,
    /// What recordings never exercised (`proclaim test --coverage --monitor`): drawn apart.
    uncovered: RwLock<Vec<Uncovered>>,
    /// Starts a branch of a replayed recording ([`Monitor::set_brancher`]).
    brancher: RwLock<Option<Brancher>>,
    /// Told to stop a live run from the page ([`Monitor::set_stopper`]).
    stopper: RwLock<Option<Arc<tokio::sync::Notify>>>,
}

/// A state never entered (no `target`), or a transition never fired, by the recordings a
/// page shows the coverage of.
#[derive(Clone, Debug, Serialize, PartialEq, Eq)]
pub struct Uncovered {
    pub machine: String,
    pub state: i64,
    pub target: Option<i64>,
    pub label: Option<String>,
}

enum Source {
    Live {
        board: Whiteboard,
        /// Pause, one ring, resume.
        stepper: Option<Stepper>,
    },
    Replay(Timeline),
}

impl Monitor {
    /// A running behaviour on `board`; `stepper` (given to its machines at launch) makes the
    /// page's pause and step buttons work.
    pub fn live(
        name: impl Into<String>,
        charts: Vec<Chart>,
        board: Whiteboard,
        stepper: Option<Stepper>,
    ) -> Monitor {
        let picture = Picture::new(&charts);
        Monitor::with(
            name.into(),
            charts,
            picture,
            Source::Live { board, stepper },
        )
    }

    /// A recorded run, shown at any of its moments.
    pub fn replay(name: impl Into<String>, charts: Vec<Chart>, events: Vec<Event>) -> Monitor {
        let timeline = Timeline::new(&charts, events);
        let picture = Picture::new(&charts);
        Monitor::with(name.into(), charts, picture, Source::Replay(timeline))
    }

    fn with(name: String, charts: Vec<Chart>, picture: Picture, source: Source) -> Monitor {
        Monitor {
            shared: Arc::new(Shared {
                name,
                charts: Mutex::new(Arc::new(charts)),
                charts_version: Default::default(),
                picture: Mutex::new(picture),
                version: watch::channel(0).0,
                source,
                access: Default::default(),
                explainer: RwLock::new(None),
                history: Mutex::new(History::default()),
                uncovered: RwLock::new(Vec::new()),
                brancher: RwLock::new(None),
                stopper: RwLock::new(None),
            }),
        }
    }

    /// Who may change the run from the page from now on.
    pub fn set_access(&self, access: Access) {
        *self.shared.access.write() = access;
    }

    /// Lets the page ask why a machine read an answer (a click on it): `explainer` is handed
    /// the run's events (a live run's are kept from now on) and what was asked.
    pub fn set_explainer(&self, explainer: Explainer) {
        *self.shared.explainer.write() = Some(explainer);
    }

    /// Lets a replay's page branch off the recording at the round its slider shows.
    pub fn set_brancher(&self, brancher: Brancher) {
        *self.shared.brancher.write() = Some(brancher);
    }

    /// Lets a live page stop the run (its Stop button): `stop` is told.
    pub fn set_stopper(&self, stop: Arc<tokio::sync::Notify>) {
        *self.shared.stopper.write() = Some(stop);
    }

    /// Draws what recordings never exercised apart (states never entered, transitions never
    /// fired).
    pub fn set_uncovered(&self, uncovered: Vec<Uncovered>) {
        *self.shared.uncovered.write() = uncovered;
        self.shared.changed();
    }

    /// Folds an event of the live run in. Cheap, and never waits on a page.
    pub fn observe(&self, event: &Event) {
        self.shared.picture().observe(event);
        if self.shared.explainer.read().is_some() {
            self.shared.history.lock().push(event.clone());
        }
        self.shared.changed();
    }

    /// A machine read again (`--watch`): its diagram replaced, the pages told to draw it anew.
    /// Draws through Graphviz, so call it off the async threads (`spawn_blocking`).
    pub fn redraw(&self, chart: Chart) {
        self.shared.picture().redraw(&chart);
        {
            let mut charts = self.shared.charts.lock();
            let mut all: Vec<Chart> = charts.as_ref().clone();
            match all.iter_mut().find(|c| c.name == chart.name) {
                Some(old) => *old = chart,
                None => all.push(chart),
            }
            *charts = Arc::new(all);
        }
        self.shared
            .charts_version
            .fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        self.shared.changed();
    }

    /// Serves the page on `addr` (port 0: any free port) until the runtime ends; returns the
    /// address it listens on.
    pub async fn serve(&self, addr: SocketAddr) -> std::io::Result<SocketAddr> {
        serve_router(self.router(), addr, "monitor").await
    }

    /// Serves the page where a user asked (`--monitor ADDR`: a port alone or an address), who
    /// may change the run decided by that address before the first request can come; when
    /// `asked` is `default` and its port is taken, any free port of the same address (a second
    /// run beside the first), while an address given is kept to or refused. Returns where it
    /// listens and what to print (the token, if any, is shown there only); an error names the
    /// option and why.
    pub async fn serve_asked(
        &self,
        asked: &str,
        default: &str,
        access: impl FnOnce(SocketAddr) -> Access,
    ) -> Result<(SocketAddr, String), String> {
        let wanted = crate::access::parse_address(asked).ok_or_else(|| {
            format!(
                "--monitor {}: not an address to listen on (write 127.0.0.1:7480, or a port alone)",
                asked.trim()
            )
        })?;
        let access = access(wanted);
        self.set_access(access.clone());
        let bound = match self.serve(wanted).await {
            Ok(bound) => bound,
            Err(e) if asked == default && e.kind() == std::io::ErrorKind::AddrInUse => self
                .serve(SocketAddr::new(wanted.ip(), 0))
                .await
                .map_err(|e| format!("--monitor: cannot listen ({e})"))?,
            Err(e) => return Err(format!("--monitor {asked}: cannot listen there ({e})")),
        };
        let shown = match &access {
            Access::Token(token) => format!("http://{bound}/?token={token}"),
            Access::ReadOnly => format!("http://{bound}/ (read-only)"),
            Access::Open => format!("http://{bound}/"),
        };
        Ok((bound, shown))
    }

    /// The routes, for serving elsewhere (tests, a program embedding the runner).
    pub fn router(&self) -> Router {
        Router::new()
            .route(
                "/",
                get(|| async { asset("text/html; charset=utf-8", INDEX_HTML) }),
            )
            .route(
                "/monitor.js",
                get(|| async { asset("text/javascript; charset=utf-8", MONITOR_JS) }),
            )
            .route(
                "/monitor.css",
                get(|| async { asset("text/css; charset=utf-8", MONITOR_CSS) }),
            )
            .route("/api/model", get(model))
            .route("/api/frame", get(frame))
            .route("/api/frames", get(frames))
            .route("/api/control", post(control))
            .route("/api/post", post(post_message))
            .route("/api/explain", get(explain))
            .route("/api/branch", post(branch))
            .with_state(self.shared.clone())
    }
}

impl Shared {
    fn charts_version(&self) -> u64 {
        self.charts_version
            .load(std::sync::atomic::Ordering::Relaxed)
    }

    /// Wakes the frame streams.
    fn changed(&self) {
        self.version.send_modify(|v| *v = v.wrapping_add(1));
    }

    fn access(&self) -> Access {
        self.access.read().clone()
    }

    /// Why a request that changes the run may not, if it may not.
    fn refusal(&self, headers: &HeaderMap) -> Option<Response> {
        refusal(
            &self.access(),
            headers,
            "this page is read-only (--monitor-read-only)",
            "this page changes the run only with the token it was given (open the address with ?token=… that proclaim printed)",
        )
    }

    fn picture(&self) -> MutexGuard<'_, Picture> {
        self.picture.lock()
    }

    /// The live frame as JSON text, with the board as it is now.
    fn live_frame(&self, board: &Whiteboard, stepper: Option<&Stepper>) -> String {
        let snapshot = board.snapshot();
        let picture = self.picture();
        let frame = picture.frame(&snapshot);
        let stepping = stepper.map(|s| Stepping {
            paused: s.is_paused(),
            step: s.step(),
        });
        serde_json::to_string(&Framed {
            frame,
            stepping,
            at: None,
            charts_version: self.charts_version(),
        })
        .unwrap_or_default()
    }
}

/// Why a request that changes something may not, under `access`, if it may not: the monitor's
/// rule, which the editor's page follows too.
pub(crate) fn refusal(
    access: &Access,
    headers: &HeaderMap,
    read_only: &'static str,
    needs_token: &'static str,
) -> Option<Response> {
    let given = |name| headers.get(name).and_then(|v| v.to_str().ok());
    if let Some(why) = foreign(access, given(header::HOST), given(header::ORIGIN)) {
        return Some((StatusCode::FORBIDDEN, why).into_response());
    }
    match access {
        Access::Open => None,
        Access::ReadOnly => Some((StatusCode::FORBIDDEN, read_only).into_response()),
        Access::Token(token) => {
            let given = headers.get(TOKEN_HEADER).and_then(|v| v.to_str().ok());
            if given == Some(token.as_str()) {
                None
            } else {
                Some((StatusCode::FORBIDDEN, needs_token).into_response())
            }
        }
    }
}

fn asset(content_type: &'static str, body: &'static str) -> Response {
    ([(header::CONTENT_TYPE, content_type)], body).into_response()
}

#[derive(Serialize)]
struct Framed<'p> {
    #[serde(flatten)]
    frame: crate::picture::Frame<'p>,
    /// Live runs with a stepper: whether paused, and the step count.
    stepping: Option<Stepping>,
    /// Replays: the event this frame shows the run after.
    at: Option<usize>,
    /// Moves when a machine's diagram was replaced: the page asks for the model again.
    charts_version: u64,
}

#[derive(Serialize)]
struct Stepping {
    paused: bool,
    step: u64,
}

#[derive(Serialize)]
struct Model<'s> {
    name: &'s str,
    /// `live` or `replay`.
    mode: &'static str,
    charts: &'s [Chart],
    charts_version: u64,
    /// Replays: how many events, and the time of each (microseconds).
    times: Option<Vec<u64>>,
    /// Replays: the round of each event.
    rounds: Option<Vec<u64>>,
    /// Replays: whether the page can branch off the recording.
    can_branch: bool,
    /// Live runs: whether the page can pause and step.
    can_step: bool,
    /// Live runs: whether the page can stop the run.
    can_stop: bool,
    /// Whether the page shows no controls at all.
    read_only: bool,
    /// What recordings never exercised, drawn apart.
    uncovered: Vec<Uncovered>,
}

async fn model(State(shared): State<Arc<Shared>>) -> Response {
    let (mode, times, rounds, can_step) = match &shared.source {
        Source::Live { stepper, .. } => ("live", None, None, stepper.is_some()),
        Source::Replay(timeline) => (
            "replay",
            Some(timeline.times()),
            Some(timeline.rounds()),
            false,
        ),
    };
    let can_branch = rounds.is_some() && shared.brancher.read().is_some();
    let can_stop = times.is_none() && shared.stopper.read().is_some();
    let charts = shared.charts.lock().clone();
    Json(Model {
        name: &shared.name,
        mode,
        charts: &charts,
        charts_version: shared.charts_version(),
        times,
        rounds,
        can_branch,
        can_step,
        can_stop,
        read_only: shared.access() == Access::ReadOnly,
        uncovered: shared.uncovered.read().clone(),
    })
    .into_response()
}

/// Why a machine read an answer: the explainer's text, or why there is none.
async fn explain(State(shared): State<Arc<Shared>>, Query(asked): Query<AnswerAsked>) -> Response {
    let Some(explainer) = shared.explainer.read().clone() else {
        let why = "this page cannot explain answers (give the behaviour: `--behaviour`)";
        return (StatusCode::NOT_IMPLEMENTED, why).into_response();
    };
    let explained = match &shared.source {
        Source::Replay(timeline) => explainer(timeline.events(), &asked),
        Source::Live { .. } => {
            let events = shared.history.lock().events();
            explainer(&events, &asked)
        }
    };
    match explained {
        Ok(text) => text.into_response(),
        Err(why) => (StatusCode::UNPROCESSABLE_ENTITY, why).into_response(),
    }
}

#[derive(Deserialize)]
struct At {
    /// Replays: after how many events (the whole run when absent).
    at: Option<usize>,
}

/// One frame: a live run's now, or a replay's moment `at`.
async fn frame(State(shared): State<Arc<Shared>>, Query(query): Query<At>) -> Response {
    let json = match &shared.source {
        Source::Live { board, stepper } => shared.live_frame(board, stepper.as_ref()),
        Source::Replay(timeline) => {
            let at = query.at.unwrap_or(usize::MAX).min(timeline.len());
            let (picture, board) = timeline.at(at);
            serde_json::to_string(&Framed {
                frame: picture.frame(&board),
                stepping: None,
                at: Some(at),
                charts_version: 0,
            })
            .unwrap_or_default()
        }
    };
    ([(header::CONTENT_TYPE, "application/json")], json).into_response()
}

/// The live frames: one at once, then one whenever something changed, at most one per
/// [`FRAME_GAP`]. A page that reads slowly gets fewer frames; nothing queues up for it.
async fn frames(State(shared): State<Arc<Shared>>) -> Response {
    if !matches!(shared.source, Source::Live { .. }) {
        return (
            StatusCode::NOT_FOUND,
            "a replay has no live frames; ask /api/frame?at=N",
        )
            .into_response();
    }
    let changes = shared.version.subscribe();
    let state = (shared, changes, None::<(u64, u64, bool, u64)>);
    let stream =
        futures_util::stream::unfold(state, |(shared, mut changes, mut sent)| async move {
            let Source::Live { board, stepper } = &shared.source else {
                return None;
            };
            loop {
                if sent.is_some() {
                    tokio::time::sleep(FRAME_GAP).await;
                }
                let seen = (
                    *changes.borrow_and_update(),
                    board.snapshot().seq,
                    stepper.as_ref().is_some_and(Stepper::is_paused),
                    stepper.as_ref().map_or(0, Stepper::step),
                );
                if sent != Some(seen) {
                    sent = Some(seen);
                    let json = shared.live_frame(board, stepper.as_ref());
                    let event = SseEvent::default().event("frame").data(json);
                    return Some((
                        Ok::<_, std::convert::Infallible>(event),
                        (shared.clone(), changes, sent),
                    ));
                }
                // Nothing new: wait for an event, or look at the board again a little later.
                let _ = tokio::time::timeout(IDLE_LOOK, changes.changed()).await;
            }
        });
    Sse::new(stream)
        .keep_alive(KeepAlive::default())
        .into_response()
}

#[derive(Deserialize)]
struct ControlRequest {
    /// `pause`, `step` or `resume`.
    action: String,
}

async fn control(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(request): Json<ControlRequest>,
) -> Response {
    if let Some(refused) = shared.refusal(&headers) {
        return refused;
    }
    if request.action == "stop" {
        let Some(stop) = shared.stopper.read().clone() else {
            let why = "this run cannot be stopped from the page";
            return (StatusCode::CONFLICT, why).into_response();
        };
        stop.notify_one();
        return StatusCode::NO_CONTENT.into_response();
    }
    let Source::Live {
        stepper: Some(stepper),
        ..
    } = &shared.source
    else {
        return (StatusCode::CONFLICT, "this run cannot be paused or stepped").into_response();
    };
    match request.action.as_str() {
        "pause" => stepper.pause(),
        "resume" => stepper.resume(),
        "step" => {
            stepper.advance();
        }
        other => {
            return (
                StatusCode::BAD_REQUEST,
                format!("unknown action `{other}`: pause, step, resume or stop"),
            )
                .into_response()
        }
    }
    tracing::debug!(action = %request.action, "monitor control");
    // Tell the frame streams at once: the buttons show the new mode without waiting.
    shared.changed();
    StatusCode::NO_CONTENT.into_response()
}

/// A branch of the replayed recording at the round after the last event the slider shows:
/// where its page is and what file records it.
async fn branch(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(asked): Json<BranchAsked>,
) -> Response {
    if let Some(refused) = shared.refusal(&headers) {
        return refused;
    }
    let Source::Replay(timeline) = &shared.source else {
        let why = "a live run is not branched: replay its recording (`proclaim replay FILE --monitor --behaviour B`)";
        return (StatusCode::CONFLICT, why).into_response();
    };
    let Some(brancher) = shared.brancher.read().clone() else {
        let why = "this page cannot branch: replay a `--record` file with its `--behaviour`";
        return (StatusCode::NOT_IMPLEMENTED, why).into_response();
    };
    let round = round_after(&timeline.rounds(), asked.at);
    // Starting a run may take a moment (a process, its page); the page's server goes on.
    match tokio::task::spawn_blocking(move || brancher(round)).await {
        Ok(Ok(branched)) => Json(branched).into_response(),
        Ok(Err(why)) => (StatusCode::UNPROCESSABLE_ENTITY, why).into_response(),
        Err(_) => (
            StatusCode::INTERNAL_SERVER_ERROR,
            "the branch could not start",
        )
            .into_response(),
    }
}

#[derive(Deserialize)]
struct PostRequest {
    #[serde(rename = "type")]
    ty: String,
    value: String,
}

/// A message posted by the person at the page, under the name `monitor` (an answer to a label
/// no expert answers is posted this way too: `doorOpen = true`).
async fn post_message(
    State(shared): State<Arc<Shared>>,
    headers: HeaderMap,
    Json(request): Json<PostRequest>,
) -> Response {
    if let Some(refused) = shared.refusal(&headers) {
        return refused;
    }
    let Source::Live { board, .. } = &shared.source else {
        return (StatusCode::CONFLICT, "a replay cannot be posted to").into_response();
    };
    let ty = request.ty.trim();
    if ty.is_empty() || ty.contains(char::is_whitespace) {
        return (
            StatusCode::BAD_REQUEST,
            format!("`{ty}` is not a message type (one word, such as doorOpen)"),
        )
            .into_response();
    }
    let message = board.post("monitor", ty, Value::parse(request.value.trim()));
    tracing::debug!(ty, seq = message.seq, "posted from the monitor page");
    Json(serde_json::json!({ "seq": message.seq })).into_response()
}

/// Serves `app` on `addr` (port 0: any free port) until the runtime ends; returns the address it
/// listens on. `page` names the page in the warning logged if serving stops.
pub(crate) async fn serve_router(
    app: Router,
    addr: SocketAddr,
    page: &'static str,
) -> std::io::Result<SocketAddr> {
    let listener = tokio::net::TcpListener::bind(addr).await?;
    let bound = listener.local_addr()?;
    tokio::spawn(async move {
        if let Err(e) = axum::serve(listener, app).await {
            tracing::warn!(error = %e, page, "the page stopped serving");
        }
    });
    Ok(bound)
}
