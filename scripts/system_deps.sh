#!/usr/bin/env bash
# System programs some tests drive for real: FreeCAD's headless freecadcmd (the FreeCAD
# macro) and Chromium (the HTML viewer). Installed from Debian's packages when missing and
# when we can (root + apt-get); otherwise those tests skip with a reason.
set -uo pipefail

need=()
command -v freecadcmd >/dev/null 2>&1 || need+=(freecad-python3)
command -v chromium >/dev/null 2>&1 || need+=(chromium)
if [ ${#need[@]} -eq 0 ]; then
    exit 0
fi
if [ "$(id -u)" != "0" ] || ! command -v apt-get >/dev/null 2>&1; then
    echo "note: ${need[*]} missing and not installable here; their tests will skip" >&2
    exit 0
fi
echo "== installing ${need[*]} (Debian packages)"
export DEBIAN_FRONTEND=noninteractive
apt-get update -qq >/dev/null 2>&1 || true
apt-get install -y -qq "${need[@]}" >/dev/null 2>&1 \
    || echo "note: could not install ${need[*]}; their tests will skip" >&2
exit 0
