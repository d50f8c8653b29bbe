"""Summarise a fuzzing log (``MEDIALCAD_FUZZ_LOG``, one JSON object a line) as a table:
examples, passed, refused and failed per test, time per example, and every failure and
refusal with its message and the exact shape kept for replay.

    python scripts/fuzz_summary.py out/fuzz/LOG.jsonl
"""

from __future__ import annotations

import json
import sys
from collections import Counter, defaultdict
from pathlib import Path


def main(path: str) -> int:
    rows = [json.loads(line) for line in Path(path).read_text().splitlines() if line.strip()]
    by_test: dict[str, Counter[str]] = defaultdict(Counter)
    seconds: dict[str, float] = defaultdict(float)
    for r in rows:
        by_test[r["test"]][r["outcome"]] += 1
        seconds[r["test"]] += r["seconds"]
    print("| test | examples | passed | refused | failed | s / example |")
    print("|---|---|---|---|---|---|")
    total: Counter[str] = Counter()
    for test in sorted(by_test):
        c = by_test[test]
        n = sum(c.values())
        total.update(c)
        print(
            f"| {test} | {n} | {c['passed']} | {c['refused']} | {c['failed']} "
            f"| {seconds[test] / n:.1f} |"
        )
    n = sum(total.values())
    print(f"| **all** | {n} | {total['passed']} | {total['refused']} | {total['failed']} | |")
    for r in rows:
        if r["outcome"] != "passed":
            print(f"- {r['outcome']}: {r['test']} ({r['label']}): {r['error']}  [{r['shape']}]")
    return 1 if total["failed"] else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
