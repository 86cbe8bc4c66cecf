//! Why an algorithm proves or refutes a literal: the supporting rule, each attacker and what
//! became of it (discounted, beaten, standing), loops cut, and optionally the same for the
//! antecedents, as a tree people can read.

use crate::goal::{goal, successors, Goal, ATTACK, BETA, PI};
use crate::literal::Lit;
use crate::session::Session;
use crate::theory::RuleKind;
use proclaim_syntax::Algorithm;
use std::collections::HashSet;
use std::fmt;

/// One line of an explanation with the lines that justify it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Explanation {
    pub text: String,
    /// What the line speaks of, as data (for `--json` and programs).
    pub about: About,
    pub children: Vec<Explanation>,
}

/// What a line of an explanation speaks of.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum About {
    /// A remark (no rule for the literal, a loop, definitely proved, …).
    Note,
    /// A goal: `±alg literal`.
    Goal {
        algorithm: Algorithm,
        literal: String,
        proved: bool,
    },
    /// A rule and its part: `supports`, `does_not_apply`, `strict_chain`, and for attackers
    /// `discounted`, `beaten` (by `by`) or `stands`.
    Rule {
        rule: String,
        role: &'static str,
        by: Option<String>,
    },
}

impl Explanation {
    fn leaf(text: impl Into<String>) -> Explanation {
        Explanation {
            text: text.into(),
            about: About::Note,
            children: Vec::new(),
        }
    }

    fn rule(text: impl Into<String>, rule: String, role: &'static str) -> Explanation {
        Explanation {
            about: About::Rule {
                rule,
                role,
                by: None,
            },
            ..Explanation::leaf(text)
        }
    }

    fn write(&self, f: &mut fmt::Formatter<'_>, depth: usize) -> fmt::Result {
        writeln!(f, "{}{}", "  ".repeat(depth), self.text)?;
        self.children.iter().try_for_each(|c| c.write(f, depth + 1))
    }
}

impl fmt::Display for Explanation {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        self.write(f, 0)
    }
}

impl Session {
    /// Explains `±alg lit`, following antecedents down to `depth` levels (each literal once).
    pub fn explain(&mut self, alg: Algorithm, lit: Lit, depth: usize) -> Explanation {
        let mut seen = HashSet::new();
        self.explain_at(alg, lit, depth, &mut seen)
    }

    fn explain_at(
        &mut self,
        alg: Algorithm,
        lit: Lit,
        depth: usize,
        seen: &mut HashSet<(Algorithm, Lit)>,
    ) -> Explanation {
        let proved = self.prove(alg, lit);
        let engine = self.engine().clone();
        let theory = engine.theory();
        let head = format!(
            "{}{} {}",
            if proved { '+' } else { '-' },
            alg,
            theory.show(lit)
        );
        if !seen.insert((alg, lit)) {
            return Explanation::leaf(format!("{head} (explained above)"));
        }
        let mut node = Explanation {
            about: About::Goal {
                algorithm: alg,
                literal: theory.show(lit).to_string(),
                proved,
            },
            ..Explanation::leaf(head)
        };
        match alg {
            Algorithm::Mu => {
                node.children.push(Explanation::leaf(if proved {
                    "follows from the facts and strict rules alone"
                } else {
                    "no chain of facts and strict rules leads to it"
                }));
                if proved && depth > 0 {
                    if let Some(r) = engine.rules_for(lit).iter().copied().find(|&r| {
                        engine.kind(r) == RuleKind::Strict
                            && engine.body(r).iter().all(|a| self.mu()[a.index()])
                    }) {
                        let mut by = Explanation::rule(
                            format!("by {}", theory.show_rule(r)),
                            theory.rule_name(r),
                            "strict_chain",
                        );
                        for &a in engine.body(r) {
                            by.children
                                .push(self.explain_at(Algorithm::Mu, a, depth - 1, seen));
                        }
                        node.children.push(by);
                    }
                }
            }
            Algorithm::Alpha | Algorithm::Delta => {
                let word = if alg == Algorithm::Alpha {
                    "both"
                } else {
                    "either"
                };
                node.children
                    .push(Explanation::leaf(format!("{alg} needs {word} pi and beta")));
                for part in [Algorithm::Pi, Algorithm::Beta] {
                    node.children.push(self.explain_at(part, lit, depth, seen));
                }
            }
            Algorithm::Beta | Algorithm::Pi => {
                self.explain_defeasible(alg, lit, depth, seen, &mut node);
            }
        }
        node
    }

