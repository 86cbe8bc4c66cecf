//! The monitor page in a real browser (Chromium driven by chromedriver over WebDriver): a live
//! `microwave` lit as it moves, stepped and posted to from the page, and a replayed trace
//! moved with its slider. Without a browser a local run skips with a message; CI never skips.

use fantoccini::{Client, ClientBuilder, Locator};
use serde_json::{json, Value as Json};
use std::io::{BufRead, BufReader};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// A child process killed when the test ends, however it ends.
pub(crate) struct Running(pub(crate) Child);

impl Drop for Running {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn on_path(program: &str) -> Option<std::path::PathBuf> {
    std::env::var_os("PATH")?
        .to_str()?
        .split(':')
        .map(|dir| std::path::Path::new(dir).join(program))
        .find(|p| p.is_file())
}

/// chromedriver and the browser, or why not (an error on CI, where `.ci/run` installs them).
fn browser() -> Option<(std::path::PathBuf, Option<std::path::PathBuf>)> {
    let driver = on_path("chromedriver");
    let chromium = ["chromium", "chromium-browser", "google-chrome"]
        .iter()
        .find_map(|b| on_path(b));
    match driver {
        Some(driver) => Some((driver, chromium)),
        None if std::env::var_os("CI").is_some() => {
            panic!("CI must test the monitor in a browser: install chromium and chromium-driver")
        }
        None => {
            eprintln!("skipped: no chromedriver on PATH (Debian: apt-get install chromium chromium-driver)");
            None
        }
    }
}

pub(crate) fn free_port() -> u16 {
    std::net::TcpListener::bind("127.0.0.1:0")
        .and_then(|l| l.local_addr())
        .map(|a| a.port())
        .expect("a free port")
}

/// Starts `proclaim ARGS` and reads its output up to the monitor's URL.
/// The microwave run for a minute with its page on a free loopback port.
fn microwave_with_monitor() -> (Running, String) {
    proclaim_with_monitor(&[
        "run",
        "microwave",
        "--monitor",
        "127.0.0.1:0",
        "--for",
        "60s",
    ])
}

pub(crate) fn proclaim_with_monitor(args: &[&str]) -> (Running, String) {
    proclaim_serving(args, "monitor: ")
}

/// Starts `proclaim ARGS` and reads its output up to the line starting `page` (after spaces),
/// whose rest is the page's URL.
pub(crate) fn proclaim_serving(args: &[&str], page: &str) -> (Running, String) {
    let mut command = Command::new(env!("CARGO_BIN_EXE_proclaim"));
    command.args(args).stderr(Stdio::inherit());
    serving(command, false, page)
}

/// Starts `command` and reads its standard output (or error, with `from_stderr`) up to the
/// line starting `page` (after spaces), whose rest is the page's URL.
pub(crate) fn serving(mut command: Command, from_stderr: bool, page: &str) -> (Running, String) {
    if from_stderr {
        command.stdout(Stdio::null()).stderr(Stdio::piped());
    } else {
        command.stdout(Stdio::piped());
    }
    let mut child = command.spawn().expect("the program starts");
    let out: Box<dyn std::io::Read + Send> = if from_stderr {
        Box::new(child.stderr.take().expect("stderr"))
    } else {
        Box::new(child.stdout.take().expect("stdout"))
    };
    let running = Running(child);
    let mut lines = BufReader::new(out).lines();
    let url = loop {
        let line = lines
            .next()
            .expect("the program printed the page's URL before ending")
            .expect("readable output");
        if let Some(url) = line.trim().strip_prefix(page) {
            break url.to_string();
        }
    };
    // Keep reading, so a full pipe never holds the run up.
    std::thread::spawn(move || for _ in lines {});
    (running, url)
}

pub(crate) async fn open_browser() -> Option<(Running, Client)> {
    let (driver, chromium) = browser()?;
    let port = free_port();
    let driver = Running(
        Command::new(driver)
            .arg(format!("--port={port}"))
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
            .expect("chromedriver starts"),
    );
    let mut options = json!({
        "args": ["--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage", "--window-size=1400,900"]
    });
    if let Some(chromium) = chromium {
        options["binary"] = json!(chromium);
    }
    let mut capabilities = serde_json::Map::new();
    capabilities.insert("goog:chromeOptions".into(), options);
    let connector = hyper_util::client::legacy::connect::HttpConnector::new();
    let deadline = Instant::now() + Duration::from_secs(20);
    loop {
        match ClientBuilder::new(connector.clone())
            .capabilities(capabilities.clone())
            .connect(&format!("http://127.0.0.1:{port}"))
            .await
        {
            Ok(client) => return Some((driver, client)),
            Err(e) if Instant::now() > deadline => {
                panic!("chromedriver did not start a browser: {e}")
            }
            Err(_) => tokio::time::sleep(Duration::from_millis(200)).await,
        }
    }
}

/// Clicks the page's element with that id, as a person would.
pub(crate) async fn click(client: &Client, id: &str) {
    let element = client
        .find(Locator::Id(id))
        .await
        .expect("the element is on the page");
    element.click().await.expect("the element takes a click");
}

/// Types `text` into the page's field with that id.
pub(crate) async fn type_into(client: &Client, id: &str, text: &str) {
    let field = client
        .find(Locator::Id(id))
        .await
        .expect("the field is on the page");
    field.send_keys(text).await.expect("the field takes typing");
}

pub(crate) async fn eval(client: &Client, script: &str) -> Json {
    client
        .execute(script, vec![])
        .await
        .expect("the script runs")
}

/// Waits until `script` returns `want`, failing with what it returned last.
pub(crate) async fn until(client: &Client, script: &str, want: Json, within: Duration) {
    let deadline = Instant::now() + within;
    loop {
        let got = eval(client, script).await;
        if got == want {
            return;
        }
        assert!(
            Instant::now() < deadline,
            "`{script}` stayed {got} instead of {want} for {within:?}"
        );
        tokio::time::sleep(Duration::from_millis(50)).await;
    }
}

pub(crate) const STATE: &str =
    "return document.querySelector('[data-machine=\"Microwave\"]')?.dataset.state ?? null";
const LIT: &str = "return document.querySelector('[data-machine=\"Microwave\"] g.node.current title')?.textContent ?? null";
const FIRED: &str = "return document.querySelector('[data-machine=\"Microwave\"] g.edge.fired title')?.textContent ?? null";

fn board_value(ty: &str) -> String {
    format!("return document.querySelector('#board tr[data-type=\"{ty}\"] td.value')?.textContent ?? null")
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_live_run_lights_its_states_steps_and_takes_postings_from_the_page() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    // The kitchen script, slower: the page is surely open before the door is, even on a
    // loaded machine.
    let script = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-monitor-{}.script", std::process::id()));
    std::fs::write(
        &script,
        "doorOpen = false\ntimeLeft = false\nat 4s doorOpen = true\nat 8s doorOpen = false\nat 10s timeLeft = true\n",
    )
    .unwrap();
    let (_run, url) = proclaim_with_monitor(&[
        "run",
        "microwave",
        "--script",
        script.to_str().unwrap(),
        "--monitor",
        "127.0.0.1:0",
        "--for",
        "90s",
    ]);
    client.goto(&url).await.expect("the page opens");
    let second = Duration::from_secs(1);
    until(&client, STATE, json!("IDLE"), 4 * second).await;
    until(&client, STATE, json!("OPEN"), 6 * second).await;
    until(&client, LIT, json!("s2"), second).await;
    until(&client, FIRED, json!("s1->s2"), second).await;
    until(&client, &board_value("doorOpen"), json!("true"), second).await;
    until(&client, STATE, json!("IDLE"), 6 * second).await;
    until(&client, STATE, json!("COOKING"), 5 * second).await;
    until(
        &client,
        "return document.querySelectorAll('#answers tbody tr').length > 0",
        json!(true),
        second,
    )
    .await;
    // README's picture: `PROCLAIM_SCREENSHOT=$PWD/docs/book/src/images/monitor.png cargo nextest run -E 'test(a_live_run)'`.
    if let Some(path) = std::env::var_os("PROCLAIM_SCREENSHOT") {
        tokio::time::sleep(Duration::from_millis(300)).await;
        std::fs::write(path, client.screenshot().await.expect("a screenshot")).expect("written");
    }

    click(&client, "pause").await;
    until(
        &client,
        "return document.getElementById('status').dataset.paused ?? null",
        json!("true"),
        2 * second,
    )
    .await;
    // Opening the door while paused: the theory sees it, the machine does not move yet.
    type_into(&client, "post-type", "doorOpen").await;
    type_into(&client, "post-value", "true").await;
    click(&client, "post-send").await;
    until(&client, &board_value("doorOpen"), json!("true"), 2 * second).await;
    tokio::time::sleep(Duration::from_millis(600)).await;
    assert_eq!(
        eval(&client, STATE).await,
        json!("COOKING"),
        "a paused machine moved"
    );
    // One ring: ~cook && light holds now.
    click(&client, "step").await;
    until(&client, STATE, json!("OPEN"), 3 * second).await;
    until(&client, FIRED, json!("s3->s2"), second).await;
    click(&client, "resume").await;
    until(
        &client,
        "return document.getElementById('status').dataset.paused ?? null",
        json!("false"),
        2 * second,
    )
    .await;
    let _ = client.close().await;
    let _ = std::fs::remove_file(&script);
}

/// `trace` replayed on a page that draws `behaviour`, open in `client`.
async fn replay_page(client: &Client, trace: &std::path::Path, behaviour: &str) -> Running {
    let trace = trace.to_str().unwrap();
    let (replay, url) = proclaim_with_monitor(&[
        "replay",
        trace,
        "--monitor",
        "127.0.0.1:0",
        "--behaviour",
        behaviour,
    ]);
    client.goto(&url).await.expect("the page opens");
    replay
}

/// The microwave behaviour run for ten virtual seconds, its trace written to a file of its own.
fn microwave_trace(tag: &str) -> std::path::PathBuf {
    behaviour_trace("microwave", "10s", tag)
}

/// A shipped behaviour run on the virtual clock for `length`, its trace written to a file of
/// its own.
fn behaviour_trace(behaviour: &str, length: &str, tag: &str) -> std::path::PathBuf {
    let trace = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "proclaim-monitor-{tag}-{}.jsonl",
        std::process::id()
    ));
    let ran = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args([
            "run",
            behaviour,
            "--virtual-clock",
            "--for",
            length,
            "--trace",
        ])
        .arg(&trace)
        .output()
        .expect("proclaim runs");
    assert!(
        ran.status.success(),
        "{}",
        String::from_utf8_lossy(&ran.stderr)
    );
    trace
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_replayed_trace_shows_any_moment_with_its_slider() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let trace = microwave_trace("slider");
    let events: Vec<Json> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    // The moment just after the machine entered OPEN and switched the light on.
    let entered = events
        .iter()
        .position(|e| e["event"] == "entered" && e["state"] == "OPEN")
        .expect("the run opened the door");
    let open = 1
        + entered
        + events[entered..]
            .iter()
            .position(|e| e["event"] == "posted" && e["type"] == "Light")
            .expect("OPEN switches the light on");
    let _replay = replay_page(&client, &trace, "microwave").await;
    let second = Duration::from_secs(1);
    // It opens at the end of the run.
    until(&client, STATE, json!("COOKING"), 5 * second).await;
    let slide = |to: usize| {
        format!("const s = document.getElementById('slider'); s.value = '{to}'; s.dispatchEvent(new Event('input')); return true")
    };
    eval(&client, &slide(open)).await;
    until(&client, STATE, json!("OPEN"), 3 * second).await;
    until(&client, LIT, json!("s2"), second).await;
    until(&client, &board_value("Light"), json!("\"on\""), second).await;
    eval(&client, &slide(0)).await;
    until(&client, STATE, json!("IDLE"), 3 * second).await;
    until(
        &client,
        "return document.querySelectorAll('#board tbody tr').length",
        json!(0),
        second,
    )
    .await;
    let _ = client.close().await;
    let _ = std::fs::remove_file(&trace);
}

