//! Loading a behaviour: its manifest, then every file it names, each checked. Every problem of
//! every file is reported, with file and line; a behaviour with errors is not started.

use crate::files::Files;
use crate::manifest::{
    parse_dictionary, parse_manifest, Manifest, ModuleEntry, Simulator, TheoryEntry, MANIFEST,
};
use proclaim_cdl::{check_source, Language};
use proclaim_experts::{parse_duration, parse_mapping, parse_script};
use proclaim_fsm::{
    import_qfsm, import_scxml, import_ta, machine_format, parse_machine, Imported, Machine,
    MachineFormat, Severity,
};
use proclaim_gcsim::parse_game;
use proclaim_runner::Loader;
use proclaim_syntax::FileDiagnostic;
use rustc_hash::FxHashMap;
use std::sync::Arc;
use std::time::Duration;

pub use crate::loaded::{Behaviour, LoadedMachine, LoadedSensor, LoadedTheory};

/// Loads the behaviour `name` from `files`. `Err` holds every error (and warning), each with its
/// file and line.
pub fn load(name: &str, files: Arc<dyn Files>) -> Result<Behaviour, Vec<FileDiagnostic>> {
    load_manifest(name, files, MANIFEST)
}

/// Loads a behaviour whose manifest has another name than `behaviour.toml` (one written by
/// `proclaim deps --launch`, beside the original).
pub fn load_manifest(
    name: &str,
    files: Arc<dyn Files>,
    manifest_name: &str,
) -> Result<Behaviour, Vec<FileDiagnostic>> {
    let mut problems = Problems::default();
    let manifest_text = files.read(manifest_name).map_err(|e| vec![e])?;
    let manifest_file = files.show(manifest_name);
    let manifest = parse_manifest(&manifest_file, &manifest_text).map_err(|e| vec![e])?;
    let Timing {
        ring_period,
        answer_timeout,
        run_for,
    } = timing(&manifest, &manifest_file, &mut problems);
    if manifest.machines.is_empty() {
        problems.error(FileDiagnostic::in_file(
            &manifest_file,
            "the behaviour names no [[machine]]",
        ));
    }

    let machines = load_machines(&files, &manifest, &manifest_file, &mut problems);
    let theories: Vec<LoadedTheory> = manifest
        .theories
        .iter()
        .filter_map(|entry| load_theory(files.as_ref(), entry, &mut problems))
        .collect();

    let programs = crate::programs::load_programs(
        files.as_ref(),
        &manifest,
        &manifest_file,
        &mut problems.found,
    );

    let sensors = load_sensors(files.as_ref(), &manifest, &mut problems);

    let script = match &manifest.impersonator {
        None => None,
        Some(i) => read_lines(files.as_ref(), &i.script, parse_script, &mut problems),
    };

    let outside = outside_modules(files.as_ref(), &manifest, &mut problems);
    let suppress = crate::subsumption::check(
        &manifest,
        &manifest_file,
        &manifest_text,
        &machines,
        &mut problems.found,
    );

    let ranges = crate::ranges::check(
        &manifest,
        &manifest_file,
        &manifest_text,
        &machines.iter().map(|m| &m.machine).collect::<Vec<_>>(),
        &mut problems.found,
    );

    let errors = problems.found.iter().any(FileDiagnostic::is_error);
    let mut all = problems.found;
    all.extend(problems.theory_warnings);
    if errors {
        return Err(all);
    }
    let warnings = all;
    Ok(Behaviour {
        name: name.to_string(),
        manifest,
        machines,
        theories,
        sensors,
        programs,
        script,
        ring_period,
        answer_timeout,
        run_for,
        outside,
        suppress,
        ranges,
        warnings,
        files,
    })
}

/// The manifest's sensors, each with the game script its simulator plays, when it has one.
fn load_sensors(
    files: &dyn Files,
    manifest: &Manifest,
    problems: &mut Problems,
) -> Vec<LoadedSensor> {
    let mut sensors = Vec::new();
    for entry in &manifest.sensors {
        let game = match &entry.simulator {
            Some(Simulator::Script(file)) => read_lines(files, file, parse_game, problems),
            _ => None,
        };
        sensors.push(LoadedSensor {
            entry: entry.clone(),
            game,
        });
    }
    sensors
}

/// The manifest's times, each a duration or an error saying what to write.
struct Timing {
    ring_period: Duration,
    answer_timeout: Duration,
    run_for: Option<Duration>,
}

