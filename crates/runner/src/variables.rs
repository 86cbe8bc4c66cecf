//! Variables with gufsm's scoping. A name declared in a machine (`int n;`) is that machine's
//! own; `extern x` binds `x` to the whiteboard message of that type for every machine of the
//! behaviour (reading gives its latest value, assigning posts it); any other name some
//! activity assigns is a global, shared by every machine of the behaviour and starting at 0.
//! gufsm kept the three in one table per machine vector (`M<id>$$name`, `E$$name`, `name`);
//! lookups go in that order: own, extern, global.

use parking_lot::RwLock;
use proclaim_board::Value;
use proclaim_fsm::{names, Machine, VarType};
use proclaim_lower::arith::{convert, zero};
use rustc_hash::{FxHashMap, FxHashSet};
use std::sync::Arc;
use tokio::sync::watch;

/// What the machines of one behaviour share: globals and the names bound to the whiteboard.
pub struct Shared {
    globals: RwLock<FxHashMap<String, Value>>,
    externs: RwLock<FxHashSet<String>>,
    /// Counts changes of globals, so a machine whose label reads one wakes when it changes.
    changes: watch::Sender<u64>,
}

impl Shared {
    /// The variables the machines of a behaviour share, from what their activities declare
    /// and assign.
    pub fn for_machines<'a>(machines: impl IntoIterator<Item = &'a Machine>) -> Arc<Shared> {
        let shared = Arc::new(Shared {
            globals: RwLock::default(),
            externs: RwLock::default(),
            changes: watch::channel(0).0,
        });
        let machines: Vec<&Machine> = machines.into_iter().collect();
        // Externs first: a name some machine binds to the whiteboard is no global anywhere.
        for m in &machines {
            shared.add_externs(m);
        }
        for m in &machines {
            shared.add_globals(m);
        }
        shared
    }

    /// Adds what a (re)loaded machine declares and assigns; values already held stay.
    pub fn register(&self, machine: &Machine) {
        self.add_externs(machine);
        self.add_globals(machine);
    }

    fn add_externs(&self, machine: &Machine) {
        let mut externs = self.externs.write();
        for name in names::externs_of(machine) {
            externs.insert(name.to_string());
        }
    }

    fn add_globals(&self, machine: &Machine) {
        let own = names::own_variables(machine);
        let externs = self.externs.read();
        let mut globals = self.globals.write();
        for name in names::globals_of(machine, &own, |n| externs.contains(n)) {
            globals.entry(name.to_string()).or_insert(Value::Int(0));
        }
    }

    pub fn is_extern(&self, name: &str) -> bool {
        self.externs.read().contains(name)
    }

    pub fn global(&self, name: &str) -> Option<Value> {
        self.globals.read().get(name).cloned()
    }

    pub fn is_global(&self, name: &str) -> bool {
        self.globals.read().contains_key(name)
    }

    /// Sets a global (creating it); machines waiting on globals wake when the value changed.
    pub fn set_global(&self, name: &str, value: Value) {
        let changed = {
            let mut globals = self.globals.write();
            match globals.get_mut(name) {
                Some(old) if *old == value => false,
                Some(old) => {
                    *old = value;
                    true
                }
                None => {
                    globals.insert(name.to_string(), value);
                    true
                }
            }
        };
        if changed {
            self.changes.send_modify(|n| *n = n.wrapping_add(1));
        }
    }

    pub(crate) fn changes(&self) -> watch::Receiver<u64> {
        self.changes.subscribe()
    }

    /// Every global and its value, and how many times one changed (a checkpoint's).
    pub(crate) fn globals_and_changes(&self) -> (Vec<(String, Value)>, u64) {
        let globals = self.globals.read();
        let all = globals.iter().map(|(n, v)| (n.clone(), v.clone()));
        (all.collect(), *self.changes.borrow())
    }

    /// Globals and the count of changes as a checkpoint holds them; globals it does not name
    /// keep their values.
    pub(crate) fn restore(&self, globals: Vec<(String, Value)>, changes: u64) {
        self.globals.write().extend(globals);
        self.changes.send_replace(changes);
    }
}

/// The names a machine's expressions see: its own variables and those of its behaviour.
#[derive(Clone, Copy)]
pub(crate) struct Scope<'a> {
    pub locals: &'a Locals,
    pub shared: &'a Shared,
}

impl Scope<'_> {
    /// Whether `name` is a variable (the machine's own, an extern, or a global) rather than a
    /// proposition to ask an expert about or a whiteboard value.
    pub fn is_variable(&self, name: &str) -> bool {
        self.locals.contains(name) || self.shared.is_extern(name) || self.shared.is_global(name)
    }

    /// Whether reading `name` reads a whiteboard message (an extern, or no variable at all).
    pub fn is_message(&self, name: &str) -> bool {
        !self.locals.contains(name) && !self.shared.is_global(name)
    }
}

/// One machine's own variables: declared types and current values.
#[derive(Clone, Debug, Default)]
pub struct Locals {
    types: FxHashMap<String, VarType>,
    values: FxHashMap<String, Value>,
}

impl Locals {
    /// Every variable the machine declares, at its type's zero (gufsm made them when it read
    /// the machine, wherever the declaration stood).
    pub fn declared(machine: &Machine) -> Locals {
        let mut locals = Locals::default();
        for own in names::own_variables(machine) {
            locals.values.insert(own.name.clone(), zero(&own.first));
            locals.types.insert(own.name, own.last);
        }
        locals
    }

    /// The variables of a reloaded machine: values of names it still declares are kept.
    pub fn reloaded(&self, machine: &Machine) -> Locals {
        let mut new = Locals::declared(machine);
        for (name, value) in &self.values {
            if let Some(ty) = new.types.get(name) {
                new.values.insert(name.clone(), convert(ty, value.clone()));
            }
        }
        new
    }

    pub fn get(&self, name: &str) -> Option<&Value> {
        self.values.get(name)
    }

    pub fn contains(&self, name: &str) -> bool {
        self.types.contains_key(name)
    }

    /// A declared variable's type, as written.
    pub(crate) fn type_of(&self, name: &str) -> Option<&str> {
        self.types.get(name).map(VarType::name)
    }

    /// Every declared variable's name.
    pub(crate) fn names(&self) -> Vec<String> {
        self.types.keys().cloned().collect()
    }

    /// Sets a declared variable, converting the value to its type as C would (`int n = 2.7`
    /// holds 2). False when the machine declares no such variable.
    pub fn set(&mut self, name: &str, value: Value) -> bool {
        match self.types.get(name) {
            Some(ty) => {
                let value = convert(ty, value);
                self.values.insert(name.to_string(), value);
                true
            }
            None => false,
        }
    }
}
