//! The round schedule (`docs/spec/behaviour.md` §3.1), gufsm's `executeOnce` and swiftfsm's
//! round-robin: one task gives every running machine of a behaviour exactly one ringlet per
//! round, in the order the machines were given (the manifest's). A control command posted in a
//! ringlet is obeyed as soon as that ringlet ends: a machine stopped or suspended later in the
//! round does not ring, and a machine started in a round takes its first ringlet in the next
//! one; commands from outside are obeyed before each round. When a machine fired, the next round
//! follows at once; when none did, the schedule waits for news: a posting or a change of globals
//! that differs from what a running machine's current labels last saw, a time test coming due,
//! or the ring period. The same outside postings arriving between the same rounds give the same
//! trace; one due just as a round is (a script's step timed for that moment) arrives before it.

use crate::activity::SharedSuppressor;
use crate::checkpoint::{Checkpoints, HoldImage, RoundsImage, SharedCheckpoints};
use crate::event::Event;
use crate::feed::{Feed, QueryHook, RoundCounter, SharedFeed};
use crate::machine::{MachineRunner, RingOutcome, RunningMachine, Status};
use crate::step::Stepper;
use proclaim_board::{nanos, Message, Pattern, Snapshot, Subscription, Value, Whiteboard};
use proclaim_runtime::Ringlet;
use std::sync::Arc;
use std::time::Duration;
use tokio::sync::mpsc;
use tokio::time::Instant;

/// Why a schedule's run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RoundsEnd {
    /// Every machine halted (or its state vanished): nothing can ring again.
    AllOver,
    /// The feed had nothing more.
    FeedDone,
    /// [`MOST_ROUNDS_WITHOUT_WAITING`] rounds fired one after another: the machines go round
    /// a cycle that takes no time, so time could never pass; every machine halted, saying so.
    NoTimePasses,
    /// The outside had said all it would ([`Rounds::ends_when_still`]) and a round was still:
    /// no machine fired or changed anything, and no time test or hold was to come due, so
    /// every later round would be the same.
    Still,
}

/// How many rounds in a row may fire with no wait between them. A round takes no time (§3.1),
/// so machines that fire round after round hold time still: on the virtual clock a run would
/// never reach its end, on the real clock it would spin a core. Synchronous languages refuse
/// such instantaneous loops (Esterel at compile time); here `check` warns of a cycle of
/// unconditional transitions and a run halts past this many rounds, far more than any
/// behaviour takes to settle at one moment.
pub const MOST_ROUNDS_WITHOUT_WAITING: u64 = 10_000;

/// Machines run in rounds of ringlets. Build it, then `run` it on a task of its own (abort the
/// task to stop it).
pub struct Rounds {
    machines: Vec<MachineRunner>,
    round: RoundCounter,
    stepper: Option<Stepper>,
    ticks: Option<mpsc::UnboundedSender<Ringlet>>,
    feed: Option<SharedFeed>,
    /// When the feed is done, the run goes on live (a branch of a recording), paused if stepped,
    /// and says so here.
    live_after_feed: Option<Arc<tokio::sync::Notify>>,
    /// The feed is done and the run went on live.
    gone_live: std::sync::atomic::AtomicBool,
    /// From when (since the machines' epoch) nothing outside will post again.
    silent_from: Option<Duration>,
    checkpoints: Option<SharedCheckpoints>,
    /// Where the schedule takes up, instead of every machine's start.
    resume: Option<RoundsImage>,
}

impl Rounds {
    /// The machines in schedule order. Their own `RunOptions::stepper` is not used: give the
    /// schedule one ([`Rounds::stepped_by`]), and a step is one round.
    pub fn new(machines: Vec<MachineRunner>) -> Rounds {
        Rounds {
            machines,
            round: RoundCounter::default(),
            stepper: None,
            ticks: None,
            feed: None,
            live_after_feed: None,
            gone_live: std::sync::atomic::AtomicBool::new(false),
            silent_from: None,
            checkpoints: None,
            resume: None,
        }
    }

    /// Written down when `checkpoints` say, at the start of a round.
    pub fn checkpointed(mut self, checkpoints: Checkpoints) -> Rounds {
        self.checkpoints = Some(Arc::new(parking_lot::Mutex::new(checkpoints)));
        self
    }

