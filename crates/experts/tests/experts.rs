//! Experts on a live whiteboard: the reasoner expert on the microwave theory, the impersonator's
//! script, API and prompt, the GameController receiver on a real UDP socket fed by the simulator
//! and by the real capture, and the debounced button and fall wrappers.

use proclaim_board::{Whiteboard, QUERY_TYPE};
use proclaim_cdl::{load, Language};
use proclaim_experts::{
    parse_mapping, parse_script, ButtonWrapper, FallWrapper, GameControllerReceiver, Impersonator,
    ReasonerExpert, ReceiverConfig,
};
use proclaim_gcsim::{self as simulator, parse_game, SimConfig};
use std::sync::atomic::Ordering;
use std::time::Duration;

fn microwave() -> proclaim_cdl::Theory {
    let text = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../theories/microwave.dl"),
    )
    .unwrap();
    load(&text, Language::Dl).unwrap()
}

/// Every message already waiting on a subscription, as its value's text (or truth).
fn drain_text(sub: &mut proclaim_board::Subscription) -> Vec<String> {
    std::iter::from_fn(|| sub.try_next())
        .map(|m| m.value.to_string())
        .collect()
}

fn drain_truth(sub: &mut proclaim_board::Subscription) -> Vec<bool> {
    std::iter::from_fn(|| sub.try_next())
        .map(|m| m.value.truthy())
        .collect()
}

