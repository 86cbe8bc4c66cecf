//! μ: the least fixpoint of the strict rules and the input facts, kept up to date as inputs
//! change (counting unsatisfied antecedents, epochs for regions), and the goals a change
//! invalidates.

use super::*;

impl Session {
    pub(super) fn compute_mu(&mut self) {
        let engine = Arc::clone(&self.engine);
        for r in 0..engine.theory.rule_count() {
            self.counters[r] = engine.strict_body_len[r];
        }
        self.queue.clear();
        for &r in &engine.strict_facts {
            let h = engine.head(r);
            if !self.mu[h.index()] {
                self.mu[h.index()] = true;
                self.queue.push(h);
            }
        }
        self.propagate_mu(&engine, None);
    }

    /// Forward chaining from the literals in `queue`; with `region`, only rules whose consequent
    /// is stamped with the current epoch are counted down.
    pub(super) fn propagate_mu(&mut self, engine: &Engine, region: Option<u32>) {
        while let Some(x) = self.queue.pop() {
            for &r in engine.strict_uses.row(x.index()) {
                let h = engine.head(r);
                if region.is_some_and(|e| self.stamp[h.index()] != e) || self.mu[h.index()] {
                    continue;
                }
                let c = &mut self.counters[r as usize];
                *c = c.saturating_sub(1);
                if *c == 0 {
                    self.mu[h.index()] = true;
                    self.queue.push(h);
                }
            }
        }
    }

    pub(super) fn next_epoch(&mut self) -> u32 {
        self.epoch = self.epoch.wrapping_add(1);
        if self.epoch == 0 {
            self.stamp.iter_mut().for_each(|s| *s = 0);
            self.epoch = 1;
        }
        self.epoch
    }

    /// Recomputes μ where the input `atom` can reach through strict rules, then forgets every
    /// answer that read a literal whose μ changed.
    pub(super) fn update_mu(&mut self, atom: Atom) {
        let engine = Arc::clone(&self.engine);
        let epoch = self.next_epoch();
        // The region: literals strict rules can derive from `atom` or `~atom`.
        let mut region = vec![Lit::positive(atom), Lit::new(atom, true)];
        for &l in &region {
            self.stamp[l.index()] = epoch;
        }
        let mut i = 0;
        while i < region.len() {
            let x = region[i];
            i += 1;
            for &r in engine.strict_uses.row(x.index()) {
                let h = engine.head(r);
                if self.stamp[h.index()] != epoch {
                    self.stamp[h.index()] = epoch;
                    region.push(h);
                }
            }
        }
        let before: Vec<bool> = region.iter().map(|l| self.mu[l.index()]).collect();
        for &l in &region {
            self.mu[l.index()] = false;
        }
        // Count first, with the whole region false, then seed: a literal that becomes true is
        // counted down exactly once, by propagation.
        for &h in &region {
            for &r in engine.rules_for(h) {
                if engine.kind(r) == RuleKind::Strict {
                    self.counters[r as usize] = engine
                        .body(r)
                        .iter()
                        .filter(|a| !self.mu[a.index()])
                        .count() as u32;
                }
            }
        }
        self.queue.clear();
        for &h in &region {
            let input_fact = self.inputs[h.atom().0 as usize] == Some(!h.is_negated());
            let derived = input_fact
                || engine
                    .rules_for(h)
                    .iter()
                    .any(|&r| engine.kind(r) == RuleKind::Strict && self.counters[r as usize] == 0);
            if derived && !self.mu[h.index()] {
                self.mu[h.index()] = true;
                self.queue.push(h);
            }
        }
        self.propagate_mu(&engine, Some(epoch));
        let changed: Vec<Lit> = region
            .iter()
            .zip(before)
            .filter(|(l, b)| self.mu[l.index()] != *b)
            .map(|(l, _)| *l)
            .collect();
        self.invalidate(&changed);
    }

    /// Forgets the answers of every goal that can read a changed literal, transitively.
    pub(super) fn invalidate(&mut self, changed: &[Lit]) {
        if changed.is_empty() {
            return;
        }
        let engine = Arc::clone(&self.engine);
        let epoch = self.next_epoch();
        let mut work: Vec<Lit> = Vec::new();
        let mark = |l: Lit, stamp: &mut Vec<u32>, work: &mut Vec<Lit>| {
            if stamp[l.index()] != epoch {
                stamp[l.index()] = epoch;
                work.push(l);
            }
        };
        for &l in changed {
            mark(l, &mut self.stamp, &mut work);
            mark(l.complement(), &mut self.stamp, &mut work);
        }
        while let Some(y) = work.pop() {
            for kind in 0..KINDS as u32 {
                let goals = [Some(goal(y, kind)), engine.aggregate_for(y, kind)];
                for g in goals.into_iter().flatten() {
                    self.values[g as usize] = UNKNOWN;
                    self.index[g as usize] = 0;
                }
            }
            for &z in engine.dependents.row(y.index()) {
                mark(Lit(z), &mut self.stamp, &mut work);
                mark(Lit(z).complement(), &mut self.stamp, &mut work);
            }
        }
    }

    pub(super) fn check_against_axioms(&self, fact: Lit) -> Result<(), InputConflict> {
        let theory = &self.engine.theory;
        let closure = theory.closure();
        for &c in self.engine.closure_by_lit.row(fact.complement().index()) {
            let clause = &closure[c as usize].lits;
            let falsified = clause
                .iter()
                .all(|&x| x == fact.complement() || self.input_falsifies(x));
            if falsified {
                let parts: Vec<String> =
                    clause.iter().map(|&l| theory.show(l).to_string()).collect();
                return Err(InputConflict {
                    input: theory.show(fact).to_string(),
                    clause: match parts.len() {
                        1 => parts[0].clone(),
                        _ => format!("\\/{{{}}}", parts.join(", ")),
                    },
                });
            }
        }
        // An implicit resolvent `\/{~fact, z}` the inputs falsify: a path from the fact to a
        // literal they make false. Found the long way round, so the clause can be named.
        if self.implied(fact, |z| self.input_falsifies(z)) {
            let z = (0..self.engine.lit_count as u32)
                .map(Lit)
                .find(|&z| self.input_falsifies(z) && self.implied(fact, |x| x == z));
            if let Some(z) = z {
                return Err(InputConflict {
                    input: theory.show(fact).to_string(),
                    clause: {
                        let mut lits = [fact.complement(), z];
                        lits.sort_unstable();
                        format!("\\/{{{}, {}}}", theory.show(lits[0]), theory.show(lits[1]))
                    },
                });
            }
        }
        Ok(())
    }
}
