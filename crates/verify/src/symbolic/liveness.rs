//! Liveness in the symbolic engine: the runs and fairness of [`crate::liveness`] (time passes;
//! `fair` expressions hold infinitely often; a run may end where no machine can ring), with the
//! bad states, the fair cycles among them and the way to them as diagrams.
//!
//! - **Fair cycles** by Emerson and Lei's fixpoint: the greatest set Z of bad states from each
//!   of which, for every acceptance set A, one step and then a way through bad states reach
//!   Z ∩ A. A run that ends stays in a bad state with no successor.
//! - **Failure**: a seed (where a run starts staying bad, as in [`crate::liveness`]) from which
//!   a way through bad states reaches either. The initial worlds' first ringlets are the
//!   explicit stepper's, as in the rest of the engine.
//! - **The lasso** is walked by the explicit stepper, one successor at a time inside the rings
//!   (breadth-first distances as diagrams) that lead on: to the nearest seed, into Z, through a
//!   state of every acceptance set and back. Where the loop cannot close (the start was a state
//!   Z passes through, not one it returns to), it starts again further on.

use super::{image, preimage, set_where, Declined, Field, Path, Searched};
use crate::liveness::property_outcome;
use crate::outcome::{PropertyOutcome, Verdict};
use crate::property::Property;
use crate::ringlet::{Choice, Successor};
use crate::trace::trace_of;
use crate::world::{Status, SystemState};
use biodivine_lib_bdd::{Bdd, BddPartialValuation};
use proclaim_behaviour::PropertyKind;

/// A way through the states: each state and the choice that left it.
type Steps = Vec<(SystemState, Choice)>;

/// How many times a loop may start again further on before the engine gives the property up
/// (each time is a step down the fair states' components, which are finitely many).
const MAX_LOOP_STARTS: usize = 256;

/// The sets a failing run is made of.
struct FairSets {
    /// Where, besides the initial worlds, a run may start staying bad (reached states, the
    /// initial worlds left out: their steps are the explicit stepper's): none for
    /// `eventually`, `leads_to`'s P, any for `always_eventually`.
    starts: Bdd,
    bad: Bdd,
    /// Bad states that lie on a fair cycle of bad states (Emerson-Lei's Z).
    fair: Bdd,
    /// Bad states where no machine can ring.
    ended: Bdd,
    acceptance: Vec<Bdd>,
}

impl Searched<'_, '_> {
    /// The verdict of liveness property `property` on the complete search's `reached` set (of
    /// which `layers` are the breadth-first layers), with a lasso when it fails.
    pub(super) fn liveness(
        &self,
        property: &Property,
        layers: &[Bdd],
        reached: &Bdd,
    ) -> Result<PropertyOutcome, Declined> {
        let outcome = self.decide(property, layers, reached);
        // Once a rival has answered every preimage is empty (`before`), so the fixed points
        // end at once and nothing found after that stands.
        super::go_on(self.model)?;
        outcome
    }

    fn decide(
        &self,
        property: &Property,
        layers: &[Bdd],
        reached: &Bdd,
    ) -> Result<PropertyOutcome, Declined> {
        let sets = self.fair_sets(property, reached)?;
        let stay = sets.fair.or(&sets.ended);
        let to_stay = self.rings(&stay, &sets.bad);
        let Some((path, at)) = self.nearest_seed(property, &sets, &to_stay, layers) else {
            return Ok(property_outcome(property, Verdict::Holds, None, None));
        };
        let (initial, mut prefix) = path;
        let mut at = at;
        self.walk(&mut at, &mut prefix, &to_stay);
        let cycle = if self.enc.contains(self.model, &sets.ended, &at) {
            Vec::new()
        } else {
            self.fair_loop(&sets, &mut at, &mut prefix)?
        };
        let split = prefix.len();
        let whole = trace_of(self.model, initial, prefix.into_iter().chain(cycle));
        let (way_in, round) = whole.split(split);
        Ok(property_outcome(
            property,
            Verdict::Fails,
            Some(way_in),
            Some(round),
        ))
    }

