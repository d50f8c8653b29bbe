"""Time recognize() on every solid fixture, and compare it with the gear's 2D MAT.

Usage: ``python bench/bench_recognition.py [--repeats N]``

Every solid of ``fixtures/step/solids`` and ``fixtures/step/freecad`` (a file of several
solids gives one row per solid; files without a solid are skipped) is read once, then
``medialcad.recognition.recognize`` is timed ``N`` times (default 5) and the median is
printed with what it found (``extrusion``, ``revolution``, ``+rev``/``+ext`` when there is
an alternative reading, or the error's class for refused solids). Last, the gear wheel's
recognition time is set against ``medialcad.medial_axis_2d(reading.profile)`` (the work
recognition enables), both medians of ``N``.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parent.parent
if str(ROOT) not in sys.path:
    sys.path.insert(0, str(ROOT))

from medialcad import medial_axis_2d  # noqa: E402
from medialcad.errors import MedialCadError, NoSolidError  # noqa: E402
from medialcad.recognition import read_step, recognize  # noqa: E402

FOLDERS = [ROOT / "fixtures" / "step" / "solids", ROOT / "fixtures" / "step" / "freecad"]


def median_time(fn: Callable[[], Any], repeats: int) -> tuple[float, Any]:
    """Median wall time of ``repeats`` calls (s), and the last result (or the exception)."""
    times, result = [], None
    for _ in range(repeats):
        t = time.perf_counter()
        try:
            result = fn()
        except MedialCadError as err:
            result = err
        times.append(time.perf_counter() - t)
    return statistics.median(times), result


def describe(result: Any) -> str:
    if isinstance(result, Exception):
        return type(result).__name__
    alt = {"extrusion": " +ext", "revolution": " +rev"}
    extra = alt[result.alternative.kind] if result.alternative is not None else ""
    return result.kind + extra


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--repeats", type=int, default=5)
    args = parser.parse_args()

    rows = []
    for folder in FOLDERS:
        for entry in json.loads((folder / "manifest.json").read_text())["solids"]:
            try:
                found = read_step(folder / entry["file"])
            except NoSolidError:
                continue
            for i, solid in enumerate(found):
                name = entry["name"] if len(found) == 1 else f"{entry['name']}[{i}]"
                dt, result = median_time(lambda s=solid: recognize(s), args.repeats)
                rows.append((name, entry["kind"], describe(result), dt))

    w = max(len(r[0]) for r in rows)
    print(f"recognize(), median of {args.repeats}\n")
    print(f"{'name':<{w}}  {'manifest kind':<17}  {'recognised':<31}  {'ms':>8}")
    print(f"{'-' * w}  {'-' * 17}  {'-' * 31}  {'-' * 8}")
    for name, kind, found, dt in rows:
        print(f"{name:<{w}}  {kind:<17}  {found:<31}  {dt * 1e3:8.1f}")
    total = sum(r[3] for r in rows)
    print(f"{'total':<{w}}  {'':<17}  {'':<31}  {total * 1e3:8.1f}")

    gear = read_step(FOLDERS[0] / "gear_wheel.step")[0]
    t_rec, reading = median_time(lambda: recognize(gear), args.repeats)
    if isinstance(reading, Exception):
        print(f"\ngear_wheel: recognition failed ({reading})")
        return
    t_mat, _ = median_time(lambda: medial_axis_2d(reading.profile), args.repeats)
    print(
        f"\ngear_wheel: recognize {t_rec * 1e3:.1f} ms, medial_axis_2d(profile) "
        f"{t_mat * 1e3:.1f} ms, ratio recognize / MAT = {t_rec / t_mat:.2f}"
    )


if __name__ == "__main__":
    main()
