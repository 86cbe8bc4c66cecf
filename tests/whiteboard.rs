//! The whiteboard: semantics of each kind, wake-ups without polling, many posters and
//! subscribers at once, the registry, and the query protocol's outcomes.

use proclaim_board::{Kind, ModuleDecl, Pattern, QueryOutcome, Value, Whiteboard, QUERY_TYPE};
use std::time::Duration;

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

#[tokio::test]
async fn states_replace_and_are_not_consumed() {
    let board = Whiteboard::local();
    assert!(board.latest("LEDS").is_none());
    board.post("m", "LEDS", "red");
    let second = board.post("m", "LEDS", "green");
    assert_eq!(board.latest("LEDS").unwrap().value, Value::from("green"));
    assert_eq!(board.latest("LEDS").unwrap().seq, second.seq);
    assert_eq!(board.latest("LEDS").unwrap().module.as_ref(), "m");
}

#[tokio::test]
async fn a_signal_is_consumed_by_its_first_reader() {
    let board = Whiteboard::local();
    board.declare("Placer", Kind::Signal);
    board.post("game", "Placer", "On");
    board.post("game", "Placer", "Off");
    assert_eq!(board.latest("Placer").unwrap().value, Value::from("On"));
    let off = board
        .wait_for("Placer", 0, Duration::from_millis(10))
        .await
        .unwrap();
    assert_eq!(off.value, Value::from("Off"));
    assert!(board.latest("Placer").is_none());
    assert!(board
        .wait_for("Placer", 0, Duration::from_millis(10))
        .await
        .is_none());
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn two_waiters_one_signal_exactly_one_gets_it() {
    let board = Whiteboard::local();
    board.declare("reload", Kind::Signal);
    let waiters: Vec<_> = (0..2)
        .map(|_| {
            let b = board.clone();
            tokio::spawn(async move { b.wait_for("reload", 0, Duration::from_millis(300)).await })
        })
        .collect();
    tokio::time::sleep(Duration::from_millis(20)).await;
    board.post("ops", "reload", true);
    let mut got = 0;
    for w in waiters {
        got += w.await.unwrap().is_some() as u32;
    }
    assert_eq!(got, 1);
}

#[tokio::test(start_paused = true)]
async fn data_keeps_a_bounded_history_read_by_time() {
    let board = Whiteboard::local();
    board.declare("ballDistance", Kind::Data);
    for d in [100i64, 90, 80] {
        board.post("vision", "ballDistance", d);
        tokio::time::advance(Duration::from_millis(100)).await;
    }
    // Posted at 0, 100 and 200 ms.
    let at = |ms| Duration::from_millis(ms);
    assert_eq!(board.latest("ballDistance").unwrap().value, Value::Int(80));
    assert_eq!(
        board.nearest("ballDistance", at(130)).unwrap().value,
        Value::Int(90)
    );
    assert_eq!(
        board
            .nearest_not_older("ballDistance", at(130))
            .unwrap()
            .value,
        Value::Int(80)
    );
    assert_eq!(
        board
            .nearest_not_newer("ballDistance", at(130))
            .unwrap()
            .value,
        Value::Int(90)
    );
    assert!(board.nearest_not_older("ballDistance", at(500)).is_none());
    // Older than the retention age (60 s) is forgotten.
    tokio::time::advance(Duration::from_secs(61)).await;
    board.post("vision", "ballDistance", 70i64);
    assert!(board.nearest_not_newer("ballDistance", at(250)).is_none());
}

#[tokio::test(start_paused = true)]
async fn a_waiter_is_woken_by_the_post_and_times_out_without_one() {
    let board = Whiteboard::local();
    let b = board.clone();
    let waiter =
        tokio::spawn(async move { b.wait_for("readyReceived", 0, Duration::from_secs(5)).await });
    tokio::time::sleep(Duration::from_secs(1)).await;
    let posted = board.post("gc", "readyReceived", true);
    let got = waiter.await.unwrap().unwrap();
    assert_eq!(got.seq, posted.seq);
    // Only messages after the given sequence number count.
    let started = tokio::time::Instant::now();
    assert!(board
        .wait_for("readyReceived", posted.seq, Duration::from_secs(2))
        .await
        .is_none());
    assert_eq!(started.elapsed(), Duration::from_secs(2));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn many_posters_many_subscribers_nothing_lost_order_kept() {
    let board = Whiteboard::local();
    let mut subscribers: Vec<_> = (0..10).map(|_| board.subscribe("tick*")).collect();
    let posters: Vec<_> = (0..4)
        .map(|p| {
            let b = board.clone();
            tokio::spawn(async move {
                for i in 0..500i64 {
                    b.post(&format!("poster{p}"), &format!("tick{p}"), i);
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
    for s in &mut subscribers {
        let mut last = 0;
        let mut count = 0;
        while let Some(m) = s.try_next() {
            assert!(m.seq > last, "out of order");
            last = m.seq;
            count += 1;
        }
        assert_eq!(count, 2000);
    }
    assert_eq!(board.stats().posts, 2000);
    assert_eq!(board.stats().drops, 0);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn no_lost_wake_ups_under_concurrent_posts() {
    // A waiter that always asks for "anything after what I saw" must see the final value, however
    // the posts interleave with its checks.
    let board = Whiteboard::local();
    let b = board.clone();
    let reader = tokio::spawn(async move {
        let mut seen = 0u64;
        loop {
            match b.wait_for("counter", seen, Duration::from_secs(5)).await {
                Some(m) if m.value == Value::Int(9_999) => return true,
                Some(m) => seen = m.seq,
                None => return false,
            }
        }
    });
    for i in 0..10_000i64 {
        board.post("w", "counter", i);
    }
    assert!(reader.await.unwrap(), "the waiter missed the last post");
}

#[test]
fn patterns() {
    assert!(Pattern::parse("*Received").matches("readyReceived"));
    assert!(!Pattern::parse("*Received").matches("readyReceivedX"));
    assert!(Pattern::parse("UDP*KickOff").matches("UDPsaysBlueKickOff"));
    assert!(Pattern::parse("*").matches("anything"));
    assert!(!Pattern::parse("LEDS").matches("LEDS2"));
}

#[tokio::test(start_paused = true)]
async fn queries_are_answered_time_out_or_find_no_expert() {
    let board = Whiteboard::local();
    // Nobody answers: false at once, never a hang.
    assert_eq!(
        board
            .query("machine", "readyReceived", Duration::from_secs(1))
            .await,
        QueryOutcome::NoExpert
    );
    board.register(
        ModuleDecl::new("gc")
            .answers(["readyReceived", "setReceived"])
            .posts(["readyReceived"]),
    );
    board.register(ModuleDecl::new("machine").waits_on(["readyReceived"]));
    assert_eq!(board.registry().answerers("readyReceived"), ["gc"]);
    assert_eq!(board.registry().listeners("readyReceived"), ["machine"]);
    // An expert that answers queries.
    let expert = board.clone();
    let mut queries = board.subscribe(QUERY_TYPE);
    tokio::spawn(async move {
        while let Some(q) = queries.next().await {
            if q.value == Value::from("readyReceived") {
                expert.post("gc", "readyReceived", true);
            }
        }
    });
    let answer = board
        .query("machine", "readyReceived", Duration::from_secs(1))
        .await;
    assert!(
        matches!(&answer, QueryOutcome::Answered { value: true, by, .. } if by.as_ref() == "gc"),
        "{answer:?}"
    );
    // A registered expert that stays silent: the label times out as false.
    let outcome = board
        .query("machine", "setReceived", Duration::from_millis(200))
        .await;
    assert_eq!(outcome, QueryOutcome::TimedOut);
    assert!(!outcome.truth());
    let stats = board.stats();
    assert_eq!(
        (stats.queries, stats.timeouts, stats.unanswerable),
        (3, 1, 1)
    );
}

#[tokio::test]
async fn dropped_subscriptions_do_not_pile_up() {
    // A machine re-subscribes on every state change; dropped subscriptions to types nobody posts
    // to must not accumulate (every post walks the list).
    let board = Whiteboard::local();
    let mut kept = board.subscribe("kept");
    for _ in 0..100_000 {
        drop(board.subscribe("never_posted"));
    }
    assert!(
        board.stats().subscribers <= 256,
        "{} subscriptions held",
        board.stats().subscribers
    );
    board.post("m", "kept", 1i64);
    assert!(
        kept.try_next().is_some(),
        "live subscriptions survive pruning"
    );
}

#[tokio::test]
async fn a_command_posted_before_its_type_is_a_signal_is_kept() {
    let board = Whiteboard::local();
    board.post("parent", "Child", "On");
    board.declare("Child", Kind::Signal);
    assert_eq!(board.latest("Child").unwrap().value, Value::from("On"));
    assert!(board.latest("Child").is_none(), "consumed once");
}
