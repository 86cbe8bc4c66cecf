//! A reasoner's answers in the model: the real expert (`proclaim_experts::ReasonerExpert`, the
//! same engine, input mapping and algorithm per output as `proclaim run` uses) fed the inputs of
//! the state at hand, its answers cached per input valuation. The logic is verified together
//! with the machines: a label the theory answers is its truth table, never a free choice.

use proclaim_behaviour::LoadedTheory;
use proclaim_board::{ModuleDecl, Value};
use proclaim_experts::ReasonerExpert;
use rustc_hash::FxHashMap;

/// What an input is at the moment of asking, as the expert reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Input {
    /// Never posted: unknown to the theory, as before its first posting in a run.
    Unknown,
    Value(bool),
}

pub struct Reasoner {
    expert: ReasonerExpert,
    /// Input types in the order a valuation lists them (set by the model).
    types: Vec<String>,
    cache: FxHashMap<Vec<Input>, Vec<bool>>,
    outputs: Vec<String>,
}

/// What the model keeps of a theory to start a [`Reasoner`] for each search: the model stays a
/// frozen value, and each search proves and caches its own answers.
pub struct ReasonerSeed {
    expert: Box<dyn Fn() -> ReasonerExpert + Send + Sync>,
}

impl ReasonerSeed {
    pub fn new(theory: &LoadedTheory) -> ReasonerSeed {
        let (name, theory, mapping, limits) = (
            theory.name.clone(),
            theory.theory.clone(),
            theory.mapping.clone(),
            theory.limits,
        );
        ReasonerSeed {
            expert: Box::new(move || {
                ReasonerExpert::new(&name, theory.clone(), &mapping).with_limits(limits)
            }),
        }
    }

    /// A reasoner with nothing proved yet.
    pub fn start(&self) -> Reasoner {
        let expert = (self.expert)();
        let decl = expert.declaration();
        Reasoner {
            expert,
            types: decl
                .reads
                .iter()
                .filter(|r| r.as_str() != proclaim_board::QUERY_TYPE)
                .cloned()
                .collect(),
            cache: FxHashMap::default(),
            outputs: decl.answers,
        }
    }
}

impl Reasoner {
    pub fn declaration(&self) -> ModuleDecl {
        self.expert.declaration()
    }

    /// How many input valuations were proved (the rest came from the cache).
    pub fn valuations(&self) -> usize {
        self.cache.len()
    }

    /// Every answer for `inputs` (one per input type, in [`Reasoner::declaration`]'s order of
    /// reads), proved once per valuation.
    pub fn answers(&mut self, inputs: &[Input]) -> &[bool] {
        if !self.cache.contains_key(inputs) {
            for (ty, input) in self.types.iter().zip(inputs) {
                let value = match input {
                    Input::Unknown => Value::Str("unknown".into()),
                    Input::Value(b) => Value::Bool(*b),
                };
                self.expert.apply(ty, &value);
            }
            let answers = self
                .outputs
                .clone()
                .iter()
                .map(|o| self.expert.answer(o).unwrap_or(false))
                .collect();
            self.cache.insert(inputs.to_vec(), answers);
        }
        &self.cache[inputs]
    }
}

/// An input value as the expert reads it (`ReasonerExpert::apply`): the string `unknown` is
/// unknown, anything else is its truth.
pub fn input(value: Option<&Value>) -> Input {
    match value {
        None => Input::Unknown,
        Some(Value::Str(s)) if s.eq_ignore_ascii_case("unknown") => Input::Unknown,
        Some(v) => Input::Value(v.truthy()),
    }
}
