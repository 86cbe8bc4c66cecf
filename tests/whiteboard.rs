//! The whiteboard: semantics of each kind, wake-ups without polling, many posters and
//! subscribers at once, the registry, and the query protocol's outcomes. One suite, run against
//! every transport: in process, and (with `--features zenoh`) a holder and two replicas joined
//! over Zenoh on loopback, where each test posts in one process and reads in another.

use proclaim_board::{Kind, ModuleDecl, Pattern, QueryOutcome, Value, Whiteboard, QUERY_TYPE};
use std::sync::atomic::{AtomicI64, Ordering};
use std::time::Duration;

/// Runs each named suite test once per transport, as its own test.
macro_rules! on_every_transport {
    ($($test:ident),* $(,)?) => {
        mod in_process {
            $(
                #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
                async fn $test() {
                    super::$test(super::Transport::InProcess).await
                }
            )*
        }
        #[cfg(feature = "zenoh")]
        mod over_zenoh {
            $(
                #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
                async fn $test() {
                    super::$test(super::Transport::Zenoh { low_latency: false }).await
                }
            )*
        }
        #[cfg(feature = "zenoh")]
        mod over_zenoh_low_latency {
            $(
                #[tokio::test(flavor = "multi_thread", worker_threads = 2)]
                async fn $test() {
                    super::$test(super::Transport::Zenoh { low_latency: true }).await
                }
            )*
        }
    };
}

on_every_transport!(
    states_replace_and_are_not_consumed,
    a_signal_is_consumed_once_by_the_process_that_declared_it,
    two_waiters_one_signal_exactly_one_gets_it,
    data_keeps_a_history_read_by_time,
    a_waiter_is_woken_by_the_post_and_times_out_without_one,
    many_posters_many_subscribers_nothing_lost_order_kept,
    no_lost_wake_ups_under_concurrent_posts,
    queries_are_answered_time_out_or_find_no_expert,
    dropped_subscriptions_do_not_pile_up,
    a_command_posted_before_its_type_is_a_signal_is_kept,
    a_snapshot_is_the_board_at_one_moment,
    a_posting_carries_its_priority_to_every_process,
);

#[derive(Clone, Copy)]
enum Transport {
    InProcess,
    #[cfg(feature = "zenoh")]
    Zenoh {
        low_latency: bool,
    },
}

/// Three handles on one whiteboard: the same board three times in process; over Zenoh, the
/// listening process and two that connect, each with its own session, socket and replica.
async fn boards(transport: Transport) -> [Whiteboard; 3] {
    match transport {
        Transport::InProcess => {
            let board = Whiteboard::local();
            [board.clone(), board.clone(), board]
        }
        #[cfg(feature = "zenoh")]
        Transport::Zenoh { low_latency } => {
            use proclaim_zenoh::{whiteboard, Role, Settings};
            let settings = Settings {
                config_file: None,
                low_latency,
                ..Settings::default()
            };
            let endpoint = crate::network::free_endpoint();
            let holder = whiteboard(&Role::Listen(endpoint.clone()), "suite", &settings)
                .await
                .expect("listens");
            let replica = Role::Connect(endpoint);
            let a = whiteboard(&replica, "suite", &settings)
                .await
                .expect("connects");
            let b = whiteboard(&replica, "suite", &settings)
                .await
                .expect("connects");
            [holder, a, b]
        }
    }
}

/// Waits until every board has seen all that `poster` posted so far: at once in process, once
/// the poster's puts reached each process over a network (a poster's postings of one type
/// arrive in order). The bound is generous, for a loaded machine draining thousands of postings
/// to ten subscribers.
async fn settle(poster: &Whiteboard, boards: &[Whiteboard]) {
    static MARK: AtomicI64 = AtomicI64::new(0);
    let mark = Value::Int(MARK.fetch_add(1, Ordering::Relaxed));
    poster.post("suite", "settled", mark.clone());
    for board in boards {
        let mut seen = 0;
        loop {
            let m = board
                .wait_for("settled", seen, Duration::from_secs(30))
                .await
                .expect("every board hears the mark within 30 s");
            if m.value == mark {
                break;
            }
            seen = m.seq;
        }
    }
}