    /// Takes up where `image` left off: its round is the first played, every machine where
    /// the image has it. Refused with why when the machines no longer fit it; what changed but
    /// fits is in the notes.
    pub fn resumed_from(
        mut self,
        image: RoundsImage,
    ) -> Result<(Rounds, Vec<String>), Vec<String>> {
        let fit = image.fit(&self.machines);
        if !fit.refused.is_empty() {
            return Err(fit.refused);
        }
        // Now, not when the schedule starts: whoever reads the globals before the first round
        // (a test stepping the run) reads them as they were.
        if let Some(first) = self.machines.first() {
            let globals = image.globals.iter();
            let globals = globals.map(|g| (g.name.clone(), Value::from_json(&g.value)));
            first
                .shared()
                .restore(globals.collect(), image.global_changes);
        }
        self.round.set(image.round.saturating_sub(1));
        self.resume = Some(image);
        Ok((self, fit.notes))
    }

    /// Ends at the first still round ([`RoundsEnd::Still`]) at or after `silent_from` (since
    /// the machines' epoch), from when nothing outside the machines will post again but the
    /// experts answering what they ask (a script over, no person, no sensor).
    pub fn ends_when_still(mut self, silent_from: Duration) -> Rounds {
        self.silent_from = Some(silent_from);
        self
    }

    /// One round per step of `stepper` while it is paused.
    pub fn stepped_by(mut self, stepper: Stepper) -> Rounds {
        self.stepper = Some(stepper);
        self
    }

    /// Paced by `feed` (a replay) instead of waiting for news.
    pub fn fed_by(mut self, feed: impl Feed + 'static) -> Rounds {
        self.feed = Some(Arc::new(parking_lot::Mutex::new(feed)));
        self
    }

    /// Paced by `feed` until it is done, then live: waiting for news as an unfed schedule does,
    /// and paused first when stepped, so a person takes over where the replay left off (a
    /// branch of a recording); `live` is told when it goes live.
    pub fn fed_then_live(
        mut self,
        feed: impl Feed + 'static,
        live: Arc<tokio::sync::Notify>,
    ) -> Rounds {
        self.live_after_feed = Some(live);
        self.fed_by(feed)
    }

    /// Every ringlet, from now on, sent once it has run, or as the schedule stops inside it
    /// (what a recording keeps).
    pub fn ringlets(&mut self) -> mpsc::UnboundedReceiver<Ringlet> {
        let (tx, rx) = mpsc::unbounded_channel();
        self.ticks = Some(tx);
        rx
    }

    /// The round under way, readable while the schedule runs.
    pub fn counter(&self) -> RoundCounter {
        self.round.clone()
    }

    /// Runs round after round until every machine halted or the feed is done.
    pub async fn run(self, board: Whiteboard) -> RoundsEnd {
        let span = tracing::info_span!("rounds", machines = self.machines.len());
        tracing::Instrument::instrument(self.serve(board), span).await
    }

