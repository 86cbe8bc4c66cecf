//! `proclaim bench --parse`: reading takes time in proportion to what is read. Each kind of file
//! a user brings (a theory, a native machine, a Qfsm machine, an impersonator script) is written
//! at each size asked for (1, 10 and 100 MB unless told) and checked by `proclaim check` as a whole
//! process, best wall time of the repeats; the table gives the rate and, from the second size
//! on, the time against the smaller size's scaled by the sizes' ratio (1.00 is linear).

use crate::failure::Failure;
use serde::Serialize;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

/// The sizes timed when none is given, in bytes.
const DEFAULT_SIZES: [u64; 3] = [1 << 20, 10 << 20, 100 << 20];

/// One kind of file at one size.
#[derive(Serialize, Debug)]
struct Timed {
    kind: &'static str,
    bytes: u64,
    check_ms: f64,
    mb_per_s: f64,
    /// This time over the previous size's, divided by the sizes' ratio: 1.0 is linear.
    against_linear: Option<f64>,
}

/// The file kinds, each with what writes it and the file `check` is given.
const KINDS: [(&str, Writer); 4] = [
    ("theory (.dl)", write_theory),
    ("machine (.machine)", write_machine),
    ("Qfsm machine (.fsm)", write_qfsm),
    ("script (in a behaviour)", write_script_behaviour),
];

/// Writes a file of about `bytes` bytes into `dir`; the path to check.
type Writer = fn(&Path, u64) -> std::io::Result<PathBuf>;

/// `1MB`, `512KB`, `100mb` or a number of bytes.
pub fn parse_size(text: &str) -> Result<u64, Failure> {
    let t = text.trim().to_ascii_uppercase();
    let (number, unit) = match t.find(|c: char| !c.is_ascii_digit()) {
        Some(i) => t.split_at(i),
        None => (t.as_str(), ""),
    };
    let n: u64 = number.parse().map_err(|_| size_error(text))?;
    let unit = match unit.trim() {
        "" | "B" => 1,
        "KB" | "K" => 1 << 10,
        "MB" | "M" => 1 << 20,
        "GB" | "G" => 1 << 30,
        _ => return Err(size_error(text)),
    };
    match n.checked_mul(unit) {
        Some(bytes) if bytes > 0 && bytes <= 4 << 30 => Ok(bytes),
        _ => Err(size_error(text)),
    }
}

fn size_error(text: &str) -> Failure {
    Failure::Argument(format!(
        "bench --parse `{text}`: a size is a whole number of bytes, KB, MB or GB, up to 4GB (1MB, 512KB)"
    ))
}

pub fn run(sizes: &[String], repeat: u32, json: bool) -> Result<ExitCode, Failure> {
    let mut sizes = sizes
        .iter()
        .map(|s| parse_size(s))
        .collect::<Result<Vec<_>, _>>()?;
    if sizes.is_empty() {
        sizes = DEFAULT_SIZES.to_vec();
    }
    sizes.sort_unstable();
    sizes.dedup();
    let dir = std::env::temp_dir().join(format!("proclaim-bench-parse-{}", std::process::id()));
    let outcome = timings(&dir, &sizes, repeat.max(1));
    let _ = std::fs::remove_dir_all(&dir);
    let timed = outcome?;
    if json {
        println!("{}", serde_json::to_string(&timed).unwrap_or_default());
    } else {
        print!("{}", table(&timed));
    }
    Ok(ExitCode::SUCCESS)
}

fn timings(dir: &Path, sizes: &[u64], repeat: u32) -> Result<Vec<Timed>, Failure> {
    let mut timed = Vec::new();
    for (kind, write) in KINDS {
        let mut previous: Option<(u64, f64)> = None;
        for &size in sizes {
            let case = dir.join(format!("{}-{size}", timed.len()));
            std::fs::create_dir_all(&case).map_err(|error| Failure::Write {
                path: case.clone(),
                error,
            })?;
            let file = write(&case, size).map_err(|error| Failure::Write {
                path: case.clone(),
                error,
            })?;
            let bytes = written_bytes(&file);
            let mut best = f64::INFINITY;
            for _ in 0..repeat {
                best = best.min(check(&file, kind)?);
            }
            let _ = std::fs::remove_dir_all(&case);
            let against_linear = previous.map(|(b, ms)| best / ms / (bytes as f64 / b as f64));
            previous = Some((bytes, best));
            timed.push(Timed {
                kind,
                bytes,
                check_ms: best,
                mb_per_s: bytes as f64 / (1 << 20) as f64 / (best / 1e3),
                against_linear,
            });
        }
    }
    Ok(timed)
}

