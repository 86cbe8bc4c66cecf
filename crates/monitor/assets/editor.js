// The proclaim machine editor: every change is an edit the server makes to the file's text, so
// the page shows exactly what Save would write; boxes are checked by the server as you type.
"use strict";

const $ = (id) => document.getElementById(id);
let model = null;
let machine = 0;
let selected = null; // the selected state's position
const token = new URLSearchParams(location.search).get("token");

function headers() {
  const h = { "content-type": "application/json" };
  if (token) h["x-proclaim-token"] = token;
  return h;
}

function status(message, kind) {
  $("status").textContent = message;
  $("status").className = "status " + (kind || "");
}

async function call(path, body) {
  const response = await fetch(path, { method: "POST", headers: headers(), body: JSON.stringify(body) });
  const type = response.headers.get("content-type") || "";
  const answer = type.includes("json") ? await response.json() : await response.text();
  if (typeof answer === "string") {
    status(answer, "error");
    return null;
  }
  return { ok: response.ok, answer };
}

function current() {
  return model.machines[machine];
}

// An edit made: the model redrawn; a refusal said in the status line.
async function change(edit) {
  const done = await call("/api/edit/change", { machine, edit });
  if (!done) return false;
  const a = done.answer;
  model = a.model;
  render();
  if (a.ok) status("edited; Save writes it", "");
  else status(a.message, "error");
  return a.ok;
}

async function command(path, okKind) {
  const done = await call(path, { machine });
  if (!done) return;
  model = done.answer.model;
  render();
  status(done.answer.message || (done.answer.ok ? "done" : ""), done.answer.ok ? okKind : "error");
}

// What an edit would give, shown in `box` while the person types.
const pending = new Map();
function tryEdit(box, edit, diag) {
  clearTimeout(pending.get(box));
  pending.set(box, setTimeout(async () => {
    const response = await fetch("/api/edit/try", { method: "POST", headers: headers(), body: JSON.stringify({ machine, edit }) });
    if (!response.ok) {
      showDiag(box, diag, [{ severity: "error", message: await response.text() }]);
      return;
    }
    const diagnostics = await response.json();
    showDiag(box, diag, diagnostics.filter((d) => d.in_box !== undefined && d.in_box !== null));
  }, 120));
}

function showDiag(box, diag, list) {
  const errors = list.filter((d) => d.severity === "error");
  diag.textContent = list.map((d) => d.message).join("\n");
  diag.className = "diag" + (errors.length ? "" : " warning");
  box.classList.toggle("bad", errors.length > 0);
}

function diagnosticsOnLines(first, last) {
  return current().diagnostics.filter((d) => d.line != null && d.line >= first && d.line <= last);
}

// The diagram's view: zoomed and panned by moving the drawing's viewBox, kept across redraws
// of one machine (an edit redraws it), fitted again by Fit or on another machine.
let view = null; // { x, y, w, h } in the drawing's units; null: the whole drawing
let drawing = null; // the drawing's own viewBox
const ZOOM_LIMITS = [0.25, 8];

function svgOf() {
  return $("diagram").querySelector("svg");
}

function applyView() {
  const svg = svgOf();
  if (!svg || !drawing) return;
  const v = view || drawing;
  svg.setAttribute("viewBox", `${v.x} ${v.y} ${v.w} ${v.h}`);
  $("diagram").dataset.zoom = (drawing.w / v.w).toFixed(3);
  $("diagram").dataset.view = `${v.x.toFixed(1)} ${v.y.toFixed(1)}`;
}

// Zooms by `factor` about a point of the drawing (its middle when none), within the limits.
function zoom(factor, at) {
  if (!drawing) return;
  const v = view || drawing;
  const zoomNow = drawing.w / v.w;
  const next = Math.min(ZOOM_LIMITS[1], Math.max(ZOOM_LIMITS[0], zoomNow * factor));
  const k = zoomNow / next;
  const p = at || { x: v.x + v.w / 2, y: v.y + v.h / 2 };
  view = { x: p.x - (p.x - v.x) * k, y: p.y - (p.y - v.y) * k, w: v.w * k, h: v.h * k };
  applyView();
}

function fit() {
  view = null;
  applyView();
}

// A point of the page in the drawing's units.
function drawingPoint(event) {
  const svg = svgOf();
  const m = svg.getScreenCTM();
  if (!m) return { x: 0, y: 0 };
  const p = new DOMPoint(event.clientX, event.clientY).matrixTransform(m.inverse());
  return { x: p.x, y: p.y };
}