    /// The machines at their start, or where the checkpoint resumed has them.
    fn scheduled(&self, board: &Whiteboard) -> ScheduledMachines<'_> {
        let announce = self.resume.is_none();
        let runs: Vec<RunningMachine<'_>> = self
            .machines
            .iter()
            .map(|m| RunningMachine::new(m, board.clone(), self.round.clone(), announce))
            .collect();
        let suppressor = self.machines.iter().find_map(MachineRunner::suppressor);
        let mut scheduled = ScheduledMachines::new(runs, board, suppressor);
        if let Some(image) = &self.resume {
            scheduled.restore(image);
        }
        scheduled
    }

    /// Where a schedule taken up in the middle of rounds at one moment goes on from: that
    /// moment, and the count of rounds fired at it; a schedule starting has neither.
    fn moment_taken_up(&self) -> (Option<Instant>, u64) {
        match &self.resume {
            Some(image) if image.same_moment => {
                (Some(Instant::now()), image.rounds_without_waiting)
            }
            Some(image) => (None, image.rounds_without_waiting),
            None => (None, 0),
        }
    }

    /// The feed pacing the schedule, while it does.
    fn feed(&self) -> Option<&SharedFeed> {
        let live = self.gone_live.load(std::sync::atomic::Ordering::Relaxed);
        self.feed.as_ref().filter(|_| !live)
    }

    async fn serve(self, board: Whiteboard) -> RoundsEnd {
        let mut scheduled = self.scheduled(&board);
        let mut wakeup = RoundWakeup::default();
        let mut last_step = 0;
        // Commands posted before the schedule subscribed are obeyed before the first round.
        let mut commanded = true;
        // The moment of the last round (a round at a later one first lets the outside catch
        // up), and how many rounds in a row fired at it.
        let (mut last_moment, mut without_waiting) = self.moment_taken_up();
        loop {
            if let Some(stepper) = &self.stepper {
                last_step = stepper.wait(last_step).await;
            }
            let round = self.round.advance();
            let moment = tokio::time::Instant::now();
            if self.feed().is_none() && last_moment != Some(moment) {
                // What was due at this moment (a script's step timed for it) is posted before
                // the round's first snapshot and belongs to this round, whichever task the
                // clock woke first.
                settle(&board).await;
            }
            if let Some(checkpoints) = &self.checkpoints {
                let same = (last_moment == Some(moment), without_waiting);
                let image = || scheduled.image(round, moment, same);
                checkpoints.lock().offer(round, image);
            }
            last_moment = Some(moment);
            let changes = self.round.changes();
            let fired = self
                .play_round(&mut scheduled, round, commanded, &board)
                .await;
            if let Some(stepper) = &self.stepper {
                for (run, over) in scheduled.runs.iter().zip(&scheduled.over) {
                    stepper.note_due(&run.name, run.due_at().filter(|_| !*over));
                    stepper.ring_done(&run.name, last_step);
                }
            }
            if scheduled.over.iter().all(|o| *o) {
                return RoundsEnd::AllOver;
            }
            commanded = false;
            if self.feed().is_some() {
                if let Some(end) = self.after_fed_round(round) {
                    return end;
                }
                continue;
            }
            if !fired && self.still(&scheduled, changes, moment) {
                return RoundsEnd::Still;
            }
            if fired {
                if self.time_stands_still(&mut without_waiting, &mut scheduled) {
                    return RoundsEnd::NoTimePasses;
                }
                // Machines whose labels are always true would otherwise never let the experts,
                // the trace or a stop request have a turn.
                tokio::task::consume_budget().await;
                continue;
            }
            without_waiting = 0;
            if self.stepper.as_ref().is_some_and(Stepper::is_paused) {
                continue;
            }
            let release = scheduled
                .suppressor
                .as_ref()
                .and_then(|s| s.lock().next_release());
            commanded = wakeup
                .wait(
                    &board,
                    &mut scheduled.runs,
                    &scheduled.over,
                    &mut scheduled.commands,
                    release,
                )
                .await;
            // News already on the board ends the wait at once: machines that keep posting what
            // the others read must not keep the experts, the trace or a stop request from a turn
            // either.
            tokio::task::consume_budget().await;
        }
    }

    /// After a round the feed paced: how the run ends when the feed is done and nothing goes
    /// on live; a branch goes on live instead (paused, when stepped).
    fn after_fed_round(&self, round: u64) -> Option<RoundsEnd> {
        let more = self
            .feed()
            .is_some_and(|feed| feed.lock().after_round(round));
        if more {
            return None;
        }
        let Some(live) = &self.live_after_feed else {
            return Some(RoundsEnd::FeedDone);
        };
        self.gone_live
            .store(true, std::sync::atomic::Ordering::Relaxed);
        if let Some(stepper) = &self.stepper {
            stepper.pause();
        }
        live.notify_one();
        None
    }

    /// Whether the round just played at `moment`, which fired nothing, was still and the outside
    /// silent by then: no change reported since the count was `changes`, and no running
    /// machine's time test or hold to come due.
    fn still(&self, scheduled: &ScheduledMachines<'_>, changes: u64, moment: Instant) -> bool {
        let (Some(from), Some(first)) = (self.silent_from, scheduled.runs.first()) else {
            return false;
        };
        let waiting = |(run, over): (&RunningMachine<'_>, &bool)| {
            !*over && run.status == Status::Running && run.next_time_test().is_some()
        };
        moment.saturating_duration_since(first.reporter.epoch) >= from
            && self.round.changes() == changes
            && scheduled
                .suppressor
                .as_ref()
                .is_none_or(|s| s.lock().next_release().is_none())
            && !scheduled.runs.iter().zip(&scheduled.over).any(waiting)
    }

    /// Counts a round that fired; past [`MOST_ROUNDS_WITHOUT_WAITING`] of them in a row, halts
    /// every machine, saying why, and is true.
    fn time_stands_still(
        &self,
        without_waiting: &mut u64,
        scheduled: &mut ScheduledMachines<'_>,
    ) -> bool {
        // Rounds stepped one at a time wait for whoever steps them.
        let stepped = self.stepper.as_ref().is_some_and(Stepper::is_paused);
        *without_waiting = if stepped { 0 } else { *without_waiting + 1 };
        if *without_waiting < MOST_ROUNDS_WITHOUT_WAITING {
            return false;
        }
        scheduled.halt_all(&format!(
            "{MOST_ROUNDS_WITHOUT_WAITING} rounds fired one after another with no wait: the machines go round a cycle that takes no time, so time cannot pass"
        ));
        true
    }

    /// One round: commands from outside obeyed, then a ringlet of every running machine in
    /// order, each followed by the commands it posted. Whether a machine fired or was started
    /// (either way the next round has work at once).
    async fn play_round(
        &self,
        scheduled: &mut ScheduledMachines<'_>,
        round: u64,
        commanded: bool,
        board: &Whiteboard,
    ) -> bool {
        // One moment for the whole round: machines entered in one round time their `timeout`s
        // from the same instant, so they come due in the same round.
        let mut round_time = tokio::time::Instant::now();
        if let (Some(suppressor), Some(first)) = (&scheduled.suppressor, scheduled.runs.first()) {
            take_over(suppressor, first, round_time, board);
        }
        scheduled.fresh.fill(false);
        scheduled.obey_commands(board, commanded, Moment::BeforeRound);
        let mut fired = false;
        // The ringlet under way, recorded once it has run (with its snapshot).
        let mut began: Option<Underway> = None;
        for machine in 0..scheduled.runs.len() {
            let run = &mut scheduled.runs[machine];
            if scheduled.over[machine]
                || scheduled.fresh[machine]
                || run.status != Status::Running
                || run.is_done()
            {
                continue;
            }
            if self.feed().is_none() {
                // Gone live after a feed: its queries are the machine's own now.
                run.query_hook = None;
            }
            if self.feed().is_some() || self.ticks.is_some() {
                let ringlet = Ringlet {
                    round,
                    machine,
                    seq: board.snapshot().seq,
                    at: round_time.saturating_duration_since(run.reporter.epoch),
                    snapshot: None,
                };
                let ringlet = self
                    .before_ringlet(run, ringlet, &mut round_time, board)
                    .await;
                began = (self.ticks.clone()).map(|ticks| Underway {
                    ticks,
                    ringlet: Some(ringlet),
                });
            }
            run.round_time = Some(round_time);
            if let Some(suppressor) = &scheduled.suppressor {
                take_over(suppressor, run, round_time, board);
            }
            let span = tracing::info_span!("machine", name = %run.name);
            let ring = tracing::Instrument::instrument(run.ring(), span).await;
            if let Some(underway) = began.take() {
                underway.ran(run.seen.seq());
            }
            // Between rounds, waits are reckoned from the clock.
            run.round_time = None;
            match ring {
                RingOutcome::Moved => fired = true,
                RingOutcome::Stayed => {}
                RingOutcome::Over => scheduled.over[machine] = true,
            }
            // A command posted in the ringlet takes effect at once: a machine stopped later in
            // the round does not ring, one started rings from the next round.
            scheduled.obey_commands(board, false, Moment::MidRound);
        }
        // Commands from outside during the round take effect before anything else looks.
        scheduled.obey_commands(board, false, Moment::MidRound);
        fired || scheduled.fresh.iter().any(|f| *f)
    }

    /// Before a ringlet, under a feed or a recording: the feed posts what came before it and
    /// moves the round to its recorded moment, and hears of the ringlet's queries. The ringlet
    /// as the recording will hear of it once it has run.
    async fn before_ringlet(
        &self,
        run: &mut RunningMachine<'_>,
        ringlet: Ringlet,
        round_time: &mut tokio::time::Instant,
        board: &Whiteboard,
    ) -> Ringlet {
        if let Some(feed) = self.feed() {
            let wait = feed.lock().before(ringlet, board);
            if let Some(at) = wait {
                *round_time = run.reporter.epoch + at;
                tokio::time::sleep_until(*round_time).await;
            }
            run.query_hook = Some(QueryHook {
                feed: feed.clone(),
                ringlet,
            });
        }
        // What the feed posted counts as before the ringlet too, and it rings at the moment
        // the feed moved it to.
        Ringlet {
            seq: board.snapshot().seq,
            at: round_time.saturating_duration_since(run.reporter.epoch),
            ..ringlet
        }
    }
}

