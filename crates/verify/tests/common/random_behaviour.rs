//! Random behaviours for the conformance test of runner and model: from a seed, one to four
//! machines of two to five states over free boolean inputs (which a script sets), globals,
//! externs and a posted type with small constant values, a local counter, time tests,
//! sub-machine control and final states, sometimes with a small `.dl` theory whose answers the
//! labels ask, sometimes with states nested in composite states (two deep at most, with their
//! own activities, transitions and `when done`, and states beside them that resume their
//! history), now and then side by side as the regions of a parallel state, transitions with
//! actions of their own, transitions into two regions at once, and sub-machines that take a
//! parameter `p`
//! from whoever starts them or announce an outcome `done` that labels wait on; then a script for
//! the run and when to run each round. Everything is a function of the seed, so a failure names the seed that repeats
//! it.

use std::fmt::Write;
use std::path::Path;
use std::time::Duration;

/// xorshift64*: small, fast, and the same sequence everywhere.
pub struct Rng(u64);

impl Rng {
    pub fn new(seed: u64) -> Rng {
        // Any seed but 0 works; mixing spreads neighbouring seeds apart.
        Rng(seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        self.0.wrapping_mul(0x2545_F491_4F6C_DD1D)
    }

    /// A number in `0..n` (`n` > 0).
    pub fn below(&mut self, n: usize) -> usize {
        (self.next_u64() % n as u64) as usize
    }

    /// A number in `low..=high`.
    pub fn between(&mut self, low: usize, high: usize) -> usize {
        low + self.below(high - low + 1)
    }

    /// True `percent` times in a hundred.
    pub fn chance(&mut self, percent: usize) -> bool {
        self.below(100) < percent
    }

    pub fn pick<'a, T>(&mut self, items: &'a [T]) -> &'a T {
        &items[self.below(items.len())]
    }
}

/// A behaviour's files, the script of one run and its rounds.
pub struct RandomBehaviour {
    /// (file name, text), `behaviour.toml` among them.
    pub files: Vec<(String, String)>,
    /// The impersonator's script (also the manifest's, so the model's domains know its values).
    pub script: String,
    /// Before each round, how long to let virtual time pass.
    pub waits: Vec<Duration>,
}

impl RandomBehaviour {
    pub fn write(&self, dir: &Path) {
        let _ = std::fs::remove_dir_all(dir);
        std::fs::create_dir_all(dir).expect("the folder can be made");
        for (name, text) in &self.files {
            std::fs::write(dir.join(name), text).expect("write");
        }
    }

    /// Every file, then the rounds, as one text for a report.
    pub fn show(&self) -> String {
        let mut out = String::new();
        for (name, text) in &self.files {
            let _ = writeln!(out, "--- {name}\n{text}");
        }
        let waits: Vec<String> = self.waits.iter().map(|w| format!("{w:?}")).collect();
        let _ = writeln!(out, "--- waits before each round: {}", waits.join(" "));
        out
    }
}

/// What the machines of one behaviour may speak of.
struct Names {
    machines: usize,
    /// Which machines take the parameter `p` (§3.3): never the first, which always runs.
    params: Vec<bool>,
    /// Which machines announce the outcome `done` in their final states.
    outcomes: Vec<bool>,
    /// Parameters and outcomes draw from a sequence of their own, as nesting does.
    iface: std::cell::RefCell<Rng>,
    /// Which transitions stay (no target, §3.2), and what they do: a sequence of their own
    /// too, so that a seed's machines are what they were before, but for those.
    stays: std::cell::RefCell<Rng>,
    /// Which transitions enter two regions of a parallel state at named states (several
    /// targets, §3.2): a sequence of its own again.
    targets: std::cell::RefCell<Rng>,
    inputs: usize,
    globals: usize,
    externs: usize,
    /// Whether the machines post the type `T0` (and read it).
    posted: bool,
    /// The theory's outputs (none without a theory).
    outputs: usize,
}