function nodeCentre(g) {
  const b = g.getBBox();
  const m = g.getCTM();
  const svg = svgOf();
  const root = svg.getCTM();
  const p = new DOMPoint(b.x + b.width / 2, b.y + b.height / 2).matrixTransform(m).matrixTransform(root.inverse());
  return { x: p.x, y: p.y };
}

function nodeUnder(event) {
  const hit = document.elementFromPoint(event.clientX, event.clientY);
  const g = hit && hit.closest("#diagram g.node");
  return g && g.dataset.index !== undefined ? Number(g.dataset.index) : null;
}

// What a press on the drawing becomes: a click on a state selects it; a drag from a state to a
// state (or back to itself) draws a transition; a drag on the background pans.
let gesture = null;

function pressed(event) {
  if (event.button !== 0) return;
  const svg = svgOf();
  const g = event.target.closest("g.node");
  const node = g && g.dataset.index !== undefined ? Number(g.dataset.index) : null;
  const editable = !model.read_only && !current().refusal;
  gesture = {
    node,
    // Where a transition would be drawn from; on a machine that cannot be edited, a drag pans.
    from: editable ? node : null,
    start: { x: event.clientX, y: event.clientY },
    last: drawingPoint(event),
    moved: false,
    line: null,
  };
  svg.setPointerCapture(event.pointerId);
  event.preventDefault();
}

function moved(event) {
  if (!gesture) return;
  const far = Math.hypot(event.clientX - gesture.start.x, event.clientY - gesture.start.y) > 4;
  gesture.moved = gesture.moved || far;
  if (!gesture.moved) return;
  const svg = svgOf();
  const p = drawingPoint(event);
  if (gesture.from === null) {
    const v = view || drawing;
    view = { ...v, x: v.x - (p.x - gesture.last.x), y: v.y - (p.y - gesture.last.y) };
    applyView();
    return; // the drawing moved under the pointer: where it points is the same place again
  }
  if (!gesture.line) {
    const node = $("diagram").querySelector(`g.node[data-index="${gesture.from}"]`);
    gesture.origin = nodeCentre(node);
    gesture.line = document.createElementNS("http://www.w3.org/2000/svg", "line");
    gesture.line.setAttribute("class", "drawing-transition");
    svg.appendChild(gesture.line);
  }
  const l = gesture.line;
  l.setAttribute("x1", gesture.origin.x);
  l.setAttribute("y1", gesture.origin.y);
  l.setAttribute("x2", p.x);
  l.setAttribute("y2", p.y);
}

function released(event) {
  if (!gesture) return;
  const done = gesture;
  gesture = null;
  if (done.line) done.line.remove();
  if (!done.moved) {
    if (done.node !== null) select(done.node);
    return;
  }
  if (done.from === null) return;
  const to = nodeUnder(event);
  if (to === null) {
    status("no transition drawn: let go over the state it leads to", "");
    return;
  }
  connect(done.from, to);
}

// A transition drawn from `from` to `to`: added at once when its label is typed already,
// otherwise the label box waits for it.
function connect(from, to) {
  select(from);
  $("new-target").value = String(to);
  const m = current();
  if ($("new-label").value.trim() !== "") {
    addTransition();
    return;
  }
  $("new-label").focus();
  status(`drawn ${m.states[from].name} → ${m.states[to].name}: type its label and press Enter`, "");
}

function renderDiagram(m) {
  const holder = $("diagram");
  holder.innerHTML = m.svg;
  const svg = svgOf();
  if (!svg) return;
  const box = svg.viewBox.baseVal;
  drawing = box && box.width > 0 ? { x: box.x, y: box.y, w: box.width, h: box.height } : null;
  // The drawing fills its frame (and Fit shows all of it) rather than keeping Graphviz's size.
  svg.removeAttribute("width");
  svg.removeAttribute("height");
  applyView();
  const byNode = new Map(m.states.map((s, i) => [s.node, i]));
  for (const g of holder.querySelectorAll("g.node")) {
    const t = g.querySelector("title");
    const index = t ? byNode.get(t.textContent.trim()) : undefined;
    if (index === undefined) continue;
    g.dataset.state = m.states[index].name;
    g.dataset.index = String(index);
    if (index === selected) g.classList.add("selected");
  }
  svg.addEventListener("pointerdown", pressed);
  svg.addEventListener("pointermove", moved);
  svg.addEventListener("pointerup", released);
  svg.addEventListener("pointercancel", () => { if (gesture && gesture.line) gesture.line.remove(); gesture = null; });
  svg.addEventListener("wheel", (e) => {
    e.preventDefault();
    zoom(e.deltaY < 0 ? 1.2 : 1 / 1.2, drawingPoint(e));
  }, { passive: false });
}

