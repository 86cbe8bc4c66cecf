//! Host functions: what `C++: f(arg)` calls, registered by name by the embedding program.
//! `msleep(ms)` and `sleep(s)` are built in.

use proclaim_fsm::Argument;
use rustc_hash::FxHashMap;
use std::sync::Arc;

pub type HostFunction = Arc<dyn Fn(Option<&Argument>) + Send + Sync>;

#[derive(Clone, Default)]
pub struct Hosts {
    functions: FxHashMap<String, HostFunction>,
}

impl Hosts {
    pub fn register(&mut self, name: &str, f: impl Fn(Option<&Argument>) + Send + Sync + 'static) {
        self.functions.insert(name.to_string(), Arc::new(f));
    }

    pub(crate) fn get(&self, name: &str) -> Option<&HostFunction> {
        self.functions.get(name)
    }
}