pub fn generate(seed: u64) -> RandomBehaviour {
    let mut rng = Rng::new(seed);
    // Nesting draws from a sequence of its own, so that the flat machines of a seed are
    // what they were before nesting was drawn.
    let mut shape = Rng::new(seed ^ 0x5EED_C4A2_0000_0000);
    let mut iface = Rng::new(seed ^ 0x0A7C_0000_1F00_0000);
    // Regions too, so that the behaviours of a seed are what they were before regions.
    let mut regions = Rng::new(seed ^ 0x9A2A_11E1_0000_0000);
    let stays = Rng::new(seed ^ 0x57A7_5000_0000_0000);
    let targets = Rng::new(seed ^ 0x7A26_E750_0000_0000);
    let machines = rng.between(1, 4);
    let names = Names {
        machines,
        params: (0..machines).map(|m| m > 0 && iface.chance(35)).collect(),
        outcomes: (0..machines).map(|_| iface.chance(35)).collect(),
        iface: std::cell::RefCell::new(iface),
        stays: std::cell::RefCell::new(stays),
        targets: std::cell::RefCell::new(targets),
        inputs: rng.between(1, 3),
        globals: rng.between(0, 2),
        externs: rng.between(0, 1),
        posted: rng.chance(40),
        outputs: if rng.chance(30) { rng.between(1, 2) } else { 0 },
    };
    let mut files = Vec::new();
    let mut manifest = String::new();
    for m in 0..names.machines {
        let text = machine(&mut rng, (&mut shape, &mut regions), &names, m);
        files.push((format!("M{m}.machine"), text));
        let _ = writeln!(manifest, "[[machine]]\nfile = \"M{m}.machine\"");
        // The first machine always runs; the others are sometimes sub-machines, always when
        // a start gives them a parameter.
        if m > 0 && (rng.chance(40) || names.params[m]) {
            let _ = writeln!(manifest, "start = false");
        }
    }
    if names.outputs > 0 {
        files.push(("th.dl".into(), theory(&mut rng, &names)));
        let _ = writeln!(manifest, "[[theory]]\nfile = \"th.dl\"");
    }
    let (script, run_for) = script(&mut rng, &names);
    files.push(("run.script".into(), script.clone()));
    let _ = writeln!(manifest, "[impersonator]\nscript = \"run.script\"");
    files.push(("behaviour.toml".into(), manifest));
    let waits = waits(&mut rng, run_for);
    RandomBehaviour {
        files,
        script,
        waits,
    }
}

fn machine(
    rng: &mut Rng,
    (shape, regions): (&mut Rng, &mut Rng),
    names: &Names,
    m: usize,
) -> String {
    let states = rng.between(2, 5);
    let counter = rng.chance(30);
    let mut blocks = Vec::new();
    for s in 0..states {
        let mut out = String::new();
        let _ = writeln!(out, "state S{s} {{");
        let mut entry = String::new();
        if s == 0 {
            if counter {
                entry.push_str("        int c;\n");
            }
            for e in 0..names.externs {
                let _ = writeln!(entry, "        extern e{e};");
            }
        }
        if m == 0 && s == 0 && rng.chance(50) {
            // Every global and extern assigned somewhere (to itself: no change), so that none
            // is a whiteboard type nobody posts; the other half leaves them free, and unposted
            // until the environment posts them (`g1` and `g1 != 1` both false).
            for g in 0..names.globals {
                let _ = writeln!(entry, "        g{g} = g{g};");
            }
            for e in 0..names.externs {
                let _ = writeln!(entry, "        e{e} = e{e};");
            }
        }
        entry.push_str(&activity(rng, names, m, counter));
        for (section, text) in [
            ("entry", entry),
            ("exit", activity(rng, names, m, counter)),
            ("internal", activity(rng, names, m, counter)),
        ] {
            if !text.is_empty() {
                let _ = writeln!(out, "    {section} {{\n{text}    }}");
            }
        }
        // A state other than the first is sometimes final.
        let transitions = if s > 0 && rng.chance(20) {
            0
        } else {
            rng.between(1, 3)
        };
        for _ in 0..transitions {
            let label = label(rng, names, counter, 2);
            let target = rng.below(states);
            let actions = own_actions(shape, names, m, counter);
            let target = format!("S{target}");
            let rest = arrow(names, m, counter, &label, (&target, &actions));
            let _ = writeln!(out, "    when {label}{rest}");
        }
        out.push_str(&interface_lines(names, m, s, transitions, states));
        let _ = writeln!(out, "}}");
        blocks.push((format!("S{s}"), out));
    }
    let nest = Nest {
        names,
        m,
        counter,
        states,
    };
    let blocks = nest.wrap(shape, blocks, 0);
    let blocks = nest.parallel(regions, blocks);
    let mut out = format!("machine M{m}\n");
    if names.params[m] {
        out.push_str("param p: int\n");
    }
    if names.outcomes[m] {
        out.push_str("outcome done\n");
    }
    for (_, block) in blocks {
        out.push_str(&block);
    }
    out
}