/// A nested state is lit inside its composite's cluster: the keeper's dive (`machines/keeper`)
/// replayed at the moment it fell to the left.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_nested_state_is_lit_inside_its_composites_cluster() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let trace = behaviour_trace("keeper", "7s", "nested");
    let events: Vec<Json> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let left = 1 + events
        .iter()
        .position(|e| e["event"] == "entered" && e["state"] == "DIVE.LEFT")
        .expect("the keeper dived to the left");
    let _replay = replay_page(&client, &trace, "keeper").await;
    let second = Duration::from_secs(1);
    let state = "return document.querySelector('[data-machine=\"Keeper\"]')?.dataset.state ?? null";
    until(&client, state, json!("GUARD"), 5 * second).await;
    eval(
        &client,
        &format!("const s = document.getElementById('slider'); s.value = '{left}'; s.dispatchEvent(new Event('input')); return true"),
    )
    .await;
    until(&client, state, json!("DIVE.LEFT"), 3 * second).await;
    let lit_in = "const n = document.querySelector('[data-machine=\"Keeper\"] g.node.current'); \
        const c = n?.closest('svg')?.querySelector('g.cluster'); \
        return n ? [n.querySelector('title').textContent, c?.querySelector('title')?.textContent ?? null, \
        c ? c.getBBox().x <= n.getBBox().x && n.getBBox().x + n.getBBox().width <= c.getBBox().x + c.getBBox().width : null] : null";
    until(&client, lit_in, json!(["s3", "cluster_c0", true]), second).await;
    let _ = client.close().await;
    let _ = std::fs::remove_file(&trace);
}

