#!/usr/bin/env bash
# The Python package's tests: a fresh venv, `pip install ./python` (maturin builds the extension
# in release mode), the typed stub `proclaim/__init__.pyi` checked against the built extension
# by mypy's stubtest, then pytest (arguments are pytest's: `-k zenoh` runs only the Zenoh test). The agreement tests run the `proclaim` binary: PROCLAIM_BIN, or
# target/debug/proclaim (under CARGO_TARGET_DIR when set), built here when missing.
set -euo pipefail
python_dir="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$python_dir")"
target="$(realpath -m "${CARGO_TARGET_DIR:-$root/target}")"
# Paths given relative to where this was called from still work after the cd below.
if [ -n "${PROCLAIM_ZENOH_BIN:-}" ]; then
  export PROCLAIM_ZENOH_BIN="$(realpath -m "$PROCLAIM_ZENOH_BIN")"
fi
if [ -n "${PROCLAIM_BIN:-}" ]; then
  export PROCLAIM_BIN="$(realpath -m "$PROCLAIM_BIN")"
fi
venv="${PROCLAIM_VENV:-$target/python-venv}"

if [ -z "${PROCLAIM_BIN:-}" ]; then
  export PROCLAIM_BIN="$target/debug/proclaim"
  [ -x "$PROCLAIM_BIN" ] || cargo build --quiet --manifest-path "$root/Cargo.toml" --bin proclaim
fi

# Debian's python3 leaves venv's pip out (python3-venv); install it the way .ci/run installs its tools.
if ! python3 -c 'import ensurepip, venv' 2>/dev/null && command -v apt-get >/dev/null 2>&1; then
  (apt-get update -qq && apt-get install -y -qq python3-venv) >/dev/null 2>&1 \
    || echo "python3-venv could not be installed; creating the venv will fail"
fi
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet --upgrade pip
# eclipse-zenoh: Zenoh's own Python package, for the whiteboard-over-Zenoh test (the Rust side is
# Zenoh 1.9); that test runs only when PROCLAIM_ZENOH_BIN names a proclaim built with `zenoh`.
"$venv/bin/pip" install --quiet maturin pytest eclipse-zenoh==1.9.0
# mypy for stubtest, pinned: a newer mypy may add checks, which should be taken on on purpose.
"$venv/bin/pip" install --quiet mypy==2.4.1
"$venv/bin/pip" install --quiet "$python_dir"
# From the tests' directory, not python/: the source tree's proclaim/ has no extension in it and
# must not shadow the installed package.
cd "$python_dir/tests"
# Every name, signature and class of the stub as the extension has it (a name only the stub has,
# for annotations, starts with an underscore); run in the venv, where mypy leaves its cache.
(cd "$venv" && "$venv/bin/python" -m mypy.stubtest proclaim)
"$venv/bin/pytest" -q "$@"
