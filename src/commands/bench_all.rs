//! `proclaim bench --all`: every conclusion against one query, as whole processes. For each case
//! it times `proclaim prove FILE --format spindle` (every conclusion, as SPINdle computes them),
//! `proclaim prove FILE QUERY` (one query) and `wc -w FILE` (reading the file and nothing more),
//! each with its output thrown away, and prints the best and median wall time of each.

use super::bench::{parse_case, write_family, Case};
use crate::failure::Failure;
use proclaim_gen::Format;
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

/// Best and median wall time of one command over the repeats, in milliseconds.
#[derive(Serialize, Clone, Copy, Debug)]
struct Timing {
    best_ms: f64,
    median_ms: f64,
}

/// One case's three timings (`wc` is absent where the machine has no `wc`).
#[derive(Serialize, Debug)]
struct Comparison {
    case: String,
    query: String,
    every_conclusion: Timing,
    one_query: Timing,
    wc_words: Option<Timing>,
}

pub fn run(cases: &[String], repeat: u32, json: bool) -> Result<ExitCode, Failure> {
    let cases = cases
        .iter()
        .map(|c| parse_case(c))
        .collect::<Result<Vec<_>, _>>()?;
    let dir = std::env::temp_dir().join(format!("proclaim-bench-all-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|error| Failure::Write {
        path: dir.clone(),
        error,
    })?;
    let outcome = cases
        .iter()
        .map(|case| compare(&dir, case, repeat.max(1)))
        .collect::<Result<Vec<_>, _>>();
    let _ = std::fs::remove_dir_all(&dir);
    let comparisons = outcome?;
    if json {
        println!(
            "{}",
            serde_json::to_string(&comparisons).unwrap_or_default()
        );
    } else {
        print_table(&comparisons);
    }
    Ok(ExitCode::SUCCESS)
}

/// The three commands on one case, taken in turn `repeat` times so that a drift in the
/// machine's speed falls on all three alike.
fn compare(dir: &Path, case: &Case, repeat: u32) -> Result<Comparison, Failure> {
    let (file, query) = match case {
        // SPINdle's own format: the comparison the issue makes is on `.dfl` files.
        Case::Family(family) => {
            let expected = family.expected();
            let query = expected
                .first()
                .map(|e| (e.algorithm.to_string(), e.literal.clone()));
            (write_family(dir, family, Format::Dfl)?, query)
        }
        Case::File(path) => (path.clone(), None),
    };
    let (alg, literal) = match query {
        Some(q) => q,
        None => ("beta".to_string(), first_atom(&file)?),
    };
    let exe = std::env::current_exe()
        .map_err(|e| Failure::Bench(format!("cannot find this program: {e}")))?;
    let every = [
        "prove".as_ref(),
        file.as_os_str(),
        "--format".as_ref(),
        "spindle".as_ref(),
    ];
    let one = [
        "prove".as_ref(),
        file.as_os_str(),
        literal.as_ref(),
        "--alg".as_ref(),
        alg.as_ref(),
    ];
    // `wc -w` on the file itself: `--version` is GNU's alone.
    let has_wc = Command::new("wc")
        .arg("-w")
        .arg(file.as_os_str())
        .stdout(Stdio::null())
        .status()
        .is_ok_and(|s| s.success());
    let (mut every_ms, mut one_ms, mut wc_ms) = (Vec::new(), Vec::new(), Vec::new());
    for _ in 0..repeat {
        every_ms.push(time(case, exe.as_os_str(), &every)?);
        one_ms.push(time(case, exe.as_os_str(), &one)?);
        if has_wc {
            wc_ms.push(time(
                case,
                "wc".as_ref(),
                &["-w".as_ref(), file.as_os_str()],
            )?);
        }
    }
    Ok(Comparison {
        case: case.to_string(),
        query: format!("{alg} {literal}"),
        every_conclusion: summary(every_ms),
        one_query: summary(one_ms),
        wc_words: has_wc.then(|| summary(wc_ms)),
    })
}

/// The wall time of one run of `program args`, its output thrown away; a failed run is an error.
fn time(case: &Case, program: &std::ffi::OsStr, args: &[&std::ffi::OsStr]) -> Result<f64, Failure> {
    let start = Instant::now();
    let output = Command::new(program)
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .output()
        .map_err(|e| Failure::Bench(format!("cannot start {program:?}: {e}")))?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if !output.status.success() {
        return Err(Failure::Bench(format!(
            "{case}: {program:?} {args:?} failed ({}): {}",
            output.status,
            String::from_utf8_lossy(&output.stderr).trim()
        )));
    }
    Ok(ms)
}

fn summary(mut ms: Vec<f64>) -> Timing {
    ms.sort_by(f64::total_cmp);
    Timing {
        best_ms: ms[0],
        median_ms: ms[ms.len() / 2],
    }
}

/// The query for a file of the user's: its first atom.
fn first_atom(file: &PathBuf) -> Result<String, Failure> {
    let text = proclaim_syntax::read_source(file).map_err(|error| Failure::Read {
        path: file.clone(),
        error,
    })?;
    let checked = proclaim_cdl::check_source(&text, proclaim_cdl::Language::from_path(file));
    match checked.theory {
        Some(theory) if theory.atom_count() > 0 => {
            Ok(theory.atom_name(proclaim_cdl::Atom(0)).to_string())
        }
        Some(_) => Err(Failure::Bench(format!(
            "{}: no atoms to ask",
            file.display()
        ))),
        None => Err(Failure::Bench(format!("{} does not check", file.display()))),
    }
}

fn print_table(comparisons: &[Comparison]) {
    println!(
        "{:<18} {:>19} {:>19} {:>19} {:>13} {:>13}",
        "case",
        "all ms best/median",
        "one ms best/median",
        "wc -w best/median",
        "all/one",
        "one/wc"
    );
    let pair = |t: Timing| format!("{:.0} / {:.0}", t.best_ms, t.median_ms);
    let ratio = |a: Timing, b: Timing| {
        format!(
            "{:.2} / {:.2}",
            a.best_ms / b.best_ms,
            a.median_ms / b.median_ms
        )
    };
    for c in comparisons {
        println!(
            "{:<18} {:>19} {:>19} {:>19} {:>13} {:>13}",
            c.case,
            pair(c.every_conclusion),
            pair(c.one_query),
            c.wc_words.map_or("-".to_string(), pair),
            ratio(c.every_conclusion, c.one_query),
            c.wc_words
                .map_or("-".to_string(), |wc| ratio(c.one_query, wc)),
        );
    }
}
