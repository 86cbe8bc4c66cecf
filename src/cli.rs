//! The command-line interface: every subcommand and option, as clap reads them.

use crate::network::Network;
use clap::{Args, Parser, Subcommand, ValueEnum};
use std::path::PathBuf;

/// Where `--monitor` serves its page when given no address. Loopback: a page that steps and
/// posts to the robot's whiteboard is not for the whole network unless asked
/// (`--monitor 0.0.0.0:7480`).
pub const MONITOR_ADDR: &str = "127.0.0.1:7480";

/// Where `proclaim edit` serves its page when given no address: its own port beside the
/// monitor's, so both can run at once.
pub const EDITOR_ADDR: &str = "127.0.0.1:7481";

#[derive(Parser)]
#[command(
    name = "proclaim",
    version,
    about = "Clausal defeasible logic for robot behaviour: prove, table, explain and check theories",
    after_help = "THEORY is a .dl or .dfl file, or an embedded theory: offside, microwave, kickoff, tweety, nixon, team-defeat, blocking, defeater, loops.\nExit status: 0 done (whatever the answers), 1 `check` found errors, 2 bad input or usage."
)]
pub struct Cli {
    #[command(subcommand)]
    pub command: CliCommand,
    /// More log lines on stderr: -v info, -vv debug, -vvv trace (RUST_LOG, when set, decides)
    #[arg(short, long, action = clap::ArgAction::Count, global = true)]
    pub verbose: u8,
    /// Log errors only
    #[arg(short, long, global = true, conflicts_with = "verbose")]
    pub quiet: bool,
    /// Log lines as text or as JSON objects, one a line
    #[arg(long, value_enum, default_value = "text", global = true)]
    pub log_format: LogFormat,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum LogFormat {
    Text,
    Json,
}

/// A model checker's language `proclaim verify --emit` writes the model in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EmitFormat {
    /// Promela, for SPIN: one `ltl` claim per property (`pan -N p<i>`)
    Promela,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum AlgArg {
    Mu,
    Pi,
    Beta,
    Alpha,
    Delta,
    All,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ProveFormat {
    Text,
    Spindle,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TableFormat {
    Text,
    Csv,
    Json,
    Markdown,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum TheoryFormat {
    Dl,
    Dfl,
}

#[derive(Subcommand)]
pub enum Sensor {
    /// The RoboCup SPL GameController receiver (UDP)
    Gamecontroller {
        #[arg(long, default_value_t = 3838)]
        port: u16,
        /// Address to listen on
        #[arg(long, default_value = "0.0.0.0")]
        bind: std::net::IpAddr,
        /// Our team number (default: the first team of each packet)
        #[arg(long)]
        team: Option<u8>,
        /// Our player number
        #[arg(long, default_value_t = 1)]
        player: u8,
        /// Send RGrt status packets back to the GameController once a second
        #[arg(long)]
        status: bool,
        /// Stop after this long (`30s`, `500ms`) and print the packet counts
        #[arg(long = "for", value_name = "DURATION")]
        duration: Option<String>,
        #[command(flatten)]
        network: Network,
    },
}

#[derive(Subcommand)]
pub enum CliCommand {
    /// Prove queries: one line per answer, `+beta offside` or `-beta offside`
    Prove(ProveArgs),
    /// Print the truth table of the declared outputs over the declared inputs
    Table {
        /// A .dl or .dfl file, or an embedded theory
        theory: String,
        #[arg(long, value_enum, default_value = "text")]
        format: TableFormat,
    },
    /// Compile a theory into decision functions of its inputs, printed as freestanding C99
    /// (`NAME.h` and `NAME.c` in the output folder): a reduced ordered decision diagram or a
    /// truth table, whichever is smaller; an answer undecided within the budget is refused. A
    /// behaviour (a folder) compiles to `behaviour.c`, its theories and a host harness `main.c`,
    /// or with `--target rust` to a Cargo project
    Compile(CompileArgs),
    /// Explain why a query is proved or not: supporters, attackers, loops
    Explain(ExplainArgs),
    /// Run a behaviour (a folder with a behaviour.toml, machines/NAME, or a built-in one:
    /// game_controller, microwave, shootout) on the in-process whiteboard, printing a live trace
    Run(RunArgs),
    /// Run a theory as an expert on a whiteboard (usually one held by another process:
    /// `--connect tcp/127.0.0.1:7447`), answering its outputs until stopped
    Expert(ExpertArgs),
    /// Post one message on a whiteboard: `proclaim post doorOpen true --connect …`
    Post {
        #[arg(value_name = "TYPE")]
        ty: String,
        value: String,
        /// The posting module's name
        #[arg(long, default_value = "terminal")]
        module: String,
        #[command(flatten)]
        network: Network,
    },
    /// Print every message of a whiteboard as it is posted (PATTERN: a type, or a glob like `gc*`)
    Watch {
        #[arg(default_value = "*")]
        pattern: String,
        /// Stop after this long (default: at Ctrl-C)
        #[arg(long = "for", value_name = "DURATION")]
        duration: Option<String>,
        #[command(flatten)]
        network: Network,
    },
    /// Time round trips to the process holding a whiteboard (`--connect ENDPOINT`): what the
    /// link costs every query, before any expert thinks
    Ping {
        /// How many round trips, one after another
        #[arg(long, default_value_t = 1000)]
        count: usize,
        #[command(flatten)]
        network: Network,
    },
    /// Replay recorded runs (`proclaim run --record`) on the behaviour as it is now, on the
    /// virtual clock, and compare its machines' states, postings, answers and variables with
    /// each recording round by round: exit 0 when all are the same, 1 naming the first
    /// difference of each that is not
    Test(TestArgs),
    /// Print a trace written by `proclaim run --trace` as the live trace was
    Replay(ReplayArgs),
    /// Draw a behaviour's module dependencies: for one module, the experts it queries above it
    /// (green), the modules hearing its postings below it (black), and a red `unknown` for a
    /// label nobody answers or a posting nobody hears
    Deps(DepsArgs),
    /// Turn liveness formulas (Gaia operators: `A.B`, `A|B`, `A||B`, `A*`, `A+`, `A~`, `[A]`) into a
    /// skeleton behaviour of native machines; `proclaim check DIR` then lists the open labels
    Liveness {
        /// One formula a line: `TestBehavior = (Play | NoPlay)+`
        file: PathBuf,
        /// The folder to write the behaviour into (created if missing)
        #[arg(short, long, value_name = "DIR")]
        output: PathBuf,
    },
    /// Write machines (T/A pairs, Qfsm .fsm) as native .machine files, one per machine
    Import {
        /// Qfsm .fsm files, or either file of a T/A pair (its partner is found beside it)
        #[arg(required = true)]
        files: Vec<String>,
        /// The folder to write into (created if missing)
        #[arg(short, long, value_name = "DIR")]
        output: PathBuf,
    },
    /// Write a native .machine file in another format (SCXML), nesting and histories kept; what the format cannot say is refused at its line (exit 1)
    Export {
        /// A native .machine file
        file: PathBuf,
        /// The format to write
        #[arg(long, value_enum, default_value = "scxml")]
        format: ExportFormat,
        /// Where to write (standard output if not given)
        #[arg(short, long, value_name = "FILE")]
        output: Option<PathBuf>,
    },
    /// Check theories, machines (native .machine, T/A pairs, Qfsm .fsm) and behaviours, and report every problem (exit 1 on errors)
    Check {
        /// Theories (.dl, .dfl), machines (.machine, .fsm, TName.txt / AName.txt) or behaviours
        #[arg(required = true, value_name = "FILE|BEHAVIOUR")]
        theories: Vec<String>,
        /// Print every problem as JSON (file, line, severity, message)
        #[arg(long)]
        json: bool,
        /// Warnings fail the check too (exit 1), as errors do: for CI, where a typo in a rule
        /// (a condition that never holds) must not pass as a warning nobody reads
        #[arg(long)]
        deny_warnings: bool,
    },
    /// Verify a behaviour under the round schedule: every run, the environment free, reasoners
    /// answering from their theories (exit 0 all hold, 1 some fails, 3 undecided, 2 bad input)
    Verify(VerifyArgs),
    /// Edit a behaviour's machines in the browser (at 127.0.0.1:7481 unless given): states,
    /// transitions, labels and activities, checked as you type; Save writes the .machine file
    /// with everything untouched kept as written, and never a machine with errors
    Edit {
        behaviour: String,
        /// Where the page listens (off loopback it needs the token printed with its address)
        #[arg(default_value = EDITOR_ADDR)]
        addr: String,
        /// The page draws the machines and changes nothing
        #[arg(long)]
        read_only: bool,
    },
    /// Draw a machine (native, T/A pair or Qfsm file) or a behaviour as a diagram: DOT, or SVG/PNG/PDF through Graphviz
    Draw {
        /// A machine file, or a behaviour (its machines in boxes, sub-machines linked)
        machine: String,
        /// Output file: .dot, .svg, .png or .pdf (default: DOT on stdout)
        #[arg(short, long)]
        output: Option<PathBuf>,
        /// Which machine, when the file holds several
        #[arg(long = "machine", value_name = "NAME")]
        name: Option<String>,
    },
    /// Write a standard benchmark theory: chain N, chains N, circle N, circles N, levels N,
    /// levels- N, teams N, tree N K, dag N K, mix M N K (the expected answer goes to stderr)
    Gen(GenArgs),
    /// Time the benchmark families end to end (parse + all conclusions for beta, then for pi),
    /// each in its own process so peak memory is its own
    Bench(BenchArgs),
    /// Run a sensor wrapper alone and print every change it posts, one line each
    Sensor {
        #[command(subcommand)]
        sensor: Sensor,
    },
    /// Play a game to robots: real GameController packets over UDP following a script
    GcSim {
        /// Game script (`TIME EVENT [key=value]` lines); default: a short game in 8 seconds
        #[arg(long)]
        script: Option<PathBuf>,
        /// Where to send the packets
        #[arg(long, default_value = "127.0.0.1:3838")]
        to: std::net::SocketAddr,
        /// Milliseconds between packets (the real GameController: 500)
        #[arg(long, default_value_t = 250)]
        interval: u64,
        /// Home team number (kicks off in the default game)
        #[arg(long, default_value_t = 18)]
        home: u8,
        /// Away team number
        #[arg(long, default_value_t = 5)]
        away: u8,
    },
    /// (internal) Run one benchmark file and print its timings as JSON
    #[command(hide = true)]
    BenchRun {
        file: PathBuf,
        /// Expected answers, `+beta a0`
        #[arg(long = "expect")]
        expect: Vec<String>,
    },
}

/// What `proclaim compile` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum CompileTarget {
    /// Freestanding C99: no heap, no library beyond `<stdint.h>`
    C,
    /// A Cargo project of a behaviour: its machines as Rust code, a host taking `run`'s options
    Rust,
}

/// What `proclaim prove` is told.
#[derive(Args, Clone, Debug)]
pub struct ProveArgs {
    /// A .dl or .dfl file, or an embedded theory (offside, microwave, tweety, …)
    pub theory: String,
    /// Literals (`a`, `~a`), clauses (`\/{a, b}`) or conjunctions (`/\{a, b}`); none:
    /// every conclusion (`+beta a` a line)
    pub queries: Vec<String>,
    #[arg(long, value_enum, default_value = "beta")]
    pub alg: AlgArg,
    /// Input values, `atom=true|false|unknown` (repeatable)
    #[arg(long = "set", value_name = "ATOM=VALUE")]
    pub set: Vec<String>,
    /// Print a JSON array instead of lines
    #[arg(long)]
    pub json: bool,
    /// `spindle`: SPINdle's conclusions, `+D`/`-D` (definite, μ) and `+d`/`-d` (defeasible,
    /// β) for every literal (or each query), negation written `-a`, to diff against SPINdle
    #[arg(long, value_enum, default_value = "text")]
    pub format: ProveFormat,
    /// Search steps allowed inside one attack cycle (default 10,000,000); an answer not
    /// decided within them prints as `?beta q  (undecided: …)` and the exit status is 3
    #[arg(long, value_name = "STEPS")]
    pub budget: Option<u64>,
}

/// What `proclaim explain` is told.
#[derive(Args, Clone, Debug)]
#[command(group(clap::ArgGroup::new("ran").args(["recording", "trace"])))]
pub struct ExplainArgs {
    /// A .dl or .dfl file, or an embedded theory; with `--recording` or `--trace`, the
    /// behaviour that ran
    pub theory: String,
    /// A literal: `offside` or `~offside`; with `--recording` or `--trace`, a label a machine
    /// asked, or a machine (which of its transitions fired in that round, and why the others
    /// did not)
    pub query: String,
    /// Explain the answer a run gave: a recording of it (`run --record`), replayed into the
    /// behaviour's theories up to the query, with the inputs the reasoner held then
    #[arg(long, value_name = "FILE.jsonl", requires = "round", conflicts_with_all = ["set", "alg"])]
    pub recording: Option<std::path::PathBuf>,
    /// The same from a run's trace (`run --trace`), whose postings are kept as text
    #[arg(long, value_name = "FILE.jsonl", requires = "round", conflicts_with_all = ["set", "alg"])]
    pub trace: Option<std::path::PathBuf>,
    /// With `--recording` or `--trace`: the round whose query of the label to explain
    #[arg(long, requires = "ran")]
    pub round: Option<u64>,
    /// With `--recording` or `--trace`: the machine that asked (default: the round's first to
    /// ask)
    #[arg(long, requires = "ran")]
    pub machine: Option<String>,
    #[arg(long, value_enum, default_value = "beta")]
    pub alg: AlgArg,
    /// Input values, `atom=true|false|unknown` (repeatable)
    #[arg(long = "set", value_name = "ATOM=VALUE")]
    pub set: Vec<String>,
    /// How many levels of antecedents to explain
    #[arg(long, default_value_t = 1)]
    pub depth: usize,
    /// Print the explanation as JSON (each node: its goal, rule, status and reasons)
    #[arg(long)]
    pub json: bool,
}

/// What `proclaim test` is told.
#[derive(Args, Clone, Debug)]
pub struct TestArgs {
    /// The behaviour the recordings are of
    pub behaviour: String,
    /// Recordings, or folders of them (every `.jsonl` inside)
    #[arg(required = true)]
    pub recordings: Vec<PathBuf>,
    /// Also say what the recordings exercised, and what they never did: states entered,
    /// transitions fired, theory rules applied, priorities that decided an answer
    #[arg(long)]
    pub coverage: bool,
    /// With `--coverage`: the coverage as JSON on standard output
    #[arg(long, requires = "coverage")]
    pub json: bool,
    /// With `--coverage`: draw the machines in the browser (at 127.0.0.1:7480 unless given),
    /// what the recordings never exercised dashed in red, until Ctrl-C
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = MONITOR_ADDR, requires = "coverage", conflicts_with = "json")]
    pub monitor: Option<String>,
    /// Accept a deliberate change: a recording that differs is recorded again on the
    /// behaviour as it is now (its outside replayed), and the rounds that changed are shown
    #[arg(long)]
    pub update: bool,
}

/// What `proclaim compile` is told.
#[derive(Args, Clone, Debug)]
pub struct CompileArgs {
    /// A .dl or .dfl file, an embedded theory, or a behaviour's folder
    pub theory: String,
    #[arg(long, value_enum, default_value = "c")]
    pub target: CompileTarget,
    /// The folder to write into (made when missing)
    #[arg(short = 'o', long = "out", value_name = "DIR")]
    pub out: PathBuf,
    /// Inputs may also be unknown (never posted), as a running behaviour's expert holds
    /// them: two decision variables an input (known, true); default: the truth table's rows
    #[arg(long)]
    pub unknown_inputs: bool,
    /// Search steps allowed inside one attack cycle (default 10,000,000)
    #[arg(long, value_name = "STEPS")]
    pub budget: Option<u64>,
    /// With `--target rust`: the program can also run on a whiteboard (`--monitor`, `--listen`,
    /// `--connect`). The project then depends on tokio and, by path, on the crates of the
    /// source tree this proclaim was built from; without it, on crates.io alone
    #[arg(long)]
    pub whiteboard: bool,
}

/// What `proclaim bench` is told.
#[derive(Args, Clone, Debug)]
pub struct BenchArgs {
    /// Cases as `family:size[:k[:m]]`, e.g. `chain:1000000 tree:12:3 clique:200`, or your
    /// own theory files (`.dl`, `.dfl`), timed the same way; default: the suite of
    /// docs/spec/benchmarks.md
    pub cases: Vec<String>,
    /// Smaller sizes (10^3 to 10^5) for a quick look
    #[arg(long)]
    pub quick: bool,
    /// Repeat each case and keep the fastest
    #[arg(long, default_value_t = 1)]
    pub repeat: u32,
    #[arg(long)]
    pub json: bool,
    /// Time every conclusion (`prove FILE --format spindle`) against one query and `wc -w`
    /// on the same `.dfl` file, as whole processes, best and median of the repeats
    #[arg(long)]
    pub all: bool,
    /// Time `proclaim check` on each kind of file (theory, machine, Qfsm, script) at the sizes
    /// given as cases (`1MB 10MB 100MB` unless given), as whole processes: reading is linear
    #[arg(long, conflicts_with = "all")]
    pub parse: bool,
}

/// What `proclaim expert` is told.
#[derive(Args, Clone, Debug)]
pub struct ExpertArgs {
    pub theory: String,
    /// Its name on the whiteboard (default: the theory's name{})
    #[arg(long)]
    pub name: Option<String>,
    /// Input atom → message type, one `atom = type` a line
    #[arg(long, value_name = "FILE")]
    pub mapping: Option<PathBuf>,
    /// Stop after this long (default: at Ctrl-C)
    #[arg(long = "for", value_name = "DURATION")]
    pub duration: Option<String>,
    #[command(flatten)]
    pub network: Network,
}

/// What `proclaim deps` is told.
#[derive(Args, Clone, Debug)]
pub struct DepsArgs {
    pub behaviour: String,
    /// The module at the centre (default: every module and link)
    #[arg(long)]
    pub module: Option<String>,
    /// Instead, write the smallest manifest that runs this machine with exactly the modules
    /// it needs (put it beside the behaviour's own, then `proclaim run FILE.toml`)
    #[arg(long, value_name = "MACHINE", conflicts_with = "module")]
    pub launch: Option<String>,
    /// Output file: .dot, .svg, .png or .pdf (default: DOT on stdout); with --launch, .toml
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// What `proclaim gen` is told.
#[derive(Args, Clone, Debug)]
pub struct GenArgs {
    pub family: String,
    #[arg(required = true, num_args = 1..=3)]
    pub sizes: Vec<u64>,
    #[arg(long, value_enum, default_value = "dl")]
    pub format: TheoryFormat,
    /// Write to this file instead of stdout
    #[arg(short, long)]
    pub output: Option<PathBuf>,
}

/// What `proclaim replay` is told.
#[derive(Args, Clone, Debug)]
pub struct ReplayArgs {
    pub trace: PathBuf,
    /// Replay at this many times the recorded pace (default: all at once)
    #[arg(long, conflicts_with = "monitor")]
    pub speed: Option<f64>,
    /// Show the trace in the browser with a time slider over every moment (at
    /// 127.0.0.1:7480 unless given), until Ctrl-C
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = MONITOR_ADDR)]
    pub monitor: Option<String>,
    /// The behaviour that made the trace, to draw its machines whole (without it, each
    /// machine is drawn from the states and transitions the trace shows)
    #[arg(long, value_name = "BEHAVIOUR", requires = "monitor")]
    pub behaviour: Option<String>,
}

