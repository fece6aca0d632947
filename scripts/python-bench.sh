#!/usr/bin/env bash
# The Python package against the command in one run (docs/python.md#speed): a million-row sweep of e alone on two
# threads, peak memory against the arrays' size, `import impact`. Builds the command and installs the package into a
# virtual environment of its own (target/python-bench-venv) first. By hand, not in CI: it measures, it judges nothing.
set -euo pipefail
cd "$(dirname "$0")/.."
cargo build --release --locked --bin impact
venv=target/python-bench-venv
[ -x "$venv/bin/python" ] || python3 -m venv "$venv"
"$venv/bin/python" -m pip install --quiet ./python
"$venv/bin/python" python/bench/bench.py --impact target/release/impact "$@"
