//! A theory's answers tabulated by the reasoner over every valuation of its inputs, and the
//! compiled form chosen from them.

use crate::diagram::Diagram;
use crate::error::CompileError;
use proclaim_cdl::{Algorithm, Atom, Engine, Lit, RowFilter, SearchLimits, Session, Theory};
use std::sync::Arc;

/// Decision variables a compiled theory may have: its table has two to this power rows.
pub const MAX_VARIABLES: usize = 20;

/// Which valuations of the inputs the functions are defined over.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Domain {
    /// The truth table's rows (`proclaim table`): every input true or false, one atom of each
    /// input group true; one variable per input atom. Rows the table leaves out (`ignore{}`,
    /// `assert{}`, contradicting the axioms) are not valid and answer false.
    Boolean,
    /// What a running expert holds: each input true, false or unknown (never posted); two
    /// variables per input, `known` then `true`. A row holding two atoms of an input group true
    /// is not valid (setting one true makes the others false, so no run reaches it). Theories
    /// with clause facts are refused here (their inputs' refusals are not compiled yet).
    Ternary,
}

/// How the functions are stored: the smaller of the two.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Form {
    Diagram,
    Table,
}

/// A theory compiled: its outputs' decision functions and the validity of a valuation.
#[derive(Clone, Debug)]
pub struct Compiled {
    pub name: String,
    pub domain: Domain,
    /// Input atoms, in the order of the theory's `input{}` declarations.
    pub inputs: Vec<String>,
    /// Output names as the reasoner expert posts them (`cook`, `~cook`).
    pub outputs: Vec<String>,
    /// One shared diagram: a root per output, then the root of validity.
    pub diagram: Diagram,
    pub form: Form,
    /// Rules in the theory as written.
    pub rules: usize,
}

impl Compiled {
    /// Decision variables: one per input (boolean) or two (ternary).
    pub fn variables(&self) -> usize {
        match self.domain {
            Domain::Boolean => self.inputs.len(),
            Domain::Ternary => 2 * self.inputs.len(),
        }
    }

    /// Functions stored: the outputs and validity.
    pub fn functions(&self) -> usize {
        self.outputs.len() + 1
    }

    /// Output `o`'s answer for one assignment of the decision variables.
    pub fn answer(&self, o: usize, variables: &[bool]) -> bool {
        self.diagram.eval(self.diagram.roots[o], variables)
    }

    /// Whether the assignment is a valuation the reasoner accepts.
    pub fn valid(&self, variables: &[bool]) -> bool {
        self.diagram
            .eval(self.diagram.roots[self.outputs.len()], variables)
    }

    /// Bytes the diagram's node arrays take in C (a variable byte and two child indices a node).
    pub fn diagram_bytes(&self) -> usize {
        self.diagram.nodes.len() * (1 + 2 * self.diagram.index_bytes())
    }

    /// Bytes a truth table of every function takes in C (a bit a row and function).
    pub fn table_bytes(&self) -> usize {
        ((1usize << self.variables()) * self.functions()).div_ceil(8)
    }

    /// Bytes of the form chosen.
    pub fn bytes(&self) -> usize {
        match self.form {
            Form::Diagram => self.diagram_bytes(),
            Form::Table => self.table_bytes(),
        }
    }
}

