//! A team of three striker robots on a network that fails (docs/spec/behaviour.md §1.1, "Roles
//! under partition"): each robot is a `proclaim run` of `machines/striker` in a network
//! namespace of its own, its vision a machine posting its ball distance and a tick every 100 ms,
//! every robot losing 10% of what it receives. The closest robot's link is cut, then healed; then
//! it is killed and started again. What is measured: how long two robots strike at once, how
//! long none does, how soon the others see the cut robot gone (its types stale) and hear it again
//! after the heal, and which of its ticks the others missed while its link worked.
//!
//! Needs root, `ip` and `nft` (CI installs nftables); elsewhere it says why and checks nothing.

#[path = "partition/lan.rs"]
mod lan;

use lan::Lan;
use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Stdio};
use std::sync::{Arc, Mutex};
use std::time::{Duration, SystemTime};

/// The lease every robot runs with (`--lease`): how soon a robot that hears nothing of another
/// counts it gone.
const LEASE: Duration = Duration::from_millis(1500);
/// The design's bound (spec §1.1): after a cut begins, a robot cut off can strike beside its
/// successor for at most this long (its lease, then one round).
const BOUND: Duration = Duration::from_secs(2);
/// A handover (a nearer robot heard again) may show two strikers, or none, for as long as a
/// message takes between them.
const HANDOVER: Duration = Duration::from_millis(100);
/// After a cut heals, the others hear the cut robot again within this: each end of a pair
/// dials the other every 100 ms with a fresh connection (`--peer`), so the link is back
/// within a dial or two of working, and the cut robot's token and values follow it. (After a
/// cut shorter than the lease the links close only when the lease runs out, after the heal,
/// and part of this goes on that wait.)
const HEAL: Duration = Duration::from_secs(1);
/// The team is never without a striker for longer, at a cut (the two sides' leases end up to
/// a keep-alive apart) or a restart.
const LEADERLESS: Duration = Duration::from_millis(500);
/// How far each robot is from the ball: robot1 is the striker while it can be.
const DISTANCES: [&str; 3] = ["0.8", "1.5", "2.5"];
/// How long a test waits for the team to settle on a striker.
const SETTLE: Duration = Duration::from_secs(20);

/// A robot's vision: its ball distance, then a tick counting up every 100 ms.
fn vision(distance: &str) -> String {
    format!(
        "machine Vision\ninitial A\nstate A {{\n  entry {{\n    int n;\n    n = n + 1;\n    ballDistance: {distance}\n    post(\"tick\", n);\n  }}\n  when timeout(100000) -> B\n}}\nstate B {{\n  entry {{\n    n = n + 1;\n    post(\"tick\", n);\n  }}\n  when timeout(100000) -> A\n}}\n"
    )
}

/// Robot `i`'s behaviour: the shipped striker with a vision of its own.
fn robot_folder(i: usize) -> PathBuf {
    let striker = Path::new(env!("CARGO_MANIFEST_DIR")).join("machines/striker");
    let read = |file: &str| std::fs::read_to_string(striker.join(file)).unwrap();
    let (player, voter) = (read("Player.machine"), read("Voter.machine"));
    let manifest = format!(
        "[[machine]]\nfile = \"Player.machine\"\n\n[[machine]]\nfile = \"Voter.machine\"\n\n[[machine]]\nfile = \"Vision.machine\"\n\n[team]\nname = \"blue\"\nmember = \"robot{i}\"\nshared = [\"ballDistance\", \"role\", \"vote\", \"tick\"]\nsize = 3\n"
    );
    crate::behaviour_folder(
        &format!("partition-robot{i}"),
        &[
            ("behaviour.toml", manifest.as_str()),
            ("Player.machine", player.as_str()),
            ("Voter.machine", voter.as_str()),
            ("Vision.machine", vision(DISTANCES[i - 1]).as_str()),
        ],
    )
}

/// When each robot became striker or supporter, as its trace said (stamped when read).
type Roles = Arc<Mutex<Vec<(SystemTime, usize, bool)>>>;

/// A robot's `proclaim run`, killed when dropped.
struct Robot(Child);

impl Robot {
    /// Stops the robot as Ctrl-C would, so its record is whole.
    fn stop(mut self) {
        let pid = self.0.id().to_string();
        let _ = std::process::Command::new("kill")
            .args(["-INT", &pid])
            .status();
        let deadline = std::time::Instant::now() + Duration::from_secs(10);
        while std::time::Instant::now() < deadline {
            if let Ok(Some(_)) = self.0.try_wait() {
                return;
            }
            std::thread::sleep(Duration::from_millis(50));
        }
    }
}

