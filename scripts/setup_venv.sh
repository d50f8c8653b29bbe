#!/usr/bin/env bash
# Create ./.venv (if absent) and install medialcad with its dev extra into it.
# Sourced by scripts/test.sh and scripts/demo.sh; safe to run on its own.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

if [ ! -x .venv/bin/python ]; then
    if command -v python3.11 >/dev/null 2>&1; then
        PY=python3.11
    else
        PY=python3
    fi
    if ! "$PY" -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
        echo "medialcad needs Python 3.11; found $("$PY" --version 2>&1)" >&2
        exit 1
    fi
    "$PY" -m venv .venv
fi

.venv/bin/python -m pip install --quiet --disable-pip-version-check -e '.[dev]'
