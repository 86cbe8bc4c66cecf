//! β, π and support goals settled component by component: Tarjan's algorithm from the goal
//! asked over the unsettled goals it reaches, each component evaluated as it closes (a single
//! goal by its condition, a cycle by `cycle.rs`).

use super::*;

impl Session {
    /// Tarjan's algorithm from `root` over the unsettled goals it reaches; each component is
    /// evaluated as soon as it closes, so its successors are all settled by then.
    pub(super) fn solve(&mut self, root: Goal) {
        let goals = self.values.len() as u32;
        if self.next_index >= u32::MAX - goals - 1 {
            self.index.iter_mut().for_each(|i| *i = 0);
            self.next_index = 1;
        }
        self.visit(root);
        while let Some(frame) = self.frames.last_mut() {
            if frame.cursor < frame.hi {
                let s = self.succ[frame.cursor as usize] & !ATTACK;
                frame.cursor += 1;
                if self.values[s as usize] != UNKNOWN {
                    continue;
                }
                match self.index[s as usize] {
                    0 => self.visit(s),
                    visited => frame.low = frame.low.min(visited),
                }
            } else {
                let f = *frame;
                self.frames.pop();
                let g = f.goal as usize;
                if f.low == self.index[g] {
                    self.close_component(f);
                }
                self.succ.truncate(f.lo as usize);
                if let Some(parent) = self.frames.last_mut() {
                    parent.low = parent.low.min(f.low);
                }
            }
        }
    }

    pub(super) fn visit(&mut self, g: Goal) {
        self.index[g as usize] = self.next_index;
        self.stack.push(g);
        let lo = self.succ.len() as u32;
        let values = &self.values;
        successors(&self.engine, &self.mu, g, &mut self.succ, |s| {
            values[s as usize] == UNKNOWN
        });
        self.frames.push(Frame {
            goal: g,
            lo,
            hi: self.succ.len() as u32,
            cursor: lo,
            low: self.next_index,
        });
        self.next_index += 1;
    }

    pub(super) fn close_component(&mut self, root: Frame) {
        self.component.clear();
        while let Some(g) = self.stack.pop() {
            self.component.push(g);
            if g == root.goal {
                break;
            }
        }
        self.evaluated += self.component.len() as u64;
        let engine = Arc::clone(&self.engine);
        if self.component.len() == 1 {
            let g = root.goal;
            let self_loop = self.succ[root.lo as usize..root.hi as usize]
                .iter()
                .any(|&s| s & !ATTACK == g);
            if !self_loop {
                self.values[g as usize] = self.evaluate_single(&engine, g);
                return;
            }
        }
        self.evaluate_cycle(&engine);
    }

    /// A goal on no cycle: its condition over settled goals. A read of an undecided goal is taken
    /// both ways (against the goal, then for it); when the two disagree the goal is undecided too.
    pub(super) fn evaluate_single(&mut self, engine: &Engine, g: Goal) -> u8 {
        let mut stalled = None;
        let values = &self.values;
        let read = |optimistic: bool| {
            let mut stalled_read = None;
            let v = condition(
                engine,
                &self.mu,
                g,
                &mut |s, how| match values[s as usize] {
                    TRUE => true,
                    UNDECIDED => {
                        stalled_read = Some(s);
                        // A support read helps when true; an attack read helps when false.
                        optimistic != (how == ATTACK_READ)
                    }
                    _ => false,
                },
            );
            (v, stalled_read)
        };
        let (pessimistic, first) = read(false);
        let v = if first.is_none() {
            pessimistic
        } else {
            let (optimistic, _) = read(true);
            if optimistic != pessimistic {
                stalled = first;
            }
            pessimistic
        };
        match stalled {
            Some(s) => {
                let origin = self.stalls.get(&s).copied().unwrap_or((s, 0));
                self.stalls.insert(g, origin);
                UNDECIDED
            }
            None if v => TRUE,
            None => FALSE,
        }
    }

    /// A component with a cycle ([`crate::cycle`]). A component that reads an undecided goal is
    /// left undecided as a whole.
    pub(super) fn evaluate_cycle(&mut self, engine: &Engine) {
        self.evaluate_component(engine, true);
    }

    /// [`Session::evaluate_cycle`]; `may_fall_apart` is false for the parts of a component that
    /// fell apart: splitting them again could peel one goal a time, quadratic on a long cycle.
    fn evaluate_component(&mut self, engine: &Engine, may_fall_apart: bool) {
        let members = std::mem::take(&mut self.component);
        for (position, &g) in members.iter().enumerate() {
            self.values[g as usize] = PENDING;
            // Its visit number is spent: a settled goal's is never read as one.
            self.index[g as usize] = position as u32;
        }
        let mut reads = Vec::new();
        let undecided_read = members.iter().find_map(|&g| {
            reads.clear();
            let values = &self.values;
            successors(engine, &self.mu, g, &mut reads, |s| {
                values[s as usize] == UNDECIDED
            });
            reads.first().map(|&s| s & !ATTACK)
        });
        if let Some(s) = undecided_read {
            let origin = self.stalls.get(&s).copied().unwrap_or((s, 0));
            for &g in &members {
                self.values[g as usize] = UNDECIDED;
                self.stalls.insert(g, origin);
            }
            self.component = members;
            return;
        }
        let component = Component {
            engine,
            mu: &self.mu,
            values: &self.values,
            position: &self.index,
            members: &members,
        };
        let evaluated = match component.evaluate(&self.limits, may_fall_apart) {
            Outcome::Evaluated(evaluated) => evaluated,
            Outcome::Parts(parts) => {
                self.evaluate_parts(engine, &members, parts);
                self.component = members;
                return;
            }
        };
        if evaluated.method == Method::Search {
            let undecided = evaluated.values.contains(&UNDECIDED);
            let algorithm = |g: Goal| match kind_of(g) {
                BETA => Algorithm::Beta,
                PI => Algorithm::Pi,
                _ => Algorithm::Delta,
            };
            self.searched.push(Searched {
                goals: members
                    .iter()
                    .filter(|&&g| !engine.is_aggregate(g) && kind_of(g) != SUP)
                    .map(|&g| (algorithm(g), lit_of(g)))
                    .collect(),
                steps: evaluated.steps,
                undecided,
            });
        }
        for (&g, &v) in members.iter().zip(&evaluated.values) {
            self.values[g as usize] = v;
            if v == UNDECIDED {
                self.stalls.insert(g, (g, members.len()));
            }
        }
        self.component = members;
    }

    /// A component that falls apart once the reads its members ignore are dropped
    /// (`relevance.rs`): each part in turn, as a component of its own. Until its part comes,
    /// a member is read only by conditions that ignore it, which read it as false.
    fn evaluate_parts(&mut self, engine: &Engine, members: &[Goal], parts: Vec<Vec<u32>>) {
        for &g in members {
            self.values[g as usize] = FALSE;
        }
        let mut reads = Vec::new();
        for part in parts {
            if let [single] = part[..] {
                let g = members[single as usize];
                reads.clear();
                successors(engine, &self.mu, g, &mut reads, |s| s == g);
                if reads.is_empty() {
                    self.values[g as usize] = self.evaluate_single(engine, g);
                    continue;
                }
            }
            self.component = part.iter().map(|&p| members[p as usize]).collect();
            self.evaluate_component(engine, false);
        }
    }
}