impl Drop for Robot {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// Starts robot `i` in its host, recording its board to `record`; its role changes go to
/// `roles`.
fn start(lan: &Lan, i: usize, folder: &Path, record: &Path, roles: &Roles) -> Robot {
    let endpoint = |i: usize| format!("tcp/{}:7447", lan.address(i));
    let mut command = lan.command(i, env!("CARGO_BIN_EXE_proclaim"));
    command.args(["run", folder.to_str().unwrap(), "--for", "300s"]);
    command.args(["--lease", &format!("{}ms", LEASE.as_millis())]);
    command.args(["--record", record.to_str().unwrap()]);
    command.args(["--listen", &endpoint(i)]);
    for peer in 1..=3 {
        command.args(["--peer", &endpoint(peer)]);
    }
    let mut child = command
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("the binary runs");
    let out = child.stdout.take().unwrap();
    let roles = Arc::clone(roles);
    std::thread::spawn(move || {
        for line in BufReader::new(out).lines().map_while(Result::ok) {
            if let Some((_, to)) = line.split_once("Player  → ") {
                let striker = to.trim() == "STRIKER";
                roles.lock().unwrap().push((SystemTime::now(), i, striker));
            }
        }
    });
    Robot(child)
}

/// Who strikes, over time: each change of the set of strikers.
fn strikers(roles: &Roles) -> Vec<(SystemTime, Vec<usize>)> {
    let mut now = [false; 4];
    let mut out = Vec::new();
    for &(at, i, striker) in roles.lock().unwrap().iter() {
        now[i] = striker;
        out.push((at, (1..=3).filter(|&r| now[r]).collect()));
    }
    out
}

/// The intervals in `[from, to)` during which `count` says yes of the set of strikers.
fn intervals(
    timeline: &[(SystemTime, Vec<usize>)],
    from: SystemTime,
    to: SystemTime,
    count: impl Fn(usize) -> bool,
) -> Vec<(SystemTime, Duration)> {
    let mut out = Vec::new();
    let mut open: Option<SystemTime> = None;
    let mut state = timeline
        .iter()
        .take_while(|(at, _)| *at <= from)
        .last()
        .map_or(0, |(_, s)| s.len());
    let mut changes: Vec<(SystemTime, usize)> = vec![(from, state)];
    changes.extend(
        timeline
            .iter()
            .filter(|(at, _)| *at > from && *at < to)
            .map(|(at, s)| (*at, s.len())),
    );
    for (at, n) in changes {
        state = n;
        match (open, count(state)) {
            (None, true) => open = Some(at),
            (Some(start), false) => {
                out.push((start, at.duration_since(start).unwrap_or_default()));
                open = None;
            }
            _ => {}
        }
    }
    if let Some(start) = open {
        out.push((start, to.duration_since(start).unwrap_or_default()));
    }
    out
}

/// One whiteboard message of a `--record` file.
struct Recorded {
    at: SystemTime,
    ty: String,
    value: serde_json::Value,
}

fn recorded(path: &Path) -> Vec<Recorded> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    text.lines()
        .filter_map(|line| {
            let v: serde_json::Value = serde_json::from_str(line).ok()?;
            let at = SystemTime::UNIX_EPOCH + Duration::from_micros(v.get("at_us")?.as_u64()?);
            Some(Recorded {
                at,
                ty: v.get("type")?.as_str()?.to_string(),
                value: v.get("value")?.clone(),
            })
        })
        .collect()
}

/// The first time after `from` that `record` says `ty` is `value`.
fn first(
    record: &[Recorded],
    from: SystemTime,
    ty: &str,
    value: serde_json::Value,
) -> Option<SystemTime> {
    record
        .iter()
        .find(|r| r.at >= from && r.ty == ty && r.value == value)
        .map(|r| r.at)
}

/// Waits until robot1 alone strikes, for `settle` at most.
fn wait_for_robot1(roles: &Roles, settle: Duration) {
    let deadline = std::time::Instant::now() + settle;
    while std::time::Instant::now() < deadline {
        if strikers(roles).last().is_some_and(|(_, s)| s == &[1]) {
            std::thread::sleep(Duration::from_millis(500));
            if strikers(roles).last().is_some_and(|(_, s)| s == &[1]) {
                return;
            }
        }
        std::thread::sleep(Duration::from_millis(50));
    }
    panic!("robot1 never struck alone: {:?}", strikers(roles));
}

fn ms(d: Duration) -> u128 {
    d.as_millis()
}

