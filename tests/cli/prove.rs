//! `prove`: answers as lines, JSON and SPINdle's form; inputs set; undecided answers; bad queries.

use super::{check, stderr, stdout, temp_file};
use crate::proclaim;

#[test]
fn prove_prints_one_line_per_answer() {
    check(
        &["prove", "tweety", "fly", "~fly"],
        0,
        "+beta fly\n-beta ~fly\n",
    );
    check(
        &[
            "prove",
            "tweety",
            "fly",
            "--alg",
            "all",
            "--set",
            "penguin=true",
        ],
        0,
        "-mu fly\n-pi fly\n-beta fly\n-alpha fly\n-delta fly\n",
    );
    check(&["prove", "blocking", "e", "--alg", "pi"], 0, "-pi e\n");
    check(
        &[
            "prove",
            "microwave",
            "\\/{cook, light}",
            "--set",
            "doorOpen=true",
        ],
        0,
        "+beta \\/{cook, light}\n",
    );
}

#[test]
fn prove_json() {
    let o = proclaim(&[
        "prove",
        "offside",
        "offside",
        "--set",
        "fewerThanTwoOpponentsBetween=true",
        "--json",
    ]);
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(
        v,
        serde_json::json!([{"algorithm": "beta", "query": "offside", "proved": true}])
    );
}

