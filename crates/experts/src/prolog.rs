//! The Prolog expert: a knowledge base (`.pl`) whose labels SWI-Prolog proves on the current
//! whiteboard inputs. It is a [`ProgramExpert`] running `swipl` with a driver shipped inside
//! proclaim (`prolog_driver.pl`) that speaks the program protocol: each input is the fact
//! `value(Type, Value)`, a label `L` holds when the goal `L` succeeds within the time limit,
//! and every error (syntax at load, an exception, no answer in time) is a located warning and a
//! false answer. SWI-Prolog runs as a process, not embedded: the reasons and the figures are in
//! the note.

use crate::program::ProgramExpert;
use crate::protocol::{read_reply, Located, Request, Said};
use std::io::{BufRead, Write};
use std::path::PathBuf;
use std::process::{Command, Stdio};
use std::time::Duration;

/// The driver, loaded by `swipl` from its command line.
pub const DRIVER: &str = include_str!("prolog_driver.pl");

/// The program that runs Prolog: `swipl`, or `PROCLAIM_SWIPL` when set.
pub fn swipl_program() -> String {
    std::env::var("PROCLAIM_SWIPL").unwrap_or_else(|_| "swipl".to_string())
}

/// Where SWI-Prolog is, when it is installed.
pub fn find_swipl() -> Option<PathBuf> {
    find_program(&swipl_program())
}

/// A program as a command names it: a path, or a name looked up on `PATH`.
pub fn find_program(program: &str) -> Option<PathBuf> {
    let path = std::path::Path::new(program);
    if path.components().count() > 1 {
        return path.is_file().then(|| path.to_path_buf());
    }
    std::env::split_paths(&std::env::var_os("PATH")?)
        .map(|dir| dir.join(program))
        .find(|p| p.is_file())
}

/// The command line that runs the driver: it reads its own text from the last argument, so
/// no file is written anywhere.
fn driver_command() -> Vec<String> {
    [
        swipl_program().as_str(),
        "-q",
        "--no-tty",
        "-f",
        "none",
        // A runaway recursion fails in a fraction of a second instead of eating memory.
        "--stack-limit=64m",
        "-g",
        "current_prolog_flag(argv, Argv), last(Argv, Text), open_string(Text, S), \
         load_files(proclaim_driver, [stream(S)]), proclaim_driver:main",
        "-t",
        "halt",
        "--",
        DRIVER,
    ]
    .map(str::to_string)
    .to_vec()
}

/// A knowledge base: its text, the name its warnings give it, how long a proof may take.
#[derive(Clone, Debug)]
pub struct KnowledgeBase {
    /// The file as shown to a person (warnings say `file:line`).
    pub file: String,
    pub text: String,
    pub time_limit: Duration,
}

impl KnowledgeBase {
    /// The default time limit of a proof.
    pub const TIME_LIMIT: Duration = Duration::from_millis(200);

    fn load(&self) -> Request {
        Request::Load {
            file: self.file.clone(),
            text: self.text.clone(),
            time_limit: self.time_limit.as_secs_f64(),
        }
    }
}

/// The expert `name` answering `answers` from `kb`, told of `inputs`.
pub fn prolog_expert(
    name: impl Into<String>,
    kb: &KnowledgeBase,
    answers: Vec<String>,
    inputs: Vec<String>,
) -> ProgramExpert {
    ProgramExpert::new(name, driver_command(), answers, inputs)
        .with_greeting(vec![kb.load()])
        .echoing_ids()
}

/// Why a knowledge base could not be checked.
#[derive(Debug)]
pub enum PrologError {
    /// No `swipl` on `PATH` (or at `PROCLAIM_SWIPL`).
    NotInstalled { program: String },
    Spawn {
        program: String,
        source: std::io::Error,
    },
    /// The driver stopped or took too long before saying it had loaded the knowledge base.
    NoReady { why: String },
}

impl std::fmt::Display for PrologError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            PrologError::NotInstalled { program } => write!(
                f,
                "SWI-Prolog is not installed (`{program}` is not on PATH), so this Prolog expert cannot answer; install it with `apt-get install swi-prolog-nox`"
            ),
            PrologError::Spawn { program, source } => write!(f, "cannot start `{program}`: {source}"),
            PrologError::NoReady { why } => write!(f, "SWI-Prolog did not load the knowledge base: {why}"),
        }
    }
}

impl std::error::Error for PrologError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            PrologError::Spawn { source, .. } => Some(source),
            _ => None,
        }
    }
}

/// How long checking a knowledge base may take (a directive that never ends).
const CHECK_LIMIT: Duration = Duration::from_secs(20);

/// Loads `kb` in SWI-Prolog as the expert would, and returns what loading it warned of, each
/// placed in its file: syntax errors, errors of directives, singleton variables, and each of
/// `answers` that the knowledge base does not define.
pub fn check_knowledge_base(
    kb: &KnowledgeBase,
    answers: &[String],
) -> Result<Vec<Located>, PrologError> {
    let program = swipl_program();
    if find_swipl().is_none() {
        return Err(PrologError::NotInstalled { program });
    }
    let command = driver_command();
    let mut child = Command::new(&command[0])
        .args(&command[1..])
        .stdin(Stdio::piped())
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .map_err(|source| PrologError::Spawn {
            program: program.clone(),
            source,
        })?;
    let hello = Request::Hello {
        expert: "check".into(),
        answers: answers.to_vec(),
        inputs: Vec::new(),
    };
    let mut stdin = child.stdin.take();
    let stdout = child.stdout.take();
    // Written from a thread: a large knowledge base fills the pipe before the driver reads it.
    let lines = format!("{}{}", hello.line(), kb.load().line());
    let writer = std::thread::spawn(move || {
        if let Some(stdin) = stdin.as_mut() {
            let _ = stdin.write_all(lines.as_bytes());
        }
        // Dropping stdin ends the driver once it has loaded.
    });
    let (tx, rx) = std::sync::mpsc::channel();
    std::thread::spawn(move || {
        let Some(stdout) = stdout else { return };
        for line in std::io::BufReader::new(stdout).lines() {
            let Ok(line) = line else { break };
            if tx.send(read_reply(&line)).is_err() {
                break;
            }
        }
    });
    let deadline = std::time::Instant::now() + CHECK_LIMIT;
    let mut warnings = Vec::new();
    let outcome = loop {
        let left = deadline.saturating_duration_since(std::time::Instant::now());
        match rx.recv_timeout(left) {
            Ok(Said::Warning(w)) => warnings.push(w),
            Ok(Said::Ready) => break Ok(warnings),
            Ok(_) => {}
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                break Err(PrologError::NoReady {
                    why: format!("no answer within {} s", CHECK_LIMIT.as_secs()),
                })
            }
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => {
                break Err(PrologError::NoReady {
                    why: "it stopped before it had loaded it".into(),
                })
            }
        }
    };
    let _ = child.kill();
    let _ = child.wait();
    let _ = writer.join();
    outcome
}
