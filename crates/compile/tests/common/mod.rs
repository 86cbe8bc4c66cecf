//! Builds compiled theories with gcc (the core freestanding, one translation unit for all of
//! them) and a hosted driver that prints every function on every row, and checks the printout
//! against the reasoner's own truth table.

#![allow(dead_code)]

use proclaim_cdl::{truth_table, Engine, Theory};
use proclaim_compile::{Compiled, Domain};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::sync::Arc;

/// Whether gcc is here: a skip said on stderr, or with `CI` set a failure (`.ci/run` runs on a
/// machine where the Rust toolchain's linker is gcc).
pub fn gcc_missing() -> bool {
    let missing = Command::new("gcc").arg("--version").output().is_err();
    if missing {
        assert!(
            std::env::var_os("CI").is_none(),
            "gcc is missing, and CI must build the compiled theories"
        );
        eprintln!("skipped: gcc is missing");
    }
    missing
}

pub fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("proclaim-compile-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Writes every theory's C as `t<k>.h` and one `theories.c`, builds the core with
/// `-std=c99 -Wall -Wextra -Werror -ffreestanding -c` and a hosted driver, runs it, and returns
/// its printout: one line a theory, a character a function (outputs, then validity) a row.
pub fn run_in_c(dir: &Path, compiled: &[Compiled]) -> Vec<String> {
    let mut core = String::new();
    let mut driver = String::from("#include <stdio.h>\n");
    let mut entries = String::new();
    for (k, theory) in compiled.iter().enumerate() {
        let prefix = format!("t{k}");
        let c = theory.to_c(&prefix);
        std::fs::write(dir.join(format!("{prefix}.h")), &c.header).unwrap();
        core.push_str(&c.source);
        driver.push_str(&format!("#include \"{prefix}.h\"\n"));
        entries.push_str(&format!(
            "    {{{}, {}, {prefix}_answer}},\n",
            theory.variables(),
            theory.functions()
        ));
    }
    driver.push_str(&format!(
        "struct entry {{ unsigned variables, functions; int (*answer)(unsigned, const unsigned char *); }};
static const struct entry entries[] = {{
{entries}}};
int main(void)
{{
    unsigned t, v, f;
    unsigned long row;
    unsigned char in[32];
    for (t = 0; t < {count}u; t++) {{
        for (row = 0; row < (1ul << entries[t].variables); row++) {{
            for (v = 0; v < entries[t].variables; v++) {{
                in[v] = (unsigned char)((row >> (entries[t].variables - 1 - v)) & 1u);
            }}
            for (f = 0; f < entries[t].functions; f++) {{
                putchar(entries[t].answer(f, in) ? '1' : '0');
            }}
        }}
        putchar('\\n');
    }}
    return 0;
}}
",
        count = compiled.len()
    ));
    std::fs::write(dir.join("theories.c"), core).unwrap();
    std::fs::write(dir.join("driver.c"), driver).unwrap();
    let gcc = |args: &[&str]| {
        let out = Command::new("gcc")
            .args(args)
            .current_dir(dir)
            .output()
            .expect("gcc runs");
        assert!(
            out.status.success(),
            "gcc {args:?} in {}:\n{}",
            dir.display(),
            String::from_utf8_lossy(&out.stderr)
        );
    };
    gcc(&[
        "-std=c99",
        "-Wall",
        "-Wextra",
        "-Werror",
        "-ffreestanding",
        "-O1",
        "-c",
        "theories.c",
        "-o",
        "theories.o",
    ]);
    gcc(&[
        "-std=c99",
        "-Wall",
        "-Wextra",
        "-Werror",
        "driver.c",
        "theories.o",
        "-o",
        "driver",
    ]);
    let out = Command::new(dir.join("driver"))
        .output()
        .expect("the driver runs");
    assert!(out.status.success(), "the driver failed");
    String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(str::to_string)
        .collect()
}

/// What the printout must be for a theory compiled over the boolean domain, from the
/// reasoner's truth table (`proclaim table`): rows the table leaves out print all zeros, rows
/// contradicting the axioms print zeros and are not valid.
pub fn expected_boolean(theory: &Theory, compiled: &Compiled) -> String {
    assert_eq!(compiled.domain, Domain::Boolean);
    let table = truth_table(Arc::new(Engine::new(theory.clone()))).expect("a table");
    assert_eq!(table.inputs, compiled.inputs);
    let width = compiled.functions();
    let mut expected = vec![b'0'; (1usize << compiled.variables()) * width];
    for row in &table.rows {
        let index = row
            .inputs
            .iter()
            .fold(0usize, |acc, &b| (acc << 1) | usize::from(b));
        if let Some(outputs) = &row.outputs {
            assert_eq!(outputs.len(), compiled.outputs.len());
            for (o, &v) in outputs.iter().enumerate() {
                expected[index * width + o] = if v { b'1' } else { b'0' };
            }
            expected[index * width + width - 1] = b'1';
        }
    }
    String::from_utf8(expected).unwrap()
}

/// The first row where the printout and the expectation differ, said plainly.
pub fn first_difference(compiled: &Compiled, got: &str, expected: &str) -> Option<String> {
    let width = compiled.functions();
    (0..expected.len() / width).find_map(|row| {
        let range = row * width..(row + 1) * width;
        (got.get(range.clone()) != expected.get(range.clone())).then(|| {
            format!(
                "theory `{}` row {row:b} (inputs {:?}): C printed {:?}, the reasoner {:?} (outputs {:?}, then validity)",
                compiled.name,
                compiled.variable_names(),
                got.get(range.clone()),
                &expected[range],
                compiled.outputs
            )
        })
    })
}

/// What the printout must be for a theory compiled over the ternary domain: a fresh session
/// a row, its inputs set as the variables say, each output asked as the reasoner expert asks.
pub fn expected_ternary(theory: &Theory, compiled: &Compiled) -> String {
    use proclaim_cdl::{Algorithm, Lit, Session};
    assert_eq!(compiled.domain, Domain::Ternary);
    let engine = Arc::new(Engine::new(theory.clone()));
    let atoms: Vec<_> = theory.input_atoms().collect();
    let queries: Vec<(Algorithm, Lit)> = if theory.outputs().is_empty() {
        (0..theory.atom_count() as u32)
            .map(proclaim_cdl::Atom)
            .filter(|a| !atoms.contains(a))
            .map(|a| (Algorithm::Beta, Lit::positive(a)))
            .collect()
    } else {
        theory
            .outputs()
            .iter()
            .map(|o| (o.algorithm, o.lit))
            .collect()
    };
    let variables = compiled.variables();
    let mut expected = String::new();
    for row in 0..1usize << variables {
        let bit = |v: usize| (row >> (variables - 1 - v)) & 1 == 1;
        let mut session = Session::new(engine.clone());
        for (i, &a) in atoms.iter().enumerate() {
            session
                .set_input(a, bit(2 * i).then(|| bit(2 * i + 1)))
                .expect("no axioms to contradict");
        }
        for &(algorithm, lit) in &queries {
            let v = session.decide(algorithm, lit).expect("decided");
            expected.push(if v { '1' } else { '0' });
        }
        expected.push('1');
    }
    expected
}

/// Each compiled theory in both forms, the one chosen and the other, so both printers are
/// checked on every theory; the theories repeated to match.
pub fn in_both_forms<T: Clone>(theories: &[T], compiled: &[Compiled]) -> (Vec<T>, Vec<Compiled>) {
    use proclaim_compile::Form;
    let mut ts = Vec::new();
    let mut cs = Vec::new();
    for (t, c) in theories.iter().zip(compiled) {
        for form in [Form::Diagram, Form::Table] {
            ts.push(t.clone());
            cs.push(Compiled { form, ..c.clone() });
        }
    }
    (ts, cs)
}