#[test]
fn truthiness_follows_gufsm() {
    let cases: [(Value, bool); 14] = [
        (true.into(), true),
        (false.into(), false),
        (0i64.into(), false),
        ((-3i64).into(), true),
        (0.0f64.into(), false),
        ("".into(), false),
        ("no".into(), false),
        ("False".into(), false),
        ("-1".into(), false),
        ("0".into(), false),
        ("OFF".into(), false),
        ("on".into(), true),
        ("yes".into(), true),
        (Value::List(vec![]), false),
    ];
    for (value, truth) in cases {
        assert_eq!(value.truthy(), truth, "{value}");
    }
}

/// A subsumption layer's priority travels with its posting (a replica's posting goes up to
/// the holder and comes down to everyone with it); a posting that gives none has 0.
async fn a_posting_carries_its_priority_to_every_process(transport: Transport) {
    let boards = boards(transport).await;
    let [_, poster, _] = &boards;
    poster.post_ranked("Reflex", "walk", "back", 2);
    poster.post("Walk", "kick", "right");
    settle(poster, &boards).await;
    for board in &boards {
        let walk = board.latest("walk").unwrap();
        assert_eq!(
            (walk.value.clone(), walk.priority),
            (Value::from("back"), 2)
        );
        assert_eq!(board.latest("kick").unwrap().priority, 0);
        let snapshot = board.snapshot();
        assert_eq!(snapshot.newest("walk").map(|m| m.priority), Some(2));
    }
}

async fn states_replace_and_are_not_consumed(transport: Transport) {
    let boards = boards(transport).await;
    let [_, poster, reader] = &boards;
    assert!(reader.latest("LEDS").is_none());
    poster.post("m", "LEDS", "red");
    poster.post("m", "LEDS", "green");
    settle(poster, &boards).await;
    let seq = reader.latest("LEDS").unwrap().seq;
    for board in &boards {
        let led = board.latest("LEDS").unwrap();
        assert_eq!(led.value, Value::from("green"));
        assert_eq!(led.module.as_ref(), "m");
        assert_eq!(led.seq, seq, "one numbering everywhere");
    }
    assert_eq!(
        reader.latest("LEDS").unwrap().seq,
        seq,
        "reading does not consume"
    );
}

async fn a_signal_is_consumed_once_by_the_process_that_declared_it(transport: Transport) {
    let boards = boards(transport).await;
    let [holder, poster, owner] = &boards;
    owner.declare("Placer", Kind::Signal);
    settle(owner, &boards).await;
    let mut observed = holder.subscribe("Placer");
    poster.post("game", "Placer", "On");
    poster.post("game", "Placer", "Off");
    let wait = || owner.wait_for("Placer", 0, Duration::from_secs(2));
    assert_eq!(wait().await.unwrap().value, Value::from("On"));
    assert_eq!(wait().await.unwrap().value, Value::from("Off"));
    for board in &boards {
        assert!(board.latest("Placer").is_none(), "each taken once");
    }
    assert!(owner
        .wait_for("Placer", 0, Duration::from_millis(50))
        .await
        .is_none());
    // Monitors still observe signals without taking them.
    let seen = tokio::time::timeout(Duration::from_secs(2), observed.next())
        .await
        .unwrap()
        .unwrap();
    assert_eq!(seen.value, Value::from("On"));
}

