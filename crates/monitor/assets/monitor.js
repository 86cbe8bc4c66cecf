// The proclaim monitor page: draws each machine once, then lights its current state and the
// transition that just fired from each frame (a live run's stream, or a replay's moment).
"use strict";

const $ = (id) => document.getElementById(id);
let model = null;
// Machine name -> { section, nodes: Map(node title -> <g>), edges: Map("sA->sB" -> [<g>]), nodeOf: Map(state id -> title) }
const drawn = new Map();
let boardSeqs = new Map();

function seconds(us) {
  return (us / 1e6).toFixed(3);
}

function text(tag, content, cls) {
  const el = document.createElement(tag);
  el.textContent = content;
  if (cls) el.className = cls;
  return el;
}

function drawMachines() {
  const holder = $("machines");
  for (const chart of model.charts) {
    const section = document.createElement("section");
    section.className = "machine";
    section.dataset.machine = chart.name;
    const title = document.createElement("h3");
    title.append(text("span", chart.name, "name"), text("span", "", "mode"), text("span", "", "state-name"), text("span", "", "fired"));
    section.append(title);
    const figure = document.createElement("div");
    figure.className = "diagram";
    // The SVG is made by the binary (Graphviz or its own layout) from the behaviour's files.
    figure.innerHTML = chart.svg;
    section.append(figure);
    holder.append(section);
    const nodes = new Map();
    const edges = new Map();
    for (const g of figure.querySelectorAll("g.node")) {
      const t = g.querySelector("title");
      if (t) nodes.set(t.textContent.trim(), g);
    }
    for (const g of figure.querySelectorAll("g.edge")) {
      const t = g.querySelector("title");
      if (!t) continue;
      const key = t.textContent.trim();
      if (!edges.has(key)) edges.set(key, []);
      edges.get(key).push(g);
    }
    joinBacks(edges);
    const nodeOf = new Map(chart.states.map((s) => [s.id, s.node]));
    // A state of a parallel state's regions is drawn as one node a region: all of them light.
    const allOf = new Map(chart.states.map((s) => [s.id, [s.node].concat(s.also || [])]));
    drawn.set(chart.name, { section, nodes, edges, nodeOf, allOf, current: null, lit: [], fired: [] });
  }
  markUncovered();
}

// A composite's transition back into itself is drawn out of its edge to a point (`…_backLINE`)
// and in again: its two halves are one edge between the states, lit together.
function joinBacks(edges) {
  for (const [key, out] of [...edges]) {
    const [from, point] = key.split("->");
    if (!point.includes("_back")) continue;
    for (const [other, back] of [...edges]) {
      if (!other.startsWith(point + "->")) continue;
      const whole = from + "->" + other.slice(point.length + 2);
      edges.set(whole, (edges.get(whole) || []).concat(out, back));
    }
  }
}

// What recordings never exercised (`proclaim test --coverage --monitor`): states never
// entered and transitions never fired, drawn dashed in red.
function markUncovered() {
  for (const u of model.uncovered || []) {
    const d = drawn.get(u.machine);
    if (!d) continue;
    if (u.target === null || u.target === undefined) {
      const g = d.nodes.get(d.nodeOf.get(u.state));
      if (g) g.classList.add("never");
      continue;
    }
    const between = d.edges.get(d.nodeOf.get(u.state) + "->" + d.nodeOf.get(u.target)) || [];
    for (const g of between) {
      if (between.length === 1 || g.textContent.includes(u.label)) g.classList.add("never");
    }
  }
}