/// What a state `s` of machine `m` with `transitions` of its own adds for parameters and
/// outcomes (§3.3): a final state announces `done`, the first state now and then tests `p`,
/// and a state now and then waits on a machine's outcome.
fn interface_lines(names: &Names, m: usize, s: usize, transitions: usize, states: usize) -> String {
    let mut iface = names.iface.borrow_mut();
    let mut out = String::new();
    if transitions == 0 {
        if names.outcomes[m] {
            out.push_str("    outcome done\n");
        }
        return out;
    }
    if s == 0 && names.params[m] && iface.chance(70) {
        let _ = writeln!(
            out,
            "    when p == {} -> S{}",
            iface.below(3),
            iface.below(states)
        );
    }
    let announcing: Vec<usize> = (0..names.machines).filter(|&t| names.outcomes[t]).collect();
    if !announcing.is_empty() && iface.chance(45) {
        let t = *iface.pick(&announcing);
        let _ = writeln!(out, "    when M{t}.done -> S{}", iface.below(states));
    }
    out
}

/// What a composite state of machine `m` may speak of.
struct Nest<'n> {
    names: &'n Names,
    m: usize,
    counter: bool,
    states: usize,
}

impl Nest<'_> {
    /// Now and then, two or three neighbouring states of the top put side by side as the
    /// regions of a parallel state (§3.2), which has activities and transitions of its own.
    fn parallel(&self, rng: &mut Rng, mut blocks: Vec<(String, String)>) -> Vec<(String, String)> {
        let atomic = |b: &(String, String)| b.0.starts_with('S');
        let starts: Vec<usize> = (0..blocks.len().saturating_sub(1))
            .filter(|&i| atomic(&blocks[i]) && atomic(&blocks[i + 1]))
            .collect();
        if starts.is_empty() || !rng.chance(30) {
            return blocks;
        }
        let from = *rng.pick(&starts);
        let mut to = from + 2;
        if to < blocks.len() && atomic(&blocks[to]) && rng.chance(40) {
            to += 1;
        }
        let regions: Vec<_> = blocks.drain(from..to).collect();
        let mut out = "parallel P0 {\n".to_string();
        for section in ["entry", "exit", "internal"] {
            let text = activity(rng, self.names, self.m, self.counter);
            if !text.is_empty() {
                let _ = writeln!(out, "    {section} {{\n{text}    }}");
            }
        }
        for _ in 0..rng.below(3) {
            let target = match rng.below(6) {
                0 => "P0".to_string(),
                _ => format!("S{}", rng.below(self.states)),
            };
            out.push_str(&self.transition(rng, &target, 35));
        }
        let named: Vec<String> = regions.iter().map(|(name, _)| name.clone()).collect();
        for (_, block) in regions {
            out.push_str(&block);
        }
        out.push_str("}\n");
        blocks.insert(from, ("P0".into(), out));
        self.entering_two_regions(&mut blocks, &named);
        blocks
    }

    /// Now and then, a transition to two of the parallel state's `regions` at once (several
    /// targets, §3.2), written on the parallel state itself (it leaves it and enters it again)
    /// or on a state beside it; a third region, if any, enters at its initial.
    fn entering_two_regions(&self, blocks: &mut [(String, String)], regions: &[String]) {
        let mut rng = self.names.targets.borrow_mut();
        if !rng.chance(40) {
            return;
        }
        let first = rng.below(regions.len() - 1);
        let second = rng.between(first + 1, regions.len() - 1);
        let (a, b) = (&regions[first], &regions[second]);
        let label = label(&mut rng, self.names, self.counter, 1);
        let on = rng.below(blocks.len());
        let block = &mut blocks[on].1;
        // A state with a way out is final no more: it announces no outcome.
        *block = block.replace("    outcome done\n", "");
        let close = block.rfind('}').unwrap_or(block.len());
        block.insert_str(close, &format!("    when {label} -> P0.{a}, P0.{b}\n"));
    }

    /// A transition of a state that holds states, to `target`: labelled `done` in
    /// `done_percent` of the draws, else a random label; with its own actions, or now and then
    /// staying instead ([`arrow`]).
    fn transition(&self, rng: &mut Rng, target: &str, done_percent: usize) -> String {
        let label = if rng.chance(done_percent) {
            "done".to_string()
        } else {
            label(rng, self.names, self.counter, 2)
        };
        let actions = own_actions(rng, self.names, self.m, self.counter);
        let rest = arrow(self.names, self.m, self.counter, &label, (target, &actions));
        format!("    when {label}{rest}\n")
    }

    /// Now and then, some neighbouring states (name, text) put into a composite state of their
    /// own, and at the first depth some of those again.
    fn wrap(
        &self,
        shape: &mut Rng,
        mut blocks: Vec<(String, String)>,
        depth: usize,
    ) -> Vec<(String, String)> {
        if blocks.len() < 2 || depth > 1 || !shape.chance(if depth == 0 { 35 } else { 40 }) {
            return blocks;
        }
        let from = shape.below(blocks.len() - 1);
        let to = shape.between(from + 1, blocks.len());
        let inner: Vec<_> = blocks.drain(from..to).collect();
        let inner = self.wrap(shape, inner, depth + 1);
        let name = format!("C{}", depth);
        let mut out = format!("state {name} {{\n");
        for section in ["entry", "exit", "internal"] {
            let text = activity(shape, self.names, self.m, self.counter);
            if !text.is_empty() {
                let _ = writeln!(out, "    {section} {{\n{text}    }}");
            }
        }
        if shape.chance(50) {
            let _ = writeln!(out, "    initial {}", shape.pick(&inner).0);
        }
        for _ in 0..shape.below(3) {
            // Back into itself: at its initial, or (from inside) where this move leaves it.
            let target = match shape.below(20) {
                0..=2 => name.clone(),
                3 => format!("{name}.history"),
                4 => format!("{name}.deep_history"),
                _ => format!("S{}", shape.below(self.states)),
            };
            // A composite's time test counts from its entry, whatever moves inside it (§3.2).
            out.push_str(&self.transition(shape, &target, 30));
        }
        for (_, block) in inner {
            out.push_str(&block);
        }
        out.push_str("}\n");
        // Now and then a state beside it comes back into it where it was left.
        if !blocks.is_empty() && shape.chance(50) {
            let beside = shape.below(blocks.len());
            let history = if shape.chance(50) {
                "history"
            } else {
                "deep_history"
            };
            let label = label(shape, self.names, self.counter, 1);
            let block = &mut blocks[beside].1;
            // A state with a way out is final no more: it announces no outcome.
            *block = block.replace("    outcome done\n", "");
            let close = block.rfind('}').unwrap_or(block.len());
            block.insert_str(close, &format!("    when {label} -> {name}.{history}\n"));
        }
        blocks.insert(from, (name, out));
        blocks
    }
}