async fn two_waiters_one_signal_exactly_one_gets_it(transport: Transport) {
    let boards = boards(transport).await;
    let [holder, a, b] = &boards;
    for board in [a, b] {
        board.declare("reload", Kind::Signal);
        settle(board, &boards).await;
    }
    let waiters: Vec<_> = [a, b]
        .into_iter()
        .map(|board| {
            let board = board.clone();
            tokio::spawn(async move {
                board
                    .wait_for("reload", 0, Duration::from_millis(500))
                    .await
            })
        })
        .collect();
    tokio::time::sleep(Duration::from_millis(20)).await;
    holder.post("ops", "reload", true);
    let mut got = 0;
    for w in waiters {
        got += w.await.unwrap().is_some() as u32;
    }
    assert_eq!(got, 1);
}

async fn data_keeps_a_history_read_by_time(transport: Transport) {
    let boards = boards(transport).await;
    let [_, poster, reader] = &boards;
    poster.declare("ballDistance", Kind::Data);
    settle(poster, &boards).await;
    for d in [100i64, 90, 80] {
        poster.post("vision", "ballDistance", d);
        tokio::time::sleep(Duration::from_millis(40)).await;
    }
    settle(poster, &boards).await;
    // When each was posted, by the board's clock (the holder's, in every process).
    let first = reader
        .nearest_not_older("ballDistance", Duration::ZERO)
        .unwrap();
    let second = reader
        .nearest_not_older("ballDistance", first.time + Duration::from_micros(1))
        .unwrap();
    assert_eq!(
        (first.value.clone(), second.value.clone()),
        (Value::Int(100), Value::Int(90))
    );
    let between = second.time + Duration::from_millis(10);
    for board in &boards {
        assert_eq!(board.latest("ballDistance").unwrap().value, Value::Int(80));
        assert_eq!(
            board.nearest("ballDistance", between).unwrap().value,
            Value::Int(90)
        );
        assert_eq!(
            board
                .nearest_not_older("ballDistance", between)
                .unwrap()
                .value,
            Value::Int(80)
        );
        assert_eq!(
            board
                .nearest_not_newer("ballDistance", between)
                .unwrap()
                .value,
            Value::Int(90)
        );
        assert!(board
            .nearest_not_older("ballDistance", second.time + Duration::from_secs(5))
            .is_none());
        let here = board
            .nearest_not_older("ballDistance", Duration::ZERO)
            .unwrap();
        assert_eq!((here.seq, here.time), (first.seq, first.time), "one clock");
    }
}

async fn a_waiter_is_woken_by_the_post_and_times_out_without_one(transport: Transport) {
    let boards = boards(transport).await;
    let [_, poster, reader] = &boards;
    let r = reader.clone();
    let waiter =
        tokio::spawn(async move { r.wait_for("readyReceived", 0, Duration::from_secs(5)).await });
    tokio::time::sleep(Duration::from_millis(50)).await;
    poster.post("gc", "readyReceived", true);
    let got = waiter.await.unwrap().expect("woken by the post");
    assert_eq!(got.value, Value::Bool(true));
    // Only messages after the given sequence number count.
    let started = std::time::Instant::now();
    assert!(reader
        .wait_for("readyReceived", got.seq, Duration::from_millis(300))
        .await
        .is_none());
    assert!(started.elapsed() >= Duration::from_millis(300));
}

async fn many_posters_many_subscribers_nothing_lost_order_kept(transport: Transport) {
    let boards = boards(transport).await;
    let reader = &boards[2];
    let mut subscribers: Vec<_> = (0..10).map(|_| reader.subscribe("tick*")).collect();
    let posters: Vec<_> = (0..4)
        .map(|p| {
            let board = boards[p % 3].clone();
            tokio::spawn(async move {
                for i in 0..500i64 {
                    board.post(&format!("poster{p}"), &format!("tick{p}"), i);
                    if i % 50 == 0 {
                        tokio::task::yield_now().await;
                    }
                }
            })
        })
        .collect();
    for p in posters {
        p.await.unwrap();
    }
    for poster in &boards {
        settle(poster, &boards).await;
    }
    for s in &mut subscribers {
        let mut last_seq = 0;
        let mut last_of_poster = [-1i64; 4];
        let mut count = 0;
        while let Some(m) = s.try_next() {
            assert!(m.seq > last_seq, "out of order");
            last_seq = m.seq;
            let p: usize = m.ty[4..].parse().unwrap();
            let Value::Int(i) = m.value else {
                panic!("{m:?}")
            };
            assert_eq!(i, last_of_poster[p] + 1, "each poster's order");
            last_of_poster[p] = i;
            count += 1;
        }
        assert_eq!(count, 2000);
    }
    assert_eq!(reader.stats().drops, 0);
}