/// A state of a parallel state's regions lights one node a region, each inside its region's
/// cluster, and a move of both regions lights both edges: the tracker (`machines/tracker`)
/// replayed at the moment its head and legs both moved on seeing the ball.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_state_of_regions_lights_a_node_in_every_region() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let trace = behaviour_trace("tracker", "5s", "regions");
    let events: Vec<Json> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let both = 1 + events
        .iter()
        .position(|e| e["event"] == "entered" && e["state"] == "PLAY.HEAD.TRACK, PLAY.LEGS.WALK")
        .expect("the head and the legs both moved");
    let _replay = replay_page(&client, &trace, "tracker").await;
    let second = Duration::from_secs(1);
    let state =
        "return document.querySelector('[data-machine=\"Striker\"]')?.dataset.state ?? null";
    // The replay opens at the run's end.
    until(&client, state, json!("CHEER"), 5 * second).await;
    eval(
        &client,
        &format!("const s = document.getElementById('slider'); s.value = '{both}'; s.dispatchEvent(new Event('input')); return true"),
    )
    .await;
    until(
        &client,
        state,
        json!("PLAY.HEAD.TRACK, PLAY.LEGS.WALK"),
        3 * second,
    )
    .await;
    // Each lit node and the label of the cluster around it: a head's state in HEAD, a leg's in LEGS.
    let lit = "return [...document.querySelectorAll('[data-machine=\"Striker\"] g.node.current')].map((n) => \
        [n.querySelector('text')?.textContent, [...n.closest('svg').querySelectorAll('g.cluster')] \
        .filter((c) => { const b = c.getBBox(), m = n.getBBox(); return b.x <= m.x && m.x + m.width <= b.x + b.width && b.y <= m.y && m.y + m.height <= b.y + b.height; }) \
        .map((c) => c.querySelector('text')?.textContent).pop()])";
    until(
        &client,
        lit,
        json!([["TRACK", "HEAD"], ["WALK", "LEGS"]]),
        second,
    )
    .await;
    let fired =
        "return [...document.querySelectorAll('[data-machine=\"Striker\"] g.edge.fired')].length";
    until(&client, fired, json!(2), second).await;
    let _ = client.close().await;
    let _ = std::fs::remove_file(&trace);
}

