//! The truth table of a theory: its declared outputs over every combination of its declared
//! inputs, less the combinations `ignore{}` and `assert{}` leave out.

use crate::engine::Engine;
use crate::literal::{Atom, Lit};
use crate::session::Session;
use crate::theory::{RowFilter, Theory};
use proclaim_syntax::Algorithm;
use std::sync::Arc;

/// Tables with more rows than this are refused (20 independent binary inputs).
pub const MAX_ROWS: usize = 1 << 20;

/// One column of outputs.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Column {
    pub algorithm: Algorithm,
    pub lit: Lit,
    /// `beta offside`
    pub heading: String,
    pub description: Option<String>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Row {
    /// One value for each input atom, in `Table::inputs` order.
    pub inputs: Vec<bool>,
    /// One value for each column; `None` when the inputs contradict the axioms.
    pub outputs: Option<Vec<bool>>,
}

#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Table {
    pub inputs: Vec<String>,
    pub columns: Vec<Column>,
    pub rows: Vec<Row>,
    /// True when the theory declares no outputs and every non-input atom was tabled with β.
    pub default_columns: bool,
}

/// Why a table could not be made.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum TableError {
    TooManyRows(u128),
}

impl std::fmt::Display for TableError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            TableError::TooManyRows(n) => write!(
                f,
                "the inputs have {n} combinations, more than the {MAX_ROWS} a table may hold; group mutually exclusive inputs as input{{a, b, c}} or ask single rows with `prove --set`"
            ),
        }
    }
}

impl std::error::Error for TableError {}

/// Builds the truth table.
pub fn truth_table(engine: Arc<Engine>) -> Result<Table, TableError> {
    let theory = engine.theory();
    let groups: Vec<Vec<Atom>> = theory.inputs().iter().map(|g| g.atoms.clone()).collect();
    let atoms: Vec<Atom> = groups.iter().flatten().copied().collect();
    let combinations = groups
        .iter()
        .map(|g| if g.len() == 1 { 2u128 } else { g.len() as u128 })
        .try_fold(1u128, |acc, n| acc.checked_mul(n))
        .unwrap_or(u128::MAX);
    if combinations > MAX_ROWS as u128 {
        return Err(TableError::TooManyRows(combinations));
    }
    let default_columns = theory.outputs().is_empty();
    let columns = columns_of(theory, &atoms);
    let filters = theory.row_filters().to_vec();
    let inputs = atoms
        .iter()
        .map(|&a| theory.atom_name(a).to_string())
        .collect();
    let mut session = Session::new(engine.clone());
    let mut rows = Vec::new();
    let mut choice = vec![0usize; groups.len()];
    for _ in 0..combinations {
        let values: Vec<bool> = groups
            .iter()
            .zip(&choice)
            .flat_map(|(g, &c)| {
                (0..g.len()).map(move |i| if g.len() == 1 { c == 1 } else { c == i })
            })
            .collect();
        advance(&mut choice, &groups);
        if !keep(&filters, &atoms, &values) {
            continue;
        }
        let outputs = row_outputs(&mut session, &atoms, &values, &columns);
        rows.push(Row {
            inputs: values,
            outputs,
        });
    }
    Ok(Table {
        inputs,
        columns,
        rows,
        default_columns,
    })
}

/// The table's columns: the theory's declared outputs, or β of every atom that is not an input.
fn columns_of(theory: &Theory, inputs: &[Atom]) -> Vec<Column> {
    if theory.outputs().is_empty() {
        (0..theory.atom_count() as u32)
            .map(Atom)
            .filter(|a| !inputs.contains(a))
            .map(|a| Column {
                algorithm: Algorithm::Beta,
                lit: Lit::positive(a),
                heading: format!("beta {}", theory.atom_name(a)),
                description: None,
            })
            .collect()
    } else {
        theory
            .outputs()
            .iter()
            .map(|o| Column {
                algorithm: o.algorithm,
                lit: o.lit,
                heading: format!("{} {}", o.algorithm, theory.show(o.lit)),
                description: o.description.clone(),
            })
            .collect()
    }
}

/// Each column's answer with the inputs set to `values`; `None` when they contradict the axioms.
fn row_outputs(
    session: &mut Session,
    atoms: &[Atom],
    values: &[bool],
    columns: &[Column],
) -> Option<Vec<bool>> {
    // Unknown first, so no half-set combination is checked against the axioms.
    for &a in atoms {
        let _ = session.set_input(a, None);
    }
    let consistent = session
        .set_inputs(atoms.iter().zip(values).map(|(&a, &v)| (a, Some(v))))
        .is_ok();
    consistent.then(|| {
        columns
            .iter()
            .map(|c| session.prove(c.algorithm, c.lit))
            .collect()
    })
}

/// Steps to the next combination: the last group varies fastest; a binary input goes false,
/// then true.
fn advance(choice: &mut [usize], groups: &[Vec<Atom>]) {
    for i in (0..choice.len()).rev() {
        let size = if groups[i].len() == 1 {
            2
        } else {
            groups[i].len()
        };
        choice[i] += 1;
        if choice[i] < size {
            return;
        }
        choice[i] = 0;
    }
}

fn keep(filters: &[RowFilter], atoms: &[Atom], values: &[bool]) -> bool {
    let holds = |l: &Lit| {
        atoms
            .iter()
            .position(|&a| a == l.atom())
            .is_some_and(|i| values[i] != l.is_negated())
    };
    filters.iter().all(|f| match f {
        RowFilter::Ignore { at_least, lits } => {
            lits.iter().filter(|l| holds(l)).count() < *at_least
        }
        RowFilter::Assert { lits } => lits.iter().any(holds),
    })
}