/// What `proclaim verify` is told.
#[derive(Args, Clone, Debug)]
pub struct VerifyArgs {
    /// A behaviour: a folder, its manifest, machines/NAME or a built-in one
    pub behaviour: String,
    /// Check that no reachable state satisfies EXPR (`Machine.STATE`, `saw(Machine, name)`,
    /// variables, whiteboard values and answers with the label language's operators).
    /// Properties given here replace the manifest's [[property]] entries
    #[arg(long, value_name = "EXPR")]
    pub never: Vec<String>,
    /// Check that every reachable state satisfies EXPR
    #[arg(long, value_name = "EXPR")]
    pub always: Vec<String>,
    /// Check that some reachable state satisfies EXPR (and show the shortest way there)
    #[arg(long, value_name = "EXPR")]
    pub reachable: Vec<String>,
    /// Check that every run reaches a state where EXPR holds (time passing; a failure is a
    /// lasso: a way in and a loop)
    #[arg(long, value_name = "EXPR")]
    pub eventually: Vec<String>,
    /// Check that after every state where P holds, every run reaches one where Q holds
    #[arg(long, value_name = "'P ~> Q'")]
    pub leads_to: Vec<String>,
    /// Check that every run makes EXPR true again and again
    #[arg(long, value_name = "EXPR")]
    pub always_eventually: Vec<String>,
    /// Assume the environment makes EXPR true infinitely often (for the liveness
    /// properties checked)
    #[arg(long, value_name = "EXPR")]
    pub fair: Vec<String>,
    /// Stop after this many states (the outcome is then incomplete where undecided)
    #[arg(long, value_name = "N", default_value_t = 1_000_000)]
    pub max_states: usize,
    /// Stop before the search holds more than this much memory, e.g. 512M or 4G (the
    /// outcome is then incomplete where undecided; default: half the memory available)
    #[arg(long, value_name = "SIZE", value_parser = parse_size)]
    pub max_memory: Option<usize>,
    /// Switch an exact reduction off (to compare; the verdicts are the same)
    #[arg(long, value_enum, value_name = "REDUCTION")]
    pub without: Vec<ReductionName>,
    /// Which engine explores: explicit states, sets of states as decision diagrams, or
    /// the explicit one first and, where it does not decide soon, both at once (the first
    /// answer wins)
    #[arg(long, value_enum, value_name = "ENGINE", default_value = "auto")]
    pub engine: EngineName,
    /// Check every property with the clocks of different machines ordered (no run in which
    /// one machine's longer timeout is up before another's shorter one started no later),
    /// with the engine given; without it, only the verdicts a run decided are checked again
    /// ordered, by the explicit engine with a budget as large (the order costs states).
    /// --emit writes the ordered model either way
    #[arg(long)]
    pub clock_order: bool,
    /// Print the report as JSON
    #[arg(long)]
    pub json: bool,
    /// Write the first counterexample as an impersonator script for `run --script FILE --virtual-clock`
    #[arg(long, value_name = "FILE")]
    pub counterexample: Option<PathBuf>,
    /// Write the model checked, with the properties, for another model checker instead of
    /// checking it here
    #[arg(long, value_enum, value_name = "LANGUAGE")]
    pub emit: Option<EmitFormat>,
    /// Where --emit writes (default: stdout)
    #[arg(short, long, value_name = "FILE", requires = "emit")]
    pub output: Option<PathBuf>,
}

