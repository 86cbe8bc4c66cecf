//! Generates the native machine format's parser from `src/native/grammar.lalrpop`.
fn main() {
    lalrpop::process_src().expect("the machine grammar must compile");
}