function renderMachine(m) {
  const d = drawn.get(m.name);
  if (!d) return;
  d.section.className = "machine mode-" + m.mode;
  d.section.dataset.mode = m.mode;
  d.section.dataset.state = m.state_name || "";
  d.section.querySelector(".mode").textContent = m.mode + (m.halted ? ": " + m.halted : "");
  d.section.querySelector(".state-name").textContent = m.state_name || "";
  d.section.querySelector(".fired").textContent = m.fired ? "after " + m.fired.label : "";
  if (d.current !== m.state) {
    for (const g of d.lit) g.classList.remove("current");
    d.lit = (m.state === null ? [] : d.allOf.get(m.state) || []).map((n) => d.nodes.get(n)).filter((g) => g);
    for (const g of d.lit) g.classList.add("current");
    d.current = m.state;
  }
  for (const g of d.fired) g.classList.remove("fired");
  d.fired = [];
  if (m.fired) {
    const from = d.allOf.get(m.fired.from) || [];
    const to = d.allOf.get(m.fired.to) || [];
    let keys = [d.nodeOf.get(m.fired.from) + "->" + d.nodeOf.get(m.fired.to)];
    // A move of regions: each region's node that changed, from its old node.
    if (from.length > 1 || to.length > 1) {
      keys = from.flatMap((a) => to.filter((b) => !from.includes(b)).map((b) => a + "->" + b));
    }
    for (const key of keys) {
      for (const g of d.edges.get(key) || []) {
        g.classList.add("fired");
        d.fired.push(g);
      }
    }
  }
}

function renderBoard(frame) {
  const filter = $("board-filter").value.trim().toLowerCase();
  const body = document.createElement("tbody");
  const seqs = new Map();
  let shown = 0;
  for (const row of frame.board) {
    seqs.set(row.type, row.seq);
    if (filter && !(row.type.toLowerCase().includes(filter) || row.value.toLowerCase().includes(filter) || row.by.toLowerCase().includes(filter))) continue;
    shown++;
    const tr = document.createElement("tr");
    tr.dataset.type = row.type;
    if (boardSeqs.size && boardSeqs.get(row.type) !== row.seq) tr.className = "fresh";
    tr.append(text("td", row.type, "type"), text("td", row.kind, "kind"), text("td", row.value, "value"), text("td", row.by, "by"), text("td", seconds(row.at_us), "at"), text("td", row.seq, "seq"), text("td", row.posts, "posts"));
    body.append(tr);
  }
  boardSeqs = seqs;
  $("board").replaceChild(body, $("board").tBodies[0]);
  const more = frame.board_more ? ` (+${frame.board_more} not shown)` : "";
  $("board-count").textContent = `${shown} of ${frame.board.length} types${more}`;
}

const HOW = { expert: "", posted: "posted by ", timed_out: "timed out", no_expert: "no expert" };

function renderAnswers(frame) {
  const body = document.createElement("tbody");
  // The labels whose answer changed last come first.
  for (const a of [...frame.answers].sort((x, y) => y.changed_us - x.changed_us)) {
    const tr = document.createElement("tr");
    tr.className = a.undecided ? "undecided" : a.how;
    tr.dataset.atom = a.atom;
    tr.append(text("td", seconds(a.changed_us)), text("td", a.machine), text("td", a.atom, "atom"), text("td", String(a.value), "value"), text("td", (a.undecided ? "undecided, answered false by " : HOW[a.how]) + a.by, "by"), text("td", a.asked, "asked"));
    // Answering a label by hand: fill the post form with it.
    tr.addEventListener("click", () => {
      $("post-type").value = a.atom;
      $("post-value").value = String(!a.value);
      $("post-value").focus();
    });
    body.append(tr);
  }
  $("answers").replaceChild(body, $("answers").tBodies[0]);
}

function describe(e) {
  switch (e.event) {
    case "entered": return `${e.machine} entered ${e.state}`;
    case "fired": return `${e.machine} fired ${e.label}`;
    case "answered": return `${e.machine} ${e.atom} = ${e.value}`;
    case "posted": return `${e.machine} posted ${e.type}: ${e.content}` + (e.priority ? ` @${e.priority}` : "");
    case "suppressed": return `${e.machine} suppressed ${e.type}: ${e.content} @${e.priority} (held by ${e.by} @${e.by_priority} until ${seconds(e.until_us)} s)`;
    case "took_over": return `${e.machine} took over ${e.type}: ${e.content} @${e.priority} (the hold above ran out)`;
    case "assigned": return `${e.machine} set ${e.variable} = ${e.value}`;
    case "control": return `${e.machine} told ${e.command}`;
    case "finished": return `${e.machine} finished in ${e.state}`;
    case "halted": return `${e.machine} halted: ${e.reason}`;
    case "printed": return `${e.machine} printed ${e.text}`;
    case "warned": return `${e.machine} warning: ${e.message}`;
    case "reloaded": return `${e.machine} reloaded, in ${e.state}`;
    case "reload_failed": return `${e.machine} could not reload: ${e.error}`;
    default: return `${e.machine} ${e.event}`;
  }
}

