//! Generates the .dl parser from `src/grammar.lalrpop` at build time.
fn main() {
    lalrpop::process_src().expect("the .dl grammar must compile");
}