impl<'r> ScheduledMachines<'r> {
    /// `runs` in schedule order, hearing their control commands from now on.
    fn new(
        runs: Vec<RunningMachine<'r>>,
        board: &Whiteboard,
        suppressor: Option<SharedSuppressor>,
    ) -> ScheduledMachines<'r> {
        let names: Vec<String> = runs.iter().map(|r| r.name.clone()).collect();
        ScheduledMachines {
            over: vec![false; runs.len()],
            fresh: vec![false; runs.len()],
            runs,
            commands: board.subscribe_pattern(Pattern::Any(names)),
            suppressor,
        }
    }

    /// The schedule at the start of `round`, at `moment`, and whether that goes on from the
    /// round before's moment (after how many rounds at it).
    fn image(&mut self, round: u64, moment: Instant, (same, rounds): (bool, u64)) -> RoundsImage {
        let epoch = self.runs.first().map_or(moment, |r| r.reporter.epoch);
        let (globals, global_changes) = self
            .runs
            .first()
            .map(|r| r.shared.image())
            .unwrap_or_default();
        let machines = self.runs.iter_mut().zip(&self.over);
        let holds = self.suppressor.as_ref().map(|s| s.lock().holdings());
        RoundsImage {
            round,
            at_ns: nanos(moment.saturating_duration_since(epoch)),
            same_moment: same,
            rounds_without_waiting: rounds,
            global_changes,
            globals,
            machines: machines.map(|(run, over)| run.image(*over)).collect(),
            holds: holds.iter().flatten().map(HoldImage::of).collect(),
        }
    }

    /// Every machine where `image` (which fits them) has it.
    fn restore(&mut self, image: &RoundsImage) {
        let machines = self.runs.iter_mut().zip(&mut self.over);
        for ((run, over), kept) in machines.zip(&image.machines) {
            run.restore(kept);
            *over = kept.over;
        }
        if let Some(suppressor) = &self.suppressor {
            let holdings = image.holds.iter().map(HoldImage::holding);
            suppressor.lock().hold_as(holdings.collect());
        }
    }

    /// Halts every machine still running, saying `why`.
    fn halt_all(&mut self, why: &str) {
        for (run, over) in self.runs.iter_mut().zip(&mut self.over) {
            if !*over && run.status == Status::Running {
                run.halt(why);
                *over = true;
            }
        }
    }
}