/// What `proclaim run` is told.
#[derive(Args, Clone, Debug)]
pub struct RunArgs {
    pub behaviour: String,
    /// Stop after this long (`30s`, `500ms`); default: when every machine that started is in
    /// a final state or, alone with its script (no page, person, sensor or network), at the
    /// first round after the script's last step that changes nothing with no time test to come
    #[arg(long = "for", value_name = "DURATION")]
    pub duration: Option<String>,
    /// Also write every event as JSON lines (read back by `proclaim replay`)
    #[arg(long, value_name = "FILE.jsonl")]
    pub trace: Option<PathBuf>,
    /// Record every whiteboard message (type, value, who posted it, when) as JSON lines, as a
    /// ROS bag does; `proclaim replay FILE` prints it again
    #[arg(long, value_name = "FILE.jsonl")]
    pub record: Option<PathBuf>,
    /// Answer labels from this impersonator script instead (experts answering the same
    /// labels are left out)
    #[arg(long, value_name = "FILE")]
    pub script: Option<PathBuf>,
    /// Reread a machine when its file changes (a file that does not parse changes nothing)
    #[arg(long)]
    pub watch: bool,
    /// Listen for a real GameController instead of playing the built-in simulator
    #[arg(long)]
    pub no_simulator: bool,
    /// Halt a machine whose label gets no answer in time, instead of counting it false
    #[arg(long)]
    pub halt_on_timeout: bool,
    /// One ring at a time at a prompt, showing every machine's state and the whiteboard;
    /// `ATOM=true` answers a label no expert answers
    #[arg(long, conflicts_with_all = ["watch", "duration"])]
    pub step: bool,
    /// Ask a person at this terminal for these atoms (`ready? [y/n]`), as the original
    /// `testcdl` did; experts answering them are left out, and machines wait for the answer
    #[arg(long, value_name = "ATOM", value_delimiter = ',', conflicts_with_all = ["step", "virtual_clock"])]
    pub ask: Vec<String>,
    /// Run on a virtual clock that jumps to the next timer whenever every machine waits: a
    /// scripted run takes no time and is the same every time (local board only; sensors that
    /// listen on real sockets hear little)
    #[arg(long, conflicts_with_all = ["watch", "step"])]
    pub virtual_clock: bool,
    /// Run even when `proclaim check` finds errors in the behaviour (a label no expert
    /// answers, a sub-machine that does not exist); they are printed as warnings
    #[arg(long)]
    pub force: bool,
    /// Show the run in the browser: each machine's diagram lit as it moves, the whiteboard,
    /// the answers, pause / step / resume and posting from the page (at 127.0.0.1:7480 unless
    /// given; port 0 takes any free port). The page stays open after the run until Ctrl-C. On
    /// an address other than loopback, pausing, stepping and posting need the token printed
    /// once in the page's address
    #[arg(long, value_name = "ADDR", num_args = 0..=1, default_missing_value = MONITOR_ADDR, conflicts_with_all = ["step", "virtual_clock"])]
    pub monitor: Option<String>,
    /// The monitor page shows the run and has no controls: nobody can pause, step or post
    #[arg(long, requires = "monitor")]
    pub monitor_read_only: bool,
    /// Start paused before the first round: the page's Step and Resume start it (a
    /// counterexample's script, say, walked through round by round, changed on the way)
    #[arg(long, requires = "monitor", conflicts_with = "monitor_read_only")]
    pub paused: bool,
    /// This robot's name in its team, in place of the manifest's `[team] member` (one behaviour
    /// run as several robots)
    #[arg(long, value_name = "NAME")]
    pub member: Option<String>,
    /// Write the whole run down (machines, whiteboard, theories, the script's place) at the
    /// start of the first round at or after ROUND where every theory and the script have
    /// handled what was posted to them, for `--resume`; a list takes several
    #[arg(long, value_name = "ROUND", value_delimiter = ',')]
    pub checkpoint_at: Vec<u64>,
    /// Write a checkpoint every N rounds, each named with the round it was taken at
    /// (`checkpoint.r200.json`)
    #[arg(long, value_name = "N", value_parser = clap::value_parser!(u64).range(1..))]
    pub checkpoint_every: Option<u64>,
    /// Where checkpoints go (default: checkpoint.json)
    #[arg(long, value_name = "FILE")]
    pub checkpoint_file: Option<PathBuf>,
    /// Take the run up where a checkpoint left it: the round it was taken at is played next,
    /// the trace and its times go on from there, and `--for` counts from the run's start. The
    /// behaviour's machines may have changed since, as long as they still fit (a state or a
    /// variable's type gone is refused, saying which)
    #[arg(long, value_name = "FILE", conflicts_with_all = ["record", "ask", "step", "watch"])]
    pub resume: Option<PathBuf>,
    /// Go back into a recording (`--record`) and branch off it: its run is replayed up to the
    /// start of round `--at` as `proclaim test` replays it, then goes on live from there (paused,
    /// under `--monitor`, for a person to post and run on); `--record` makes the branch a
    /// recording of its own, naming its parent and round, that `proclaim test` replays
    #[arg(long, value_name = "RECORDING", requires = "at", conflicts_with_all = ["script", "resume", "ask", "step", "watch", "checkpoint_at", "checkpoint_every"])]
    pub branch: Option<PathBuf>,
    /// The round of `--branch`'s recording the branch starts at (2 or later)
    #[arg(long, value_name = "ROUND", requires = "branch")]
    pub at: Option<u64>,
    #[command(flatten)]
    pub network: Network,
}