    fn fair_sets(&self, property: &Property, reached: &Bdd) -> Result<FairSets, Declined> {
        let (model, enc) = (self.model, self.enc);
        let mut initial = enc.vars.mk_false();
        for w in self.initial {
            initial = initial.or(&enc.mk(&enc.world(model, w)));
        }
        let graph = reached.and_not(&initial);
        let good = match property.source.kind {
            PropertyKind::LeadsTo => set_where(
                model,
                enc,
                property.then_term().unwrap_or(property.term()),
                &property.source.name,
                &|w| property.then_holds_in(model, w),
            )?,
            _ => set_where(model, enc, property.term(), &property.source.name, &|w| {
                property.holds_in(model, w)
            })?,
        };
        let bad = graph.and_not(&good);
        let starts = match property.source.kind {
            PropertyKind::Eventually => enc.vars.mk_false(),
            PropertyKind::LeadsTo => graph.and(&set_where(
                model,
                enc,
                property.term(),
                &property.source.name,
                &|w| property.holds_in(model, w),
            )?),
            _ => graph.clone(),
        };
        let acceptance: Vec<Bdd> = self
            .acceptance(property)?
            .into_iter()
            .filter(|a| !bad.and_not(a).is_false())
            .collect();
        let ended = bad.and_not(&self.before(&enc.vars.mk_true(), &bad));
        let fair = self.fair_cycles(&bad, &acceptance);
        Ok(FairSets {
            starts,
            bad,
            fair,
            ended,
            acceptance,
        })
    }

    /// One acceptance set a clock of each machine (it is not running, or the clock just
    /// started, or every test of it in the machine's state is due, or there is none:
    /// [`crate::acceptance::time_passes`]), then one a `fair` expression.
    fn acceptance(&self, property: &Property) -> Result<Vec<Bdd>, Declined> {
        let (model, enc) = (self.model, self.enc);
        let field_is = |f: &Field, i: usize| {
            let mut cube = BddPartialValuation::empty();
            f.set(i, &mut cube);
            enc.mk(&cube)
        };
        let mut sets = Vec::new();
        for (k, m) in model.machines.iter().enumerate() {
            let f = &enc.machines[k];
            let running = field_is(&f.status, super::status_index(Status::Running));
            for &clock in &m.clocks {
                let mut met = running.not();
                for (s, state) in m.states.iter().enumerate() {
                    let mut cube = BddPartialValuation::empty();
                    f.state.set(s, &mut cube);
                    if state.arrival_starts(clock) {
                        let mut entered = cube.clone();
                        f.just_entered.set(1, &mut entered);
                        met = met.or(&enc.mk(&entered));
                    }
                    let mask = state.clock_mask(clock);
                    for (i, bit) in f.time.bits.iter().enumerate() {
                        if mask & (1 << i) != 0 {
                            cube.set_value(*bit, true);
                        }
                    }
                    met = met.or(&enc.mk(&cube));
                }
                sets.push(met);
            }
        }
        for (i, term) in property.fair_terms().iter().enumerate() {
            sets.push(set_where(model, enc, term, &property.source.name, &|w| {
                property.fair_holds_in(i, model, w)
            })?);
        }
        Ok(sets)
    }

    /// Every state of `within` with a successor in `set`.
    fn before(&self, set: &Bdd, within: &Bdd) -> Bdd {
        if self.model.overtaken() {
            return self.enc.vars.mk_false();
        }
        preimage(self.enc, self.steps, self.guards, set, within)
    }

    /// The states of `within` (and `target`) that reach `target` through `within`, ring by
    /// ring: ring `j` holds those at most `j` steps away. Never empty.
    fn rings(&self, target: &Bdd, within: &Bdd) -> Vec<Bdd> {
        self.rings_until(target, within, &|_| false)
    }

    /// [`Self::rings`], stopping at the first ring `enough` accepts.
    fn rings_until(&self, target: &Bdd, within: &Bdd, enough: &dyn Fn(&Bdd) -> bool) -> Vec<Bdd> {
        let mut reached = target.clone();
        let mut frontier = target.clone();
        let mut rings = vec![reached.clone()];
        while !enough(&reached) {
            let new = self.before(&frontier, &within.and_not(&reached));
            if new.is_false() {
                break;
            }
            reached = reached.or(&new);
            rings.push(reached.clone());
            frontier = new;
        }
        rings
    }

