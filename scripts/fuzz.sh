#!/usr/bin/env bash
# The longer fuzzing run (README, "Fuzzing"; docs/fuzzing.md): fresh random faces,
# extrusions and revolutions from the hypothesis strategies, judged by the oracles.
#   bash scripts/fuzz.sh [EXAMPLES_2D] [EXAMPLES_3D]
# EXAMPLES_2D per 2D strategy (5 strategies and a fifth as many spline loops, default 500:
# 2,600 faces), EXAMPLES_3D per 3D
# strategy (5 extrusion and 5 revolution strategies, pie slices among them, default 20:
# 200 solids).
# Unlike CI, a failing example does not stop its strategy: every example is logged as
# passed, refused (a clear medialcad InputError) or failed to out/fuzz/<stamp>.jsonl, failing
# shapes are kept as exact BREP under out/fuzz/<stamp>/ for replay, and the table at the
# end (scripts/fuzz_summary.py) counts them. Exit code 1 if any example failed.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup_venv.sh

n2d="${1:-500}"
n3d="${2:-20}"
stamp="$(date -u +%Y%m%dT%H%M%S)-$(git rev-parse --short HEAD 2>/dev/null || echo nogit)"
mkdir -p out/fuzz
export MPLBACKEND=Agg MEDIALCAD_HYPOTHESIS_RANDOM=1
export MEDIALCAD_FUZZ_LOG="$PWD/out/fuzz/$stamp.jsonl"
export MEDIALCAD_FAILED_FACES="$PWD/out/fuzz/$stamp/faces"
export MEDIALCAD_FAILED_SHAPES="$PWD/out/fuzz/$stamp/solids"
: >"$MEDIALCAD_FUZZ_LOG"

echo "== 2D: ${n2d} examples per strategy (log: $MEDIALCAD_FUZZ_LOG)"
MEDIALCAD_HYPOTHESIS_EXAMPLES="$n2d" .venv/bin/pytest -q -p no:cacheprovider \
    tests/test_mat2d_oracle.py -k "test_random" || true
echo "== 3D: ${n3d} examples per strategy"
MEDIALCAD_HYPOTHESIS_EXAMPLES_3D="$n3d" .venv/bin/pytest -q -p no:cacheprovider \
    tests/test_mat3d_extrusion.py tests/test_mat3d_revolution.py -k "test_random" || true
echo "== summary"
exec .venv/bin/python scripts/fuzz_summary.py "$MEDIALCAD_FUZZ_LOG"