    /// β or π for `q`: settled by μ, or the first rule that supports it (or an implicit
    /// resolvent), then what attacks it; or why nothing supports it.
    fn explain_defeasible(
        &mut self,
        alg: Algorithm,
        q: Lit,
        depth: usize,
        seen: &mut HashSet<(Algorithm, Lit)>,
        node: &mut Explanation,
    ) {
        if let Some(settled) = self.settled_by_mu(q) {
            node.children.push(settled);
            return;
        }
        let (supporter, failed) = self.first_supporter(alg, q);
        let Some(r) = supporter else {
            if !self.explain_implicit_support(alg, q, depth, seen, node) {
                self.explain_unsupported(alg, q, failed, depth, seen, node);
            }
            return;
        };
        let engine = self.engine().clone();
        let theory = engine.theory();
        let mut line = Explanation::rule(
            format!("supported by {}", theory.show_rule(r)),
            theory.rule_name(r),
            "supports",
        );
        if depth > 0 {
            for &a in engine.body(r) {
                line.children.push(self.explain_at(alg, a, depth - 1, seen));
            }
        }
        node.children.push(line);
        self.explain_implicit_attackers(alg, q, node);
        self.explain_attackers(alg, q, node);
        self.note_loop(alg, q, node);
    }

    /// The line that says μ decides `q` (it or its complement definitely proved), if it does.
    fn settled_by_mu(&mut self, q: Lit) -> Option<Explanation> {
        let engine = self.engine().clone();
        let show = |l: Lit| engine.theory().show(l).to_string();
        if self.mu()[q.index()] {
            Some(Explanation::leaf(format!(
                "+mu {}: definitely proved",
                show(q)
            )))
        } else if self.mu()[q.complement().index()] {
            Some(Explanation::leaf(format!(
                "+mu {}: the complement is definitely proved",
                show(q.complement())
            )))
        } else {
            None
        }
    }

    /// The first supporting rule for `q` whose body `alg` proves, and, before it, each rule
    /// that does not apply with the antecedent that fails it.
    fn first_supporter(&mut self, alg: Algorithm, q: Lit) -> (Option<u32>, Vec<(u32, Lit)>) {
        let engine = self.engine().clone();
        let mut failed = Vec::new();
        for &r in engine.rules_for(q) {
            if !engine.kind(r).supports() {
                continue;
            }
            match engine
                .body(r)
                .iter()
                .copied()
                .find(|&x| !self.prove(alg, x))
            {
                None => return (Some(r), failed),
                Some(a) => failed.push((r, a)),
            }
        }
        (None, failed)
    }

    /// Support by a resolvent of the clause axioms the closure left implicit (`x -> q` for a
    /// path of implications from `x`), when one is proved; false when there is none.
    fn explain_implicit_support(
        &mut self,
        alg: Algorithm,
        q: Lit,
        depth: usize,
        seen: &mut HashSet<(Algorithm, Lit)>,
        node: &mut Explanation,
    ) -> bool {
        let engine = self.engine().clone();
        let Some(x) = implicit_sources(&engine, q)
            .into_iter()
            .find(|&x| self.prove(alg, x))
        else {
            return false;
        };
        let theory = engine.theory();
        let mut line = Explanation::leaf(format!(
            "supported by {} -> {}, a resolvent of the clause axioms",
            theory.show(x),
            theory.show(q)
        ));
        if depth > 0 {
            line.children.push(self.explain_at(alg, x, depth - 1, seen));
        }
        node.children.push(line);
        self.explain_implicit_attackers(alg, q, node);
        self.note_loop(alg, q, node);
        true
    }

    /// Why no rule supports `q`: each rule for it that does not apply, and the antecedent that
    /// is not proved.
    fn explain_unsupported(
        &mut self,
        alg: Algorithm,
        q: Lit,
        failed: Vec<(u32, Lit)>,
        depth: usize,
        seen: &mut HashSet<(Algorithm, Lit)>,
        node: &mut Explanation,
    ) {
        let engine = self.engine().clone();
        let theory = engine.theory();
        if failed.is_empty() {
            node.children.push(Explanation::leaf(format!(
                "no strict or defeasible rule has {} as consequent",
                theory.show(q)
            )));
        }
        for (r, a) in failed {
            let mut line = Explanation::rule(
                format!(
                    "{} does not apply: antecedent {} is not proved",
                    theory.rule_name(r),
                    theory.show(a)
                ),
                theory.rule_name(r),
                "does_not_apply",
            );
            if depth > 0 {
                line.children.push(self.explain_at(alg, a, depth - 1, seen));
            }
            node.children.push(line);
        }
        self.note_loop(alg, q, node);
    }