/// The schedule's machines as it runs them.
struct ScheduledMachines<'r> {
    runs: Vec<RunningMachine<'r>>,
    /// Machines that halted (or whose state vanished): they ring no more.
    over: Vec<bool>,
    /// Machines started during this round: they ring from the next.
    fresh: Vec<bool>,
    /// Every posting to a machine's name (its control commands).
    commands: Subscription,
    /// The behaviour's suppressed types, if it declares any.
    suppressor: Option<SharedSuppressor>,
}

/// Before a ringlet, at its round's moment: every suppressed type whose hold has run out with a
/// lower-priority posting behind it gets that posting, posted again as its machine's (the same
/// moments in a replay give the same takeovers in the same rounds).
fn take_over(
    suppressor: &SharedSuppressor,
    run: &RunningMachine<'_>,
    round_time: tokio::time::Instant,
    board: &Whiteboard,
) {
    let now = round_time.saturating_duration_since(run.reporter.epoch);
    let released = suppressor.lock().release(now);
    for posting in released {
        let content = proclaim_lower::arith::text(&posting.value);
        board.post_ranked(
            &posting.module,
            &posting.ty,
            posting.value,
            posting.priority,
        );
        run.reporter.emit(|at, round| Event::TookOver {
            machine: posting.module.to_string(),
            ty: posting.ty.to_string(),
            content,
            priority: posting.priority,
            posted: posting.at,
            at,
            round,
        });
    }
}