async fn no_lost_wake_ups_under_concurrent_posts(transport: Transport) {
    // A waiter that always asks for "anything after what I saw" must see the final value, however
    // the posts interleave with its checks.
    let [_holder, poster, reader] = boards(transport).await;
    let waiter = tokio::spawn(async move {
        let mut seen = 0u64;
        loop {
            match reader
                .wait_for("counter", seen, Duration::from_secs(20))
                .await
            {
                Some(m) if m.value == Value::Int(9_999) => return Ok(()),
                Some(m) => seen = m.seq,
                None => return Err(reader.latest("counter")),
            }
        }
    });
    for i in 0..10_000i64 {
        poster.post("w", "counter", i);
    }
    if let Err(last) = waiter.await.unwrap() {
        panic!("the waiter missed the last post; it saw {last:?}");
    }
}

async fn queries_are_answered_time_out_or_find_no_expert(transport: Transport) {
    let boards = boards(transport).await;
    let [_, expert, machine] = &boards;
    // Nobody answers: false at once, never a hang.
    assert_eq!(
        machine
            .query("machine", "readyReceived", Duration::from_secs(1))
            .await,
        QueryOutcome::NoExpert
    );
    expert.register(
        ModuleDecl::new("gc")
            .answers(["readyReceived", "setReceived"])
            .posts(["readyReceived"]),
    );
    settle(expert, &boards).await;
    machine.register(ModuleDecl::new("machine").waits_on(["readyReceived"]));
    settle(machine, &boards).await;
    for board in &boards {
        assert_eq!(board.registry().answerers("readyReceived"), ["gc"]);
        assert_eq!(board.registry().listeners("readyReceived"), ["machine"]);
    }
    // An expert that answers queries, in another process than the asking machine.
    let answering = expert.clone();
    let mut queries = expert.subscribe(QUERY_TYPE);
    tokio::spawn(async move {
        while let Some(q) = queries.next().await {
            if q.value == Value::from("readyReceived") {
                answering.post("gc", "readyReceived", true);
            }
        }
    });
    let answer = machine
        .query("machine", "readyReceived", Duration::from_secs(2))
        .await;
    assert!(
        matches!(&answer, QueryOutcome::Answered { value: true, by, .. } if by.as_ref() == "gc"),
        "{answer:?}"
    );
    // A registered expert that stays silent: the label times out as false.
    let outcome = machine
        .query("machine", "setReceived", Duration::from_millis(200))
        .await;
    assert_eq!(outcome, QueryOutcome::TimedOut);
    assert!(!outcome.truth());
    let stats = machine.stats();
    assert_eq!(
        (stats.queries, stats.timeouts, stats.unanswerable),
        (3, 1, 1)
    );
}

async fn dropped_subscriptions_do_not_pile_up(transport: Transport) {
    // A machine re-subscribes on every state change; dropped subscriptions to types nobody posts
    // to must not accumulate (every post walks the list).
    let boards = boards(transport).await;
    let [_, poster, reader] = &boards;
    let mut kept = reader.subscribe("kept");
    for _ in 0..100_000 {
        drop(reader.subscribe("never_posted"));
    }
    assert!(
        reader.stats().subscribers <= 256,
        "{} subscriptions held",
        reader.stats().subscribers
    );
    poster.post("m", "kept", 1i64);
    settle(poster, &boards).await;
    assert!(
        kept.try_next().is_some(),
        "live subscriptions survive pruning"
    );
}