    /// Emerson and Lei: the bad states from which, for every acceptance set, a step and a way
    /// through bad states reach a state of the set that is again such a state.
    fn fair_cycles(&self, bad: &Bdd, acceptance: &[Bdd]) -> Bdd {
        if acceptance.is_empty() {
            return self.infinite_runs(bad);
        }
        let mut z = bad.clone();
        loop {
            let mut next = z.clone();
            for set in acceptance {
                let reach = self.rings(&next.and(set), bad).pop();
                next = next.and(&self.before(&reach.unwrap_or_else(|| next.clone()), &next));
            }
            if z.and_not(&next).is_false() {
                return next;
            }
            z = next;
        }
    }

    /// With every state in every acceptance set, the states of `bad` from which a run can
    /// stay in `bad` for ever: those with no successor in it are taken away, and then only
    /// the predecessors of what was taken need looking at again (each a small preimage).
    fn infinite_runs(&self, bad: &Bdd) -> Bdd {
        let mut z = bad.clone();
        let mut gone = z.and_not(&self.before(&z, &z));
        while !gone.is_false() {
            z = z.and_not(&gone);
            let touched = self.before(&gone, &z);
            gone = touched.and_not(&self.before(&z, &touched));
        }
        z
    }

    /// The nearest seed from which a failing run starts: an initial world's (through its first
    /// ringlet), else the first breadth-first layer that holds one.
    fn nearest_seed(
        &self,
        property: &Property,
        sets: &FairSets,
        to_stay: &[Bdd],
        layers: &[Bdd],
    ) -> Option<(Path, SystemState)> {
        let fails = to_stay.last()?;
        let (model, enc) = (self.model, self.enc);
        let kind = property.source.kind;
        for (i, w) in self.initial.iter().enumerate() {
            let bad = match kind {
                PropertyKind::LeadsTo => !property.then_holds_in(model, w),
                _ => !property.holds_in(model, w),
            };
            let seed = bad && (kind != PropertyKind::LeadsTo || property.holds_in(model, w));
            if !seed {
                continue;
            }
            if self.first_steps[i].is_empty() {
                return Some(((i, Vec::new()), w.clone()));
            }
            // Of the first ringlets that can fail, the one nearest to staying bad, and of
            // those the one in most acceptance sets (a loop may start there).
            let next = self.first_steps[i]
                .iter()
                .filter_map(|step| {
                    let ring = to_stay
                        .iter()
                        .position(|r| enc.contains(model, r, &step.0))?;
                    let sets = sets
                        .acceptance
                        .iter()
                        .filter(|a| enc.contains(model, a, &step.0))
                        .count();
                    Some(((ring, std::cmp::Reverse(sets)), step))
                })
                .min_by_key(|(key, _)| *key)
                .map(|(_, step)| step);
            if let Some((s, choice)) = next {
                return Some(((i, vec![(w.clone(), *choice)]), s.clone()));
            }
        }
        let seeds = fails.and(&sets.starts);
        let nearest = layers.iter().position(|l| !l.and(&seeds).is_false())?;
        self.rebuild(&layers[..=nearest], &seeds)
    }

    /// From `at`, in some ring of `rings`, one successor at a time into ring 0; the steps taken
    /// go on `path`.
    fn walk(&self, at: &mut SystemState, path: &mut Vec<(SystemState, Choice)>, rings: &[Bdd]) {
        let ring_of = |w: &SystemState| {
            rings
                .iter()
                .position(|r| self.enc.contains(self.model, r, w))
        };
        let mut ring = ring_of(at).unwrap_or(0);
        let mut successors: Vec<Successor> = Vec::new();
        while ring > 0 {
            successors.clear();
            self.stepper.successors(at, false, &mut successors);
            let nearer = successors
                .iter()
                .filter_map(|s| Some((ring_of(&s.world)?, s)))
                .filter(|(r, _)| *r < ring)
                .min_by_key(|(r, _)| *r);
            let Some((r, s)) = nearer else {
                // The stepper's ringlets are the diagrams' steps; a way not found again would
                // be a bug in the engine, and the walk ends where it could be followed.
                return;
            };
            path.push((at.clone(), s.choice));
            *at = s.world.clone();
            ring = r;
        }
    }

