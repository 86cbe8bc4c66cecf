//! The .dl and .dfl languages as the parser reads them: what parses, and the parser's own
//! diagnostics for what does not, one `check(input, expect)` per case. What the checker adds
//! (undefined labels, cycles, unused inputs) is tested in crates/cdl.

use proclaim_syntax::{parse, render, Item, Language};

/// Every diagnostic the parser gives `input`, in the short form `line:column: severity:
/// message`, one a line.
fn diagnostics(input: &str, language: Language) -> String {
    parse(input, language)
        .diagnostics
        .iter()
        .map(|d| d.short("t", input).trim_start_matches("t:").to_string() + "\n")
        .collect()
}

fn check(input: &str, expect: &str) {
    assert_eq!(
        diagnostics(input, Language::Dl),
        expect,
        "for input:\n{input}"
    );
}

fn check_dfl(input: &str, expect: &str) {
    assert_eq!(
        diagnostics(input, Language::Dfl),
        expect,
        "for input:\n{input}"
    );
}

#[test]
fn the_whole_language_parses() {
    let text = "% a comment\n/* a block\ncomment */\nname{demo}.\ninput{a}. input{b, c, d}.\n\
         ignore{a, ~b}. ignore 2 of {b, c, d}. assert{a, b}.\n\
         Off: a => Offside. R2: {a, b} -> x. {} => y. => z. w ~> ~z. R4: a, b => {Offside}.\n\
         f. ~g. \\/{h, ~i}.\nOff > R2 > R4.\n\
         output{beta Offside, \"is off-side\"}. output{mu x}. output{y}.\n";
    check(text, "");
    let parsed = parse(text, Language::Dl);
    let rules = parsed
        .items
        .iter()
        .filter(|item| matches!(item, Item::Rule(_)))
        .count();
    assert_eq!(rules, 6, "{:?}", parsed.items);
}

/// `//` starts a comment in `.dl` as it does in `.machine` files and the activity language (a
/// first line like `// Law 12, handling` was five errors); `\/` and `/\` still join. `.dfl`
/// keeps SPINdle's `#` alone, so what proclaim reads SPINdle reads too.
#[test]
fn double_slash_comments_in_dl() {
    check(
        "// Law 12, handling\na. // the ball\n\\/{a, b}. /\\ // not a conjunction\n",
        "3:13: error: missing `.` at the end of the statement\n",
    );
    check("// only a comment", "");
    check_dfl("// a\n", "1:1: error: unexpected characters\n");
}

#[test]
fn upper_case_atoms_and_keywords_as_atoms() {
    check("UDPsaysBlueKickOff. input. output => name.", "");
}

/// Each statement is parsed on its own, so one that does not parse hides none after it; a
/// broken rule's label is kept so that the checker does not call it undefined.
#[test]
fn every_problem_is_reported_at_once() {
    check(
        "a => b\nc => d.\nR1: a b => c.\nR2: x => y.\nR2: z => w.\nR1 > R9.\ne -> .\n",
        "2:1: error: unexpected `c`\n\
         3:7: error: unexpected `b`\n\
         7:6: error: unexpected `.`\n",
    );
    let source = "Sure: a => b $ Doubt: c => ~b.\nDoubt > Sure.\n";
    check(source, "1:14: error: unexpected characters\n");
    let parsed = parse(source, Language::Dl);
    let broken: Vec<&str> = parsed
        .broken_labels
        .iter()
        .map(|span| span.text(source))
        .collect();
    assert!(broken.contains(&"Doubt"), "{broken:?}");
}

#[test]
fn lexical_errors() {
    check(
        "a $$ b.\nc.\n\"open\n",
        "1:3: error: unexpected characters\n3:1: error: string has no closing `\"`\n",
    );
    check(
        "a. /* never closed",
        "1:4: error: comment has no closing `*/`\n",
    );
    check("2abc => d.", "1:1: error: unexpected characters\n");
    check("é => d.", "1:1: error: unexpected characters\n");
}

#[test]
fn missing_final_dot() {
    check(
        "a. b => c",
        "1:10: error: missing `.` at the end of the statement\n",
    );
}

#[test]
fn declarations_that_do_not_parse() {
    check(
        "output{gamma a}. a.",
        "1:8: error: unknown algorithm `gamma` in output\n",
    );
    check(
        "input{a}. ignore 2 off {a}.",
        "1:20: error: expected `of` after `ignore 2`, found `off`\n",
    );
}

#[test]
fn rendered_errors_show_the_line_and_a_caret() {
    let source = "a.\nb => c\n";
    let parsed = parse(source, Language::Dl);
    let text = render(&parsed.diagnostics, "demo.dl", source, false);
    assert!(
        text.contains("error: missing `.` at the end of the statement"),
        "{text}"
    );
    assert!(text.contains("demo.dl:2:7"), "{text}");
    assert!(text.contains("b => c"), "{text}");
    assert!(text.contains('^'), "{text}");
}

#[test]
fn a_flood_of_errors_is_capped() {
    let garbage = "$ ".repeat(100_000);
    let report = diagnostics(&garbage, Language::Dl);
    assert!(
        report.lines().count() <= 201,
        "{} lines",
        report.lines().count()
    );
}

#[test]
fn spindle_dfl() {
    check_dfl(
        "# a SPINdle theory\n>> bird\n>> -penguin, quaker\nr1: bird => fly\nr2: penguin -> -fly\nr3: p(x, y) ~> fly\nr2 > r1\n",
        "",
    );
    check_dfl(
        "r1: a =>\nr2 >\nr3: a b => c\n",
        "1:7: error: rule has no consequent\n\
         2:1: error: malformed superiority relation\n\
         3:7: error: expected `,` between literals\n",
    );
}

/// Lines and comments are found in the same pass as the tokens: a `#` ends a line's code wherever
/// it is, even inside an unclosed predicate-style atom, and a file may end without a newline.
#[test]
fn spindle_dfl_lines_and_comments() {
    let source = ">> a # >> b\r\nr1: a => c # r1 > r2\n  # only a comment\n\n>> d";
    check_dfl(source, "");
    let parsed = parse(source, Language::Dfl);
    assert_eq!(
        parsed.items.len(),
        3,
        "`>> b` and `r1 > r2` are in comments"
    );
    check_dfl(">> p(x # y)\n>> q\n", "1:4: error: unexpected characters\n");
    check_dfl(">> p(x\n>> q", "1:4: error: unexpected characters\n");
    check_dfl(">> q\n>> p(x", "2:4: error: unexpected characters\n");
    check_dfl(
        ">> a = b\nr1: é => a\n",
        "1:6: error: unexpected characters\n2:5: error: unexpected characters\n",
    );
    check_dfl("r1: a -> b\nr2: a ~> -b\nr3: => ~b\n>> !a\n", "");
}