    /// Each rule for the complement of a supported `q`: discounted (an antecedent not proved,
    /// or for π not supported), beaten by a superior applicable rule for `q`, or standing.
    fn explain_attackers(&mut self, alg: Algorithm, q: Lit, node: &mut Explanation) {
        let engine = self.engine().clone();
        let theory = engine.theory();
        let show = |l: Lit| theory.show(l).to_string();
        let attack_word = if alg == Algorithm::Beta {
            "proved"
        } else {
            "supported"
        };
        let applicable = |s: &mut Session, r: u32, a: Algorithm| -> Option<Lit> {
            engine.body(r).iter().copied().find(|&x| !s.prove(a, x))
        };
        for &s in engine.rules_for(q.complement()) {
            let name = theory.rule_name(s);
            let counted = if alg == Algorithm::Beta {
                applicable(self, s, Algorithm::Beta)
            } else {
                engine
                    .body(s)
                    .iter()
                    .copied()
                    .find(|&x| !self.support_value(x))
            };
            if let Some(a) = counted {
                node.children.push(Explanation::rule(
                    format!(
                        "attacker {name} is discounted: its antecedent {} is not {attack_word}",
                        show(a)
                    ),
                    name,
                    "discounted",
                ));
                continue;
            }
            let beaten_by = engine.superiors_of(s).iter().copied().find(|&t| {
                engine.head(t) == q
                    && engine.kind(t).supports()
                    && applicable(self, t, alg).is_none()
            });
            node.children.push(match beaten_by {
                Some(t) => Explanation {
                    about: About::Rule {
                        rule: name.clone(),
                        role: "beaten",
                        by: Some(theory.rule_name(t)),
                    },
                    ..Explanation::leaf(format!(
                        "attacker {name} is beaten by {}",
                        theory.rule_name(t)
                    ))
                },
                None => Explanation::rule(
                    format!("attacker {name} stands: its antecedent is {attack_word} and no applicable rule for {} beats it", show(q)),
                    name,
                    "stands",
                ),
            });
        }
    }

    /// The first standing attacker among the clause axioms' implicit resolvents `x -> ~q` (they
    /// are unlabelled, so nothing beats them); the discounted ones are too many to list.
    fn explain_implicit_attackers(&mut self, alg: Algorithm, q: Lit, node: &mut Explanation) {
        let engine = self.engine().clone();
        let standing = implicit_sources(&engine, q.complement())
            .into_iter()
            .find(|&x| {
                if alg == Algorithm::Beta {
                    self.prove(Algorithm::Beta, x)
                } else {
                    self.support_value(x)
                }
            });
        if let Some(x) = standing {
            let theory = engine.theory();
            node.children.push(Explanation::leaf(format!(
                "attacker {} -> {}, a resolvent of the clause axioms, stands: its antecedent is {}",
                theory.show(x),
                theory.show(q.complement()),
                if alg == Algorithm::Beta {
                    "proved"
                } else {
                    "supported"
                }
            )));
        }
    }

    /// Adds a line when the goal lies on a cycle of the goal graph, where a goal met again on the
    /// proof path fails (cdl.md §4).
    fn note_loop(&mut self, alg: Algorithm, q: Lit, node: &mut Explanation) {
        let kind = if alg == Algorithm::Beta { BETA } else { PI };
        if self.on_cycle(goal(q, kind)) {
            node.children.push(Explanation::leaf(
                "it lies on a loop of the goal graph: a goal met again on its own proof path fails",
            ));
        }
    }

    /// Whether `start` reaches itself in the goal graph (bounded search; explanations only).
    fn on_cycle(&self, start: Goal) -> bool {
        let engine = self.engine().clone();
        let mut seen = HashSet::new();
        let mut work = Vec::new();
        successors(&engine, self.mu(), start, &mut work, |_| true);
        while let Some(g) = work.pop() {
            let g = g & !ATTACK;
            if g == start {
                return true;
            }
            if seen.len() > 10_000 || !seen.insert(g) {
                continue;
            }
            successors(&engine, self.mu(), g, &mut work, |_| true);
        }
        false
    }
}

/// The literals with a path of two or more implications to `q`: the antecedents of the strict
/// rules the closure left implicit (a path of one is a written clause's own rule).
fn implicit_sources(engine: &crate::Engine, q: Lit) -> Vec<Lit> {
    let i = &engine.implications;
    let mut sources: Vec<Lit> = i.cycle_mates(q).collect();
    let mut parts: Vec<u32> = engine
        .aggregate_for(q, 0)
        .map(|a| engine.aggregate_parts(a).0)
        .into_iter()
        .collect();
    let mut seen_parts: HashSet<u32> = parts.iter().copied().collect();
    while let Some(r) = parts.pop() {
        sources.extend(i.direct.row(r as usize).iter().map(|&x| Lit(x)));
        for &c in i.chained.row(r as usize) {
            if seen_parts.insert(c) {
                parts.push(c);
            }
        }
    }
    sources.sort_unstable();
    sources.dedup();
    sources.retain(|&x| x != q && !i.forward.row(x.index()).contains(&q.0));
    sources
}