fn timing(manifest: &Manifest, manifest_file: &str, problems: &mut Problems) -> Timing {
    let duration = |field: &str, value: &Option<String>, problems: &mut Problems| {
        let text = value.as_ref()?;
        let parsed = parse_duration(text).filter(|d| !d.is_zero());
        if parsed.is_none() {
            problems.error(FileDiagnostic::in_file(
                manifest_file,
                format!("{field} = \"{text}\" is not a duration (write 100ms, 2s or 1.5s)"),
            ));
        }
        parsed
    };
    let ring_period = duration("ring_period", &manifest.ring_period, problems)
        .unwrap_or(Duration::from_millis(100));
    let answer_timeout = duration("answer_timeout", &manifest.answer_timeout, problems)
        .unwrap_or(Duration::from_secs(1));
    let run_for = duration("run_for", &manifest.run_for, problems);
    Timing {
        ring_period,
        answer_timeout,
        run_for,
    }
}

/// The modules outside the behaviour: the manifest's `[[module]]`s and its dictionary's.
fn outside_modules(
    files: &dyn Files,
    manifest: &Manifest,
    problems: &mut Problems,
) -> Vec<ModuleEntry> {
    let mut outside = manifest.modules.clone();
    if let Some(file) = &manifest.dictionary {
        match files
            .read(file)
            .and_then(|t| parse_dictionary(&files.show(file), &t))
        {
            Ok(d) => outside.extend(d.modules),
            Err(e) => problems.error(e),
        }
    }
    outside
}

/// The machines the manifest names, each from its file; two of one name, or none that
/// starts, are errors.
fn load_machines(
    files: &Arc<dyn Files>,
    manifest: &Manifest,
    manifest_file: &str,
    problems: &mut Problems,
) -> Vec<LoadedMachine> {
    let mut machines: Vec<LoadedMachine> = Vec::new();
    let mut entries = Vec::new();
    for entry in &manifest.machines {
        let loader = machine_loader(files.clone(), entry.file.clone(), entry.name.clone());
        let imported = read_machines(files.as_ref(), &entry.file);
        problems.file(&imported);
        match pick(imported, &entry.file, entry.name.as_deref(), files.as_ref()) {
            Ok(Some(machine)) => {
                if let Some(other) = machines.iter().find(|m| m.machine.name == machine.name) {
                    problems.error(FileDiagnostic::in_file(
                        manifest_file,
                        format!(
                            "two machines are named `{}` ({} and {}); a machine's name is its control message type, so names must differ",
                            machine.name, other.file, entry.file
                        ),
                    ));
                }
                machines.push(LoadedMachine {
                    machine,
                    file: entry.file.clone(),
                    start: entry.start,
                    priority: entry.priority,
                    loader,
                });
                entries.push(entry);
            }
            Ok(None) => {}
            Err(message) => problems.error(message),
        }
    }
    if !manifest.machines.is_empty() && manifest.machines.iter().all(|m| !m.start) {
        problems.error(FileDiagnostic::in_file(
            manifest_file,
            "every machine has `start = false`; nothing would run",
        ));
    }
    crate::linking::link_loaded(
        &mut machines,
        &entries,
        &|file| files.show(file),
        manifest_file,
        &mut problems.found,
    );
    machines
}

/// One `[[theory]]`: checked (its warnings kept), its mapping read, its expert named.
fn load_theory(
    files: &dyn Files,
    entry: &TheoryEntry,
    problems: &mut Problems,
) -> Option<LoadedTheory> {
    let Ok(text) = files.read(&entry.file).map_err(|e| problems.error(e)) else {
        return None;
    };
    let shown = files.show(&entry.file);
    let checked = check_source(
        &text,
        Language::from_path(std::path::Path::new(&entry.file)),
    );
    let located = checked.diagnostics.iter().map(|d| d.in_file(&shown, &text));
    let Some(theory) = checked.theory else {
        problems.found.extend(located);
        return None;
    };
    problems.theory_warnings.extend(located);
    let mapping = match &entry.mapping {
        None => FxHashMap::default(),
        Some(file) => read_lines(files, file, parse_mapping, problems)?,
    };
    let name = entry
        .name
        .clone()
        .or_else(|| theory.name().map(str::to_string))
        .unwrap_or_else(|| stem(&entry.file));
    Some(LoadedTheory {
        name,
        file: entry.file.clone(),
        theory,
        mapping,
        limits: proclaim_cdl::SearchLimits {
            steps: entry
                .budget
                .unwrap_or(proclaim_cdl::SearchLimits::default().steps),
            ..proclaim_cdl::SearchLimits::default()
        },
    })
}

