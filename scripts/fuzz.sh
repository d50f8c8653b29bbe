#!/usr/bin/env bash
# The longer fuzzing run (README, "Fuzzing"): fresh random faces, extrusions and revolutions
# from the hypothesis strategies, judged by the oracles.
#   bash scripts/fuzz.sh [EXAMPLES_2D] [EXAMPLES_3D]
# EXAMPLES_2D per 2D strategy (4 strategies, default 500: 2,000 faces), EXAMPLES_3D per 3D
# strategy (4 extrusion and 3 revolution strategies, default 100: 700 solids).
# Known failures stay xfail; a failing example is printed by hypothesis (set
# MEDIALCAD_FAILED_FACES=DIR to keep the 2D faces as BREP). Sets up ./.venv if needed.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup_venv.sh
export MPLBACKEND=Agg MEDIALCAD_HYPOTHESIS_RANDOM=1

n2d="${1:-500}"
n3d="${2:-100}"
rc=0
echo "== 2D: ${n2d} examples per strategy"
MEDIALCAD_HYPOTHESIS_EXAMPLES="$n2d" .venv/bin/pytest -q -rxXf -p no:cacheprovider \
    tests/test_mat2d_oracle.py -k random || rc=1
echo "== 3D: ${n3d} examples per strategy"
MEDIALCAD_HYPOTHESIS_EXAMPLES_3D="$n3d" .venv/bin/pytest -q -rxXf -p no:cacheprovider \
    tests/test_mat3d_extrusion.py tests/test_mat3d_revolution.py -k "random" || rc=1
exit "$rc"