/// Whether anything came on `subscription` (all of it taken).
fn took(subscription: &mut Subscription) -> bool {
    let mut any = false;
    while subscription.try_next().is_some() {
        any = true;
    }
    any
}

/// When control commands are obeyed: a machine they start mid-round rings from the next round.
#[derive(Clone, Copy, PartialEq, Eq)]
enum Moment {
    BeforeRound,
    MidRound,
}

impl ScheduledMachines<'_> {
    /// If a control command came since the last look (or `already` says one did), applies the
    /// commands waiting for each machine, in schedule order; mid-round, marking in `fresh` the
    /// machines they start.
    fn obey_commands(&mut self, board: &Whiteboard, already: bool, moment: Moment) {
        if !took(&mut self.commands) && !already {
            return;
        }
        for (machine, run) in self.runs.iter_mut().enumerate() {
            if self.over[machine] {
                continue;
            }
            while let Some(command) = board.latest(&run.name) {
                if run.control(&command) && moment == Moment::MidRound {
                    self.fresh[machine] = true;
                }
            }
        }
    }
}

/// Waiting between rounds: one subscription to every type a running machine's current labels
/// read (and every machine's name, for control commands), made again only when that set
/// changes.
#[derive(Default)]
struct RoundWakeup {
    types: Vec<String>,
    subscription: Option<Subscription>,
}

