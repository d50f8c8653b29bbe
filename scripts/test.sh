#!/usr/bin/env bash
# Everything CI checks: lint, format, types, tests. Sets up ./.venv from scratch if needed.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup_venv.sh
bash scripts/system_deps.sh

export MPLBACKEND=Agg
# random examples per hypothesis strategy (the suite default is 6 faces and 2 solids; more in
# CI: 5 x 50 faces, 10 spline loops and 10 x 5 solids, 310 examples)
export MEDIALCAD_HYPOTHESIS_EXAMPLES="${MEDIALCAD_HYPOTHESIS_EXAMPLES:-50}"
export MEDIALCAD_HYPOTHESIS_EXAMPLES_3D="${MEDIALCAD_HYPOTHESIS_EXAMPLES_3D:-5}"

# Lint only the folders that exist (bench/ may be absent in a fresh clone).
paths=()
for d in medialcad tests bench; do
    if [ -d "$d" ]; then paths+=("$d"); fi
done

echo "== ruff check ${paths[*]}"
.venv/bin/ruff check "${paths[@]}"
echo "== ruff format --check"
.venv/bin/ruff format --check "${paths[@]}"
echo "== mypy"
.venv/bin/mypy medialcad
echo "== pytest"
.venv/bin/pytest -q "$@"