/// The whole goalkeeper (`machines/goalkeeper`) replayed at the moment its head braced beside
/// its dive to the left: one node lit in the head's region, and one in the dive's cluster, which
/// is itself inside the body's region.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_nested_state_in_a_region_is_lit_inside_both_clusters() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let trace = behaviour_trace("goalkeeper", "7s", "goalkeeper");
    let events: Vec<Json> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let braced = "PLAY.HEAD.BRACE, PLAY.BODY.DIVE.LEFT";
    let at = 1 + events
        .iter()
        .position(|e| e["event"] == "entered" && e["state"] == braced)
        .expect("the head braced while the keeper dived to the left");
    let _replay = replay_page(&client, &trace, "goalkeeper").await;
    let second = Duration::from_secs(1);
    let state =
        "return document.querySelector('[data-machine=\"Goalkeeper\"]')?.dataset.state ?? null";
    until(
        &client,
        state,
        json!("PLAY.HEAD.TRACK, PLAY.BODY.GUARD"),
        5 * second,
    )
    .await;
    eval(
        &client,
        &format!("const s = document.getElementById('slider'); s.value = '{at}'; s.dispatchEvent(new Event('input')); return true"),
    )
    .await;
    until(&client, state, json!(braced), 3 * second).await;
    // Each lit node and the first line of every cluster around it, outermost first.
    let lit = "return [...document.querySelectorAll('[data-machine=\"Goalkeeper\"] g.node.current')].map((n) => \
        [n.querySelector('text')?.textContent, ...[...n.closest('svg').querySelectorAll('g.cluster')] \
        .filter((c) => { const b = c.getBBox(), m = n.getBBox(); return b.x <= m.x && m.x + m.width <= b.x + b.width && b.y <= m.y && m.y + m.height <= b.y + b.height; }) \
        .map((c) => c.querySelector('text')?.textContent)])";
    until(
        &client,
        lit,
        json!([["BRACE", "PLAY", "HEAD"], ["LEFT", "PLAY", "BODY", "DIVE"]]),
        second,
    )
    .await;
    let _ = client.close().await;
    let _ = std::fs::remove_file(&trace);
}

/// A composite's transition back into itself is drawn out of its cluster to a point and in
/// again; when it fires, both halves are lit.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_composite_entered_again_lights_both_halves_of_its_edge() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let machine = "machine M\ninitial PLAY\nstate PLAY {\n    entry {\n        int n;\n        n = n + 1;\n    }\n    when again && n < 2 -> PLAY\n    state A { when a -> B }\n    state B { when b -> A }\n}\n";
    let folder = crate::behaviour_folder(
        "monitor-back",
        &[
            ("M.machine", machine),
            (
                "run.script",
                "a = false\nagain = false\nb = false\nat 1s a = true\nat 2s again = true\n",
            ),
            (
                "behaviour.toml",
                "[[machine]]\nfile = \"M.machine\"\n[impersonator]\nscript = \"run.script\"\n",
            ),
        ],
    );
    let trace = behaviour_trace(folder.to_str().unwrap(), "3s", "back");
    let events: Vec<Json> = std::fs::read_to_string(&trace)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let again = 1 + events
        .iter()
        .position(|e| e["event"] == "fired" && e["label"] == "again && n < 2")
        .expect("PLAY was entered again");
    let _replay = replay_page(&client, &trace, folder.to_str().unwrap()).await;
    let second = Duration::from_secs(1);
    let halves = "return [...document.querySelectorAll('[data-machine=\"M\"] g.edge')].filter((g) => g.querySelector('title')?.textContent.includes('_back')).map((g) => g.classList.contains('fired'))";
    until(&client, halves, json!([false, false]), 5 * second).await;
    eval(
        &client,
        &format!("const s = document.getElementById('slider'); s.value = '{again}'; s.dispatchEvent(new Event('input')); return true"),
    )
    .await;
    until(&client, halves, json!([true, true]), 3 * second).await;
    let _ = client.close().await;
    let _ = std::fs::remove_file(&trace);
}