/// A file in one of the small line formats (scripts, game scripts, mappings), or `None` with
/// its problems, each with file and line.
fn read_lines<T>(
    files: &dyn Files,
    file: &str,
    parse: fn(&str) -> Result<T, proclaim_syntax::LineErrors>,
    problems: &mut Problems,
) -> Option<T> {
    match files.read(file).map(|text| parse(&text)) {
        Ok(Ok(parsed)) => Some(parsed),
        Ok(Err(errors)) => {
            for e in errors {
                problems.error(FileDiagnostic::error(&files.show(file), e.line, e.message));
            }
            None
        }
        Err(e) => {
            problems.error(e);
            None
        }
    }
}

/// What loading found, in the order found; a theory's warnings come last.
#[derive(Default)]
struct Problems {
    found: Vec<FileDiagnostic>,
    theory_warnings: Vec<FileDiagnostic>,
}

impl Problems {
    fn error(&mut self, diagnostic: FileDiagnostic) {
        self.found.push(diagnostic);
    }

    fn file(&mut self, imported: &Imported) {
        self.found.extend(imported.diagnostics.iter().cloned());
    }
}

fn stem(file: &str) -> String {
    std::path::Path::new(file)
        .file_stem()
        .and_then(|s| s.to_str())
        .unwrap_or(file)
        .to_string()
}

/// The machines of one file: native `.machine`, Qfsm `.fsm`, SCXML `.scxml`, or either file of
/// a T/A pair (`TName.txt` / `AName.txt`, its partner beside it).
pub fn read_machines(files: &dyn Files, relative: &str) -> Imported {
    let shown = files.show(relative);
    let unreadable = |diagnostic: FileDiagnostic| Imported {
        machines: Vec::new(),
        diagnostics: vec![diagnostic],
    };
    let read = |file: &str| files.read(file);
    match machine_format(std::path::Path::new(relative)) {
        Some(MachineFormat::Native) => match read(relative) {
            Ok(text) => parse_machine(&shown, &text),
            Err(e) => unreadable(e),
        },
        Some(MachineFormat::Qfsm { stem }) => match read(relative) {
            Ok(text) => import_qfsm(&shown, &text, &stem),
            Err(e) => unreadable(e),
        },
        Some(MachineFormat::Scxml { stem }) => match read(relative) {
            Ok(text) => import_scxml(&shown, &text, &stem).imported,
            Err(e) => unreadable(e),
        },
        Some(MachineFormat::TablePair { t, a, name }) => {
            let (t, a) = (t.to_string_lossy(), a.to_string_lossy());
            match (read(&t), read(&a)) {
                (Ok(t_text), Ok(a_text)) => {
                    import_ta(&name, &files.show(&t), &t_text, &files.show(&a), &a_text)
                }
                (Err(e), _) | (_, Err(e)) => unreadable(e),
            }
        }
        None => unreadable(FileDiagnostic::in_file(&shown, format!(
            "`{relative}` is not a machine file (a native .machine file, a Qfsm .fsm file, an SCXML .scxml document, or TName.txt / AName.txt of a T/A pair)"
        ))),
    }
}

/// The one machine an entry names, or why not (`None` when the file's own diagnostics said so).
fn pick(
    imported: Imported,
    file: &str,
    name: Option<&str>,
    files: &dyn Files,
) -> Result<Option<Machine>, FileDiagnostic> {
    let names: Vec<String> = imported.machines.iter().map(|m| m.name.clone()).collect();
    let has_errors = imported.has_errors();
    let mut machines = imported.machines;
    match (name, machines.len()) {
        (_, 0) => Ok(None),
        (None, 1) => Ok((!has_errors).then(|| machines.remove(0))),
        (None, _) => Err(FileDiagnostic::in_file(
            &files.show(file),
            format!(
                "the file holds several machines ({}); say which with `name = \"…\"`",
                names.join(", ")
            ),
        )),
        (Some(n), _) => match machines.iter().position(|m| m.name == n) {
            Some(i) => Ok((!has_errors).then(|| machines.remove(i))),
            None => Err(FileDiagnostic::in_file(
                &files.show(file),
                format!("the file has no machine `{n}`; it has {}", names.join(", ")),
            )),
        },
    }
}

/// Reads the machine of a manifest entry again; the file's errors come back each at its place.
fn machine_loader(files: Arc<dyn Files>, file: String, name: Option<String>) -> Loader {
    Arc::new(move || {
        let imported = read_machines(files.as_ref(), &file);
        let errors: Vec<FileDiagnostic> = imported
            .diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .cloned()
            .collect();
        if !errors.is_empty() {
            return Err(errors);
        }
        match pick(imported, &file, name.as_deref(), files.as_ref()) {
            Ok(Some(m)) => Ok(m),
            Ok(None) => Err(vec![FileDiagnostic::in_file(
                &files.show(&file),
                "no machine could be read",
            )]),
            Err(e) => Err(vec![e]),
        }
    })
}