/// The value of `ty` once it is posted after `after`, or panics after a second.
async fn next_value(board: &Whiteboard, ty: &str, after: u64) -> (bool, u64) {
    let m = board
        .wait_for(ty, after, Duration::from_secs(1))
        .await
        .unwrap_or_else(|| panic!("no {ty}"));
    (m.value.truthy(), m.seq)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_reasoner_expert_follows_postings_and_answers_queries() {
    let board = Whiteboard::local();
    let expert = ReasonerExpert::new("oven", microwave(), &Default::default());
    let decl = expert.declaration();
    assert_eq!(decl.answers, ["cook", "light"]);
    assert_eq!(decl.reads, ["doorOpen", "timeLeft", QUERY_TYPE]);
    tokio::spawn(expert.run(board.clone()));
    // Inputs unknown: no cooking, no light; posted at start.
    let (cook, seq) = next_value(&board, "cook", 0).await;
    assert!(!cook);
    board.post("sensors", "doorOpen", false);
    let timer = board.post("sensors", "timeLeft", 30i64); // a number: true when non-zero
    let (cook, _) = next_value(&board, "cook", timer.seq).await;
    assert!(cook && seq < timer.seq);
    let answer = board
        .query("machine", "light", Duration::from_secs(1))
        .await;
    assert!(answer.truth(), "{answer:?}");
    let door = board.post("sensors", "doorOpen", "yes");
    let (cook, _) = next_value(&board, "cook", door.seq).await;
    assert!(!cook);
    assert!(board
        .query("machine", "light", Duration::from_secs(1))
        .await
        .truth());
    assert!(!board
        .query("machine", "cook", Duration::from_secs(1))
        .await
        .truth());
}

#[test]
fn mapping_files_rename_inputs() {
    let map =
        parse_mapping("# sensors\ndoorOpen = DoorSensor\n\ntimeLeft=Timer # seconds\n").unwrap();
    assert_eq!(map["doorOpen"], "DoorSensor");
    assert_eq!(map["timeLeft"], "Timer");
    let errors = parse_mapping("a = b\nnonsense\na = c\n").unwrap_err();
    let lines: Vec<String> = errors.iter().map(ToString::to_string).collect();
    assert_eq!(
        lines,
        [
            "line 2: expected `atom = MessageType`, found `nonsense`",
            "line 3: `a` is mapped twice"
        ]
    );
    let expert = ReasonerExpert::new("oven", microwave(), &map);
    assert_eq!(
        expert.declaration().reads,
        ["DoorSensor", "Timer", QUERY_TYPE]
    );
}

#[tokio::test(start_paused = true)]
async fn the_impersonator_answers_from_its_script() {
    let script = parse_script(
        "readyReceived = false\nat 2s readyReceived = true\nstep 2: setReceived = yes\nsetReceived = no # until the second query\n",
    )
    .unwrap();
    let board = Whiteboard::local();
    let imp = Impersonator::new("testcdl", ["playingReceived"], script);
    let handle = imp.clone();
    tokio::spawn(imp.run(board.clone()));
    tokio::task::yield_now().await;
    let t = Duration::from_millis(100);
    assert!(!board.query("m", "readyReceived", t).await.truth());
    assert!(
        board.query("m", "setReceived", t).await.truth(),
        "step 2 applies before the second answer"
    );
    tokio::time::sleep(Duration::from_secs(2)).await;
    assert!(board.query("m", "readyReceived", t).await.truth());
    // No scripted value and no person: the query times out.
    assert_eq!(
        board.query("m", "playingReceived", t).await,
        proclaim_board::QueryOutcome::TimedOut
    );
    handle.set("playingReceived", true);
    assert_eq!(
        board.truth("playingReceived"),
        Some(true),
        "posted unprompted"
    );
    assert!(board.query("m", "playingReceived", t).await.truth());
}

#[tokio::test(start_paused = true)]
async fn timed_steps_wait_until_the_machines_start_and_queries_are_answered_meanwhile() {
    let script = parse_script("readyReceived = true\nat 0ms setReceived = true\n").unwrap();
    let board = Whiteboard::local();
    let started = std::sync::Arc::new(tokio::sync::Notify::new());
    let imp =
        Impersonator::new("testcdl", Vec::<String>::new(), script).timed_after(started.clone());
    tokio::spawn(imp.run(board.clone()));
    tokio::task::yield_now().await;
    let t = Duration::from_millis(100);
    assert!(board.query("m", "readyReceived", t).await.truth());
    tokio::time::sleep(Duration::from_secs(1)).await;
    assert_eq!(
        board.truth("setReceived"),
        None,
        "held back until the machines start, however long that takes"
    );
    started.notify_one();
    eventually("the step timed for 0 ms", || {
        board.truth("setReceived") == Some(true)
    })
    .await;
}

#[test]
fn script_errors_name_their_lines() {
    let errors = parse_script(
        "at soon x = true\nstep 0: y = 1\nz true\nok = true\npenalised = maybe\nballSeen == true\nfine = Off\n",
    )
    .unwrap_err();
    let lines: Vec<String> = errors.iter().map(ToString::to_string).collect();
    assert_eq!(
        lines,
        [
            "line 1: `soon` is not a time up to 1000000000s; write `at 2s` or `at 500ms`",
            "line 2: `0` is not a step number (1, 2, …)",
            "line 3: expected `atom = value`, found `z true`",
            "line 5: `maybe` is not a value: write true or false (or yes/no, on/off, 1/0), a number, or text in double quotes (`\"maybe\"`)",
            "line 6: write `ballSeen = true`, with one `=`",
        ]
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_impersonator_asks_a_person() {
    let board = Whiteboard::local();
    let (mut person, terminal) = tokio::io::duplex(256);
    let (read, write) = tokio::io::split(terminal);
    let imp = Impersonator::new("testcdl", ["readyReceived"], Default::default())
        .with_person(tokio::io::BufReader::new(read), write);
    tokio::spawn(imp.run(board.clone()));
    eventually("registration", || {
        !board.registry().answerers("readyReceived").is_empty()
    })
    .await;
    let b = board.clone();
    let query =
        tokio::spawn(async move { b.query("m", "readyReceived", Duration::from_secs(2)).await });
    use tokio::io::{AsyncReadExt, AsyncWriteExt};
    let mut prompt = [0u8; 64];
    let n = person.read(&mut prompt).await.unwrap();
    assert_eq!(&prompt[..n], b"readyReceived? [y/n] ");
    person.write_all(b"maybe\ny\n").await.unwrap();
    assert!(query.await.unwrap().truth());
}

/// Waits (bounded) until `done` holds: robust under a loaded CI machine, quick otherwise.
async fn eventually(what: &str, done: impl Fn() -> bool) {
    let deadline = tokio::time::Instant::now() + Duration::from_secs(5);
    while !done() {
        assert!(
            tokio::time::Instant::now() < deadline,
            "timed out waiting for {what}"
        );
        tokio::time::sleep(Duration::from_millis(5)).await;
    }
}

async fn receiver(team: Option<u8>, player: u8) -> (GameControllerReceiver, std::net::SocketAddr) {
    let config = ReceiverConfig {
        bind: "127.0.0.1:0".parse().unwrap(),
        team,
        player,
        ..Default::default()
    };
    let r = GameControllerReceiver::bind(config).await.unwrap();
    let addr = r.local_addr().unwrap();
    (r, addr)
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn simulator_to_receiver_over_loopback_udp() {
    let board = Whiteboard::local();
    let (receiver, addr) = receiver(Some(18), 2).await;
    let counters = receiver.counters();
    let mut states = board.subscribe("gameState");
    let mut penalties = board.subscribe("penaltyReceived");
    tokio::spawn(receiver.run(board.clone()));
    let script = parse_game(
        "0s initial kick=18\n100ms ready\n200ms set\n300ms playing\n400ms penalty team=18 player=2 secs=1\n600ms unpenalise team=18 player=2\n800ms finished\n",
    )
    .unwrap();
    let config = SimConfig {
        to: addr,
        interval: Duration::from_millis(20),
        ..Default::default()
    };
    let sent = simulator::play(&script, &config, |_| {}).await.unwrap();
    eventually("every packet", || {
        counters.accepted.load(Ordering::Relaxed) == sent
    })
    .await;
    let seen = drain_text(&mut states);
    assert_eq!(
        seen,
        [
            "\"INITIAL\"",
            "\"READY\"",
            "\"SET\"",
            "\"PLAYING\"",
            "\"FINISHED\""
        ]
    );
    let penalty = drain_truth(&mut penalties);
    assert_eq!(penalty, [false, true, false]);
    assert_eq!(board.truth("weKickOff"), Some(true));
    assert_eq!(
        board.truth("UDPsaysBlueKickOff"),
        Some(true),
        "the simulator's home team wears blue"
    );
    assert_eq!(board.truth("finishedReceived"), Some(true));
    // A machine asks: the receiver answers queries with its current values, unchanged or not.
    let asked = board
        .query("machine", "finishedReceived", Duration::from_secs(1))
        .await;
    assert!(
        matches!(&asked, proclaim_board::QueryOutcome::Answered { value: true, by, .. } if by.as_ref() == "gamecontroller"),
        "{asked:?}"
    );
    let asked = board
        .query("machine", "readyReceived", Duration::from_secs(1))
        .await;
    assert!(
        matches!(
            asked,
            proclaim_board::QueryOutcome::Answered { value: false, .. }
        ),
        "{asked:?}"
    );
    assert!(board.registry().answerers("readyReceived") == ["gamecontroller"]);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn malformed_and_foreign_packets_are_counted_and_ignored() {
    let board = Whiteboard::local();
    let (receiver, addr) = receiver(Some(18), 1).await;
    let counters = receiver.counters();
    tokio::spawn(receiver.run(board.clone()));
    let socket = tokio::net::UdpSocket::bind("127.0.0.1:0").await.unwrap();
    let good = proclaim_gamecontroller::encode(&simulator::initial_packet(&SimConfig::default()));
    let mut wrong_version = good.clone();
    wrong_version[4] = 19;
    let mut wrong_header = good.clone();
    wrong_header[0] = b'X';
    let foreign = proclaim_gamecontroller::encode(&simulator::initial_packet(&SimConfig {
        home: 30,
        away: 31,
        ..Default::default()
    }));
    let mut garbage = vec![0u8; 700];
    for (i, b) in garbage.iter_mut().enumerate() {
        *b = (i * 37 % 251) as u8;
    }
    for datagram in [
        &good[..5],
        &good[..117],
        &wrong_version[..],
        &wrong_header[..],
        &foreign[..],
        &garbage[..],
        &good[..],
    ] {
        socket.send_to(datagram, addr).await.unwrap();
    }
    // The receiver counts a datagram before it posts what it means: wait for both.
    eventually("seven datagrams, the good one posted", || {
        counters.received.load(Ordering::Relaxed) == 7 && board.truth("initialReceived").is_some()
    })
    .await;
    let load = |c: &std::sync::atomic::AtomicU64| c.load(Ordering::Relaxed);
    assert_eq!(load(&counters.received), 7);
    assert_eq!(load(&counters.wrong_length), 2);
    assert_eq!(load(&counters.wrong_version), 1);
    assert_eq!(
        load(&counters.wrong_header),
        2,
        "garbage has no RGme header"
    );
    assert_eq!(load(&counters.other_team), 1);
    assert_eq!(load(&counters.accepted), 1);
    assert_eq!(counters.ignored(), 6);
    assert_eq!(
        board.truth("initialReceived"),
        Some(true),
        "the good packet still got through"
    );
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_real_capture_over_udp() {
    let Some(dir) = corpus_dir() else {
        eprintln!("skipped: ../shared/corpus is absent");
        return;
    };
    let text = std::fs::read_to_string(dir.join("gamecontroller/gc3-capture.hex")).unwrap();
    let board = Whiteboard::local();
    let (receiver, addr) = receiver(Some(5), 2).await;
    let counters = receiver.counters();
    let mut states = board.subscribe("gameState");
    let mut penalties = board.subscribe("penaltyReceived");
    tokio::spawn(receiver.run(board.clone()));
    let socket = tokio::net::UdpSocket::bind("127.0.0.1:0").await.unwrap();
    for line in text.lines().filter(|l| !l.trim().is_empty()) {
        let hex = line.split_whitespace().nth(1).unwrap();
        let bytes: Vec<u8> = (0..hex.len())
            .step_by(2)
            .map(|i| u8::from_str_radix(&hex[i..i + 2], 16).unwrap())
            .collect();
        socket.send_to(&bytes, addr).await.unwrap();
        tokio::time::sleep(Duration::from_millis(2)).await;
    }
    eventually("49 packets", || {
        counters.accepted.load(Ordering::Relaxed) == 49
    })
    .await;
    let seen = drain_text(&mut states);
    assert_eq!(
        seen,
        [
            "\"INITIAL\"",
            "\"STANDBY\"",
            "\"SET\"",
            "\"PLAYING\"",
            "\"FINISHED\""
        ]
    );
    let penalty = drain_truth(&mut penalties);
    assert_eq!(penalty.first(), Some(&false));
    assert!(
        penalty.contains(&true),
        "team 5's player 2 was penalised for pushing"
    );
    assert_eq!(board.truth("weKickOff"), Some(false), "team 18 kicks off");
}

#[tokio::test(start_paused = true)]
async fn a_short_chest_press_is_a_command_a_bounce_is_not() {
    let board = Whiteboard::local();
    tokio::spawn(ButtonWrapper::chest().run(board.clone()));
    let mut label = board.subscribe("shortChestButtonPressed");
    tokio::task::yield_now().await;
    let ms = |n| tokio::time::sleep(Duration::from_millis(n));
    let asked = board
        .query("machine", "shortChestButtonPressed", Duration::from_secs(1))
        .await;
    assert!(
        matches!(
            asked,
            proclaim_board::QueryOutcome::Answered { value: false, .. }
        ),
        "{asked:?}"
    );
    // A 10 ms bounce: nothing.
    board.post("sensors", "ChestButton", true);
    ms(10).await;
    board.post("sensors", "ChestButton", false);
    ms(200).await;
    // A 300 ms press with a bounce at its start: one command, cleared a second later.
    board.post("sensors", "ChestButton", true);
    ms(5).await;
    board.post("sensors", "ChestButton", false);
    ms(5).await;
    board.post("sensors", "ChestButton", true);
    ms(300).await;
    board.post("sensors", "ChestButton", false);
    ms(100).await;
    assert_eq!(board.truth("shortChestButtonPressed"), Some(true));
    ms(1500).await;
    assert_eq!(board.truth("shortChestButtonPressed"), Some(false));
    // A long press (3 s) is not a short press.
    board.post("sensors", "ChestButton", true);
    ms(3000).await;
    board.post("sensors", "ChestButton", false);
    ms(200).await;
    let values = drain_truth(&mut label);
    assert_eq!(
        values,
        [false, false, true, false],
        "initial, the answer to the query, the command, its clearing"
    );
}

#[tokio::test(start_paused = true)]
async fn a_stumble_is_not_a_fall() {
    let board = Whiteboard::local();
    tokio::spawn(FallWrapper::default().run(board.clone()));
    tokio::task::yield_now().await;
    let ms = |n| tokio::time::sleep(Duration::from_millis(n));
    board.post("imu", "FallDetected", true);
    ms(50).await;
    board.post("imu", "FallDetected", false);
    ms(300).await;
    assert_eq!(board.truth("fallen"), Some(false));
    board.post("imu", "FallDetected", 1i64);
    ms(150).await;
    assert_eq!(board.truth("fallen"), Some(true));
    let asked = board
        .query("machine", "fallen", Duration::from_secs(1))
        .await;
    assert!(
        matches!(
            asked,
            proclaim_board::QueryOutcome::Answered { value: true, .. }
        ),
        "{asked:?}"
    );
    board.post("imu", "FallDetected", 0i64);
    ms(200).await;
    assert_eq!(board.truth("fallen"), Some(true), "still getting up");
    ms(400).await;
    assert_eq!(board.truth("fallen"), Some(false));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_receiver_sends_rgrt_status_back_once_a_second() {
    let controller = tokio::net::UdpSocket::bind("127.0.0.1:0").await.unwrap();
    let status_port = controller.local_addr().unwrap().port();
    let config = ReceiverConfig {
        bind: "127.0.0.1:0".parse().unwrap(),
        team: Some(18),
        player: 3,
        send_status: true,
        status_port,
        ..Default::default()
    };
    let receiver = GameControllerReceiver::bind(config).await.unwrap();
    let addr = receiver.local_addr().unwrap();
    let counters = receiver.counters();
    let board = Whiteboard::local();
    board.post("imu", "fallen", true);
    tokio::spawn(receiver.run(board.clone()));
    let packet = proclaim_gamecontroller::encode(&simulator::initial_packet(&SimConfig::default()));
    controller.send_to(&packet, addr).await.unwrap();
    let mut buffer = [0u8; 64];
    let (len, _) = tokio::time::timeout(Duration::from_secs(3), controller.recv_from(&mut buffer))
        .await
        .expect("a status packet within a second or two")
        .unwrap();
    let status =
        proclaim_gamecontroller::StatusPacket::decode(&buffer[..len]).expect("an RGrt packet");
    assert_eq!(
        (status.team_number, status.player_number, status.fallen),
        (18, 3, true)
    );
    assert!(counters.status_sent.load(Ordering::Relaxed) >= 1);
}

/// A crossed ladder of attack cycles whose `t0` a budget of 1,000 steps leaves undecided (it
/// is true), and that budget.
fn ladder_and_a_tight_budget() -> (proclaim_cdl::Theory, proclaim_cdl::SearchLimits) {
    let theory =
        proclaim_cdl::load(&proclaim_gen::crossed_ladder(), proclaim_cdl::Language::Dl).unwrap();
    let tight = proclaim_cdl::SearchLimits {
        steps: 1000,
        ..Default::default()
    };
    (theory, tight)
}

#[test]
fn the_reasoner_expert_answers_an_undecided_label_false_and_counts_it() {
    let (theory, tight) = ladder_and_a_tight_budget();
    let mut expert =
        proclaim_experts::ReasonerExpert::new("ladder", theory.clone(), &Default::default())
            .with_limits(tight);
    let count = expert.undecided();
    assert_eq!(expert.answer("t0"), Some(false));
    assert_eq!(count.load(std::sync::atomic::Ordering::Relaxed), 1);
    assert_eq!(expert.undecided_changes(), [("t0".to_string(), true)]);
    assert_eq!(expert.answer("t0"), Some(false));
    assert!(
        expert.undecided_changes().is_empty(),
        "posted once, not per answer"
    );
    let mut roomy = proclaim_experts::ReasonerExpert::new("ladder", theory, &Default::default());
    assert_eq!(roomy.answer("t0"), Some(true));
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn an_undecided_answer_is_marked_on_the_board_before_it_is_posted() {
    let (theory, tight) = ladder_and_a_tight_budget();
    let board = Whiteboard::local();
    let expert = proclaim_experts::ReasonerExpert::new("ladder", theory, &Default::default())
        .with_limits(tight);
    tokio::spawn(expert.run(board.clone()));
    while board.registry().answerers("t0").is_empty() {
        tokio::task::yield_now().await;
    }
    let outcome = board.query("machine", "t0", Duration::from_secs(2)).await;
    assert!(
        matches!(
            outcome,
            proclaim_board::QueryOutcome::Answered { value: false, .. }
        ),
        "{outcome:?}"
    );
    assert_eq!(
        board.truth(&proclaim_board::undecided_type("t0")),
        Some(true)
    );
}

/// The shared corpus (`../shared/corpus` from the repository's root), when present beside it.
fn corpus_dir() -> Option<std::path::PathBuf> {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../../shared/corpus");
    dir.is_dir().then_some(dir)
}
