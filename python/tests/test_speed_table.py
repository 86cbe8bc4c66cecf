"""benches/speed_table.py, which writes README's speed table: its table from a fixture of
`proclaim bench --all --json` output, its README rewrite between the markers, and one real
`bench --all` run of the debug binary on a small case (PROCLAIM_BIN, as test_proclaim.py)."""

import importlib.util
import os
import re
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]

spec = importlib.util.spec_from_file_location("speed_table", ROOT / "benches" / "speed_table.py")
speed_table = importlib.util.module_from_spec(spec)
spec.loader.exec_module(speed_table)


def timing(best, median):
    return {"best_ms": best, "median_ms": median}


# Two rows as `bench --all --json` prints them: a generated case with `wc -w` timed, and a file
# case without it.
FIXTURE = [
    {
        "case": "chain(1000000)",
        "query": "beta a1000000",
        "every_conclusion": timing(900.4, 1000.6),
        "one_query": timing(300.0, 400.0),
        "wc_words": timing(150.0, 160.0),
    },
    {
        "case": "team.dfl",
        "query": "beta kick",
        "every_conclusion": timing(12.0, 13.0),
        "one_query": timing(6.0, 6.5),
    },
]


def test_the_table_gives_each_case_its_pairs_and_ratios():
    sizes = {"chain:1000000": 41.6}
    text = speed_table.format_table(FIXTURE, ["chain:1000000", "team.dfl"], 5, sizes.__getitem__)
    assert text == (
        "`proclaim bench --all --repeat 5 chain:1000000 team.dfl`:\n"
        "\n"
        "| case (`.dfl`) | every conclusion | one query | `wc -w` | all ÷ one | one ÷ `wc -w` |\n"
        "|---|---|---|---|---|---|\n"
        "| chain(1000000) (42 MB) | 900 / 1001 ms | 300 / 400 ms | 150 / 160 ms | 3.00 / 2.50 | 2.00 / 2.50 |\n"
        "| team.dfl | 12 / 13 ms | 6 / 6 ms | - | 2.00 / 2.00 | - |\n"
    )


def test_the_readme_is_rewritten_between_its_markers_only(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text(f"# Title\n\nBefore.\n{speed_table.BEGIN}\nold table\n{speed_table.END}\nAfter.\n")
    speed_table.rewrite_readme("new table\n", readme)
    assert readme.read_text() == (
        f"# Title\n\nBefore.\n{speed_table.BEGIN}\nnew table\n{speed_table.END}\nAfter.\n"
    )


def test_a_readme_without_the_markers_is_refused_and_left_alone(tmp_path):
    readme = tmp_path / "README.md"
    readme.write_text("# Title\n\nNo table here.\n")
    with pytest.raises(SystemExit) as refused:
        speed_table.rewrite_readme("new table\n", readme)
    assert "markers are missing" in str(refused.value)
    assert readme.read_text() == "# Title\n\nNo table here.\n"


def proclaim():
    path = os.environ.get("PROCLAIM_BIN") or str(
        Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target")) / "debug" / "proclaim"
    )
    if not os.access(path, os.X_OK):
        pytest.fail(f"the proclaim binary is needed to run a bench: {path} (build it with cargo)")
    return Path(path)


def test_a_real_bench_run_makes_a_row_a_case():
    text = speed_table.table(proclaim(), ["chain:1000", "tree:3:2"], 1)
    lines = text.splitlines()
    assert lines[0] == "`proclaim bench --all --repeat 1 chain:1000 tree:3:2`:"
    pair = r"\d+ / \d+ ms"
    ratio = r"\d+\.\d\d / \d+\.\d\d"
    row = rf"\| {{}} \(0 MB\) \| {pair} \| {pair} \| (?:{pair}|-) \| {ratio} \| (?:{ratio}|-) \|"
    assert re.fullmatch(row.format(r"chain\(1000\)"), lines[4]), lines[4]
    assert re.fullmatch(row.format(r"tree\(3, 2\)"), lines[5]), lines[5]
    assert len(lines) == 6, text