/// The size of what `check` reads: the file, or every file of a behaviour's folder.
fn written_bytes(file: &Path) -> u64 {
    if file.is_dir() {
        std::fs::read_dir(file)
            .map(|entries| {
                entries
                    .filter_map(|e| e.ok()?.metadata().ok())
                    .map(|m| m.len())
                    .sum()
            })
            .unwrap_or(0)
    } else {
        std::fs::metadata(file).map_or(0, |m| m.len())
    }
}

/// `proclaim check FILE` as a child process: its wall time in milliseconds. A file it finds
/// errors in would time the wrong thing, so that fails the bench.
fn check(file: &Path, kind: &str) -> Result<f64, Failure> {
    let exe = std::env::current_exe()
        .map_err(|e| Failure::Bench(format!("cannot find this program: {e}")))?;
    let start = Instant::now();
    let output = Command::new(exe)
        .arg("check")
        .arg(file)
        .arg("-q")
        .stdin(Stdio::null())
        .output()
        .map_err(|e| Failure::Bench(format!("cannot start `check`: {e}")))?;
    let ms = start.elapsed().as_secs_f64() * 1e3;
    if !output.status.success() {
        let said = String::from_utf8_lossy(&output.stdout);
        return Err(Failure::Bench(format!(
            "{kind}: `check` found errors in the generated file ({}): {}",
            output.status,
            said.lines().take(5).collect::<Vec<_>>().join(" / ")
        )));
    }
    Ok(ms)
}

fn table(timed: &[Timed]) -> String {
    let mut out = format!(
        "{:<26} {:>11} {:>11} {:>10} {:>15}\n",
        "kind", "size", "check", "rate", "against linear"
    );
    for t in timed {
        let _ = writeln!(
            out,
            "{:<26} {:>8.2} MB {:>9.0} ms {:>5.1} MB/s {:>15}",
            t.kind,
            t.bytes as f64 / (1 << 20) as f64,
            t.check_ms,
            t.mb_per_s,
            t.against_linear
                .map_or(String::new(), |r| format!("{r:.2}")),
        );
    }
    out
}

/// Writes lines from `line(i)` until the file holds `bytes`.
fn write_lines(
    path: &Path,
    head: &str,
    bytes: u64,
    tail: &str,
    mut line: impl FnMut(u64) -> String,
) -> std::io::Result<()> {
    use std::io::Write;
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    out.write_all(head.as_bytes())?;
    let mut written = head.len() as u64 + tail.len() as u64;
    let mut i = 0;
    while written < bytes {
        let text = line(i);
        written += text.len() as u64;
        out.write_all(text.as_bytes())?;
        i += 1;
    }
    out.write_all(tail.as_bytes())?;
    out.flush()
}

/// A chain of defeasible rules, each tenth with an exception that a priority overrules.
fn write_theory(dir: &Path, bytes: u64) -> std::io::Result<PathBuf> {
    let path = dir.join("big.dl");
    write_lines(
        &path,
        "name{big}.\ninput{a0}.\ninput{quiet}.\n",
        bytes,
        "output{beta a1}.\n",
        |i| {
            let mut rule = format!("R{i}: a{i} => a{}.\n", i + 1);
            if i % 10 == 0 {
                let _ = write!(rule, "E{i}: quiet => ~a{}.\nR{i} > E{i}.\n", i + 1);
            }
            rule
        },
    )?;
    Ok(path)
}

fn machine_state(i: u64) -> String {
    format!(
        "state S{i} {{\n    entry {{\n        Motion: step {i}\n        count = count + {i};\n    }}\n    when ready && count > {i} -> S{}\n    when timeout(2s) -> S0\n}}\n",
        i + 1
    )
}

/// A ring of states, each posting, assigning and leaving on a label or a timeout.
fn write_machine(dir: &Path, bytes: u64) -> std::io::Result<PathBuf> {
    let path = dir.join("Big.machine");
    write_states(
        &path,
        bytes,
        "machine Big\ninitial S0\n",
        machine_state,
        |n| format!("state S{n} {{\n    when TRUE -> S0\n}}\n"),
    )?;
    Ok(path)
}

