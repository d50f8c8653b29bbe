#!/usr/bin/env bash
# Medial axis of the gear fixture: writes out/gear_mat.step and a picture out/gear_mat.png.
# Sets up ./.venv from scratch if needed.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup_venv.sh

export MPLBACKEND=Agg
mkdir -p out
.venv/bin/medialcad fixtures/step/faces/gear_with_hole.step -o out/gear_mat.step --png out/gear_mat.png
echo "wrote out/gear_mat.step and out/gear_mat.png"