/// What one run measured.
#[derive(Debug, Default)]
struct Figures {
    /// Cut begins → each of robot2's and robot3's `robot1.tickStale` and robot1's stepping
    /// down, those seen before a lease after the heal (none for a cut shorter than the lease).
    detect: Vec<Duration>,
    /// The longest time with two strikers or more before the heal, and when it began after the
    /// cut.
    overlap: Duration,
    overlap_after_cut: Duration,
    /// The longest time with two strikers or more from the heal to the crash: measured, not
    /// bounded (spec §1.1: while links come back one at a time, two robots can each hear a
    /// majority).
    heal_overlap: Duration,
    /// The longest time with none, from the team's first settling to the heal.
    leaderless: Duration,
    /// Heal → both others hear robot1 again (`robot1.tickStale` false), and robot1 hears both
    /// of them again, each side counting those it saw go.
    heal: Option<Duration>,
    /// robot1's ticks robot2 missed while robot1's link worked, from the team's settling.
    lost: usize,
    /// The time with no striker after robot1 was killed: its teammates see the crash when its
    /// links close, or, if the kernel's reset was lost, when its lease ends.
    crash_leaderless: Duration,
    /// The longest time with no striker, and with two or more, after robot1 restarted (the
    /// overlap measured, not bounded, as `heal_overlap`).
    restart_leaderless: Duration,
    restart_overlap: Duration,
}

/// When each step of a run happened.
struct Moments {
    settled: SystemTime,
    cut_at: SystemTime,
    heal_at: SystemTime,
    kill_at: SystemTime,
    restart_at: SystemTime,
    end: SystemTime,
}

/// One run: three robots at 10% loss, robot1 cut for `cut`, healed, then killed and restarted.
/// `Err` says the robots had not all linked to each other before the cut, so the run measured
/// nothing.
fn run_team(lan: &Lan, cut: Duration) -> Result<Figures, String> {
    let roles: Roles = Arc::default();
    let folders: Vec<PathBuf> = (1..=3).map(robot_folder).collect();
    let at = play(lan, cut, &roles, &folders);
    let timeline = strikers(&roles);
    let mut figures = Figures::default();
    strikers_over_time(&timeline, &at, &mut figures);
    let records: Vec<Vec<Recorded>> = (1..=3)
        .map(|i| recorded(&folders[i - 1].join("record0.jsonl")))
        .collect();
    heard_over_time(&records, &timeline, &at, &mut figures)?;
    Ok(figures)
}

/// Starts the robots, cuts robot1 off, heals it, kills it and starts it again.
fn play(lan: &Lan, cut: Duration, roles: &Roles, folders: &[PathBuf]) -> Moments {
    let record = |i: usize, n: usize| folders[i - 1].join(format!("record{n}.jsonl"));
    for i in 1..=3 {
        lan.lose(i, 10).unwrap();
    }
    let mut robots: Vec<Robot> = Vec::new();
    for i in 1..=3 {
        robots.push(start(lan, i, &folders[i - 1], &record(i, 0), roles));
        if i == 1 {
            std::thread::sleep(Duration::from_millis(500));
        }
    }
    wait_for_robot1(roles, SETTLE);
    let settled = SystemTime::now();
    std::thread::sleep(Duration::from_secs(2));

    let cut_at = SystemTime::now();
    lan.cut(1).unwrap();
    std::thread::sleep(cut);
    let heal_at = SystemTime::now();
    lan.lose(1, 10).unwrap();
    // Every link must have come back before the crash, for the heal to be measured: robot1 may
    // strike again (its voters back) while one teammate still does not hear it.
    std::thread::sleep(HEAL);
    wait_for_robot1(roles, SETTLE);

    let kill_at = SystemTime::now();
    drop(robots.remove(0));
    roles.lock().unwrap().push((SystemTime::now(), 1, false));
    std::thread::sleep(Duration::from_secs(2));
    let restart_at = SystemTime::now();
    robots.insert(0, start(lan, 1, &folders[0], &record(1, 1), roles));
    wait_for_robot1(roles, SETTLE);
    std::thread::sleep(Duration::from_secs(1));
    let end = SystemTime::now();
    for robot in robots {
        robot.stop();
    }
    Moments {
        settled,
        cut_at,
        heal_at,
        kill_at,
        restart_at,
        end,
    }
}