/// Tabulates every output of `theory` with the reasoner under `limits` over `domain` and
/// compiles them. The outputs are the declared ones, or β of every atom that is not an input
/// when none is declared (as the reasoner expert answers).
pub fn compile(
    theory: &Theory,
    limits: SearchLimits,
    domain: Domain,
) -> Result<Compiled, CompileError> {
    let atoms: Vec<Atom> = theory.input_atoms().collect();
    let inputs: Vec<String> = atoms
        .iter()
        .map(|&a| theory.atom_name(a).to_string())
        .collect();
    let queries = queries(theory, &atoms);
    let variables = match domain {
        Domain::Boolean => atoms.len(),
        Domain::Ternary => 2 * atoms.len(),
    };
    if variables > MAX_VARIABLES {
        return Err(CompileError::TooManyInputs {
            variables,
            limit: MAX_VARIABLES,
        });
    }
    if domain == Domain::Ternary && !theory.axioms().is_empty() {
        return Err(CompileError::Unsupported {
            what: "a clause fact (axiom) in a theory a behaviour runs".into(),
        });
    }
    let rows = 1usize << variables;
    let mut columns: Vec<Vec<bool>> = vec![Vec::with_capacity(rows); queries.len() + 1];
    let mut session = Session::with_limits(Arc::new(Engine::new(theory.clone())), limits);
    let mut values: Vec<Option<bool>> = vec![None; atoms.len()];
    for row in 0..rows {
        let bit = |v: usize| (row >> (variables - 1 - v)) & 1 == 1;
        let valid = match domain {
            Domain::Boolean => {
                for (i, value) in values.iter_mut().enumerate() {
                    *value = Some(bit(i));
                }
                in_table(theory, &atoms, &values) && set_row(&mut session, &atoms, &values)
            }
            Domain::Ternary => {
                for (i, value) in values.iter_mut().enumerate() {
                    *value = bit(2 * i).then(|| bit(2 * i + 1));
                }
                set_row(&mut session, &atoms, &values)
            }
        };
        for (q, &(ref name, algorithm, lit)) in queries.iter().enumerate() {
            let answer = valid
                && session
                    .decide(algorithm, lit)
                    .map_err(|undecided| CompileError::Undecided {
                        output: name.clone(),
                        row: show_row(&inputs, &values),
                        why: undecided.to_string(),
                    })?;
            columns[q].push(answer);
        }
        columns[queries.len()].push(valid);
    }
    let diagram = Diagram::from_columns(variables, &columns);
    let mut compiled = Compiled {
        name: theory.name().unwrap_or("theory").to_string(),
        domain,
        inputs,
        outputs: queries.into_iter().map(|(name, _, _)| name).collect(),
        diagram,
        form: Form::Diagram,
        rules: theory.written_rule_count(),
    };
    if compiled.table_bytes() < compiled.diagram_bytes() {
        compiled.form = Form::Table;
    }
    Ok(compiled)
}

/// The outputs asked: (name as posted, algorithm, literal).
fn queries(theory: &Theory, inputs: &[Atom]) -> Vec<(String, Algorithm, Lit)> {
    if theory.outputs().is_empty() {
        (0..theory.atom_count() as u32)
            .map(Atom)
            .filter(|a| !inputs.contains(a))
            .map(|a| {
                (
                    theory.atom_name(a).to_string(),
                    Algorithm::Beta,
                    Lit::positive(a),
                )
            })
            .collect()
    } else {
        theory
            .outputs()
            .iter()
            .map(|o| (theory.show(o.lit).to_string(), o.algorithm, o.lit))
            .collect()
    }
}

/// Sets the session's inputs to `values`; false when the reasoner refuses the valuation (it
/// contradicts the axioms) or holds a different one after it (an input group's update).
fn set_row(session: &mut Session, atoms: &[Atom], values: &[Option<bool>]) -> bool {
    if !session.engine().theory().axioms().is_empty() {
        // Unknown first, so no half-set valuation is checked against the axioms.
        for &a in atoms {
            let _ = session.set_input(a, None);
        }
    }
    let accepted = atoms
        .iter()
        .zip(values)
        .all(|(&a, &v)| session.set_input(a, v).is_ok());
    accepted
        && atoms
            .iter()
            .zip(values)
            .all(|(&a, &v)| session.input(a) == v)
}

/// Whether the truth table holds this valuation: one atom of each group true, and every
/// `ignore{}` and `assert{}` kept.
fn in_table(theory: &Theory, atoms: &[Atom], values: &[Option<bool>]) -> bool {
    let value = |atom: Atom| {
        atoms
            .iter()
            .position(|&a| a == atom)
            .and_then(|i| values[i])
    };
    let one_hot = theory
        .inputs()
        .iter()
        .filter(|g| g.atoms.len() > 1)
        .all(|g| g.atoms.iter().filter(|&&a| value(a) == Some(true)).count() == 1);
    let holds = |l: &Lit| value(l.atom()).is_some_and(|v| v != l.is_negated());
    one_hot
        && theory.row_filters().iter().all(|f| match f {
            RowFilter::Ignore { at_least, lits } => {
                lits.iter().filter(|l| holds(l)).count() < *at_least
            }
            RowFilter::Assert { lits } => lits.iter().any(holds),
        })
}

fn show_row(inputs: &[String], values: &[Option<bool>]) -> Vec<String> {
    inputs
        .iter()
        .zip(values)
        .map(|(name, v)| match v {
            Some(v) => format!("{name}={v}"),
            None => format!("{name}=unknown"),
        })
        .collect()
}
