//! The manifest's `[team]` checked against the behaviour (`proclaim check`): its names must be
//! key chunks, every shared type must be posted by one of its modules, and a label that reads
//! the team (`robot2.ballDistance`, `team.min(ballDistance)`) needs a `[team]` sharing that
//! type. Each problem is placed at its line of the manifest or of the machine.

use crate::load::Behaviour;
use crate::manifest::{TeamEntry, MANIFEST};
use crate::modules::Module;
use proclaim_fsm::{team_words, Aggregate, FileDiagnostic, TeamWord};
use proclaim_syntax::{line_column, nearest};
use toml::Spanned;

pub(crate) fn findings(behaviour: &Behaviour, all: &[Module]) -> Vec<FileDiagnostic> {
    let mut out = Vec::new();
    if let Some(team) = &behaviour.manifest.team {
        out.extend(manifest_findings(behaviour, team, all));
    }
    let sized = behaviour
        .manifest
        .team
        .as_ref()
        .is_some_and(|t| t.size.is_some());
    let shared: Vec<&str> = behaviour
        .manifest
        .team
        .iter()
        .flat_map(|t| t.shared.iter().map(|s| s.get_ref().as_str()))
        .collect();
    for loaded in &behaviour.machines {
        let file = behaviour.files.show(&loaded.file);
        for t in &loaded.machine.transitions {
            for word in team_words(&t.label) {
                let has_team = behaviour.manifest.team.is_some();
                let problem = match word {
                    TeamWord::Quorum => quorum_problem("team.quorum", has_team, sized),
                    word => label_problem(&word, has_team, &shared).or_else(|| match word {
                        TeamWord::Aggregate {
                            function,
                            aggregate: Some(Aggregate::Majority),
                            ..
                        } => quorum_problem(function, has_team, sized),
                        _ => None,
                    }),
                };
                if let Some(problem) = problem {
                    out.push(problem.at(&file, t.line));
                }
            }
        }
    }
    out
}

/// Why a team entry's name cannot be what it names, if it cannot.
pub fn name_error(name: &str) -> Option<&'static str> {
    if name.is_empty() {
        Some("it is empty")
    } else if name.starts_with('@') {
        Some("it starts with `@`, which Zenoh keeps for its own keys")
    } else if name.contains(['/', '*', '$', '?', '#', '.']) {
        Some("it holds one of / * $ ? # . (it is a Zenoh key chunk, and what comes before the dot in `robot2.ballDistance`)")
    } else if name == proclaim_board::team::TEAM || name == proclaim_board::team::ME {
        Some("`team` and `me` are words of the label language")
    } else {
        None
    }
}

fn manifest_findings(
    behaviour: &Behaviour,
    team: &TeamEntry,
    all: &[Module],
) -> Vec<FileDiagnostic> {
    let file = behaviour.files.show(MANIFEST);
    let text = behaviour.files.read(MANIFEST).unwrap_or_default();
    let at = |spanned: &Spanned<String>, message: String| {
        let (line, column) = line_column(&text, spanned.span().start.min(text.len()));
        FileDiagnostic::error(&file, line, message).at_column(column, &text)
    };
    let mut out = Vec::new();
    for (what, spanned) in [("name", &team.name), ("member", &team.member)] {
        if let Some(why) = name_error(spanned.get_ref()) {
            out.push(at(
                spanned,
                format!(
                    "[team] {what} `{}` cannot name a team's {what}: {why}",
                    spanned.get_ref()
                ),
            ));
        }
    }
    if let Some(size) = &team.size {
        if !(1..=MOST_ROBOTS).contains(size.get_ref()) {
            let (line, column) = line_column(&text, size.span().start.min(text.len()));
            out.push(
                FileDiagnostic::error(
                    &file,
                    line,
                    format!(
                        "[team] size = {}: a team has from 1 to {MOST_ROBOTS} robots",
                        size.get_ref()
                    ),
                )
                .at_column(column, &text),
            );
        }
    }
    let posted: Vec<&str> = all
        .iter()
        .flat_map(|m| m.decl.posts.iter().map(String::as_str))
        .collect();
    for ty in &team.shared {
        let name = ty.get_ref();
        if name.contains('.') || name.starts_with('@') || name.contains(['/', '*', '$', '?', '#']) {
            out.push(at(ty, format!("[team] shared `{name}` cannot be a shared type's name: no `.`, `/ * $ ? #` or leading `@`")));
        } else if let Some(what) = TEAM_OWN.iter().find(|(n, _)| n == name).map(|(_, w)| w) {
            out.push(at(ty, format!("[team] shared `{name}`: `team.{name}` already says {what}; share the type under another name")));
        } else if !posted.contains(&name.as_str()) {
            let problem = at(
                ty,
                format!("[team] shares `{name}`, which no module of the behaviour posts"),
            );
            out.push(match nearest(posted.iter().copied(), name) {
                Some(near) => problem.with_hint(format!("did you mean `{near}`?")),
                None => problem.with_hint(
                    "share a type a machine posts, or name the module that posts it in [[module]]",
                ),
            });
        }
    }
    out
}