function renderEvents(frame) {
  const list = $("events");
  const first = frame.events_listed - frame.events.length + 1;
  list.start = first;
  list.replaceChildren(...frame.events.map((e) => {
    const li = text("li", (e.at_us !== undefined ? seconds(e.at_us) + "  " : "") + describe(e), e.event);
    if (e.event === "answered" && e.by && e.by.expert) {
      li.classList.add("explainable");
      li.addEventListener("click", () => explainAnswer(e));
    }
    return li;
  }));
  list.scrollTop = list.scrollHeight;
}

// Why a machine read an answer: the proof tree from the inputs its theory held then.
async function explainAnswer(e) {
  const why = $("why");
  const query = new URLSearchParams({ round: e.round, machine: e.machine, label: e.atom });
  why.hidden = false;
  why.textContent = "…";
  try {
    const response = await fetch("/api/explain?" + query);
    why.textContent = await response.text();
  } catch (error) {
    why.textContent = `could not ask: ${error}`;
  }
}

let lastFrame = null;

// A machine read again (`run --watch`): its diagram is drawn anew from the model.
let redrawing = false;
async function redraw() {
  if (redrawing) return;
  redrawing = true;
  try {
    model = await (await fetch("/api/model")).json();
    drawn.clear();
    $("machines").replaceChildren();
    drawMachines();
    if (lastFrame) render(lastFrame);
  } finally {
    redrawing = false;
  }
}

function render(frame) {
  lastFrame = frame;
  if (frame.charts_version !== undefined && frame.charts_version !== model.charts_version) {
    redraw();
    return;
  }
  for (const m of frame.machines) renderMachine(m);
  renderBoard(frame);
  renderAnswers(frame);
  renderEvents(frame);
  const status = $("status");
  if (frame.stepping) {
    status.className = frame.stepping.paused ? "status paused" : "status";
    status.textContent = frame.stepping.paused ? `paused at step ${frame.stepping.step}` : `running · ${seconds(frame.time_us)} s`;
    status.dataset.paused = String(frame.stepping.paused);
  } else if (model.mode === "live") {
    status.className = "status";
    status.textContent = `running · ${seconds(frame.time_us)} s`;
  }
  document.body.dataset.frames = String(Number(document.body.dataset.frames || 0) + 1);
}

// A page served on the network changes the run only with the token of its address.
const token = new URLSearchParams(location.search).get("token");

async function send(path, body) {
  const headers = { "content-type": "application/json" };
  if (token) headers["x-proclaim-token"] = token;
  const response = await fetch(path, { method: "POST", headers, body: JSON.stringify(body) });
  if (!response.ok) throw new Error(await response.text());
  return response;
}

function live() {
  if (model.read_only) return;
  $("post").hidden = false;
  if (model.can_step) {
    $("controls").hidden = false;
    for (const action of ["pause", "step", "resume"]) {
      $(action).addEventListener("click", () => send("/api/control", { action }).catch((e) => { $("status").textContent = e.message; }));
    }
  }
  // A branch's page (the replay page sent us here) says where the branch is recorded.
  const given = new URLSearchParams(location.hash.slice(1));
  const recordedIn = given.get("branch");
  if (recordedIn) {
    $("branch-info").hidden = false;
    $("branch-info").textContent = `a branch, paused where it left its recording; recorded in ${recordedIn}`;
    // The behaviour changed since the recording: the branch is not where the recording was.
    if (given.get("notes")) {
      $("branch-info").textContent += ` · ${given.get("notes")}`;
      $("branch-info").classList.add("lost");
    }
  }
  if (model.can_stop) {
    $("controls").hidden = false;
    $("stop").hidden = false;
    $("stop").addEventListener("click", async () => {
      try {
        await send("/api/control", { action: "stop" });
        $("stop").disabled = true;
        if (recordedIn) $("branch-info").textContent = `stopped; ${recordedIn} is kept: \`proclaim test\` replays it`;
        document.body.dataset.stopped = "true";
      } catch (e) {
        $("status").textContent = e.message;
      }
    });
  }
  $("post").addEventListener("submit", async (event) => {
    event.preventDefault();
    const type = $("post-type").value.trim();
    const value = $("post-value").value.trim();
    try {
      const response = await send("/api/post", { type, value });
      const { seq } = await response.json();
      $("post-result").textContent = `posted ${type} = ${value} (#${seq})`;
    } catch (e) {
      $("post-result").textContent = e.message;
    }
  });
  // The picture at once; the stream follows.
  fetch("/api/frame").then((r) => r.json()).then((frame) => lastFrame || render(frame)).catch(() => {});
  const stream = new EventSource("/api/frames");
  stream.addEventListener("frame", (e) => render(JSON.parse(e.data)));
  // The browser reconnects by itself; only a closed stream is the end.
  stream.onerror = () => {
    const closed = stream.readyState === EventSource.CLOSED;
    $("status").className = "status lost";
    $("status").textContent = closed ? "the run is over or the connection was lost" : "reconnecting…";
  };
}

