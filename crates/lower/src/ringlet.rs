//! What one ringlet of a machine does (`docs/spec/behaviour.md` §3.1), said once for every back
//! end: which activities run on arrival, which transitions are tried in which order, what runs
//! on leaving by each and what runs when none fires ([`RingletPlan`]), and the order of those
//! steps ([`RingletRun`]). The runner and the checker run a ringlet by asking a [`RingletRun`]
//! what comes next; Promela and the code generators print a [`RingletPlan`].

use proclaim_fsm::{Action, Label, Machine, State, StateId, Transition};

/// A state's ringlet as data.
#[derive(Clone, Copy, Debug)]
pub struct RingletPlan<'m> {
    machine: &'m Machine,
    state: &'m State,
}

/// A transition as its state's ringlet tries it.
#[derive(Clone, Copy, Debug)]
pub struct Arm<'m> {
    /// Its place among its state's transitions: 0 is tried first.
    pub index: usize,
    /// Its place among all its machine's transitions (`Machine::transitions`).
    pub number: usize,
    pub transition: &'m Transition,
    state: &'m State,
}

impl<'m> RingletPlan<'m> {
    /// The ringlet of `machine`'s state `id`; `None` for an id that is no state of it.
    pub fn of(machine: &'m Machine, id: StateId) -> Option<RingletPlan<'m>> {
        let state = machine.state(id)?;
        Some(RingletPlan { machine, state })
    }

    /// The ringlet of `machine`'s state `state`, which is one of its states.
    pub fn of_state(machine: &'m Machine, state: &'m State) -> RingletPlan<'m> {
        RingletPlan { machine, state }
    }

    pub fn state(&self) -> &'m State {
        self.state
    }

    /// What runs when the machine has just entered the state, before the snapshot.
    pub fn arriving(&self) -> &'m [Action] {
        &self.state.on_entry
    }

    /// The transitions in the order their labels are tried.
    pub fn arms(&self) -> Arms<'m> {
        Arms {
            all: self.machine.transitions.iter().enumerate(),
            state: self.state,
            index: 0,
        }
    }

    /// Every activity the ringlet may run, each once: arriving, leaving by each arm, staying.
    pub fn activities(&self) -> Vec<&'m [Action]> {
        let mut all = vec![self.arriving()];
        for arm in self.arms() {
            if !all.iter().any(|a| std::ptr::eq(*a, arm.leaving())) {
                all.push(arm.leaving());
            }
        }
        all.push(self.staying());
        all
    }

    /// What runs when no label held.
    pub fn staying(&self) -> &'m [Action] {
        &self.state.internal
    }

    /// Whether the state has no way out: the machine's run ends once it has arrived (§3).
    pub fn is_final(&self) -> bool {
        self.arms().next().is_none()
    }
}

/// A state's arms in the order they are tried ([`RingletPlan::arms`]).
#[derive(Clone, Debug)]
pub struct Arms<'m> {
    all: std::iter::Enumerate<std::slice::Iter<'m, Transition>>,
    state: &'m State,
    index: usize,
}

impl<'m> Iterator for Arms<'m> {
    type Item = Arm<'m>;

    fn next(&mut self) -> Option<Arm<'m>> {
        let state = self.state;
        let (number, transition) = self.all.find(|(_, t)| t.source == state.id)?;
        self.index += 1;
        Some(Arm {
            index: self.index - 1,
            number,
            transition,
            state,
        })
    }
}

impl<'m> Arm<'m> {
    pub fn label(&self) -> &'m Label {
        &self.transition.label
    }

    pub fn target(&self) -> StateId {
        self.transition.target
    }

    /// What runs when this transition fires, before the machine moves to its target: its
    /// state's OnExit, or, for a nested state's transition that leaves its composites too,
    /// their OnExits after it, innermost first (§3.2); for one that stays, its own actions.
    pub fn leaving(&self) -> &'m [Action] {
        match &self.transition.leaving {
            Some(leaving) => leaving,
            None if self.stays() => &[],
            None => &self.state.on_exit,
        }
    }

    /// Whether it fires without moving (`when p { … }`, §3.2): after [`Arm::leaving`] the
    /// machine is where it was, not just entered (no OnEntry runs next) and with every clock
    /// still counting from where it started.
    pub fn stays(&self) -> bool {
        self.transition.stays
    }
}

