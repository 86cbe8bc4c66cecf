#!/usr/bin/env python3
"""Writes README's speed table from `proclaim bench --all`, so that its figures are measured, not typed.

Builds the release binary, times every conclusion against one query and `wc -w` on each case
(`proclaim bench --all --repeat R --json`, whole processes, best and median), and replaces the
lines between README's two speed-table markers with the table it prints. Run from anywhere:

    python3 benches/speed_table.py            # measure and rewrite README.md
    python3 benches/speed_table.py --print    # measure and print the table only
    python3 benches/speed_table.py --repeat 3 chain:1000 tree:6:3   # other cases, fewer repeats
    python3 benches/speed_table.py --print --binary target/debug/proclaim chain:1000  # a quick try
"""

import argparse
import json
import os
import pathlib
import subprocess
import sys
import tempfile

ROOT = pathlib.Path(__file__).resolve().parent.parent
README = ROOT / "README.md"
BEGIN = "<!-- speed table: written by `python3 benches/speed_table.py`; do not edit by hand -->"
END = "<!-- end of the speed table -->"
# The families of docs/spec/benchmarks.md at the sizes README reports.
CASES = ["chain:1000000", "circle:1000000", "dag:333333:3", "tree:12:3", "teams:9"]


def release_binary() -> pathlib.Path:
    """The release `proclaim`, built by cargo into its usual target directory."""
    subprocess.run(["cargo", "build", "--release", "--quiet", "--bin", "proclaim"], cwd=ROOT, check=True)
    target = pathlib.Path(os.environ.get("CARGO_TARGET_DIR", ROOT / "target"))
    if not target.is_absolute():
        target = ROOT / target
    return target / "release" / "proclaim"


def size_mb(binary: pathlib.Path, case: str) -> float:
    """The size of `case` written as `.dfl` (as `bench --all` writes it), in megabytes."""
    family, *numbers = case.split(":")
    with tempfile.TemporaryDirectory() as scratch:
        path = pathlib.Path(scratch) / "case.dfl"
        subprocess.run([binary, "gen", family, *numbers, "--format", "dfl", "-o", path], check=True,
                       stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        return path.stat().st_size / 1e6


def pair(timing: dict) -> str:
    return f"{timing['best_ms']:.0f} / {timing['median_ms']:.0f} ms"


def ratio(a: dict, b: dict) -> str:
    return f"{a['best_ms'] / b['best_ms']:.2f} / {a['median_ms'] / b['median_ms']:.2f}"


def table(binary: pathlib.Path, cases: list, repeat: int) -> str:
    """The markdown table of one `bench --all` run over `cases`, with the command that made it."""
    run = subprocess.run([binary, "bench", "--all", "--repeat", str(repeat), "--json", *cases],
                         check=True, capture_output=True, text=True)
    return format_table(json.loads(run.stdout), cases, repeat, lambda case: size_mb(binary, case))


def format_table(rows: list, cases: list, repeat: int, size_of) -> str:
    """The markdown table of `bench --all --json`'s `rows` for `cases`; `size_of(case)` is a
    generated case's size in megabytes (a file case is labelled by its name alone)."""
    lines = [
        f"`proclaim bench --all --repeat {repeat} {' '.join(cases)}`:",
        "",
        "| case (`.dfl`) | every conclusion | one query | `wc -w` | all ÷ one | one ÷ `wc -w` |",
        "|---|---|---|---|---|---|",
    ]
    for case, row in zip(cases, rows):
        label = f"{row['case']} ({size_of(case):.0f} MB)" if ":" in case else row["case"]
        wc = row.get("wc_words")
        lines.append(" | ".join([
            f"| {label}",
            pair(row["every_conclusion"]),
            pair(row["one_query"]),
            pair(wc) if wc else "-",
            ratio(row["every_conclusion"], row["one_query"]),
            (ratio(row["one_query"], wc) if wc else "-") + " |",
        ]))
    return "\n".join(lines) + "\n"


def rewrite_readme(text: str, readme_path: pathlib.Path = README) -> None:
    """Replaces what lies between the markers; says so and fails when they are missing."""
    readme = readme_path.read_text()
    start, end = readme.find(BEGIN), readme.find(END)
    if start < 0 or end < start:
        sys.exit(f"{readme_path}: the speed table's markers are missing:\n{BEGIN}\n{END}")
    start += len(BEGIN)
    readme_path.write_text(readme[:start] + "\n" + text + readme[end:])


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("cases", nargs="*", default=CASES, help="family:size[:k[:m]] (default: README's)")
    parser.add_argument("--repeat", type=int, default=11, help="runs of each command (default 11)")
    parser.add_argument("--print", action="store_true", help="print the table; leave README as it is")
    parser.add_argument("--binary", type=pathlib.Path, help="time this proclaim instead of building the release one")
    args = parser.parse_args()
    text = table(args.binary or release_binary(), args.cases, args.repeat)
    if args.print:
        print(text, end="")
    else:
        rewrite_readme(text)
        print(f"{README}: speed table rewritten", file=sys.stderr)


if __name__ == "__main__":
    main()
