//! The checking stage: a syntax tree becomes a [`Theory`], or diagnostics that say what is wrong
//! and where (duplicate and undefined labels, priority cycles, contradicting facts, misused
//! input and output declarations).

use crate::closure::{close, normalize, ClosureOutcome, Resolvents, MAX_CLOSURE};
use crate::literal::{Atom, Lit, RuleId};
use crate::scc::{strongly_connected, Roots};
use crate::slots::{hash, hash_bytes, Slots};
use crate::theory::{Clause, InputGroup, Origin, Output, RowFilter, RuleKind, Theory};
use proclaim_syntax::{ast, Algorithm, Diagnostic, Item, Language, ParsedTheory, Span};
use rustc_hash::FxHashMap;

/// A theory, or everything wrong with it. Warnings come with a theory too.
#[derive(Debug)]
pub struct Checked {
    pub theory: Option<Theory>,
    /// Parse and check diagnostics, in file order.
    pub diagnostics: Vec<Diagnostic>,
}

/// Checks a parsed file against its source text. Parse errors are kept; a theory is built only
/// when there are no errors at all.
pub fn check(parsed: ParsedTheory, source: &str) -> Checked {
    let rules = parsed
        .items
        .iter()
        .filter(|i| matches!(i, Item::Rule(_)))
        .count();
    let mut checker = Checker::new(source, rules);
    let mut batch = Batch::default();
    for item in parsed.items {
        batch.push(item, source);
    }
    checker.batch(&batch);
    checker.finish(parsed.diagnostics, &parsed.broken_labels)
}

/// How many priorities left to the end have their labels asked for from memory before the first
/// of them is resolved.
const AHEAD: usize = 32;

/// How far ahead of the literal being interned its table slot is asked for from memory, in
/// literals, and likewise for labels.
const LITS_AHEAD: usize = 64;
const LABELS_AHEAD: usize = 16;

/// Statements on their way to the checker, with the work on them that needs nothing but the
/// statement itself done beforehand (by the parser's thread, in a pipeline): their literals laid
/// out flat and every name hashed. The checker then reads the literals in one sweep instead of
/// from each statement's own vectors, which lie scattered over the parser's heap, and hashes
/// nothing.
#[derive(Default)]
struct Batch {
    items: Vec<Item>,
    /// The literals of each rule (its body, then its head) and fact, in statement order.
    lits: Vec<ast::SourceLiteral>,
    /// The hash of each literal's atom name in `lits`.
    lit_hashes: Vec<u64>,
    /// The hash of each label written, in a rule or a priority, in statement order.
    label_hashes: Vec<u64>,
}

impl Batch {
    fn with_capacity(items: usize) -> Batch {
        Batch {
            items: Vec::with_capacity(items),
            lits: Vec::with_capacity(items * 4),
            lit_hashes: Vec::with_capacity(items * 4),
            label_hashes: Vec::with_capacity(items),
        }
    }

    fn push(&mut self, item: Item, source: &str) {
        // By bytes: a span of the source always falls on character boundaries.
        let name = |span: Span| hash_bytes(&source.as_bytes()[span.range()]);
        let mut add = |lit: &ast::SourceLiteral| {
            self.lits.push(*lit);
            self.lit_hashes.push(name(lit.atom));
        };
        match &item {
            Item::Rule(rule) => {
                rule.body.iter().for_each(&mut add);
                add(&rule.head);
                if let Some(label) = rule.label {
                    self.label_hashes.push(name(label));
                }
            }
            Item::Fact { clause, .. } => clause.iter().for_each(add),
            Item::Priority { labels, .. } => {
                for &label in labels {
                    self.label_hashes.push(name(label));
                }
            }
            _ => {}
        }
        self.items.push(item);
    }

    fn len(&self) -> usize {
        self.items.len()
    }
}

/// Where the checker is in a [`Batch`]'s flat arrays.
#[derive(Default)]
struct Cursor {
    lit: usize,
    label: usize,
}

/// Files at least this large are parsed and checked at the same time, on two threads.
const PIPELINE_BYTES: usize = 1 << 20;