#[test]
fn bad_input_exits_2_and_says_why() {
    // An atom the theory never mentions is not provable (as SPINdle and Deimos answer it):
    // `-` under every algorithm, a warning with a did-you-mean, exit 0.
    let o = proclaim(&["prove", "tweety", "flyy", "--alg", "all"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(
        stdout(&o),
        "-mu flyy\n-pi flyy\n-beta flyy\n-alpha flyy\n-delta flyy\n"
    );
    assert!(
        stderr(&o).contains("warning: the theory has no atom `flyy`"),
        "{}",
        stderr(&o)
    );
    assert!(stderr(&o).contains("did you mean `fly`?"), "{}", stderr(&o));
    // Inside a clause it is still an error: the clause means something else than was written.
    let o = proclaim(&["prove", "tweety", "\\/{flyy, fly}"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    // No query: every conclusion.
    let o = proclaim(&["prove", "tweety"]);
    assert_eq!(o.status.code(), Some(0));
    assert_eq!(stdout(&o), "+beta bird\n+beta fly\n");
    let o = proclaim(&["prove", "microwave", "cook", "--set", "door=true"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("its inputs are doorOpen, timeLeft"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["prove", "microwave", "cook", "--set", "doorOpen=maybe"]);
    assert!(
        stderr(&o).contains("use true, false or unknown"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["prove", "/no/such/theory.dl", "a"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("cannot read /no/such/theory.dl"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["prove"]);
    assert_eq!(o.status.code(), Some(2));
}

#[test]
fn a_theory_with_errors_is_refused_by_prove() {
    let bad = temp_file("refused.dl", b"a => b\nc.\n");
    let o = proclaim(&["prove", bad.to_str().unwrap(), "b"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("did you forget the `.`"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn a_bad_query_is_called_a_query() {
    let o = proclaim(&["prove", "tweety", "fly ~"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("error: the query has 1 error"),
        "{}",
        stderr(&o)
    );
}

#[test]
fn set_takes_declared_inputs_only_and_one_of_a_group() {
    let theory = temp_file(
        "group.dl",
        b"input{throwIn, goalKick, openPlay}.\nR1: openPlay => restartFree.\nR2: throwIn => handsAllowed.\nR3: goalKick => ~handsAllowed.\noutput{restartFree}.\noutput{handsAllowed}.\n",
    );
    let path = theory.to_str().unwrap();
    let o = proclaim(&["prove", path, "restartFree", "--set", "restartFree=true"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o).contains("`restartFree` is not an input of the theory, so it is concluded, not set (its inputs are throwIn, goalKick, openPlay)"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&[
        "prove",
        path,
        "restartFree",
        "--set",
        "throwIn=true",
        "--set",
        "goalKick=true",
    ]);
    assert_eq!(o.status.code(), Some(2));
    assert!(
        stderr(&o)
            .contains("`goalKick` and `throwIn` are one input group, of which exactly one is true"),
        "{}",
        stderr(&o)
    );
    // One of the group true makes the others false.
    let o = proclaim(&[
        "prove",
        path,
        "~openPlay",
        "~goalKick",
        "--alg",
        "mu",
        "--set",
        "throwIn=true",
    ]);
    assert_eq!(
        stdout(&o),
        "+mu ~openPlay\n+mu ~goalKick\n",
        "{}",
        stderr(&o)
    );
}

#[test]
fn prove_in_spindles_form() {
    let o = proclaim(&["prove", "tweety", "fly", "~fly", "--format", "spindle"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert_eq!(stdout(&o), "-D fly\n+d fly\n-D -fly\n-d -fly\n");
    let o = proclaim(&[
        "prove",
        "tweety",
        "--format",
        "spindle",
        "--set",
        "penguin=true",
    ]);
    assert!(
        stdout(&o).contains("+D penguin\n+d penguin\n"),
        "{}",
        stdout(&o)
    );
    assert!(stdout(&o).contains("-D fly\n-d fly\n"), "{}", stdout(&o));
}

#[test]
fn prove_prints_an_undecided_answer_and_exits_3() {
    let ladder = temp_file(
        "crossed-ladder.dl",
        proclaim_gen::crossed_ladder().as_bytes(),
    );
    let path = ladder.to_str().unwrap();
    check(
        &["prove", path, "t0", "~t0", "--budget", "1000"],
        3,
        "?beta t0  (undecided: search budget of 1000 steps spent in an attack cycle of 24 goals; raise it with --budget)\n-beta ~t0\n",
    );
    check(&["prove", path, "t0"], 0, "+beta t0\n");
    let o = proclaim(&["prove", path, "t0", "--json", "--budget", "1000"]);
    let answers: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(answers[0]["proved"], serde_json::Value::Null);
    assert!(answers[0]["undecided"]
        .as_str()
        .unwrap()
        .contains("24 goals"));
    let o = proclaim(&[
        "prove", path, "t0", "--format", "spindle", "--budget", "1000",
    ]);
    assert_eq!(
        (o.status.code(), stdout(&o).as_str()),
        (Some(3), "-D t0\n?d t0\n")
    );
    assert!(
        stderr(&o).contains("`beta t0` is undecided"),
        "{}",
        stderr(&o)
    );
    // Every atom in SPINdle's form: the same `?`, explained, and the exit status that says so.
    let o = proclaim(&["prove", path, "--format", "spindle", "--budget", "1000"]);
    assert_eq!(o.status.code(), Some(3));
    assert!(stdout(&o).contains("-D t0\n?d t0\n"), "{}", stdout(&o));
    assert!(
        stderr(&o).contains("`beta t0` is undecided"),
        "{}",
        stderr(&o)
    );
}

/// `prove FILE` with no query prints every conclusion (as lines, as JSON, in SPINdle's form)
/// exactly as asking for each literal prints it, on generated theories of several families in
/// both languages, under every algorithm.
#[test]
fn every_conclusion_is_what_each_literal_asked_alone_answers() {
    use proclaim_gen::Format::{Dfl, Dl};
    for (family, sizes, format) in [
        ("chain", vec![20], Dl),
        ("circle", vec![12], Dfl),
        ("teams", vec![2], Dfl),
        ("tree", vec![3, 3], Dfl),
        ("dag", vec![6, 3], Dl),
        ("levels-", vec![6], Dl),
        ("mix", vec![2, 2, 3], Dl),
        ("attack-ring", vec![9], Dl),
        ("clique", vec![5], Dl),
    ] {
        let f = proclaim_gen::Family::parse(family, &sizes).unwrap();
        let mut text = Vec::new();
        f.write(&mut text, format).unwrap();
        let (name, language) = match format {
            Dl => (format!("every-{family}.dl"), proclaim_cdl::Language::Dl),
            Dfl => (format!("every-{family}.dfl"), proclaim_cdl::Language::Dfl),
        };
        let path = temp_file(&name, &text);
        let path = path.to_str().unwrap();
        let theory = proclaim_cdl::load(std::str::from_utf8(&text).unwrap(), language).unwrap();
        let mut names: Vec<&str> = (0..theory.atom_count() as u32)
            .map(|a| theory.atom_name(proclaim_cdl::Atom(a)))
            .collect();
        names.sort();
        let lits: Vec<String> = names
            .iter()
            .flat_map(|n| [n.to_string(), format!("~{n}")])
            .collect();
        let run = |extra: &[&str], each: bool| {
            let mut args = vec!["prove", path];
            if each {
                args.extend(lits.iter().map(String::as_str));
            }
            args.extend(extra);
            let o = proclaim(&args);
            assert_eq!(
                o.status.code(),
                Some(0),
                "{family} {args:?}: {}",
                stderr(&o)
            );
            stdout(&o)
        };
        // Lines: every answer but the `-` ones, algorithm by algorithm.
        let lines = |out: String| {
            let mut kept: Vec<String> = out
                .lines()
                .filter(|l| !l.starts_with('-'))
                .map(String::from)
                .collect();
            kept.sort();
            kept
        };
        let all = ["--alg", "all"];
        assert_eq!(lines(run(&all, false)), lines(run(&all, true)), "{family}");
        let json = |out: String| {
            let value: serde_json::Value = serde_json::from_str(&out).unwrap();
            let mut kept: Vec<String> = value
                .as_array()
                .unwrap()
                .iter()
                .filter(|a| a["proved"] != false)
                .map(|a| a.to_string())
                .collect();
            kept.sort();
            kept
        };
        let all_json = ["--alg", "all", "--json"];
        assert_eq!(
            json(run(&all_json, false)),
            json(run(&all_json, true)),
            "{family}"
        );
        // SPINdle's form lists every literal, atoms by name: the same bytes either way.
        let spindle = ["--format", "spindle"];
        assert_eq!(run(&spindle, false), run(&spindle, true), "{family}");
    }
}