    /// The shortest way of at least one step from `from` to `to` through `within`, found by
    /// images of the frontier (cheap while the frontier is small) and then walked back to
    /// front by the explicit stepper. Where there is none, `Err` holds the way to a state of
    /// the farthest frontier (empty if `from` has no successor not met before): a loop that
    /// cannot close here starts again there, far on rather than one step on.
    fn way(
        &self,
        from: &SystemState,
        to: &SystemState,
        within: &Bdd,
    ) -> Result<Steps, (Steps, SystemState)> {
        let (model, enc) = (self.model, self.enc);
        let target = enc.mk(&enc.world(model, to));
        let mut frontiers = vec![enc.mk(&enc.world(model, from))];
        let mut seen = frontiers[0].clone();
        let found = loop {
            let next = image(
                enc,
                self.steps,
                self.guards,
                &frontiers[frontiers.len() - 1],
            )
            .and(within);
            if !next.and(&target).is_false() {
                break true;
            }
            let new = next.and_not(&seen);
            if new.is_false() {
                break false;
            }
            seen = seen.or(&new);
            frontiers.push(new);
        };
        let end = if found {
            target
        } else {
            let farthest = frontiers.pop().and_then(|f| f.sat_witness());
            match farthest {
                Some(state) if !frontiers.is_empty() => {
                    enc.vars.mk_conjunctive_clause(&state.into())
                }
                _ => return Err((Vec::new(), from.clone())),
            }
        };
        // Back from the end: the states of each frontier that lead on to it.
        let mut leads = vec![end];
        for frontier in frontiers[1..].iter().rev() {
            leads.push(self.before(&leads[leads.len() - 1], frontier));
        }
        leads.reverse();
        let mut at = from.clone();
        let mut way = Vec::new();
        let mut successors: Vec<Successor> = Vec::new();
        for lead in &leads {
            successors.clear();
            self.stepper.successors(&at, false, &mut successors);
            let Some(s) = successors
                .iter()
                .find(|s| enc.contains(model, lead, &s.world))
            else {
                // The stepper's ringlets are the diagrams' steps (see `walk`).
                return Err((Vec::new(), from.clone()));
            };
            way.push((at.clone(), s.choice));
            at = s.world.clone();
        }
        if found {
            Ok(way)
        } else {
            Err((way, at))
        }
    }

    /// A loop from `at` (a fair-cycle state) through a state of every acceptance set and back,
    /// at least one step long; where it cannot come back, the way on joins `prefix` and the
    /// loop starts again from where it got to.
    fn fair_loop(
        &self,
        sets: &FairSets,
        at: &mut SystemState,
        prefix: &mut Vec<(SystemState, Choice)>,
    ) -> Result<Vec<(SystemState, Choice)>, Declined> {
        let (model, enc) = (self.model, self.enc);
        for _ in 0..MAX_LOOP_STARTS {
            let start = at.clone();
            let mut cycle = Vec::new();
            let mut here = start.clone();
            let mut met: Vec<bool> = sets
                .acceptance
                .iter()
                .map(|a| enc.contains(model, a, &here))
                .collect();
            for (i, set) in sets.acceptance.iter().enumerate() {
                if met[i] {
                    continue;
                }
                let from = cycle.len();
                self.walk(
                    &mut here,
                    &mut cycle,
                    &self.rings(&sets.fair.and(set), &sets.fair),
                );
                for w in cycle[from..].iter().map(|(w, _)| w).chain([&here]) {
                    for (m, a) in met.iter_mut().zip(&sets.acceptance) {
                        *m = *m || enc.contains(model, a, w);
                    }
                }
            }
            if cycle.is_empty() || here != start {
                let (on, end) = match self.way(&here, &start, &sets.fair) {
                    Ok(way) => {
                        cycle.extend(way);
                        return Ok(cycle);
                    }
                    Err(on) => on,
                };
                // No way back: `start` is a fair state runs pass through, not one they return
                // to. The loop starts again further on: at the farthest state from here, or
                // one step on where every state after this one was met already.
                if !on.is_empty() {
                    cycle.extend(on);
                    here = end;
                } else if cycle.is_empty() {
                    let mut successors: Vec<Successor> = Vec::new();
                    self.stepper.successors(&here, false, &mut successors);
                    let on = successors
                        .iter()
                        .find(|s| enc.contains(model, &sets.fair, &s.world));
                    let Some(s) = on else { break };
                    cycle.push((here.clone(), s.choice));
                    here = s.world.clone();
                }
            } else {
                return Ok(cycle);
            }
            prefix.extend(cycle);
            *at = here;
        }
        Err(Declined(
            "a failing liveness property's loop was not closed".into(),
        ))
    }
}