/// Parses and checks a source text. A large file is parsed on a second thread that hands
/// statements over in batches while this one checks them: the two stages overlap.
pub fn check_source(source: &str, language: Language) -> Checked {
    if source.len() < PIPELINE_BYTES {
        return check(proclaim_syntax::parse(source, language), source);
    }
    const BATCH: usize = 4096;
    let (sender, batches) = std::sync::mpsc::sync_channel::<Batch>(16);
    // Checked batches go back to the parser to be freed: memory is freed fastest by the thread
    // that allocated it, and the checker is the busier of the two.
    let (give_back, checked) = std::sync::mpsc::channel::<Batch>();
    std::thread::scope(|scope| {
        let parser = scope.spawn(move || {
            let mut batch = Batch::with_capacity(BATCH);
            let parsed = proclaim_syntax::parse_each(source, language, |item| {
                batch.push(item, source);
                if batch.len() == BATCH {
                    // The checker only stops receiving when it is gone; nothing to do then.
                    let _ = sender.send(std::mem::replace(&mut batch, Batch::with_capacity(BATCH)));
                    checked.try_iter().for_each(drop);
                }
            });
            let _ = sender.send(batch);
            parsed
        });
        // About 25 bytes a rule in large generated theories.
        let mut checker = Checker::new(source, source.len() / 25);
        for batch in batches {
            checker.batch(&batch);
            let _ = give_back.send(batch);
        }
        match parser.join() {
            Ok(parsed) => checker.finish(parsed.diagnostics, &parsed.broken_labels),
            // The parser never panics (it is fuzzed); should it, parse again here to report.
            Err(_) => check(proclaim_syntax::parse(source, language), source),
        }
    })
}

struct Checker<'s> {
    source: &'s str,
    theory: Theory,
    diagnostics: Vec<Diagnostic>,
    /// The first rule of each label, found by the label's text (which the theory's
    /// `label_text` holds). Filled as rules come in, so a label used twice is found at once.
    labels: Slots,
    input_spans: FxHashMap<Atom, Span>,
    /// Where each body literal was written (parallel to the theory's `bodies`).
    body_spans: Vec<Span>,
    /// Labels of rules that did not parse: priorities naming them are not reported again.
    broken_labels: rustc_hash::FxHashSet<&'s str>,
    /// Each label in lower case, to the first in order of the labels written so: made at the
    /// first unknown label a priority names, so a theory of many is hinted in linear time.
    similar: std::cell::OnceCell<FxHashMap<String, String>>,
    /// The priorities, resolved once every label is known: each is where its labels end in
    /// `priority_labels` (every priority's labels one after another, so a million priorities
    /// are two arrays rather than a million small ones) and its span.
    priorities: Vec<(u32, Span)>,
    priority_labels: Vec<Span>,
    name_span: Option<Span>,
    /// The literal of every fact, one after another, while every fact is one literal (as in
    /// nearly every large theory): closing and compiling the facts then reads one flat array
    /// instead of a vector per fact. `None` once a fact is a longer clause.
    units: Option<Vec<Unit>>,
}

/// A fact of one literal, read as a clause.
#[derive(Clone, Copy)]
struct Unit(Lit);

impl AsRef<[Lit]> for Unit {
    fn as_ref(&self) -> &[Lit] {
        std::slice::from_ref(&self.0)
    }
}

impl<'s> Checker<'s> {
    fn atom(&mut self, span: Span) -> Atom {
        self.theory.atoms.intern(span.text(self.source))
    }

    fn lit(&mut self, lit: &ast::SourceLiteral) -> Lit {
        Lit::new(self.atom(lit.atom), lit.negated)
    }