/// Now and then, a transition's own actions (` { … }`, run as it fires), else nothing.
/// What follows a transition's label, drawn as before (` -> TARGET` and its own `actions`); now
/// and then, as `Names::stays` draws, no target and a block of actions instead: it acts and
/// stays (§3.2). Never for `done`, which stays true.
fn arrow(
    names: &Names,
    m: usize,
    counter: bool,
    label: &str,
    (target, actions): (&str, &str),
) -> String {
    let mut stays = names.stays.borrow_mut();
    if label == "done" || !stays.chance(12) {
        return format!(" -> {target}{actions}");
    }
    let block = activity(&mut stays, names, m, counter);
    format!(" {{\n{block}    }}")
}

fn own_actions(shape: &mut Rng, names: &Names, m: usize, counter: bool) -> String {
    if !shape.chance(15) {
        return String::new();
    }
    let actions = activity(shape, names, m, counter);
    if actions.is_empty() {
        return String::new();
    }
    format!(" {{\n{actions}    }}")
}

/// Zero to three actions, one a line.
fn activity(rng: &mut Rng, names: &Names, m: usize, counter: bool) -> String {
    let mut out = String::new();
    let count = *rng.pick(&[0, 0, 1, 1, 2, 3]);
    for _ in 0..count {
        let line = match rng.below(8) {
            0 | 1 if names.globals > 0 => {
                let g = rng.below(names.globals);
                match rng.below(3) {
                    0 => format!("g{g} = {};", rng.below(3)),
                    1 => format!("g{g} = in{};", rng.below(names.inputs)),
                    _ => format!("g{g} = (g{g} + 1) % 3;"),
                }
            }
            2 if names.externs > 0 => format!("e{} = {};", rng.below(names.externs), rng.below(3)),
            3 if names.posted => format!("T0: {}", rng.below(3)),
            4 if counter => "c = c + 1;".to_string(),
            5 | 6 if names.machines > 1 => control(rng, names, m),
            7 if rng.chance(30) => control(rng, names, m),
            _ => format!("g = {};", rng.below(2)),
        };
        let _ = writeln!(out, "        {line}");
    }
    out
}