/// Two strikers and none, from each robot's trace.
fn strikers_over_time(timeline: &[(SystemTime, Vec<usize>)], at: &Moments, figures: &mut Figures) {
    let Moments {
        settled,
        cut_at,
        heal_at,
        kill_at,
        restart_at,
        end,
    } = *at;
    for (at, s) in timeline {
        let since = |t: SystemTime| at.duration_since(t).map_or(-1.0, |d| d.as_secs_f64());
        eprintln!(
            "{:>8.3} s after the cut, {:>8.3} s after the kill: strikers {s:?}",
            since(cut_at),
            since(kill_at)
        );
    }
    let longest = |v: Vec<(SystemTime, Duration)>| v.into_iter().max_by_key(|(_, d)| *d);
    if let Some((start, d)) = longest(intervals(timeline, settled, heal_at, |n| n >= 2)) {
        figures.overlap = d;
        figures.overlap_after_cut = start.duration_since(cut_at).unwrap_or_default();
    }
    figures.heal_overlap = longest(intervals(timeline, heal_at, kill_at, |n| n >= 2))
        .map_or(Duration::ZERO, |(_, d)| d);
    figures.leaderless = longest(intervals(timeline, settled, heal_at, |n| n == 0))
        .map_or(Duration::ZERO, |(_, d)| d);
    let none = |from, to| longest(intervals(timeline, from, to, |n| n == 0));
    figures.crash_leaderless = none(kill_at, restart_at).map_or(Duration::ZERO, |(_, d)| d);
    figures.restart_leaderless = none(restart_at, end).map_or(Duration::ZERO, |(_, d)| d);
    figures.restart_overlap =
        longest(intervals(timeline, kill_at, end, |n| n >= 2)).map_or(Duration::ZERO, |(_, d)| d);
}

/// Seen gone, heard again and ticks lost, from the robots' records.
fn heard_over_time(
    records: &[Vec<Recorded>],
    timeline: &[(SystemTime, Vec<usize>)],
    at: &Moments,
    figures: &mut Figures,
) -> Result<(), String> {
    let Moments {
        settled,
        cut_at,
        heal_at,
        kill_at,
        ..
    } = *at;
    for (i, j) in [(2, 3), (3, 2)] {
        let heard = format!("robot{j}.tick");
        if !records[i - 1]
            .iter()
            .any(|r| r.at < cut_at && r.ty == heard)
        {
            return Err(format!("robot{i} never heard robot{j} before the cut"));
        }
    }
    let seen_until = (heal_at + LEASE).min(kill_at);
    let before = |at: Option<SystemTime>| at.filter(|at| *at < seen_until);
    let gone = |i: usize, ty: &str| before(first(&records[i - 1], cut_at, ty, true.into()));
    // robot1's own step down is read from its trace, where it is said as it happens.
    let stepped_down = timeline
        .iter()
        .find(|(at, s)| *at >= cut_at && !s.contains(&1))
        .map(|(at, _)| *at)
        .filter(|at| *at < seen_until);
    let seen = [
        gone(2, "robot1.tickStale"),
        gone(3, "robot1.tickStale"),
        stepped_down,
    ];
    figures.detect = seen
        .iter()
        .flatten()
        .map(|at| at.duration_since(cut_at).unwrap_or_default())
        .collect();
    // Of the teammates that saw robot1 go, the later to hear it again; and robot1, of the
    // teammates it saw go, the later it hears again: every value converged.
    let back = |i: usize, went: Option<SystemTime>, ty: &str| {
        let went = went?;
        let back = first(&records[i - 1], went, ty, false.into());
        Some(back.map_or(Duration::MAX, |at| {
            at.duration_since(heal_at).unwrap_or_default()
        }))
    };
    let teammates = [2, 3].iter().zip(&seen[..2]);
    let robot1 = [2, 3].map(|j| {
        let ty = format!("robot{j}.tickStale");
        (
            ty.clone(),
            before(first(&records[0], cut_at, &ty, true.into())),
        )
    });
    figures.heal = (teammates.filter_map(|(&i, went)| back(i, *went, "robot1.tickStale")))
        .chain(robot1.iter().filter_map(|(ty, went)| back(1, *went, ty)))
        .max();
    let ticks: Vec<(SystemTime, i64)> = records[1]
        .iter()
        .filter(|r| r.ty == "robot1.tick")
        .filter_map(|r| Some((r.at, r.value.as_i64()?)))
        .collect();
    for w in ticks.windows(2) {
        // From the team's settling (a joining robot's first puts can go out before its
        // teammates' subscriptions reach it) to the crash, but for the cut.
        let working = (w[0].0 > settled && w[1].0 < cut_at) || w[0].0 > heal_at + BOUND;
        if working && w[1].0 < kill_at && w[1].1 > w[0].1 + 1 {
            let at = w[1]
                .0
                .duration_since(cut_at)
                .map_or(-1.0, |d| d.as_secs_f64());
            eprintln!(
                "robot2 heard robot1's tick {} after {}, {at:.3} s after the cut",
                w[1].1, w[0].1
            );
            figures.lost += (w[1].1 - w[0].1 - 1) as usize;
        }
    }
    Ok(())
}