/// Writes states from `state(i)` until the file holds about `bytes`, then the last state
/// `last(n)` that the transitions of state `n - 1` lead to.
fn write_states(
    path: &Path,
    bytes: u64,
    head: &str,
    state: fn(u64) -> String,
    last: impl Fn(u64) -> String,
) -> std::io::Result<()> {
    let per = state(10_000).len() as u64;
    let n = (bytes.saturating_sub(head.len() as u64) / per).max(1);
    let mut text = String::with_capacity(bytes as usize + per as usize);
    text.push_str(head);
    for i in 0..n {
        text.push_str(&state(i));
    }
    text.push_str(&last(n));
    std::fs::write(path, text)
}

fn qfsm_state(i: u64) -> String {
    format!(
        "    <state code=\"{i}\" description=\"OnEntry {{&#xa;post(&quot;Motion&quot;, &quot;step {i}&quot;);&#xa;}}&#xa;OnExit {{ }}&#xa;{{ }}\" xpos=\"{i}\" ypos=\"0\" radius=\"40\">S{i}</state>\n    <transition type=\"2\"><from>{i}</from><to>{}</to><inputs default=\"0\" any=\"0\" invert=\"0\">ready &amp;&amp; !fallen</inputs><outputs></outputs></transition>\n",
        i + 1
    )
}

/// A Qfsm project of one machine, a ring of states as Qfsm writes them.
fn write_qfsm(dir: &Path, bytes: u64) -> std::io::Result<PathBuf> {
    let path = dir.join("Big.fsm");
    let head = "<?xml version='1.0'?>\n<qfsmproject version=\"0.53\" author=\"Qfsm\">\n  <machine name=\"Big\" type=\"3\" initialstate=\"0\">\n";
    write_states(&path, bytes, head, qfsm_state, |n| {
        format!("    <state code=\"{n}\" description=\"\">S{n}</state>\n    <transition type=\"2\"><from>{n}</from><to>0</to><inputs default=\"0\" any=\"0\" invert=\"0\">TRUE</inputs><outputs></outputs></transition>\n  </machine>\n</qfsmproject>\n")
    })?;
    Ok(path)
}

/// A behaviour whose impersonator script is the large file: a posting a line, truths and
/// numbers, every few milliseconds.
fn write_script_behaviour(dir: &Path, bytes: u64) -> std::io::Result<PathBuf> {
    std::fs::write(
        dir.join("behaviour.toml"),
        "[[machine]]\nfile = \"Keeper.machine\"\n\n[impersonator]\nscript = \"big.script\"\n\n[[module]]\nname = \"legs\"\nreads = [\"Motion\"]\n",
    )?;
    std::fs::write(
        dir.join("Keeper.machine"),
        "machine Keeper\nstate GUARD {\n    when ballNear && ballDistance < 20 -> DIVE\n}\nstate DIVE {\n    entry {\n        Motion: dive\n    }\n}\n",
    )?;
    write_lines(
        &dir.join("big.script"),
        "# generated by proclaim bench --parse\nballNear = false\n",
        bytes,
        "",
        |i| {
            if i % 2 == 0 {
                format!("at {}ms ballNear = {}\n", i * 5, i % 4 == 0)
            } else {
                format!("at {}ms ballDistance = {}\n", i * 5, i % 1000)
            }
        },
    )?;
    Ok(dir.to_path_buf())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_as_people_write_them() {
        assert_eq!(parse_size("1MB").ok(), Some(1 << 20));
        assert_eq!(parse_size("512kb").ok(), Some(512 << 10));
        assert_eq!(parse_size("2048").ok(), Some(2048));
        for bad in ["", "MB", "1TB", "0", "-1MB", "8GB", "99999999999999999999"] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn the_table_says_how_far_from_linear() {
        let timed = [
            Timed {
                kind: "theory (.dl)",
                bytes: 1 << 20,
                check_ms: 100.0,
                mb_per_s: 10.0,
                against_linear: None,
            },
            Timed {
                kind: "theory (.dl)",
                bytes: 10 << 20,
                check_ms: 1200.0,
                mb_per_s: 8.3,
                against_linear: Some(1.2),
            },
        ];
        let t = table(&timed);
        assert!(t.contains("10.00 MB"), "{t}");
        assert!(t.trim_end().ends_with("1.20"), "{t}");
    }
}