/// A command to another machine (now and then to itself), as a call or as a posting.
fn control(rng: &mut Rng, names: &Names, m: usize) -> String {
    let target = if names.machines > 1 && !rng.chance(10) {
        (m + rng.between(1, names.machines - 1)) % names.machines
    } else {
        m
    };
    let (posted, call) = if rng.chance(30) {
        let word = *rng.pick(&["On", "Off", "suspend", "resume", "restart"]);
        (Some(word), format!("M{target}: {word}"))
    } else {
        let call = rng.pick(&["start", "stop", "suspend", "resume", "restart"]);
        (None, format!("{call}(\"M{target}\");"))
    };
    if !names.params[target] && !names.outcomes[target] {
        return call;
    }
    // A machine with a parameter or an outcome is started by `restart`, given its parameter on
    // a line of its own (§3.3).
    let starts = match posted {
        Some(word) => ["On", "restart"].contains(&word),
        None => call.starts_with("start(") || call.starts_with("restart("),
    };
    if !starts {
        return call;
    }
    if !names.params[target] {
        return match posted {
            Some(_) => format!("M{target}: restart"),
            None => format!("restart(\"M{target}\");"),
        };
    }
    let mut iface = names.iface.borrow_mut();
    let value = match iface.below(3) {
        0 if names.globals > 0 => format!("(g{} + 1) % 3", iface.below(names.globals)),
        _ => iface.below(3).to_string(),
    };
    format!("M{target}: restart(p = {value})")
}