    /// A checker expecting about `rules` rules (tables are sized for them up front).
    fn new(source: &'s str, rules: usize) -> Checker<'s> {
        let mut checker = Checker {
            source,
            theory: Theory::default(),
            diagnostics: Vec::new(),
            labels: Slots::default(),
            input_spans: FxHashMap::default(),
            body_spans: Vec::new(),
            broken_labels: Default::default(),
            similar: std::cell::OnceCell::new(),
            priorities: Vec::new(),
            priority_labels: Vec::new(),
            name_span: None,
            units: Some(Vec::new()),
        };
        // Nothing to rehash in an empty table, so this hasher is never called.
        checker.labels.reserve(rules, |_| 0);
        let t = &mut checker.theory;
        t.atoms.reserve(rules + 1);
        t.heads.reserve(rules);
        t.kinds.reserve(rules);
        t.body_start.reserve(rules + 1);
        t.labels.reserve(rules);
        t.origins.reserve(rules);
        // As many facts as rules at most, in the benchmark families: memory reserved and never
        // written costs nothing, where growing by doubling copies every clause each time.
        t.axioms.reserve(rules);
        t.body_start.push(0);
        checker
    }

    /// Takes in a batch of statements, in file order. By reference, so that a pipeline's
    /// batches are freed by the thread that made them. The table slots of the literals and
    /// labels a little further on are asked for before these are taken in, so their cache
    /// misses overlap instead of coming one after another (most of checking a large theory was
    /// waiting on them).
    fn batch(&mut self, batch: &Batch) {
        for hash in batch.lit_hashes.iter().take(LITS_AHEAD) {
            self.theory.atoms.prefetch_hashed(*hash);
        }
        for hash in batch.label_hashes.iter().take(LABELS_AHEAD) {
            self.labels.prefetch(*hash);
        }
        let mut at = Cursor::default();
        for item in &batch.items {
            self.item(item, batch, &mut at);
        }
    }

    /// The next literal of the batch, interned; the slot of the one `LITS_AHEAD` further on is
    /// asked for.
    fn next_lit(&mut self, batch: &Batch, at: &mut Cursor) -> (Lit, Span) {
        if let Some(&ahead) = batch.lit_hashes.get(at.lit + LITS_AHEAD) {
            self.theory.atoms.prefetch_hashed(ahead);
        }
        let written = batch.lits[at.lit];
        let name = written.atom.text(self.source);
        let atom = self
            .theory
            .atoms
            .intern_hashed(name, batch.lit_hashes[at.lit]);
        at.lit += 1;
        (Lit::new(atom, written.negated), written.span)
    }

    /// The hash of the next label of the batch; the slot of the one `LABELS_AHEAD` further on
    /// is asked for.
    fn next_label_hash(&mut self, batch: &Batch, at: &mut Cursor) -> u64 {
        if let Some(&ahead) = batch.label_hashes.get(at.label + LABELS_AHEAD) {
            self.labels.prefetch(ahead);
        }
        at.label += 1;
        batch.label_hashes[at.label - 1]
    }

    /// Takes in one statement, in file order.
    fn item(&mut self, item: &Item, batch: &Batch, at: &mut Cursor) {
        match item {
            Item::Rule(rule) => self.add_rule(rule, batch, at),
            &Item::Fact { ref clause, span } => self.add_fact(clause.len(), span, batch, at),
            Item::Priority { labels, span } => self.add_priority_item(labels, *span, batch, at),
            &Item::Name { name, span } => {
                if let Some(first) = self.name_span {
                    self.diagnostics.push(
                        Diagnostic::error(span, "the theory is named twice")
                            .with_related(first, "first named here"),
                    );
                } else {
                    self.name_span = Some(span);
                    self.theory.name = Some(name.text(self.source).to_string());
                }
            }
            Item::Input { atoms, span } => self.add_input(atoms, *span),
            &Item::Ignore {
                at_least,
                ref lits,
                span,
            } => {
                let lits = self.filter_lits(lits);
                let at_least = at_least.map_or(lits.len(), |k| k as usize);
                if at_least == 0 || at_least > lits.len() {
                    self.diagnostics.push(
                        Diagnostic::error(
                            span,
                            format!("`ignore {at_least} of` names only {} literals", lits.len()),
                        )
                        .with_hint("the count must be between 1 and the number of literals"),
                    );
                }
                self.theory
                    .filters
                    .push(RowFilter::Ignore { at_least, lits });
            }
            &Item::Assert { ref lits, span } => {
                let lits = self.filter_lits(lits);
                if lits.is_empty() {
                    self.diagnostics.push(
                        Diagnostic::error(span, "`assert{}` names no literal").with_hint(
                            "an empty assert would leave out every row of the truth table",
                        ),
                    );
                }
                self.theory.filters.push(RowFilter::Assert { lits });
            }
            Item::Output { parts, span } => self.add_outputs(parts, *span),
        }
    }

    /// Takes in a fact of `len` literals, the next ones of the batch.
    fn add_fact(&mut self, len: usize, span: Span, batch: &Batch, at: &mut Cursor) {
        let lits = (0..len)
            .map(|_| self.next_lit(batch, at).0)
            .collect::<Vec<_>>();
        match (&mut self.units, lits.as_slice()) {
            (Some(units), &[unit]) => units.push(Unit(unit)),
            _ => self.units = None,
        }
        // One literal is no tautology: a fact, nearly always, needs no copy to tell.
        if lits.len() > 1 && normalize(lits.clone()).is_none() {
            self.diagnostics.push(
                Diagnostic::warning(
                    span,
                    "this clause holds a literal and its complement, so it says nothing",
                )
                .with_label("a tautology"),
            );
        }
        self.theory.axioms.push(Clause {
            lits,
            span: Some(span),
        });
    }

    /// Takes in a priority, its labels' hashes the next ones of the batch. Resolved now when
    /// every label names a rule read already (as in nearly every theory, whose priorities come
    /// after its rules): while the parser is the slower stage this costs no time. Else at the
    /// end, once every label is known, and every later priority with it, so that priorities
    /// keep their file order.
    fn add_priority_item(&mut self, labels: &[Span], span: Span, batch: &Batch, at: &mut Cursor) {
        let mut ids = Vec::with_capacity(labels.len());
        for &label in labels {
            let label_hash = self.next_label_hash(batch, at);
            if self.priorities.is_empty() {
                let text = label.text(self.source);
                ids.push(self.labelled_hashed(text, label_hash));
            }
        }
        if ids.len() == labels.len() && ids.iter().all(Option::is_some) {
            self.add_priority_ids(&ids, span);
        } else {
            self.priority_labels.extend_from_slice(labels);
            let end = self.priority_labels.len() as u32;
            self.priorities.push((end, span));
        }
    }

    /// Every statement is in: resolves priorities, runs the whole-theory checks and closes the
    /// axioms. `parse_diagnostics` come first in the merged, position-sorted list.
    fn finish(mut self, parse_diagnostics: Vec<Diagnostic>, broken_labels: &[Span]) -> Checked {
        for span in broken_labels {
            self.broken_labels.insert(span.text(self.source));
        }
        self.theory.written_rules = self.theory.heads.len();
        // The labels of the next few priorities are asked for from memory first, as `items`
        // does for rules: their slots lie anywhere in the table.
        let priorities = std::mem::take(&mut self.priorities);
        let labels = std::mem::take(&mut self.priority_labels);
        let mut start = 0;
        for chunk in priorities.chunks(AHEAD) {
            let chunk_end = chunk.last().map_or(start, |&(end, _)| end as usize);
            for label in &labels[start..chunk_end] {
                self.labels.prefetch(hash(label.text(self.source)));
            }
            for &(end, span) in chunk {
                self.add_priority(&labels[start..end as usize], span);
                start = end as usize;
            }
        }
        self.check_priority_cycles();
        self.check_filters_name_inputs();
        // Only in a theory that says what its inputs are (so an undeclared condition is a slip,
        // not a value from outside), and that has no errors to fix first.
        let errors = parse_diagnostics
            .iter()
            .chain(&self.diagnostics)
            .any(Diagnostic::is_error);
        if !self.theory.inputs.is_empty() && !errors {
            self.check_conditions_can_hold();
        }
        self.close_axioms();
        let mut diagnostics = parse_diagnostics;
        diagnostics.append(&mut self.diagnostics);
        diagnostics.sort_by_key(|d| (d.span.start, d.span.end));
        let has_errors = diagnostics.iter().any(Diagnostic::is_error);
        Checked {
            theory: (!has_errors).then_some(self.theory),
            diagnostics,
        }
    }

    /// Takes in a rule, its literals and label hash the next ones of the batch.
    fn add_rule(&mut self, rule: &ast::RuleItem, batch: &Batch, at: &mut Cursor) {
        let id = self.theory.heads.len() as RuleId;
        let mut label_range = (0, 0);
        if let Some(label) = rule.label {
            let text = label.text(self.source);
            let label_hash = self.next_label_hash(batch, at);
            self.add_label(text, label_hash, id, label.start);
            let start = self.theory.label_text.len() as u32;
            self.theory.label_text.push_str(text);
            label_range = (start, self.theory.label_text.len() as u32);
        }
        for _ in 0..rule.body.len() {
            let (lit, span) = self.next_lit(batch, at);
            self.theory.bodies.push(lit);
            self.body_spans.push(span);
        }
        let (head, _) = self.next_lit(batch, at);
        self.theory.heads.push(head);
        self.theory.kinds.push(match rule.arrow {
            ast::Arrow::Strict => RuleKind::Strict,
            ast::Arrow::Defeasible => RuleKind::Defeasible,
            ast::Arrow::Warning => RuleKind::Warning,
        });
        self.theory.body_start.push(self.theory.bodies.len() as u32);
        self.theory.labels.push(label_range);
        self.theory.origins.push(Origin::Written(rule.span));
    }

    fn add_input(&mut self, atoms: &[ast::SourceLiteral], span: Span) {
        let mut group = Vec::new();
        for lit in atoms {
            if lit.negated {
                self.diagnostics.push(
                    Diagnostic::error(lit.span, "inputs are atoms, not negated literals")
                        .with_hint(format!(
                            "write `input{{{}}}`: the input can then be true or false",
                            lit.atom.text(self.source)
                        )),
                );
                continue;
            }
            let atom = self.atom(lit.atom);
            if let Some(&first) = self.input_spans.get(&atom) {
                self.diagnostics.push(
                    Diagnostic::error(
                        lit.span,
                        format!(
                            "`{}` is declared as an input twice",
                            lit.atom.text(self.source)
                        ),
                    )
                    .with_related(first, "first declared here"),
                );
                continue;
            }
            self.input_spans.insert(atom, lit.span);
            group.push(atom);
        }
        if atoms.is_empty() {
            self.diagnostics
                .push(Diagnostic::error(span, "`input{}` names no atom"));
        }
        if !group.is_empty() {
            self.theory.inputs.push(InputGroup { atoms: group, span });
        }
    }

    fn filter_lits(&mut self, lits: &[ast::SourceLiteral]) -> Vec<Lit> {
        lits.iter().map(|l| self.lit(l)).collect()
    }

    fn add_outputs(&mut self, parts: &[ast::OutputPart], span: Span) {
        let description = parts.iter().find_map(|p| match p {
            ast::OutputPart::Description(d) => Some(d.clone()),
            ast::OutputPart::Lit { .. } => None,
        });
        let mut any = false;
        for part in parts {
            if let ast::OutputPart::Lit { algorithm, lit } = part {
                any = true;
                let lowered = self.lit(lit);
                self.theory.outputs.push(Output {
                    lit: lowered,
                    algorithm: algorithm.map_or(Algorithm::Beta, |(a, _)| a),
                    description: description.clone(),
                    span: lit.span,
                });
            }
        }
        if !any {
            self.diagnostics.push(
                Diagnostic::error(span, "`output{}` names no literal")
                    .with_hint("write `output{beta offside, \"description\"}`"),
            );
        }
    }

    fn add_priority(&mut self, labels: &[Span], span: Span) {
        let mut ids = Vec::with_capacity(labels.len());
        for &label in labels {
            let text = label.text(self.source);
            match self.labelled(text) {
                Some(id) => ids.push(Some(id)),
                None if self.broken_labels.contains(text) => ids.push(None),
                None => {
                    let mut d = Diagnostic::error(label, format!("no rule is labelled `{text}`"))
                        .with_label("undefined label");
                    if let Some(similar) = self.similar_label(text) {
                        d = d.with_hint(format!("did you mean `{similar}`?"));
                    } else {
                        d = d.with_hint(
                            "priorities name rules by their labels, as in `R1: a => b.`",
                        );
                    }
                    self.diagnostics.push(d);
                    ids.push(None);
                }
            }
        }
        self.add_priority_ids(&ids, span);
    }

    /// The priorities between each two rules next to each other in `ids` (`None` for a label
    /// reported already), with what is wrong with them.
    fn add_priority_ids(&mut self, ids: &[Option<RuleId>], span: Span) {
        for pair in ids.windows(2) {
            if let [Some(winner), Some(loser)] = *pair {
                if winner == loser {
                    self.diagnostics.push(
                        Diagnostic::error(
                            span,
                            format!(
                                "rule `{}` is given priority over itself",
                                label_of(&self.theory, winner)
                            ),
                        )
                        .with_hint("priorities must be acyclic"),
                    );
                } else {
                    let (w, l) = (
                        self.theory.heads[winner as usize],
                        self.theory.heads[loser as usize],
                    );
                    if w != l.complement() {
                        self.diagnostics.push(
                            Diagnostic::warning(
                                span,
                                format!(
                                    "`{} > {}` changes nothing: they conclude `{}` and `{}`, which do not conflict",
                                    label_of(&self.theory, winner),
                                    label_of(&self.theory, loser),
                                    self.theory.show(w),
                                    self.theory.show(l)
                                ),
                            )
                            .with_hint("a priority decides between rules for a literal and its negation"),
                        );
                    }
                    self.theory.priorities.push((winner, loser));
                }
            }
        }
    }

    /// Indexes the first rule of each label; reports a label used again.
    fn add_label(&mut self, text: &str, label_hash: u64, rule: RuleId, start: u32) {
        let theory = &self.theory;
        let found = self.labels.find_or_insert(
            label_hash,
            rule,
            |r| theory.label(r) == Some(text),
            |r| hash(theory.label(r).unwrap_or_default()),
        );
        if let Ok(first) = found {
            // A label is the first thing its rule's statement holds; rules of the closure are
            // made after every written one, so the first is always written.
            let first_start = match theory.origins[first as usize] {
                Origin::Written(span) => span.start,
                Origin::Clause(_) => start,
            };
            self.diagnostics
                .push(label_used_twice(text, start, first_start));
        }
    }

    /// The rule labelled `text`, if one is.
    fn labelled(&self, text: &str) -> Option<RuleId> {
        self.labelled_hashed(text, hash(text))
    }

    /// [`Checker::labelled`] for a label whose hash is known already.
    fn labelled_hashed(&self, text: &str, label_hash: u64) -> Option<RuleId> {
        self.labels
            .find(label_hash, |r| self.theory.label(r) == Some(text))
    }

    fn similar_label(&self, text: &str) -> Option<String> {
        let similar = self.similar.get_or_init(|| {
            let mut similar: FxHashMap<String, String> = FxHashMap::default();
            for label in self.labels.ids().filter_map(|r| self.theory.label(r)) {
                let least = similar.entry(label.to_ascii_lowercase()).or_default();
                if least.is_empty() || label < least.as_str() {
                    *least = label.to_string();
                }
            }
            similar
        });
        similar.get(&text.to_ascii_lowercase()).cloned()
    }

    /// Tarjan over the priority graph; every strongly connected component with more than one
    /// rule is a cycle.
    fn check_priority_cycles(&mut self) {
        // Over the priorities that may lie on a cycle only: one whose winner is beaten by some
        // rule and whose loser beats some rule. Every cycle keeps all its priorities, and a
        // theory of a million priorities between pairs of rules is a graph of no nodes.
        let rules = self.theory.heads.len();
        let (mut beats, mut beaten) = (vec![false; rules], vec![false; rules]);
        for &(w, l) in &self.theory.priorities {
            beats[w as usize] = true;
            beaten[l as usize] = true;
        }
        let edges: Vec<(RuleId, RuleId)> = self
            .theory
            .priorities
            .iter()
            .filter(|&&(w, l)| beaten[w as usize] && beats[l as usize])
            .copied()
            .collect();
        if edges.is_empty() {
            return;
        }
        let mut named: Vec<RuleId> = edges.iter().flat_map(|&(w, l)| [w, l]).collect();
        named.sort_unstable();
        named.dedup();
        let node = |r: RuleId| named.binary_search(&r).unwrap_or_default() as RuleId;
        let mut succ: Vec<Vec<RuleId>> = vec![Vec::new(); named.len()];
        for &(w, l) in &edges {
            succ[node(w) as usize].push(node(l));
        }
        for component in strongly_connected(succ.len(), |v| &succ[v], Roots::WithSuccessors) {
            if component.len() < 2 {
                continue;
            }
            let mut component: Vec<RuleId> = component.iter().map(|&i| named[i as usize]).collect();
            component.sort_unstable();
            let mut names: Vec<String> = component
                .iter()
                .map(|&r| label_of(&self.theory, r))
                .collect();
            names.sort();
            let first = component[0] as usize;
            let span = match self.theory.origins[first] {
                Origin::Written(s) => s,
                Origin::Clause(_) => Span::default(),
            };
            let on_cycle: Vec<String> = self
                .theory
                .priorities
                .iter()
                .filter(|(w, l)| component.contains(w) && component.contains(l))
                .map(|&(w, l)| {
                    format!(
                        "`{} > {}`",
                        label_of(&self.theory, w),
                        label_of(&self.theory, l)
                    )
                })
                .collect();
            let mut d = Diagnostic::error(
                span,
                format!("priorities form a cycle among rules {}", names.join(", ")),
            )
            .with_label("this rule is on the cycle")
            .with_hint(format!(
                "the priority relation must be acyclic: remove one of {}",
                on_cycle.join(", ")
            ));
            for &r in &component[1..] {
                if let Origin::Written(s) = self.theory.origins[r as usize] {
                    d = d.with_related(s, "also on the cycle");
                }
            }
            self.diagnostics.push(d);
        }
    }

    fn check_filters_name_inputs(&mut self) {
        // Every atom a rule, fact or input names, marked once: a theory of many outputs is
        // checked in linear time.
        let theory = &self.theory;
        let mut named = vec![false; theory.atom_count()];
        let axioms = theory.axioms.iter().flat_map(|c| c.lits.iter());
        for l in theory.heads.iter().chain(&theory.bodies).chain(axioms) {
            named[l.atom().0 as usize] = true;
        }
        for a in theory.input_atoms() {
            named[a.0 as usize] = true;
        }
        for output in &self.theory.outputs {
            let atom = output.lit.atom();
            let used = named.get(atom.0 as usize).copied().unwrap_or(false);
            if !used {
                self.diagnostics.push(
                    Diagnostic::warning(
                        output.span,
                        format!(
                            "output `{}` appears in no rule, fact or input",
                            self.theory.atom_name(atom)
                        ),
                    )
                    .with_label("it can never be proved")
                    .with_hint("check the spelling against the rules"),
                );
            }
        }
    }

    /// A condition whose atom no rule concludes, no fact states and no input sets can never
    /// hold: most often a typo (`cornerkick` for the input `cornerKick`), which otherwise would
    /// pass silently. The input it was meant to be is then read by no rule; both are said.
    fn check_conditions_can_hold(&mut self) {
        let theory = &self.theory;
        let mut grounded = vec![false; theory.atom_count()];
        let mut mark = |a: Atom| grounded[a.0 as usize] = true;
        theory.heads.iter().for_each(|l| mark(l.atom()));
        theory.input_atoms().for_each(&mut mark);
        theory
            .axioms
            .iter()
            .flat_map(|c| &c.lits)
            .for_each(|l| mark(l.atom()));
        let grounded_names: Vec<&str> = (0..theory.atom_count())
            .filter(|&i| grounded[i])
            .map(|i| theory.atom_name(Atom(i as u32)))
            .collect();
        let mut reported = vec![false; theory.atom_count()];
        let mut found = Vec::new();
        for (lit, span) in theory.bodies.iter().zip(&self.body_spans) {
            let a = lit.atom();
            if grounded[a.0 as usize] || reported[a.0 as usize] {
                continue;
            }
            reported[a.0 as usize] = true;
            let name = theory.atom_name(a);
            let hint = match proclaim_syntax::nearest(grounded_names.iter().copied(), name) {
                Some(near) => format!("did you mean `{near}`?"),
                None => format!("declare it an input (`input{{{name}}}.`) or give it a rule"),
            };
            found.push(
                Diagnostic::warning(
                    *span,
                    format!("`{name}` is concluded by no rule and is no input or fact"),
                )
                .with_label("so this condition never holds")
                .with_hint(hint),
            );
        }
        let mut read = vec![false; theory.atom_count()];
        theory
            .bodies
            .iter()
            .for_each(|l| read[l.atom().0 as usize] = true);
        theory
            .heads
            .iter()
            .for_each(|l| read[l.atom().0 as usize] = true);
        theory
            .axioms
            .iter()
            .flat_map(|c| &c.lits)
            .for_each(|l| read[l.atom().0 as usize] = true);
        theory
            .outputs
            .iter()
            .for_each(|o| read[o.lit.atom().0 as usize] = true);
        for a in theory.input_atoms() {
            if read[a.0 as usize] {
                continue;
            }
            let Some(&span) = self.input_spans.get(&a) else {
                continue;
            };
            found.push(
                Diagnostic::warning(
                    span,
                    format!("input `{}` is read by no rule", theory.atom_name(a)),
                )
                .with_label("its value changes nothing"),
            );
        }
        self.diagnostics.extend(found);
    }

    fn reserve_strict_rules(&mut self, strict: usize) {
        let theory = &mut self.theory;
        theory.heads.reserve(strict);
        theory.kinds.reserve(strict);
        theory.body_start.reserve(strict);
        theory.labels.reserve(strict);
        theory.origins.reserve(strict);
    }

    fn close_axioms(&mut self) {
        let span_of =
            |theory: &Theory, given: Option<usize>| given.and_then(|i| theory.axioms[i].span);
        let units = self.units.take();
        let outcome = match &units {
            Some(units) => close(units, Resolvents::ImplicationsImplicit),
            None => close(&self.theory.axioms, Resolvents::ImplicationsImplicit),
        };
        match outcome {
            ClosureOutcome::Closed { clauses, given } => {
                self.reserve_strict_rules(clauses.iter().map(Vec::len).sum::<usize>());
                self.theory.closure.reserve(clauses.len());
                for (index, (lits, given)) in clauses.into_iter().zip(given).enumerate() {
                    add_strict_rules(&mut self.theory, index, &lits);
                    let span = span_of(&self.theory, given);
                    self.theory.closure.push(Clause { lits, span });
                }
            }
            ClosureOutcome::Input => {
                self.reserve_strict_rules(self.theory.axioms.len());
                strict_rules_of_axioms(&mut self.theory, units.as_deref());
                self.theory.closure_is_axioms = true;
            }
            ClosureOutcome::Inconsistent { first, second } => {
                let show = |lits: &[Lit]| {
                    let parts: Vec<String> = lits
                        .iter()
                        .map(|&l| self.theory.show(l).to_string())
                        .collect();
                    parts.join(", ")
                };
                let message = if first.0.is_empty() {
                    "the axioms hold the empty clause, which is always false".to_string()
                } else {
                    format!(
                        "the facts are inconsistent: they prove both `{}` and `{}`",
                        show(&first.0),
                        show(&second.0)
                    )
                };
                let place =
                    span_of(&self.theory, first.1).or_else(|| span_of(&self.theory, second.1));
                let mut d = Diagnostic::error(place.unwrap_or_default(), message)
                    .with_label("contradicted")
                    .with_hint("remove one of the contradicting facts, or make one of them a defeasible rule `=> l.`");
                if let Some(other) = span_of(&self.theory, second.1).filter(|s| Some(*s) != place) {
                    d = d.with_related(other, "contradicts this");
                }
                if first.1.is_none() || second.1.is_none() {
                    d = d.with_hint(
                        "the clash is derived by resolution from the clause axioms `\\/{…}`",
                    );
                }
                self.diagnostics.push(d);
            }
            ClosureOutcome::TooLarge => {
                let span = self
                    .theory
                    .axioms
                    .iter()
                    .find(|c| c.lits.len() > 1)
                    .and_then(|c| c.span);
                self.diagnostics.push(
                    Diagnostic::error(span.unwrap_or_default(), format!("the resolution closure of the clause axioms exceeds {MAX_CLOSURE} clauses"))
                        .with_hint("write fewer or shorter clause axioms `\\/{…}`, or state them as rules"),
                );
            }
        }
    }
}

/// The strict rules of closure clause number `index` (cdl.md §2): each literal, from the
/// complements of the others.
/// The strict rules of the axioms, which are their own closure; `units`, when given, are the
/// axioms' one literal each, in order.
fn strict_rules_of_axioms(theory: &mut Theory, units: Option<&[Unit]>) {
    match units {
        // Each fact the strict rule `-> fact`, made for all of them at once.
        Some(units) => {
            let body_end = theory.bodies.len() as u32;
            theory.heads.extend(units.iter().map(|unit| unit.0));
            theory.kinds.extend(units.iter().map(|_| RuleKind::Strict));
            theory.body_start.extend(units.iter().map(|_| body_end));
            theory.labels.extend(units.iter().map(|_| (0, 0)));
            theory
                .origins
                .extend((0..units.len() as u32).map(Origin::Clause));
        }
        None => {
            let axioms = std::mem::take(&mut theory.axioms);
            for (index, clause) in axioms.iter().enumerate() {
                add_strict_rules(theory, index, &clause.lits);
            }
            theory.axioms = axioms;
        }
    }
}

fn add_strict_rules(theory: &mut Theory, index: usize, lits: &[Lit]) {
    for (i, &head) in lits.iter().enumerate() {
        for (j, &other) in lits.iter().enumerate() {
            if i != j {
                theory.bodies.push(other.complement());
            }
        }
        theory.heads.push(head);
        theory.kinds.push(RuleKind::Strict);
        theory.body_start.push(theory.bodies.len() as u32);
        theory.labels.push((0, 0));
        theory.origins.push(Origin::Clause(index as u32));
    }
}

fn label_of(theory: &Theory, rule: RuleId) -> String {
    theory.label(rule).unwrap_or("?").to_string()
}

/// Label `text` written again at `start`, first written at `first_start`.
fn label_used_twice(text: &str, start: u32, first_start: u32) -> Diagnostic {
    let at = |start: u32| Span::new(start as usize, start as usize + text.len());
    Diagnostic::error(at(start), format!("rule label `{text}` is used twice"))
        .with_label("second use")
        .with_related(at(first_start), "first used here")
        .with_hint("labels name rules in priorities, so each must be unique")
}
