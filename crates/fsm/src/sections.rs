//! Descriptions as the later gufsm editors (MiCASE, for clfsm) save them in Qfsm files: a line
//! `$Name$` opens each section (`$includes$`, `$variables$`, `$OnEntry$`, `$OnExit$`,
//! `$Internal$`, `$OnSuspend$`, `$OnResume$`, `$Layout.plist$`), but the first, which the
//! editors write `Name$` (`Version$`, or `OnEntry$` in the team's own files, whose sections then
//! hold braced blocks). The older descriptions are blocks in braces (`OnEntry { … }`), read by
//! [`crate::parse_gufsm_activities`].

/// The sections of a description, in order, each with its text; `None` when the description
/// has no `$Name$` line (the older form).
pub(crate) fn split_sections(text: &str) -> Option<Vec<(&str, &str)>> {
    let mut sections: Vec<(&str, &str)> = Vec::new();
    let mut open: Option<(&str, usize)> = None;
    let mut offset = 0;
    for (i, line) in text.split_inclusive('\n').enumerate() {
        if let Some(name) = section_name(line.trim(), i == 0) {
            if let Some((previous, start)) = open {
                sections.push((previous, &text[start..offset]));
            }
            open = Some((name, offset + line.len()));
        }
        offset += line.len();
    }
    let (last, start) = open?;
    sections.push((last, &text[start..]));
    Some(sections)
}

/// Whether `text` is in the sectioned form.
pub(crate) fn is_sectioned(text: &str) -> bool {
    text.lines()
        .enumerate()
        .any(|(i, line)| section_name(line.trim(), i == 0).is_some())
}

/// `$Name$`, or on the first line `Name$` too.
fn section_name(line: &str, first: bool) -> Option<&str> {
    let line = line.strip_suffix('$')?;
    let name = match line.strip_prefix('$') {
        Some(name) => name,
        None if first => line,
        None => return None,
    };
    let plain = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '.' || c == '_');
    plain.then_some(name)
}

/// What a section is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Section {
    /// Activity-language statements run on entry, exit, or while the state waits.
    Activity(usize),
    /// The machine's (or state's) variables, as declarations.
    Variables,
    /// C++ includes for the generated code: nothing proclaim runs; kept as a note.
    Includes,
    /// Run when a machine is suspended or resumed, which proclaim's machines do not do.
    SuspendResume,
    /// The editor's own: its version, and where it drew each state (`Layout.plist`).
    Editor,
    Unknown,
}

pub(crate) fn section(name: &str) -> Section {
    match name {
        "OnEntry" => Section::Activity(0),
        "OnExit" => Section::Activity(1),
        "Internal" => Section::Activity(2),
        "variables" => Section::Variables,
        "includes" => Section::Includes,
        "OnSuspend" | "OnResume" => Section::SuspendResume,
        "Version" | "Layout.plist" => Section::Editor,
        _ => Section::Unknown,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn check(text: &str, expect: Option<&[(&str, &str)]>) {
        assert_eq!(split_sections(text).as_deref(), expect, "{text:?}");
    }

    #[test]
    fn sections_are_split_at_their_marker_lines() {
        check(
            "Version$\n1.3\n$includes$\n#include <cmath>\n$OnEntry$\nx = 1;\n$Layout.plist$\n{\n \"x\" : 3\n}\n",
            Some(&[
                ("Version", "1.3\n"),
                ("includes", "#include <cmath>\n"),
                ("OnEntry", "x = 1;\n"),
                ("Layout.plist", "{\n \"x\" : 3\n}\n"),
            ]),
        );
    }

    #[test]
    fn the_first_section_may_lack_its_opening_dollar() {
        check(
            "OnEntry$\n{ light=0; }\n$OnExit$\n{ light=1; }\n$Internal$\n{}\n",
            Some(&[
                ("OnEntry", "{ light=0; }\n"),
                ("OnExit", "{ light=1; }\n"),
                ("Internal", "{}\n"),
            ]),
        );
        // Only the first line.
        check("x = 1;\nOnExit$\ny = 2;\n", None);
    }

    #[test]
    fn the_older_braced_form_has_no_sections() {
        check("OnEntry { post(\"Say\", \"hi\"); } OnExit { }", None);
        check("", None);
        // A `$` inside code is not a marker.
        check("OnEntry { cost = $5$; }", None);
    }

    #[test]
    fn sections_name_what_they_are_for() {
        assert_eq!(section("OnExit"), Section::Activity(1));
        assert_eq!(section("variables"), Section::Variables);
        assert_eq!(section("Layout.plist"), Section::Editor);
        assert_eq!(section("Transitions"), Section::Unknown);
    }
}