// The round a branch from the moment after `at` events starts: the one after the last shown.
function roundAfter(at) {
  const rounds = model.rounds;
  const last = Math.min(at, rounds.length) - 1;
  return last < 0 ? 1 : rounds[last] + 1;
}

// Round 1 is the run's start: there is nothing to go back to before it.
function labelBranch(at) {
  const round = roundAfter(at);
  const button = $("branch");
  button.disabled = round < 2;
  button.textContent = round < 2 ? "Branch (from round 2 on)" : `Branch at round ${round}`;
  button.dataset.round = String(round);
}

// "Branch here": the recording replayed to the round the slider shows, live from there on a
// page of its own, which this page goes to.
function branching(slider) {
  const button = $("branch");
  button.hidden = false;
  slider.addEventListener("input", () => labelBranch(Number(slider.value)));
  labelBranch(Number(slider.value));
  button.addEventListener("click", async () => {
    button.disabled = true;
    $("status").textContent = `starting a branch at round ${button.dataset.round}…`;
    try {
      const response = await send("/api/branch", { at: Number(slider.value) });
      const { url, file, notes } = await response.json();
      const said = notes.length ? `&notes=${encodeURIComponent(notes.join(" "))}` : "";
      location.href = `${url}#branch=${encodeURIComponent(file)}${said}`;
    } catch (e) {
      $("status").textContent = e.message;
      labelBranch(Number(slider.value));
    }
  });
}

function replay() {
  const slider = $("slider");
  const times = model.times;
  $("timeline").hidden = false;
  slider.max = String(times.length - 1);
  let wanted = null;
  let busy = false;
  // One request at a time; moving the slider faster only asks for where it is now.
  async function show(at) {
    wanted = at;
    if (busy) return;
    busy = true;
    while (wanted !== null) {
      const now = wanted;
      wanted = null;
      const frame = await (await fetch(`/api/frame?at=${now}`)).json();
      render(frame);
      $("moment").textContent = `event ${now} of ${times.length - 1} · ${seconds(times[now])} s`;
      if (model.can_branch) labelBranch(now);
      $("status").textContent = "replay";
    }
    busy = false;
  }
  slider.addEventListener("input", () => show(Number(slider.value)));
  if (model.can_branch) branching(slider);
  let playing = null;
  $("play").addEventListener("click", () => {
    if (playing) {
      clearInterval(playing);
      playing = null;
      $("play").textContent = "▶";
      return;
    }
    $("play").textContent = "⏸";
    const started = performance.now();
    const from = times[Number(slider.value)];
    playing = setInterval(() => {
      const now = from + (performance.now() - started) * 1000;
      let at = Number(slider.value);
      while (at < times.length - 1 && times[at + 1] <= now) at++;
      if (at !== Number(slider.value)) {
        slider.value = String(at);
        show(at);
      }
      if (at >= times.length - 1) $("play").click();
    }, 50);
  });
  slider.value = String(times.length - 1);
  show(times.length - 1);
}

async function start() {
  model = await (await fetch("/api/model")).json();
  document.title = `${model.name} · proclaim monitor`;
  $("name").textContent = model.name;
  $("mode").textContent = model.mode;
  drawMachines();
  $("board-filter").addEventListener("input", () => lastFrame && renderBoard(lastFrame));
  if (model.mode === "replay") replay();
  else live();
}

start().catch((e) => {
  $("status").className = "status lost";
  $("status").textContent = "the monitor could not start: " + e.message;
});