/// What a ringlet does next.
#[derive(Clone, Copy, Debug)]
pub enum Next<'m> {
    /// Run these activities: the machine has just entered its state.
    Arrive(&'m [Action]),
    /// Take the snapshot the labels read (§3.1).
    Snapshot,
    /// Prove this arm's label, then say whether it held ([`RingletRun::proved`]).
    Try(Arm<'m>),
    /// The arm's label held: run what [`Arm::leaving`] gives and move to its target (or, when
    /// [`Arm::stays`], stay as the machine is).
    Leave(Arm<'m>),
    /// No label held: run these activities and stay.
    Stay(&'m [Action]),
    /// The ringlet is over; the index of the arm that fired, if one did.
    Done(Option<usize>),
}

/// One ringlet under way: [`RingletRun::next_step`] says what to do, in the order of §3.1, so that
/// a reader that waits (the runner, on experts) and one that does not (the checker) follow one
/// order.
#[derive(Clone, Debug)]
pub struct RingletRun<'m> {
    plan: RingletPlan<'m>,
    arms: Arms<'m>,
    at: Step<'m>,
}

#[derive(Clone, Copy, Debug)]
enum Step<'m> {
    Arrive,
    Snapshot,
    /// The next arm is to be tried (after the last: stay).
    Try,
    /// This arm's label is being proved.
    Proving(Arm<'m>),
    Leave(Arm<'m>),
    Done(Option<usize>),
}

impl<'m> RingletRun<'m> {
    /// A ringlet of `plan`'s state; `just_entered` when the machine has not yet run its arrival.
    pub fn new(plan: RingletPlan<'m>, just_entered: bool) -> RingletRun<'m> {
        RingletRun {
            plan,
            arms: plan.arms(),
            at: if just_entered {
                Step::Arrive
            } else {
                Step::Snapshot
            },
        }
    }

    /// What to do now. After a [`Next::Try`], call [`RingletRun::proved`] first: asking again
    /// unanswered reads the label as not proved.
    pub fn next_step(&mut self) -> Next<'m> {
        if let Step::Proving(_) = self.at {
            self.at = Step::Try;
        }
        let (next, then) = match self.at {
            Step::Arrive => (Next::Arrive(self.plan.arriving()), Step::Snapshot),
            Step::Snapshot => (Next::Snapshot, Step::Try),
            Step::Try | Step::Proving(_) => match self.arms.next() {
                Some(arm) => (Next::Try(arm), Step::Proving(arm)),
                None => (Next::Stay(self.plan.staying()), Step::Done(None)),
            },
            Step::Leave(arm) => (Next::Leave(arm), Step::Done(Some(arm.index))),
            Step::Done(fired) => (Next::Done(fired), Step::Done(fired)),
        };
        self.at = then;
        next
    }

    /// Whether the label of the arm last given by [`Next::Try`] held.
    pub fn proved(&mut self, holds: bool) {
        if let Step::Proving(arm) = self.at {
            self.at = if holds { Step::Leave(arm) } else { Step::Try };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proclaim_fsm::parse_machine;

    const MACHINE: &str = "\
machine M
initial A
state A {
    entry { x = 1; }
    exit { x = 2; }
    internal { x = 3; }
    when p -> B
    when q -> A
}
state B { }
";

    fn machine() -> Machine {
        let mut read = parse_machine("M.machine", MACHINE);
        assert!(read.diagnostics.is_empty(), "{:?}", read.diagnostics);
        read.machines.remove(0)
    }

    /// The steps of a ringlet of state A whose labels hold as `holds` says, written out.
    fn check(just_entered: bool, holds: &[bool], expect: &[&str]) {
        let machine = machine();
        let plan = RingletPlan::of(&machine, machine.initial).expect("A is a state");
        let mut run = RingletRun::new(plan, just_entered);
        let mut said = Vec::new();
        loop {
            match run.next_step() {
                Next::Arrive(actions) => said.push(format!("arrive {}", actions.len())),
                Next::Snapshot => said.push("snapshot".into()),
                Next::Try(arm) => {
                    said.push(format!("try {}", arm.label()));
                    run.proved(holds[arm.index]);
                }
                Next::Leave(arm) => {
                    let target = machine.state(arm.target()).expect("a state");
                    let leaving = arm.leaving().len();
                    said.push(format!("leave {leaving} for {}", target.name));
                }
                Next::Stay(actions) => said.push(format!("stay {}", actions.len())),
                Next::Done(fired) => {
                    said.push(format!("done {fired:?}"));
                    break;
                }
            }
        }
        assert_eq!(said, expect);
    }

    #[test]
    fn arrival_comes_before_the_snapshot_and_only_when_just_entered() {
        check(
            true,
            &[false, false],
            &[
                "arrive 1",
                "snapshot",
                "try p",
                "try q",
                "stay 1",
                "done None",
            ],
        );
        check(
            false,
            &[false, false],
            &["snapshot", "try p", "try q", "stay 1", "done None"],
        );
    }

    #[test]
    fn the_first_label_that_holds_fires_and_later_ones_are_not_tried() {
        check(
            false,
            &[true, true],
            &["snapshot", "try p", "leave 1 for B", "done Some(0)"],
        );
        check(
            false,
            &[false, true],
            &[
                "snapshot",
                "try p",
                "try q",
                "leave 1 for A",
                "done Some(1)",
            ],
        );
    }

    #[test]
    fn a_transition_that_stays_runs_its_own_actions_and_not_the_exit() {
        let text = "machine M\nstate A {\n    exit { x = 2; }\n    when p {\n        x = 5;\n        y = 6;\n    }\n    when q -> A\n}\n";
        let read = parse_machine("M.machine", text);
        assert!(read.diagnostics.is_empty(), "{:?}", read.diagnostics);
        let machine = &read.machines[0];
        let plan = RingletPlan::of(machine, machine.initial).expect("A is a state");
        let said: Vec<(bool, usize)> = plan
            .arms()
            .map(|a| (a.stays(), a.leaving().len()))
            .collect();
        assert_eq!(said, [(true, 2), (false, 1)]);
        assert!(!plan.is_final());
    }

    #[test]
    fn a_state_with_no_way_out_is_final() {
        let machine = machine();
        let finals: Vec<bool> = machine
            .states
            .iter()
            .map(|s| RingletPlan::of_state(&machine, s).is_final())
            .collect();
        assert_eq!(finals, [false, true]);
    }
}