async fn a_command_posted_before_its_type_is_a_signal_is_kept(transport: Transport) {
    let boards = boards(transport).await;
    let [_, parent, child] = &boards;
    parent.post("parent", "Child", "On");
    settle(parent, &boards).await;
    child.declare("Child", Kind::Signal);
    let command = child.wait_for("Child", 0, Duration::from_secs(2)).await;
    assert_eq!(command.unwrap().value, Value::from("On"));
    assert!(child.latest("Child").is_none(), "consumed once");
}

async fn a_snapshot_is_the_board_at_one_moment(transport: Transport) {
    let boards = boards(transport).await;
    let [poster, _, reader] = &boards;
    reader.declare("kick", Kind::Signal);
    reader.declare("ballDistance", Kind::Data);
    settle(reader, &boards).await;
    poster.post("vision", "ballSeen", true);
    poster.post("coach", "kick", "left");
    for d in [90i64, 80, 70] {
        poster.post("vision", "ballDistance", d);
    }
    settle(poster, &boards).await;
    let before = reader.snapshot();
    poster.post("vision", "ballSeen", false);
    poster.post("vision", "ballDistance", 60i64);
    settle(poster, &boards).await;
    assert_eq!(
        reader.latest("kick").map(|m| m.value),
        Some(Value::from("left"))
    );
    let after = reader.snapshot();
    let newest = |s: &proclaim_board::Snapshot, ty: &str| s.newest(ty).map(|m| m.value.clone());
    // The earlier snapshot is untouched by what came after it.
    assert_eq!(newest(&before, "ballSeen"), Some(Value::Bool(true)));
    assert_eq!(newest(&before, "ballDistance"), Some(Value::Int(70)));
    assert_eq!(newest(&after, "ballSeen"), Some(Value::Bool(false)));
    assert_eq!(newest(&after, "ballDistance"), Some(Value::Int(60)));
    // A signal shows its last posting whether read or not; only the unread are contents.
    assert_eq!(newest(&after, "kick"), Some(Value::from("left")));
    let unread =
        |s: &proclaim_board::Snapshot| s.contents().1.iter().filter(|m| &*m.ty == "kick").count();
    assert_eq!((unread(&before), unread(&after)), (1, 0));
    assert!(after.seq > before.seq);
    let rows: Vec<(&str, u64)> = after
        .rows()
        .into_iter()
        .filter(|r| ["ballSeen", "ballDistance", "kick"].contains(&r.ty))
        .map(|r| (r.ty, r.posts))
        .collect();
    assert_eq!(rows, [("ballDistance", 4), ("ballSeen", 2), ("kick", 1)]);
}

#[tokio::test(start_paused = true)]
async fn data_older_than_the_retention_age_is_forgotten() {
    let board = Whiteboard::local();
    board.declare("ballDistance", Kind::Data);
    board.post("vision", "ballDistance", 90i64);
    // Older than the retention age (60 s) is forgotten.
    tokio::time::advance(Duration::from_secs(61)).await;
    board.post("vision", "ballDistance", 70i64);
    assert!(board
        .nearest_not_newer("ballDistance", Duration::from_secs(1))
        .is_none());
    assert_eq!(board.latest("ballDistance").unwrap().value, Value::Int(70));
}

#[test]
fn patterns() {
    assert!(Pattern::parse("*Received").matches("readyReceived"));
    assert!(!Pattern::parse("*Received").matches("readyReceivedX"));
    assert!(Pattern::parse("UDP*KickOff").matches("UDPsaysBlueKickOff"));
    assert!(Pattern::parse("*").matches("anything"));
    assert!(!Pattern::parse("LEDS").matches("LEDS2"));
}