/// The page lists an assignment with its variable and value (the press's controller counts
/// how long it waited).
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_events_list_says_which_variable_an_activity_set_and_to_what() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let trace = behaviour_trace("press", "5s", "assigned");
    let _replay = replay_page(&client, &trace, "press").await;
    until(
        &client,
        "return [...document.querySelectorAll('#events li.assigned')].some((li) => /Controller set (waited|motor|low) = -?[0-9]+$/.test(li.textContent))",
        json!(true),
        5 * Duration::from_secs(1),
    )
    .await;
    let _ = client.close().await;
    let _ = std::fs::remove_file(&trace);
}

/// A click on an answer in the events list shows why the machine read it: the inputs its
/// theory held then and the proof tree, as `explain --trace` prints them.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn a_click_on_an_answer_shows_why_the_theory_gave_it() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let trace = microwave_trace("why");
    let _replay = replay_page(&client, &trace, "microwave").await;
    let second = Duration::from_secs(1);
    until(&client, STATE, json!("COOKING"), 5 * second).await;
    let clicked = "const li = [...document.querySelectorAll('#events li.explainable')].pop(); if (!li) return null; li.click(); return li.textContent.replace(/^[0-9.]+ +/, '')";
    let answer = eval(&client, clicked).await;
    let answer = answer
        .as_str()
        .expect("the list shows an expert's answer")
        .to_string();
    // `Microwave cook = true`: the machine, the label and the value the page showed.
    let (machine, rest) = answer.split_once(' ').unwrap();
    let (label, value) = rest.split_once(" = ").unwrap();
    let said = format!(
        "{machine} asked `{label}`; the theory `microwave` answered {value}, its inputs then: "
    );
    until(
        &client,
        &format!(
            "return document.getElementById('why').textContent.includes({})",
            json!(said)
        ),
        json!(true),
        5 * second,
    )
    .await;
    let why = eval(&client, "return document.getElementById('why').textContent").await;
    assert!(
        why.as_str().unwrap().contains(&format!("beta {label}")),
        "{why}"
    );
    let _ = client.close().await;
    // A live run's page explains from the events it has seen (no browser needed).
    let (_run, url) = proclaim_with_monitor(&[
        "run",
        "microwave",
        "--monitor",
        "127.0.0.1:0",
        "--for",
        "20s",
    ]);
    let deadline = std::time::Instant::now() + 10 * second;
    loop {
        let (status, body) = http(
            &url,
            "GET",
            "/api/explain?round=2&machine=Microwave&label=cook",
            None,
        );
        if status == 200 {
            assert!(
                body.starts_with(
                    "round 2: Microwave asked `cook`; the theory `microwave` answered false"
                ),
                "{body}"
            );
            break;
        }
        assert!(std::time::Instant::now() < deadline, "{status}: {body}");
        tokio::time::sleep(Duration::from_millis(100)).await;
    }
    let (status, body) = http(
        &url,
        "GET",
        "/api/explain?round=2&machine=Microwave&label=bake",
        None,
    );
    assert_eq!(status, 422, "{body}");
    assert!(
        body.contains("`bake` is no output of the behaviour's theories"),
        "{body}"
    );
    let _ = std::fs::remove_file(&trace);
}

/// `test --coverage --monitor` draws the machines with what the recordings never exercised
/// dashed in red: the kitchen run never cooks from OPEN, nor leaves COOKING but by its timeout.
#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_coverage_page_marks_the_transition_no_recording_fired() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let recording = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!(
        "proclaim-monitor-coverage-{}.jsonl",
        std::process::id()
    ));
    let ran = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args([
            "run",
            "microwave",
            "--virtual-clock",
            "--for",
            "70s",
            "--record",
        ])
        .arg(&recording)
        .output()
        .expect("proclaim runs");
    assert!(
        ran.status.success(),
        "{}",
        String::from_utf8_lossy(&ran.stderr)
    );
    let (_page, url) = proclaim_with_monitor(&[
        "test",
        "microwave",
        recording.to_str().unwrap(),
        "--coverage",
        "--monitor",
        "127.0.0.1:0",
    ]);
    client.goto(&url).await.expect("the page opens");
    let never = "return [...document.querySelectorAll('[data-machine=\"Microwave\"] g.edge.never title')].map((t) => t.textContent).sort().join(' ')";
    let expected = json!("s2->s3 s3->s1 s3->s2");
    until(&client, never, expected, 5 * Duration::from_secs(1)).await;
    let states =
        "return document.querySelectorAll('[data-machine=\"Microwave\"] g.node.never').length";
    assert_eq!(eval(&client, states).await, json!(0));
    let _ = client.close().await;
    let _ = std::fs::remove_file(&recording);
}

/// One HTTP/1.1 request over a plain socket: the status code and the body.
pub(crate) fn http(url: &str, method: &str, path: &str, body: Option<&str>) -> (u16, String) {
    http_with(url, method, path, body, "")
}

