//! A theory's truth table as one read-only struct of arrays C indexes directly: its declared
//! outputs over every combination of its declared inputs, as `proclaim table` prints it.

use crate::detail::{fail, reported};
use crate::guard::guarded;
use crate::status::ProclaimStatus;
use crate::theory::{live_theory, ProclaimTheory};
use proclaim_cdl::{truth_table, TableError};
use std::ffi::{c_char, CString};
use std::sync::atomic::{AtomicBool, Ordering};

/// A truth table, read-only for C: row `r`'s value of input `i` is
/// `inputs[r * input_count + i]`, its value of output `c` is `outputs[r * output_count + c]`.
/// [`proclaim_table_free`] frees what it points to and leaves the struct itself empty.
#[repr(C)]
#[derive(Debug)]
pub struct ProclaimTable {
    /// How many input atoms (the declared inputs, in the order the theory declares them).
    pub input_count: usize,
    /// Their names: `input_count` NUL-terminated strings.
    pub input_names: *const *const c_char,
    /// How many output columns (the declared outputs; every other atom under β when the theory
    /// declares none).
    pub output_count: usize,
    /// Their headings, algorithm and literal (`beta cook`): `output_count` strings.
    pub output_names: *const *const c_char,
    /// How many rows: every combination of the inputs that `ignore{}` and `assert{}` keep.
    pub row_count: usize,
    /// `row_count * input_count` values, row by row.
    pub inputs: *const bool,
    /// `row_count` values: false where the row's inputs contradict the theory's axioms, whose
    /// outputs are then all false and mean nothing (`proclaim table` prints "inconsistent").
    pub consistent: *const bool,
    /// `row_count * output_count` values, row by row.
    pub outputs: *const bool,
}

/// The table with what its pointers point to. `table` comes first (and the struct is `repr(C)`)
/// so a pointer to the whole is a pointer to the table C sees. The header (`table` and `live`) is
/// never deallocated: [`proclaim_table_free`] drops `storage`, empties `table` (counts 0,
/// pointers null) and clears `live`, so a second free says `DEAD_HANDLE`.
#[repr(C)]
struct Owned {
    table: ProclaimTable,
    live: AtomicBool,
    storage: Option<Box<Storage>>,
}

/// What a table's pointers point to. The vectors' buffers stay where they are when the vectors
/// move.
#[allow(
    dead_code,
    reason = "held, never read: they keep alive what the table points to"
)]
struct Storage {
    names: Vec<CString>,
    input_names: Vec<*const c_char>,
    output_names: Vec<*const c_char>,
    inputs: Vec<bool>,
    consistent: Vec<bool>,
    outputs: Vec<bool>,
}

fn c_string(text: &str) -> CString {
    // Atom names and headings hold no NUL (the lexer stops at one); replaced rather than trusted.
    CString::new(text.replace('\0', "\u{FFFD}")).unwrap_or_default()
}

fn build(table: &proclaim_cdl::Table) -> Box<Owned> {
    let names: Vec<CString> = table
        .inputs
        .iter()
        .map(|name| c_string(name))
        .chain(table.columns.iter().map(|c| c_string(&c.heading)))
        .collect();
    let (input_names, output_names) = names.split_at(table.inputs.len());
    let input_names: Vec<*const c_char> = input_names.iter().map(|n| n.as_ptr()).collect();
    let output_names: Vec<*const c_char> = output_names.iter().map(|n| n.as_ptr()).collect();
    let columns = table.columns.len();
    let mut inputs = Vec::with_capacity(table.rows.len() * table.inputs.len());
    let mut consistent = Vec::with_capacity(table.rows.len());
    let mut outputs = Vec::with_capacity(table.rows.len() * columns);
    for row in &table.rows {
        inputs.extend_from_slice(&row.inputs);
        consistent.push(row.outputs.is_some());
        match &row.outputs {
            Some(values) => outputs.extend_from_slice(values),
            None => outputs.extend(std::iter::repeat_n(false, columns)),
        }
    }
    let table = ProclaimTable {
        input_count: table.inputs.len(),
        input_names: input_names.as_ptr(),
        output_count: columns,
        output_names: output_names.as_ptr(),
        row_count: table.rows.len(),
        inputs: inputs.as_ptr(),
        consistent: consistent.as_ptr(),
        outputs: outputs.as_ptr(),
    };
    Box::new(Owned {
        table,
        live: AtomicBool::new(true),
        storage: Some(Box::new(Storage {
            names,
            input_names,
            output_names,
            inputs,
            consistent,
            outputs,
        })),
    })
}

/// Makes the truth table of `theory` and writes it to `*table_out`: `OK`, or `TOO_MANY_ROWS`
/// when the inputs have more than 2^20 combinations (group exclusive inputs as `input{a, b}`),
/// or `BAD_ARGUMENT`, or `DEAD_HANDLE` for a freed theory; then `*table_out` is left alone.
///
/// # Safety
/// `theory` is null or from `proclaim_theory_load` (freed or not); `table_out` is null or writable.
#[no_mangle]
pub unsafe extern "C" fn proclaim_theory_table(
    theory: *const ProclaimTheory,
    table_out: *mut *mut ProclaimTable,
) -> ProclaimStatus {
    if table_out.is_null() {
        return reported(fail(ProclaimStatus::BadArgument, "table_out is null"));
    }
    let (engine, _tag) = match live_theory(theory) {
        Ok(live) => live,
        Err(status) => return reported(status),
    };
    reported(guarded(ProclaimStatus::Panic, || {
        match truth_table(engine) {
            Ok(table) => {
                *table_out = Box::into_raw(build(&table)).cast::<ProclaimTable>();
                ProclaimStatus::Ok
            }
            Err(error @ TableError::TooManyRows(_)) => {
                fail(ProclaimStatus::TooManyRows, error.to_string())
            }
        }
    }))
}

/// Frees what a table points to: `OK`, or `DEAD_HANDLE` when it was freed already. Null is
/// ignored (`OK`), as with `free()`. The struct itself stays readable, emptied (counts 0,
/// pointers null), so that a loop over a freed table's rows reads nothing; it is never reused.
/// Pointers copied out of the table before the free dangle, as with any freed memory.
///
/// # Safety
/// `table` is null or a pointer from [`proclaim_theory_table`] (freed or not), not read by
/// another thread during the free.
#[no_mangle]
pub unsafe extern "C" fn proclaim_table_free(table: *mut ProclaimTable) -> ProclaimStatus {
    if table.is_null() {
        return ProclaimStatus::Ok;
    }
    let owned = table.cast::<Owned>();
    // Only `live` is borrowed before the swap: a second free racing this one touches nothing else.
    let live = &*std::ptr::addr_of!((*owned).live);
    if !live.swap(false, Ordering::AcqRel) {
        return reported(ProclaimStatus::DeadHandle);
    }
    crate::kept::keep(owned);
    (*owned).table = emptied();
    let storage = (*owned).storage.take();
    guarded(ProclaimStatus::Panic, || {
        drop(storage);
        ProclaimStatus::Ok
    })
}

/// What a freed table reads as.
fn emptied() -> ProclaimTable {
    ProclaimTable {
        input_count: 0,
        input_names: std::ptr::null(),
        output_count: 0,
        output_names: std::ptr::null(),
        row_count: 0,
        inputs: std::ptr::null(),
        consistent: std::ptr::null(),
        outputs: std::ptr::null(),
    }
}
