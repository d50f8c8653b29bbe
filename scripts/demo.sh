#!/usr/bin/env bash
# The main job on a bundled fixture: the 3D medial axis of the paper's gear wheel (Fig. 19).
# Writes out/gear_wheel_mat.step (named entities), out/gear_wheel_mat.radius.json (radius
# sidecar), out/gear_wheel_mat.json (report with the wall thickness), out/gear_wheel_mat.png
# (picture) and out/gear_wheel_mat.html (interactive 3D viewer, open it in a browser).
# Sets up ./.venv from scratch if needed.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/setup_venv.sh

export MPLBACKEND=Agg
mkdir -p out
.venv/bin/medialcad fixtures/step/solids/gear_wheel.step -o out/gear_wheel_mat.step \
    --report out/gear_wheel_mat.json --png out/gear_wheel_mat.png \
    --html out/gear_wheel_mat.html