function option(value, label) {
  const o = document.createElement("option");
  o.value = value;
  o.textContent = label;
  return o;
}

function render() {
  const m = current();
  $("name").textContent = model.name;
  const pick = $("machine");
  if (pick.options.length !== model.machines.length) {
    pick.replaceChildren(...model.machines.map((x, i) => option(i, x.name)));
  }
  pick.value = String(machine);
  $("machine-name").textContent = m.name;
  $("file").textContent = m.file;
  $("unsaved").textContent = m.saved ? "" : "unsaved changes";
  const editable = !model.read_only && !m.refusal;
  $("refusal").hidden = !m.refusal;
  $("refusal").textContent = m.refusal || "";
  for (const id of ["undo", "redo", "save"]) $(id).hidden = model.read_only;
  $("undo").disabled = !m.can_undo;
  $("redo").disabled = !m.can_redo;
  $("panel").hidden = !editable;
  renderDiagram(m);
  const said = m.diagnostics.length ? m.diagnostics : [{ severity: "clean", message: "nothing: the machine reads and lints clean" }];
  $("diagnostics").replaceChildren(...said.map((d) => {
    const li = document.createElement("li");
    li.className = d.severity;
    li.textContent = d.severity === "clean" ? d.message : `${d.line != null ? "line " + d.line + ": " : ""}${d.severity}: ${d.message}`;
    return li;
  }));
  if (selected !== null && selected >= m.states.length) selected = null;
  const states = $("states");
  states.replaceChildren(...m.states.map((s, i) => {
    const b = document.createElement("button");
    b.textContent = s.name + (i === m.initial ? " (initial)" : "");
    b.dataset.state = s.name;
    if (i === selected) b.className = "selected";
    b.addEventListener("click", () => select(i));
    return b;
  }));
  renderState();
}

function targets(select, chosen) {
  const m = current();
  select.replaceChildren(...m.states.map((s, i) => option(i, s.name)));
  if (chosen !== null && chosen !== undefined) select.value = String(chosen);
}

function renderState() {
  const m = current();
  $("state").hidden = selected === null;
  if (selected === null) return;
  const s = m.states[selected];
  $("state-title").textContent = s.name;
  $("state-name").value = s.name;
  for (const section of ["entry", "exit", "internal"]) {
    const a = s[section];
    const box = $(section);
    if (document.activeElement !== box) box.value = a ? a.text : "";
    showDiag(box, $(section + "-diag"), a ? diagnosticsOnLines(a.first_line, a.last_line) : []);
  }
  targets($("new-target"), $("new-target").value === "" ? selected : Number($("new-target").value));
  const list = $("transitions");
  list.replaceChildren(...s.transitions.map((t, i) => {
    const li = document.createElement("li");
    const row = document.createElement("div");
    row.className = "row";
    const label = document.createElement("input");
    label.type = "text";
    label.className = "label";
    label.value = t.label;
    label.setAttribute("aria-label", `label of transition ${i + 1}`);
    const diag = document.createElement("div");
    diag.className = "diag";
    label.addEventListener("input", () => tryEdit(label, { kind: "set_label", state: selected, transition: i, label: label.value }, diag));
    label.addEventListener("keydown", (e) => {
      if (e.key === "Enter") change({ kind: "set_label", state: selected, transition: i, label: label.value });
    });
    const target = document.createElement("select");
    targets(target, t.target);
    target.addEventListener("change", () => change({ kind: "set_target", state: selected, transition: i, target: Number(target.value) }));
    const button = (text, title, edit) => {
      const b = document.createElement("button");
      b.textContent = text;
      b.title = title;
      b.addEventListener("click", () => change(edit));
      return b;
    };
    row.append(label, "→", target);
    if (i > 0) row.append(button("↑", "Tried earlier", { kind: "move_transition", state: selected, from: i, to: i - 1 }));
    if (i + 1 < s.transitions.length) row.append(button("↓", "Tried later", { kind: "move_transition", state: selected, from: i, to: i + 1 }));
    row.append(button("✕", "Delete the transition", { kind: "delete_transition", state: selected, transition: i }));
    li.append(row, diag);
    showDiag(label, diag, diagnosticsOnLines(t.line, t.line));
    return li;
  }));
}

