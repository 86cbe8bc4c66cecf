//! The diagrams are reduced: for each output of every shipped theory (both domains), an
//! independent library (biodivine-lib-bdd, the verifier's) builds the same function from its
//! true rows, in the same variable order, and gets the same function with exactly as many
//! nodes as those reachable from the output's root here.

use biodivine_lib_bdd::{BddPartialValuation, BddValuation, BddVariableSet};
use proclaim_cdl::{load_named, Language, SearchLimits};
use proclaim_compile::{compile, Compiled, Domain};
use std::collections::HashSet;
use std::path::Path;

/// Internal nodes reachable from `root`.
fn reachable(c: &Compiled, root: u32) -> usize {
    let mut seen = HashSet::new();
    let mut stack = vec![root];
    while let Some(n) = stack.pop() {
        if n > 1 && seen.insert(n) {
            let node = c.diagram.nodes[n as usize];
            stack.extend([node.low, node.high]);
        }
    }
    seen.len()
}

fn check(c: &Compiled) {
    let n = c.variables();
    let vars = BddVariableSet::new_anonymous(n as u16);
    let order = vars.variables();
    for (f, &root) in c.diagram.roots.iter().enumerate() {
        let mut bdd = vars.mk_false();
        let mut column = Vec::new();
        for row in 0..1usize << n {
            let assignment: Vec<bool> = (0..n).map(|v| (row >> (n - 1 - v)) & 1 == 1).collect();
            let value = c.diagram.eval(root, &assignment);
            column.push((assignment.clone(), value));
            if value {
                let cube = BddPartialValuation::from_values(
                    &order.iter().copied().zip(assignment).collect::<Vec<_>>(),
                );
                bdd = bdd.or(&vars.mk_conjunctive_clause(&cube));
            }
        }
        for (assignment, value) in &column {
            let mut valuation = BddValuation::all_false(n as u16);
            for (v, &b) in order.iter().zip(assignment) {
                valuation.set_value(*v, b);
            }
            assert_eq!(bdd.eval_in(&valuation), *value, "{} function {f}", c.name);
        }
        // biodivine counts its terminals: one for false, two for anything else.
        let terminals = if bdd.is_false() { 1 } else { 2 };
        let internal = if root <= 1 { 0 } else { reachable(c, root) };
        assert_eq!(
            internal + terminals,
            bdd.size(),
            "{} function {f}: {internal} nodes here, {} there",
            c.name,
            bdd.size()
        );
    }
}

#[test]
fn every_shipped_theorys_diagram_is_as_small_as_an_independent_librarys() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mut checked = 0;
    for dir in ["theories", "theories/classics"] {
        for entry in std::fs::read_dir(root.join(dir)).unwrap().flatten() {
            let path = entry.path();
            if path.extension().is_none_or(|e| e != "dl") {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap();
            let theory = load_named(&path.display().to_string(), &text, Language::Dl).unwrap();
            for domain in [Domain::Boolean, Domain::Ternary] {
                if let Ok(c) = compile(&theory, SearchLimits::default(), domain) {
                    check(&c);
                    checked += 1;
                }
            }
        }
    }
    assert!(
        checked >= 13,
        "both domains of the shipped theories: {checked}"
    );
}