/// [`run_team`] again while the robots did not link (at most three times in all).
fn measured(lan: &Lan, cut: Duration) -> Figures {
    let mut why = Vec::new();
    for _ in 0..3 {
        match run_team(lan, cut) {
            Ok(figures) => return figures,
            Err(e) => {
                eprintln!("run again: {e}");
                why.push(e);
            }
        }
    }
    panic!("the robots never linked: {why:?}");
}

/// The network this machine can make, or why not: printed, and the test checks nothing,
/// except in CI (`CI` set), whose script installs what it needs, where it fails.
fn lan() -> Option<Lan> {
    match Lan::new(3) {
        Ok(lan) => Some(lan),
        Err(why) if std::env::var_os("CI").is_some() => {
            panic!("network namespaces cannot be made here: {why}")
        }
        Err(why) => {
            eprintln!("skipped: network namespaces cannot be made here: {why}");
            None
        }
    }
}

/// What the design guarantees (spec §1.1), or the first bound a run broke; `heal_overlap` and
/// `restart_overlap` are only printed.
fn check(figures: &Figures, cut: Duration) -> Result<(), String> {
    println!("cut {} ms: {figures:?}", ms(cut));
    let bounded = figures.overlap <= HANDOVER
        || (figures.overlap_after_cut <= BOUND && figures.overlap <= BOUND);
    let (overlap, after) = (ms(figures.overlap), ms(figures.overlap_after_cut));
    let mut broken = Vec::new();
    if !bounded {
        broken.push(format!(
            "two strikers for {overlap} ms, {after} ms after the cut began"
        ));
    }
    // A cut longer than the lease by a keep-alive is seen by all three within the bound. (A
    // shorter one may be seen too: TCP sends what the cut lost again only after a backoff, so
    // a 1 s cut can silence a link for 1.4 s.)
    let detect = &figures.detect;
    if cut > LEASE + LEASE / 4 && !(detect.len() == 3 && detect.iter().all(|d| *d <= BOUND)) {
        broken.push(format!("robot1 seen gone after {detect:?}"));
    }
    if figures.leaderless > LEADERLESS {
        broken.push(format!(
            "no striker for {} ms around the cut",
            ms(figures.leaderless)
        ));
    }
    if let Some(heal) = figures.heal.filter(|h| *h > HEAL) {
        broken.push(format!("robot1 heard again {} ms after the heal", ms(heal)));
    }
    if figures.lost > 0 {
        broken.push(format!(
            "robot2 missed {} ticks of robot1 while its link worked",
            figures.lost
        ));
    }
    if figures.crash_leaderless > BOUND {
        broken.push(format!(
            "no striker for {} ms after a crash",
            ms(figures.crash_leaderless)
        ));
    }
    if figures.restart_leaderless > LEADERLESS {
        broken.push(format!(
            "no striker for {} ms after a restart",
            ms(figures.restart_leaderless)
        ));
    }
    if broken.is_empty() {
        Ok(())
    } else {
        Err(broken.join("; "))
    }
}

/// One run with a 5 s cut must keep every bound. At 10% loss a run can lose what the design
/// does not bound (a crash's reset and then a lease's keep-alives): of three
/// runs one must keep them all, and each run that did not says which it broke.
#[test]
fn a_team_cut_and_restarted_keeps_one_striker() {
    let Some(lan) = lan() else { return };
    let cut = Duration::from_secs(5);
    let mut broken = Vec::new();
    for _ in 0..3 {
        match check(&measured(&lan, cut), cut) {
            Ok(()) => return,
            Err(e) => {
                eprintln!("a run broke a bound: {e}");
                broken.push(e);
            }
        }
    }
    panic!("three runs broke bounds: {broken:?}");
}

/// The figures of the note: cuts of 1, 5 and 15 s, ten runs each (about 15 minutes);
/// fails if more than one run in ten breaks a bound.
#[test]
#[ignore]
fn ten_runs_of_each_cut() {
    let Some(lan) = lan() else { return };
    let mut broken = Vec::new();
    for cut in [1, 5, 15].map(Duration::from_secs) {
        for _ in 0..10 {
            if let Err(e) = check(&measured(&lan, cut), cut) {
                eprintln!("a run broke a bound: {e}");
                broken.push(format!("cut {} ms: {e}", ms(cut)));
            }
        }
    }
    println!("{} of 30 runs broke a bound: {broken:#?}", broken.len());
    assert!(broken.len() <= 3, "{broken:#?}");
}