/// A label's problem, before it is placed.
struct Problem {
    message: String,
    hint: String,
}

impl Problem {
    fn at(self, file: &str, line: usize) -> FileDiagnostic {
        FileDiagnostic::error(file, line, self.message).with_hint(self.hint)
    }
}

/// The team's own words, which a shared type's `team.<type>` would collide with, and what
/// each says.
const TEAM_OWN: [(&str, &str); 2] = [
    ("quorum", "whether the robot hears a majority of its team"),
    ("size", "how many robots the team has"),
];

/// The most robots a team's `size` may say.
const MOST_ROBOTS: i64 = 1000;

/// `word` (`team.quorum`, `team.majority`) counts against the team's size, which [team] must
/// say.
fn quorum_problem(word: &str, has_team: bool, sized: bool) -> Option<Problem> {
    if !has_team {
        return Some(Problem {
            message: format!("label reads the team (`{word}`), but the manifest has no [team]"),
            hint: "add [team] with name, member, shared and size to behaviour.toml".into(),
        });
    }
    (!sized).then(|| Problem {
        message: format!(
            "label reads `{word}`, but [team] does not say how many robots the team has"
        ),
        hint: "add size = N to [team] in behaviour.toml: a majority is more than half of N".into(),
    })
}

fn label_problem(word: &TeamWord<'_>, has_team: bool, shared: &[&str]) -> Option<Problem> {
    let (shown, ty) = match word {
        TeamWord::Aggregate {
            function,
            aggregate: None,
            ..
        } => {
            let known: Vec<&str> = Aggregate::ALL.iter().map(|a| a.name()).collect();
            return Some(Problem {
                message: format!("`{function}` is no team aggregate"),
                hint: format!("the team's aggregates are team.{}", known.join(", team.")),
            });
        }
        TeamWord::Aggregate {
            function, ty: None, ..
        } => {
            return Some(Problem {
                message: format!("`{function}(…)` takes one shared type's name"),
                hint: format!("write `{function}(ballDistance)`"),
            })
        }
        TeamWord::Aggregate {
            function,
            ty: Some(ty),
            ..
        } => (format!("{function}({ty})"), *ty),
        TeamWord::Member { member, ty } => (format!("{member}.{ty}"), *ty),
        TeamWord::Quorum => return quorum_problem("team.quorum", has_team, true),
    };
    if !has_team {
        return Some(Problem {
            message: format!("label reads the team (`{shown}`), but the manifest has no [team]"),
            hint: format!(
                "add [team] with name = \"…\", member = \"…\" and shared = [\"{ty}\"] to behaviour.toml"
            ),
        });
    }
    if !shared.contains(&ty) {
        return Some(Problem {
            message: format!("label reads `{shown}`, but `{ty}` is not shared with the team"),
            hint: format!("add \"{ty}\" to [team] shared in behaviour.toml"),
        });
    }
    None
}