function newTransition() {
  return { kind: "add_transition", state: selected, label: $("new-label").value, target: Number($("new-target").value) };
}

async function addTransition() {
  if (await change(newTransition())) {
    $("new-label").value = "";
    $("new-label-diag").textContent = "";
    $("new-label").classList.remove("bad");
  }
}

function select(index) {
  selected = index;
  $("new-target").value = "";
  render();
}

function activities() {
  return ["entry", "exit", "internal"];
}

async function applyActivities() {
  const s = current().states[selected];
  for (const section of activities()) {
    const text = $(section).value;
    const was = s[section] ? s[section].text : "";
    if (text.trimEnd() !== was) {
      if (!(await change({ kind: "set_activity", state: selected, section, text }))) return;
    }
  }
}

function wire() {
  $("machine").addEventListener("change", () => {
    machine = Number($("machine").value);
    selected = null;
    view = null;
    render();
  });
  $("undo").addEventListener("click", () => command("/api/edit/undo", ""));
  $("redo").addEventListener("click", () => command("/api/edit/redo", ""));
  $("save").addEventListener("click", () => command("/api/edit/save", "done"));
  const addState = async () => {
    const name = $("add-state-name").value.trim();
    if (await change({ kind: "add_state", name })) {
      $("add-state-name").value = "";
      select(current().states.length - 1);
    }
  };
  $("add-state").addEventListener("click", addState);
  $("add-state-name").addEventListener("keydown", (e) => { if (e.key === "Enter") addState(); });
  const rename = () => change({ kind: "rename_state", state: selected, to: $("state-name").value });
  $("rename-state").addEventListener("click", rename);
  $("state-name").addEventListener("keydown", (e) => { if (e.key === "Enter") rename(); });
  $("make-initial").addEventListener("click", () => change({ kind: "set_initial", state: selected }));
  $("make-final").addEventListener("click", () => change({ kind: "make_final", state: selected }));
  $("delete-state").addEventListener("click", async () => {
    if (await change({ kind: "delete_state", state: selected })) selected = null, render();
  });
  for (const section of activities()) {
    const box = $(section);
    box.addEventListener("input", () => tryEdit(box, { kind: "set_activity", state: selected, section, text: box.value }, $(section + "-diag")));
    box.addEventListener("keydown", (e) => { if (e.key === "Enter" && e.ctrlKey) { e.preventDefault(); applyActivities(); } });
  }
  $("apply-activities").addEventListener("click", applyActivities);
  $("new-label").addEventListener("input", () => tryEdit($("new-label"), newTransition(), $("new-label-diag")));
  $("zoom-in").addEventListener("click", () => zoom(1.25));
  $("zoom-out").addEventListener("click", () => zoom(1 / 1.25));
  $("zoom-fit").addEventListener("click", fit);
  $("add-transition").addEventListener("click", addTransition);
  $("new-label").addEventListener("keydown", (e) => { if (e.key === "Enter") addTransition(); });
  document.addEventListener("keydown", (e) => {
    const inBox = ["INPUT", "TEXTAREA", "SELECT"].includes(document.activeElement?.tagName);
    const key = e.key.toLowerCase();
    if ((e.ctrlKey || e.metaKey) && key === "s") {
      e.preventDefault();
      command("/api/edit/save", "done");
    } else if ((e.ctrlKey || e.metaKey) && !inBox && (key === "y" || (key === "z" && e.shiftKey))) {
      e.preventDefault();
      command("/api/edit/redo", "");
    } else if ((e.ctrlKey || e.metaKey) && !inBox && key === "z") {
      e.preventDefault();
      command("/api/edit/undo", "");
    }
  });
}

async function start() {
  wire();
  const response = await fetch("/api/edit/model");
  model = await response.json();
  render();
  status(model.read_only ? "read-only: the machines are drawn, nothing can be changed" : "ready", "");
  // Since navigation began: what the editor's load figure measures.
  document.body.dataset.drawnAt = performance.now().toFixed(1);
  document.body.dataset.ready = "true";
}

start();