#[cfg(test)]
mod tests {
    /// Clap's own consistency checks (names, conflicts, defaults) for every subcommand.
    #[test]
    fn the_command_line_is_consistent() {
        use clap::CommandFactory;
        super::Cli::command().debug_assert();
    }

    /// `--max-memory` sizes as people write them, and what is no size.
    #[test]
    fn sizes_read_as_written() {
        use super::parse_size;
        assert_eq!(parse_size("1048576"), Ok(1 << 20));
        assert_eq!(parse_size("512K"), Ok(512 << 10));
        assert_eq!(parse_size("256M"), Ok(256 << 20));
        assert_eq!(parse_size("4G"), Ok(4 << 30));
        assert_eq!(parse_size("2GiB"), Ok(2 << 30));
        assert!(parse_size("12Q").unwrap_err().contains("unit"));
        assert!(parse_size("G").unwrap_err().contains("not a size"));
    }
}

/// The verifier's exact reductions, by the names `verify --without` takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum ReductionName {
    /// Free types stored in every state instead of chosen where a ringlet reads them
    ChosenWhenRead,
    /// Slots nothing reads stored too
    ConeOfInfluence,
    /// The search goes on after every property is decided
    StopWhenDecided,
}

/// A size in bytes as people write it: `1048576`, `512K`, `256M`, `4G` (powers of 1024).
pub fn parse_size(text: &str) -> Result<usize, String> {
    let text = text.trim();
    let (digits, unit) = match text.char_indices().find(|(_, c)| !c.is_ascii_digit()) {
        Some((at, _)) => text.split_at(at),
        None => (text, ""),
    };
    let scale: usize = match unit
        .trim()
        .to_ascii_uppercase()
        .trim_end_matches("IB")
        .trim_end_matches('B')
    {
        "" => 1,
        "K" => 1 << 10,
        "M" => 1 << 20,
        "G" => 1 << 30,
        "T" => 1 << 40,
        _ => return Err(format!("`{text}`: the unit is not one of K, M, G, T")),
    };
    let n: usize = digits
        .parse()
        .map_err(|_| format!("`{text}` is not a size (a whole number, then K, M or G)"))?;
    n.checked_mul(scale)
        .ok_or_else(|| format!("`{text}` is larger than this machine can count"))
}

/// The verifier's engines, by the names `verify --engine` takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum EngineName {
    Auto,
    Explicit,
    Symbolic,
}

/// The formats `proclaim export` writes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum ExportFormat {
    /// W3C SCXML, as `proclaim import` reads it back.
    Scxml,
}
