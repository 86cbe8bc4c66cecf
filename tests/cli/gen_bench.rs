//! `gen`, `bench-run` and `bench`: generated theory families, their expected answers and timings.

use super::{check, generated, stderr, stdout, temp_file};
use crate::proclaim;

#[test]
fn gen_writes_the_family_and_its_expected_answer() {
    let o = proclaim(&["gen", "chain", "3"]);
    assert_eq!(
        stdout(&o),
        "a0.\nr1: a0 => a1.\nr2: a1 => a2.\nr3: a2 => a3.\n"
    );
    assert!(
        stderr(&o).contains("expected: +beta a3 +pi a3"),
        "{}",
        stderr(&o)
    );
    let o = proclaim(&["gen", "levels", "0", "--format", "dfl"]);
    assert_eq!(
        stdout(&o),
        "r0: => a0\nr1: a1 => -a0\nr2: => a1\nr3: a2 => -a1\nr4: => a2\nr3 > r2\n"
    );
    let o = proclaim(&["gen", "tree", "2", "2"]);
    assert_eq!(
        stdout(&o),
        "r0: a1, a2 => a0.\nr1: a3, a4 => a1.\nr2: a5, a6 => a2.\na3.\na4.\na5.\na6.\n"
    );
    let o = proclaim(&["gen", "teams", "0"]);
    assert_eq!(
        stdout(&o),
        "r0: => a0.\nr1: => a0.\nr2: => ~a0.\nr3: => ~a0.\nr0 > r2.\nr1 > r3.\n"
    );
    let o = proclaim(&["gen", "bogus", "3"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("unknown family `bogus`"));
}

#[test]
fn generated_families_give_their_expected_answers() {
    for (family, sizes) in [
        ("chain", vec![50]),
        ("chains", vec![50]),
        ("circle", vec![50]),
        ("circles", vec![50]),
        ("levels", vec![20]),
        ("levels-", vec![20]),
        ("teams", vec![3]),
        ("tree", vec![4, 3]),
        ("dag", vec![10, 3]),
        ("mix", vec![3, 2, 4]),
        ("attack-ring", vec![1001]),
        ("pairs-ring", vec![40]),
        ("priority-ring", vec![40]),
        ("defeater-ring", vec![200]),
        ("clique", vec![31]),
        ("ladder", vec![4]),
    ] {
        let f = proclaim_gen::Family::parse(family, &sizes).unwrap();
        let mut text = Vec::new();
        f.write(&mut text, proclaim_gen::Format::Dl).unwrap();
        let path = temp_file(&format!("{family}.dl"), &text);
        let expect: Vec<String> = f
            .expected()
            .iter()
            .map(|e| format!("--expect={e}"))
            .collect();
        let mut args = vec!["bench-run", path.to_str().unwrap()];
        args.extend(expect.iter().map(String::as_str));
        let o = proclaim(&args);
        let m: serde_json::Value = serde_json::from_slice(&o.stdout)
            .unwrap_or_else(|_| panic!("{family}: {}", stderr(&o)));
        assert_eq!(m["answers_ok"], true, "{family}");
        assert_eq!(
            m["rules"].as_u64().unwrap() as u128,
            f.rule_count() + facts(&f),
            "{family}"
        );
    }
}

/// Facts are unit clauses, which become rules `-> l` of the checked theory.
fn facts(f: &proclaim_gen::Family) -> u128 {
    use proclaim_gen::Family::*;
    match *f {
        Chain(_) | Chains(_) => 1,
        Tree(n, k) => (k as u128).pow(n as u32),
        Dag(_, k) => k as u128,
        Mix(m, n, _) => 2 * (m * n) as u128,
        _ => 0,
    }
}

#[test]
fn bench_times_the_users_own_files() {
    let ladder = generated("ladder", 3);
    let o = proclaim(&["bench", ladder.to_str().unwrap(), "clique:9", "--json"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let rows: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    assert_eq!(rows[0]["case"], "ladder-3.dl");
    assert_eq!(rows[0]["rules"], 30);
    assert_eq!(rows[0]["undecided"], 0);
    assert_eq!(rows[1]["case"], "clique(9)");
    assert_eq!(rows[1]["answers_ok"], true);
    check(&["bench", "no-such-theory.dl"], 2, "");
}

/// `bench --all` runs every conclusion, one query and `wc -w` as processes of their own and
/// reports each one's best and median time.
#[test]
fn bench_all_times_every_conclusion_against_one_query() {
    let o = proclaim(&[
        "bench",
        "--all",
        "--json",
        "--repeat",
        "2",
        "chain:200",
        "tree:3:3",
    ]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let cases: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let cases = cases.as_array().unwrap();
    assert_eq!(cases.len(), 2);
    assert_eq!(cases[0]["query"], "beta a200");
    for case in cases {
        for timing in ["every_conclusion", "one_query"] {
            let (best, median) = (&case[timing]["best_ms"], &case[timing]["median_ms"]);
            assert!(best.as_f64().unwrap() > 0.0, "{case}");
            assert!(best.as_f64() <= median.as_f64(), "{case}");
        }
    }
    let o = proclaim(&["bench", "--all", "chain:nope"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
}

/// `bench --parse`: every kind of file a user brings, written at each size and checked whole
/// (the generated files check clean, or the bench would fail), each size timed once.
#[test]
fn bench_parse_times_check_on_each_kind_of_file_at_each_size() {
    let o = proclaim(&["bench", "--parse", "20KB", "60KB", "--json"]);
    assert!(o.status.success(), "{}", stderr(&o));
    let timed: serde_json::Value = serde_json::from_str(&stdout(&o)).unwrap();
    let timed = timed.as_array().unwrap();
    assert_eq!(timed.len(), 8, "{timed:?}");
    for (i, t) in timed.iter().enumerate() {
        assert!(t["check_ms"].as_f64().unwrap() > 0.0, "{t}");
        let bytes = t["bytes"].as_u64().unwrap();
        let wanted = if i % 2 == 0 { 20 << 10 } else { 60 << 10 };
        assert!(bytes >= wanted * 9 / 10 && bytes <= wanted * 12 / 10, "{t}");
        assert_eq!(t["against_linear"].is_null(), i % 2 == 0, "{t}");
    }
    check(&["bench", "--parse", "1TB"], 2, "");
}