fn label(rng: &mut Rng, names: &Names, counter: bool, depth: usize) -> String {
    if depth > 0 && rng.chance(40) {
        let left = label(rng, names, counter, depth - 1);
        return match rng.below(3) {
            0 => format!("!({left})"),
            1 => format!("({left} && {})", label(rng, names, counter, depth - 1)),
            _ => format!("({left} || {})", label(rng, names, counter, depth - 1)),
        };
    }
    loop {
        let atom = match rng.below(11) {
            0 | 1 => format!("in{}", rng.below(names.inputs)),
            2 => format!("~in{}", rng.below(names.inputs)),
            3 if names.globals > 0 => {
                let g = rng.below(names.globals);
                match rng.below(3) {
                    0 => format!("g{g}"),
                    1 => format!("g{g} == {}", rng.below(3)),
                    _ => format!("g{g} != 1"),
                }
            }
            4 if names.externs > 0 => format!("e{} == {}", rng.below(names.externs), rng.below(3)),
            10 if names.posted => format!("T0 == {}", rng.below(3)),
            5 => {
                let d = rng.pick(&["50ms", "100ms", "200ms", "500ms", "1s"]);
                match rng.below(4) {
                    0 => format!("after_ms({})", rng.pick(&[100, 300])),
                    _ => format!("timeout({d})"),
                }
            }
            6 if counter => format!("c >= {}", rng.between(1, 3)),
            7 if names.outputs > 0 => format!("o{}", rng.below(names.outputs)),
            8 if names.machines > 1 => format!("M{}IsRunning", rng.below(names.machines)),
            9 if rng.chance(50) => "TRUE".to_string(),
            _ => continue,
        };
        return atom;
    }
}

/// A theory answering `o0`, `o1` from some of the inputs (and the posted type): each output
/// false by default, true by a rule or two over its inputs, with now and then an exception.
fn theory(rng: &mut Rng, names: &Names) -> String {
    let mut inputs: Vec<String> = (0..names.inputs).map(|i| format!("in{i}")).collect();
    if names.posted {
        inputs.push("T0".into());
    }
    let mut out = String::from("name{th}.\n");
    for i in &inputs {
        let _ = writeln!(out, "input{{{i}}}.");
    }
    let literal = |rng: &mut Rng| {
        let i = rng.pick(&inputs).clone();
        if rng.chance(30) {
            format!("~{i}")
        } else {
            i
        }
    };
    for o in 0..names.outputs {
        let _ = writeln!(out, "D{o}: => ~o{o}.");
        for r in 0..rng.between(1, 2) {
            let conditions = if rng.chance(40) {
                format!("{}, {}", literal(rng), literal(rng))
            } else {
                literal(rng)
            };
            let _ = writeln!(out, "R{o}x{r}: {conditions} => o{o}.\nR{o}x{r} > D{o}.");
            if rng.chance(30) {
                let _ = writeln!(
                    out,
                    "X{o}x{r}: {} => ~o{o}.\nX{o}x{r} > R{o}x{r}.",
                    literal(rng)
                );
            }
        }
        let _ = writeln!(out, "output{{beta o{o}, \"output {o}\"}}.");
    }
    out
}

/// The inputs' values at the start (some left unset: false until set) and their changes;
/// how long the run goes on.
fn script(rng: &mut Rng, names: &Names) -> (String, Duration) {
    let run_ms = rng.between(500, 4000);
    let mut out = String::new();
    // Most inputs set from the start; one the script sets only later, or never, stays
    // unposted until then (a silent sensor, which the model allows until it first speaks).
    for i in 0..names.inputs {
        if rng.chance(70) {
            let _ = writeln!(out, "in{i} = {}", rng.chance(50));
        }
    }
    for _ in 0..rng.between(0, 8) {
        let at = rng.between(1, run_ms);
        let _ = writeln!(
            out,
            "at {at}ms in{} = {}",
            rng.below(names.inputs),
            rng.chance(50)
        );
    }
    (out, Duration::from_millis(run_ms as u64))
}

/// Waits before rounds until `run_for` has passed: often none (rounds back to back), often a
/// ring period's worth or less, sometimes long enough for every time test. The first is never
/// zero, so that the experts have started before the first round asks them.
fn waits(rng: &mut Rng, run_for: Duration) -> Vec<Duration> {
    let mut waits = vec![Duration::from_millis(1)];
    let mut total = Duration::ZERO;
    while total < run_for && waits.len() < 60 {
        let wait = match rng.below(10) {
            0..=3 => Duration::ZERO,
            4..=7 => Duration::from_millis(rng.between(1, 150) as u64),
            _ => Duration::from_millis(rng.between(200, 1200) as u64),
        };
        total += wait;
        waits.push(wait);
    }
    waits
}