impl RoundWakeup {
    /// Waits for news; whether a control command came (to be obeyed before the next round).
    async fn wait(
        &mut self,
        board: &Whiteboard,
        runs: &mut [RunningMachine<'_>],
        over: &[bool],
        commands: &mut Subscription,
        release: Option<Duration>,
    ) -> bool {
        if commands.try_next().is_some() {
            return true;
        }
        let mut types: Vec<String> = Vec::new();
        let mut reads_globals = false;
        let mut due: Option<Duration> = None;
        for (run, _) in runs.iter_mut().zip(over).filter(|(_, over)| !**over) {
            if run.status != Status::Running {
                continue;
            }
            let (reads, globals) = run.reads();
            types.extend(reads.iter().cloned());
            reads_globals |= globals;
            let next = run.next_due();
            due = Some(due.map_or(next, |d| d.min(next)));
        }
        types.sort_unstable();
        types.dedup();
        if self.subscription.is_none() || types != self.types {
            self.subscription = Some(board.subscribe_pattern(Pattern::Any(types.clone())));
            self.types = types;
        }
        let Some(subscription) = self.subscription.as_mut() else {
            return false;
        };
        // What was posted during the round is judged on the board as it is now; the
        // subscription is for what comes after.
        while subscription.try_next().is_some() {}
        if missed(&board.snapshot(), runs, over) {
            return false;
        }
        let Some(first) = runs.first() else {
            return false;
        };
        let mut globals = first.globals_changed.clone();
        let changes = *globals.borrow_and_update();
        let unseen = runs
            .iter_mut()
            .zip(over)
            .filter(|(run, over)| !**over && run.status == Status::Running)
            .any(|(run, _)| run.globals_seen != changes && run.reads().1);
        if unseen {
            return false;
        }
        let mut deadline = due.map(|d| tokio::time::Instant::now() + d);
        // A hold running out with a lower posting behind it is a change of what readers see.
        if let (Some(release), Some(first)) = (release, runs.first()) {
            let at = first.reporter.epoch + release;
            deadline = Some(deadline.map_or(at, |d| d.min(at)));
        }
        let commanded = loop {
            tokio::select! {
                biased;
                _ = commands.next() => break true,
                message = subscription.next() => match message {
                    Some(m) if !is_news(&m, runs) => continue,
                    _ => break false,
                },
                _ = globals.changed(), if reads_globals => break false,
                _ = sleep_until(deadline) => return false,
            }
        };
        // News before the round was due belongs to the wait: whatever else came at its moment
        // (the rest of a script's steps, the trace's note of them) is in before the round
        // begins. News just as the round is due is the round's (the schedule settles after it
        // counts the round).
        if deadline.is_none_or(|d| tokio::time::Instant::now() < d) {
            settle(board).await;
        }
        commanded
    }
}

/// Lets every other task that is ready at this moment run, and the tasks they wake, until a
/// turn (two yields, for a task woken by one woken first) posts nothing: on the virtual clock
/// (tokio's current-thread scheduler, which runs a yielding task again only once no other task
/// is ready) that is everything due at this moment, so what arrives before a round does not
/// depend on which task the clock woke first. On the real clock a poster that never pauses must
/// not hold the round back, hence the bound.
async fn settle(board: &Whiteboard) {
    for _ in 0..SETTLE_TURNS {
        let seq = board.snapshot().seq;
        tokio::task::yield_now().await;
        tokio::task::yield_now().await;
        if board.snapshot().seq == seq {
            return;
        }
    }
}

/// How many times [`settle`] lets the others run while they keep posting.
const SETTLE_TURNS: usize = 16;

/// Whether a running machine's current labels read a type whose value on the board is not
/// what its last ringlet saw. A control command is not such a type: commands are obeyed as they
/// come (`obey_commands`), and one that changed nothing (`resume` to a machine in a final state)
/// must not start round after round at one moment.
fn missed(board: &Snapshot, runs: &mut [RunningMachine<'_>], over: &[bool]) -> bool {
    runs.iter_mut()
        .zip(over)
        .filter(|(_, over)| !**over)
        .any(|(run, _)| {
            let since = run.seen.seq().unwrap_or(0);
            if run.status != Status::Running {
                return false;
            }
            let types = run.reads().0.to_vec();
            types.iter().filter(|ty| **ty != run.name).any(|ty| {
                board
                    .newest(ty)
                    .is_some_and(|m| m.seq > since && tells(run, m))
            })
        })
}

/// Whether a posting tells some machine something its last ringlet did not see: a control
/// command, or a value of a type its current labels read that differs from the one it saw
/// (a machine posting the same value every ringlet, or an expert answering what was just
/// asked, wakes nobody).
fn is_news(message: &Message, runs: &mut [RunningMachine<'_>]) -> bool {
    runs.iter_mut().any(|run| {
        if *message.ty == *run.name {
            return true;
        }
        run.status == Status::Running
            && run.reads().0.iter().any(|t| *t == *message.ty)
            && tells(run, message)
    })
}

/// Whether a posting of a type the machine's labels read is news to it: neither the answer
/// to its own question nor the value it saw.
fn tells(run: &RunningMachine<'_>, message: &Message) -> bool {
    match run.asked.iter().find(|(atom, _)| *atom == *message.ty) {
        Some((_, answer)) => *answer != message.value.truthy(),
        None => !run.seen.saw(&message.ty, &message.value),
    }
}

async fn sleep_until(deadline: Option<tokio::time::Instant>) {
    match deadline {
        Some(at) => tokio::time::sleep_until(at).await,
        None => std::future::pending().await,
    }
}

/// A ringlet under way, on its way to the recording. It is sent once it has run, with its
/// snapshot; a run stopped inside it (Ctrl-C, the page's Stop, `--for`) drops the schedule
/// there, and it is sent then without one: the recording holds every round it holds events of,
/// so its replay plays that round too.
struct Underway {
    ticks: mpsc::UnboundedSender<Ringlet>,
    ringlet: Option<Ringlet>,
}

impl Underway {
    fn ran(mut self, snapshot: Option<u64>) {
        if let Some(ringlet) = self.ringlet.take() {
            let _ = self.ticks.send(Ringlet {
                snapshot,
                ..ringlet
            });
        }
    }
}

impl Drop for Underway {
    fn drop(&mut self) {
        if let Some(ringlet) = self.ringlet.take() {
            let _ = self.ticks.send(ringlet);
        }
    }
}