/// `http` with more header lines (each ending in `\r\n`).
pub(crate) fn http_with(
    url: &str,
    method: &str,
    path: &str,
    body: Option<&str>,
    headers: &str,
) -> (u16, String) {
    use std::io::{Read, Write};
    let host = url
        .trim_start_matches("http://")
        .split('/')
        .next()
        .unwrap_or_default();
    let mut stream = std::net::TcpStream::connect(host).expect("the monitor listens");
    let body = body.unwrap_or("");
    // A test may name the host itself (as a rebound name would).
    let own_host = if headers.to_ascii_lowercase().contains("host:") {
        String::new()
    } else {
        format!("Host: {host}\r\n")
    };
    write!(
        stream,
        "{method} {path} HTTP/1.1\r\n{own_host}Connection: close\r\nContent-Type: application/json\r\n{headers}Content-Length: {}\r\n\r\n{body}",
        body.len()
    )
    .unwrap();
    let mut response = String::new();
    stream.read_to_string(&mut response).unwrap();
    let status = response
        .split_whitespace()
        .nth(1)
        .and_then(|s| s.parse().ok())
        .unwrap_or(0);
    let body = response.split_once("\r\n\r\n").map_or("", |(_, b)| b);
    (status, body.to_string())
}

#[test]
fn the_page_api_serves_the_run_and_refuses_bad_requests() {
    let (_run, url) = microwave_with_monitor();
    let (status, page) = http(&url, "GET", "/", None);
    assert_eq!(status, 200);
    assert!(page.contains("<title>proclaim monitor</title>"), "{page}");
    let (status, model) = http(&url, "GET", "/api/model", None);
    assert_eq!(status, 200);
    let model: Json = serde_json::from_str(&model).unwrap();
    assert_eq!(model["mode"], "live");
    assert_eq!(model["charts"][0]["name"], "Microwave");
    assert!(model["charts"][0]["svg"]
        .as_str()
        .unwrap()
        .contains("<title>s1</title>"));
    let (status, why) = http(&url, "POST", "/api/control", Some(r#"{"action":"jump"}"#));
    assert_eq!(
        (status, why.as_str()),
        (400, "unknown action `jump`: pause, step, resume or stop")
    );
    let (status, why) = http(
        &url,
        "POST",
        "/api/post",
        Some(r#"{"type":"door open","value":"1"}"#),
    );
    assert_eq!(status, 400, "{why}");
    assert!(why.contains("not a message type"), "{why}");
    let (status, _) = http(
        &url,
        "POST",
        "/api/post",
        Some(r#"{"type":"visitor","value":"42"}"#),
    );
    assert_eq!(status, 200);
    let (_, frame) = http(&url, "GET", "/api/frame", None);
    let frame: Json = serde_json::from_str(&frame).unwrap();
    let row = frame["board"]
        .as_array()
        .unwrap()
        .iter()
        .find(|r| r["type"] == "visitor")
        .cloned()
        .expect("the posting is on the board");
    assert_eq!(
        (row["value"].as_str(), row["by"].as_str()),
        (Some("42"), Some("monitor"))
    );
    assert_eq!(frame["machines"][0]["name"], "Microwave");
    assert_eq!(frame["stepping"]["paused"], false);
}

#[test]
fn a_request_from_another_site_changes_nothing() {
    let (_run, url) = microwave_with_monitor();
    let posting = Some(r#"{"type":"visitor","value":"42"}"#);
    let post = |headers: &str| http_with(&url, "POST", "/api/post", posting, headers);
    // DNS rebinding: a page the operator visits rebinds its own name to 127.0.0.1.
    let port = url.rsplit(':').next().unwrap().trim_end_matches('/');
    let (status, why) = post(&format!(
        "Host: evil.example:{port}\r\nOrigin: http://evil.example:{port}\r\n"
    ));
    assert_eq!(status, 403, "{why}");
    assert!(why.contains("`Host: evil.example:"), "{why}");
    let (status, why) = post("Origin: http://evil.example\r\n");
    assert_eq!(status, 403, "{why}");
    assert!(why.contains("another site"), "{why}");
    let (status, why) = http_with(
        &url,
        "POST",
        "/api/control",
        Some(r#"{"action":"pause"}"#),
        "Origin: null\r\n",
    );
    assert_eq!(status, 403, "{why}");
    let (_, frame) = http(&url, "GET", "/api/frame", None);
    assert!(
        !frame.contains("\"monitor\""),
        "a refused posting reached the board: {frame}"
    );
    // The page's own requests carry its own origin, and are taken.
    let host = url.trim_start_matches("http://").trim_end_matches('/');
    let (status, why) = post(&format!("Origin: http://{host}\r\n"));
    assert_eq!(status, 200, "{why}");
}

#[test]
fn bad_monitor_arguments_say_what_is_wrong() {
    let run = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args(["run", "microwave", "--monitor", "the-kitchen"])
        .output()
        .unwrap();
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(
        stderr.contains("--monitor the-kitchen: not an address to listen on"),
        "{stderr}"
    );
    let not_a_trace = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("proclaim-not-a-trace-{}.jsonl", std::process::id()));
    std::fs::write(&not_a_trace, "{\"event\": \"entered\"}\n").unwrap();
    let replay = Command::new(env!("CARGO_BIN_EXE_proclaim"))
        .args([
            "replay",
            not_a_trace.to_str().unwrap(),
            "--monitor",
            "127.0.0.1:0",
        ])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&replay.stderr);
    assert!(!replay.status.success());
    assert!(stderr.contains("line 1: not a trace event"), "{stderr}");
    let _ = std::fs::remove_file(&not_a_trace);
}

#[test]
fn a_trace_replayed_without_its_behaviour_draws_what_the_trace_shows() {
    let trace = microwave_trace("alone");
    let trace_arg = trace.to_str().unwrap();
    let (_replay, url) = proclaim_with_monitor(&["replay", trace_arg, "--monitor", "127.0.0.1:0"]);
    let (status, model) = http(&url, "GET", "/api/model", None);
    assert_eq!(status, 200);
    let model: Json = serde_json::from_str(&model).unwrap();
    assert_eq!(model["mode"], "replay");
    // The impersonator's postings are in the trace too, but it is no machine.
    let charts = model["charts"].as_array().unwrap();
    assert_eq!(charts.len(), 1, "{charts:?}");
    let states: Vec<&str> = charts[0]["states"]
        .as_array()
        .unwrap()
        .iter()
        .map(|s| s["name"].as_str().unwrap())
        .collect();
    assert_eq!(states, ["IDLE", "OPEN", "COOKING"]);
    let (_, first) = http(&url, "GET", "/api/frame?at=0", None);
    let first: Json = serde_json::from_str(&first).unwrap();
    assert_eq!(first["machines"][0]["state_name"], "IDLE");
    assert_eq!(first["at"], 0);
    let _ = std::fs::remove_file(&trace);
}

#[test]
fn a_machine_read_again_is_drawn_anew() {
    let (dir, _run, url) = watched_machine("monitor-watch");
    let states = |url: &str| -> (Vec<String>, u64) {
        let (_, model) = http(url, "GET", "/api/model", None);
        let model: Json = serde_json::from_str(&model).unwrap();
        let names = model["charts"][0]["states"]
            .as_array()
            .unwrap()
            .iter()
            .map(|s| s["name"].as_str().unwrap().to_string())
            .collect();
        (names, model["charts_version"].as_u64().unwrap())
    };
    assert_eq!(
        states(&url),
        (vec!["Wait".to_string(), "Done".to_string()], 0)
    );
    std::thread::sleep(Duration::from_millis(500));
    std::fs::write(dir.join("W.machine"), W_WITH_LATER).unwrap();
    let deadline = Instant::now() + Duration::from_secs(10);
    loop {
        let (names, version) = states(&url);
        if names == ["Wait", "Later", "Done"] {
            assert!(version >= 1);
            break;
        }
        assert!(Instant::now() < deadline, "the page still draws {names:?}");
        std::thread::sleep(Duration::from_millis(100));
    }
    let (_, frame) = http(&url, "GET", "/api/frame", None);
    let frame: Json = serde_json::from_str(&frame).unwrap();
    assert_eq!(frame["machines"][0]["state_name"], "Wait");
    assert!(frame["charts_version"].as_u64().unwrap() >= 1);
}

#[tokio::test(flavor = "multi_thread", worker_threads = 2)]
async fn the_page_draws_a_machine_anew_when_its_file_changes() {
    let Some((_driver, client)) = open_browser().await else {
        return;
    };
    let (dir, _run, url) = watched_machine("monitor-watch-page");
    client.goto(&url).await.expect("the page opens");
    // States' groups are titled `s<id>` (the start point is `start`).
    let nodes = "return Array.from(document.querySelectorAll('[data-machine=\"W\"] g.node title')).filter(t => /^s[0-9]+$/.test(t.textContent)).length";
    let second = Duration::from_secs(1);
    until(&client, nodes, json!(2), 3 * second).await;
    std::fs::write(dir.join("W.machine"), W_WITH_LATER).unwrap();
    until(&client, nodes, json!(3), 10 * second).await;
    // Still lit where the machine is.
    let lit = "return document.querySelector('[data-machine=\"W\"] g.node.current title')?.textContent ?? null";
    until(&client, lit, json!("s1"), 2 * second).await;
    let _ = client.close().await;
}

/// A behaviour of one machine `W` (`Wait -go-> Done`; nobody answers `go`, so `--force`) run
/// with `--watch` and the monitor; its folder, the run and the page's URL.
fn watched_machine(tag: &str) -> (std::path::PathBuf, Running, String) {
    let dir = crate::behaviour_folder(
        tag,
        &[
            ("behaviour.toml", "[[machine]]\nfile = \"W.machine\"\n"),
            (
                "W.machine",
                "machine W\nstate Wait {\n  when go -> Done\n}\nstate Done {\n}\n",
            ),
        ],
    );
    let (run, url) = proclaim_with_monitor(&[
        "run",
        dir.to_str().unwrap(),
        "--watch",
        "--force",
        "--for",
        "60s",
        "--monitor",
        "127.0.0.1:0",
    ]);
    (dir, run, url)
}

/// `W` with a state `Later` between `Wait` and `Done`.
const W_WITH_LATER: &str =
    "machine W\nstate Wait {\n  when go -> Later\n}\nstate Later {\n  when go -> Done\n}\nstate Done {\n}\n";

/// A page on an address other than loopback changes the run only with the token printed in
/// its address; `--monitor-read-only` changes nothing and says so. (The page listens on every
/// address; the test talks to it on loopback.)
#[test]
fn a_page_on_the_network_needs_its_token_and_a_read_only_page_changes_nothing() {
    let (_run, url) =
        proclaim_with_monitor(&["run", "microwave", "--monitor", "0.0.0.0:0", "--for", "60s"]);
    let (address, token) = url
        .split_once("/?token=")
        .expect("the address carries a token");
    assert_eq!(token.len(), 32, "128 bits in hex: {token}");
    let local = address.replace("0.0.0.0", "127.0.0.1");
    let posting = Some(r#"{"type":"visitor","value":"42"}"#);
    let (status, why) = http(&local, "POST", "/api/post", posting);
    assert_eq!(status, 403, "{why}");
    assert!(why.contains("token"), "{why}");
    let wrong = "x-proclaim-token: 0123\r\n";
    assert_eq!(
        http_with(&local, "POST", "/api/post", posting, wrong).0,
        403
    );
    let right = format!("x-proclaim-token: {token}\r\n");
    let (status, why) = http_with(&local, "POST", "/api/post", posting, &right);
    assert_eq!(status, 200, "{why}");
    let (status, _) = http(&local, "GET", "/api/model", None);
    assert_eq!(status, 200, "reading needs no token");

    let (_run, url) = proclaim_with_monitor(&[
        "run",
        "microwave",
        "--monitor",
        "127.0.0.1:0",
        "--monitor-read-only",
        "--for",
        "60s",
    ]);
    let local = url.trim_end_matches(" (read-only)");
    let (status, why) = http(local, "POST", "/api/control", Some(r#"{"action":"pause"}"#));
    assert_eq!(
        (status, why.as_str()),
        (403, "this page is read-only (--monitor-read-only)")
    );
    assert_eq!(http(local, "POST", "/api/post", posting).0, 403);
    let (_, model) = http(local, "GET", "/api/model", None);
    let model: Json = serde_json::from_str(&model).unwrap();
    assert_eq!(model["read_only"], true);
}

/// A behaviour whose one transition has a label longer than Graphviz takes (16,384 characters
/// in a quoted string), in a folder of the test's own.
fn too_long_for_graphviz() -> std::path::PathBuf {
    let label = format!("\"{}\" == \"y\"", "x".repeat(100_000));
    let machine =
        format!("machine Long\ninitial A\nstate A {{\n    when {label} -> B\n}}\nstate B {{ }}\n");
    crate::behaviour_folder(
        "long-label",
        &[
            ("Long.machine", &machine),
            ("behaviour.toml", "[[machine]]\nfile = \"Long.machine\"\n"),
        ],
    )
}

/// Graphviz stops reading a diagram it refuses; the broken pipe once killed proclaim (SIGPIPE),
/// so a viewer took the robot down. Now each stays alive and says what Graphviz said.
#[test]
fn a_label_too_long_for_graphviz_kills_neither_draw_nor_the_run_nor_the_editor() {
    let dir = too_long_for_graphviz();
    let graphviz = on_path("dot").is_some();
    let svg = dir.join("long.svg");
    let drawn = crate::proclaim(&["draw", dir.to_str().unwrap(), "-o", svg.to_str().unwrap()]);
    let said = String::from_utf8_lossy(&drawn.stderr);
    assert_eq!(drawn.status.code(), Some(0), "{said}");
    if graphviz {
        assert!(
            said.contains("Graphviz failed") && said.contains("16384"),
            "{said}"
        );
        assert!(svg.with_extension("dot").exists());
    }
    let (mut run, url) = proclaim_with_monitor(&[
        "run",
        dir.to_str().unwrap(),
        "--monitor",
        "127.0.0.1:0",
        "--for",
        "60s",
    ]);
    let (status, model) = http(&url, "GET", "/api/model", None);
    assert_eq!(status, 200, "{model}");
    assert!(model.contains("<svg"), "the page draws the machine itself");
    assert!(run.0.try_wait().unwrap().is_none(), "the run died");
    let (mut editor, url) =
        proclaim_serving(&["edit", dir.to_str().unwrap(), "127.0.0.1:0"], "editor: ");
    let (status, model) = http(&url, "GET", "/api/edit/model", None);
    assert_eq!(status, 200, "{model}");
    assert!(editor.0.try_wait().unwrap().is_none(), "the editor died");
    assert!(run.0.try_wait().unwrap().is_none(), "the run died");
    let _ = std::fs::remove_dir_all(&dir);
}
