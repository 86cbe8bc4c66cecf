//! Compiles a checked theory into decision functions: each declared output's answer is a boolean
//! function of the theory's inputs, tabulated with the reasoner itself, reduced to an ordered
//! decision diagram or kept as a truth table (whichever is smaller), and printed as freestanding
//! C99. An answer the reasoner leaves undecided within its budget is refused, never guessed. A
//! behaviour compiles the same way, its machines planned once and printed as C
//! ([`compile_behaviour`]) or as a Cargo project ([`compile_behaviour_rust`]).
//!
//! ```
//! use proclaim_cdl::{load, Language, SearchLimits};
//! use proclaim_compile::{compile, Domain};
//! let theory = load("input{a}. input{b}. R: a, b => c. output{beta c}.", Language::Dl).unwrap();
//! let compiled = compile(&theory, SearchLimits::default(), Domain::Boolean).unwrap();
//! assert_eq!(compiled.answer(0, &[true, true]), true);
//! assert_eq!(compiled.answer(0, &[true, false]), false);
//! ```

mod activity;
mod answer_code;
mod behaviour;
mod c;
mod code;
mod diagram;
mod error;
mod machine_code;
mod plan;
mod print_c;
mod print_rust;
mod refusal;
mod rust_template;
mod spell_c;
mod spell_rust;
mod tabulate;

pub use behaviour::{
    compile_behaviour, compile_behaviour_rust, source_repository, CBehaviour, RustBehaviour,
};
pub use c::{c_identifier, CSource};
pub use diagram::{Diagram, Node};
pub use error::CompileError;
pub use refusal::Refusal;
pub use tabulate::{compile, Compiled, Domain, Form, MAX_VARIABLES};
