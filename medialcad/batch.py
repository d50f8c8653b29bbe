"""``medialcad batch IN_DIR -o OUT_DIR``: the medial axis of every STEP file of a folder.

Every ``*.step``/``*.stp`` under ``IN_DIR`` (recursively; hidden files and folders and
anything inside ``OUT_DIR`` are skipped) is converted by the same code as the single-file
command (:func:`medialcad.cli.convert`) into ``OUT_DIR/<relative folder>/``:

- ``<stem>.mat.step``: the medial axis (one product per solid),
- ``<stem>.radius.json``: its radius sidecar (solids only),
- ``<stem>.report.json``: the per-file report (also written when a solid is refused),

plus ``OUT_DIR/batch_report.json`` for the whole run. (Two inputs with the same stem in
one folder, ``part.step`` and ``part.stp``, keep their suffix: ``part.step.mat.step``.)

Files run in parallel, each in a worker process (:class:`ProcessPoolExecutor`, ``--jobs``
workers). A worker that dies (a segfault in OpenCascade, the OOM killer) only fails its
own file: the files that were running beside it are retried, each in a fresh process, and
the rest go on in a new pool. With ``--scheduler ADDRESS`` the same per-file function is
submitted to a running Dask distributed cluster instead (its workers need medialcad
installed and must see ``IN_DIR`` and ``OUT_DIR`` at the same paths).

Runs are resumable: a file whose outputs exist, are newer than the input, were made with
the same ``--tol`` and succeeded is skipped (``--force`` recomputes everything).
"""

from __future__ import annotations

import argparse
import json
import logging
import math
import multiprocessing
import os
import sys
import time
from collections import deque
from collections.abc import Callable, Iterable
from concurrent.futures import FIRST_COMPLETED, Future, ProcessPoolExecutor, wait
from concurrent.futures.process import BrokenProcessPool
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from medialcad.errors import InputError, MedialCadError, ReadError

__all__ = [
    "Job",
    "find_inputs",
    "format_table",
    "main",
    "plan_jobs",
    "process_file",
    "run_dask",
    "run_local",
    "up_to_date",
]

log = logging.getLogger(__name__)

STEP_SUFFIXES = (".step", ".stp")
BATCH_REPORT = "batch_report.json"
BATCH_REPORT_FORMAT = "medialcad-batch/1"

_DESCRIPTION = """\
Medial axis of every STEP file (*.step, *.stp) under IN_DIR, recursively, in parallel.

Each IN_DIR/<folder>/<stem>.step gives OUT_DIR/<folder>/<stem>.mat.step (the medial
axis), <stem>.radius.json (radius sidecar) and <stem>.report.json (per-file report, as
'medialcad --report'); OUT_DIR/batch_report.json sums up the run and a table (file,
status, seconds, reason) is printed on stdout.

status: ok; skipped (outputs up to date); refused (the file was read but a solid or face
cannot be handled, e.g. neither an extrusion nor a revolution: nothing but the report is
written for it); failed (unreadable file, internal error or crashed worker).

A failing file never stops the others; a crashing worker (segfault) fails only its own
file. Rerunning skips files whose outputs are newer than the input and were made with
the same --tol (use --force to recompute)."""

_EPILOG = """\
exit codes: 0 every file ok or skipped; 2 any file refused or failed (or bad arguments);
1 the batch itself could not run (e.g. the scheduler is unreachable); 130 interrupted."""


# --------------------------------------------------------------------------- jobs


@dataclass(frozen=True)
class Job:
    """One input file and where its outputs go (absolute paths, as strings)."""

    src: str
    rel: str
    output: str
    radius: str
    report: str
    tol: float | None = None


def find_inputs(in_dir: Path, out_dir: Path | None = None) -> list[Path]:
    """Every STEP file under ``in_dir`` (sorted), skipping hidden entries and ``out_dir``."""
    in_dir = in_dir.resolve()
    skip = out_dir.resolve() if out_dir is not None else None
    if skip is not None and skip == in_dir:
        skip = None  # outputs beside the inputs: recognised by their .mat.step suffix below
    found = []
    for root, dirs, files in os.walk(in_dir):
        here = Path(root)
        dirs[:] = sorted(d for d in dirs if not d.startswith(".") and here / d != skip)
        for name in files:
            low = name.lower()
            if name.startswith(".") or not low.endswith(STEP_SUFFIXES):
                continue
            if skip is None and out_dir is not None and low.endswith(".mat.step"):
                continue
            found.append(here / name)
    return sorted(found)


def plan_jobs(
    inputs: Iterable[Path], in_dir: Path, out_dir: Path, tol: float | None = None
) -> list[Job]:
    """The :class:`Job` of every input (output names as in the module docstring)."""
    in_dir, out_dir = in_dir.resolve(), out_dir.resolve()
    rels = [Path(os.path.abspath(p)).relative_to(in_dir) for p in inputs]  # keep symlinks
    stems: dict[Path, int] = {}
    for rel in rels:
        key = rel.parent / rel.stem
        stems[key] = stems.get(key, 0) + 1
    jobs = []
    for rel in rels:
        key = rel.parent / rel.stem
        base = out_dir / (rel if stems[key] > 1 else key)
        jobs.append(
            Job(
                src=str(in_dir / rel),
                rel=rel.as_posix(),
                output=f"{base}.mat.step",
                radius=f"{base}.radius.json",
                report=f"{base}.report.json",
                tol=tol,
            )
        )
    return jobs


def up_to_date(job: Job) -> bool:
    """Whether ``job``'s outputs exist, are newer than its input, succeeded and used the
    same tolerance."""
    try:
        src_time = Path(job.src).stat().st_mtime
        for p in (job.output, job.report):
            if Path(p).stat().st_mtime < src_time:
                return False
        report = json.loads(Path(job.report).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return False
    if not isinstance(report, dict) or report.get("status", "ok") != "ok":
        return False
    if report.get("options", {}).get("tol") != job.tol:
        return False
    return "solids" not in report or Path(job.radius).exists()


# --------------------------------------------------------------------------- the worker


def process_file(job: Job) -> dict[str, Any]:
    """Convert one file (the function run by every worker, local or Dask).

    Never raises for a bad file: returns ``{"file", "status", "reason", "seconds", ...}``
    with status ``ok``, ``refused`` or ``failed``.
    """
    from medialcad.cli import convert

    t0 = time.perf_counter()
    status, reason = "ok", ""
    try:
        result = convert(
            job.src, job.output, tol=job.tol, report_path=job.report, radius_path=job.radius
        )
    except ReadError as err:
        status, reason = "failed", str(err)
    except InputError as err:
        status, reason = "refused", str(err)
    except MedialCadError as err:
        status, reason = "failed", str(err)
    except Exception as err:  # noqa: BLE001 -- a bad file must not stop the batch
        status, reason = "failed", f"internal error: {type(err).__name__}: {err}"
    else:
        if result.code != 0:
            status = "refused" if result.code == 2 else "failed"
            reason = result.error or ""
    return _result(job, status, reason, time.perf_counter() - t0)


def _result(job: Job, status: str, reason: str, seconds: float | None) -> dict[str, Any]:
    ok = status in ("ok", "skipped")
    return {
        "file": job.rel,
        "status": status,
        "reason": " ".join(reason.split()),
        "seconds": None if seconds is None else round(seconds, 3),
        "input": job.src,
        "output": job.output if ok else None,
        "radius": job.radius if ok and Path(job.radius).exists() else None,
        "report": job.report if Path(job.report).exists() else None,
    }


_CRASH = "the worker process died (crash in native code, or killed)"


# --------------------------------------------------------------------------- runners

OnDone = Callable[[dict[str, Any]], None]
Worker = Callable[[Job], dict[str, Any]]


def run_local(jobs: list[Job], workers: int, on_done: OnDone, fn: Worker = process_file) -> None:
    """Run ``jobs`` on a pool of ``workers`` processes (spawned: no fork of OCC state).

    At most ``workers`` jobs are in flight, so when a worker dies only those are suspects:
    each is rerun alone in a fresh process (a crash there fails that file only), and the
    queue goes on in a new pool. ``fn`` (module-level, picklable) is run on each job.
    """
    ctx = multiprocessing.get_context("spawn")
    queue = deque(jobs)
    while queue:
        suspects: list[Job] = []
        pool = ProcessPoolExecutor(max_workers=min(workers, len(queue)), mp_context=ctx)
        running: dict[Future[dict[str, Any]], Job] = {}
        try:
            broken = False
            while running or (queue and not broken):
                while queue and not broken and len(running) < workers:
                    job = queue.popleft()
                    try:
                        running[pool.submit(fn, job)] = job
                    except BrokenProcessPool:
                        queue.appendleft(job)
                        broken = True
                if not running:
                    break
                done, _ = wait(running, return_when=FIRST_COMPLETED)
                for fut in done:
                    job = running.pop(fut)
                    try:
                        on_done(fut.result())
                    except BrokenProcessPool:
                        suspects.append(job)
                        broken = True
        except BaseException:
            _kill(pool)
            raise
        pool.shutdown(wait=True)
        if suspects:
            log.warning("a worker died; rerunning %d file(s) one per process", len(suspects))
            _run_isolated(suspects, ctx, on_done, fn)


def _run_isolated(jobs: list[Job], ctx: Any, on_done: OnDone, fn: Worker) -> None:
    """Each job in its own one-worker pool (all at once: at most ``--jobs`` of them)."""
    pools = [ProcessPoolExecutor(max_workers=1, mp_context=ctx) for _ in jobs]
    try:
        futures = [(job, pool.submit(fn, job)) for job, pool in zip(jobs, pools, strict=True)]
        for job, fut in futures:
            try:
                res = fut.result()
            except BrokenProcessPool:
                res = _result(job, "failed", _CRASH, None)
            on_done(res)
    except BaseException:
        for pool in pools:
            _kill(pool)
        raise
    for pool in pools:
        pool.shutdown(wait=True)


def _kill(pool: ProcessPoolExecutor) -> None:
    """Stop a pool now: cancel what is queued, terminate its workers."""
    procs = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for p in procs:
        p.terminate()


def run_dask(jobs: list[Job], address: str, on_done: OnDone) -> None:
    """Submit ``jobs`` to the Dask distributed scheduler at ``address``."""
    from dask.distributed import Client, as_completed

    with Client(address, timeout=30) as client:
        futures = {client.submit(process_file, job, pure=False): job for job in jobs}
        try:
            for fut in as_completed(list(futures)):
                job = futures[fut]
                try:
                    res = fut.result()
                except Exception as err:  # noqa: BLE001 -- KilledWorker, lost worker, ...
                    res = _result(job, "failed", f"dask: {type(err).__name__}: {err}", None)
                on_done(res)
        except BaseException:
            client.cancel(list(futures))
            raise


# --------------------------------------------------------------------------- output


def format_table(rows: list[dict[str, Any]]) -> str:
    """The final table: file, status, seconds, reason (one row per file)."""
    head = ("FILE", "STATUS", "SECONDS", "REASON")
    cells = [
        (
            r["file"],
            r["status"],
            "-" if r["seconds"] is None else f"{r['seconds']:.2f}",
            r["reason"] or "-",
        )
        for r in rows
    ]
    w0 = max(len(head[0]), *(len(c[0]) for c in cells)) if cells else len(head[0])
    w1 = max(len(head[1]), *(len(c[1]) for c in cells)) if cells else len(head[1])
    w2 = max(len(head[2]), *(len(c[2]) for c in cells)) if cells else len(head[2])
    lines = [f"{a:<{w0}}  {b:<{w1}}  {c:>{w2}}  {d}" for a, b, c, d in (head, *cells)]
    return "\n".join(lines)


def _counts(rows: list[dict[str, Any]]) -> dict[str, int]:
    counts = {"ok": 0, "skipped": 0, "refused": 0, "failed": 0}
    for r in rows:
        counts[r["status"]] = counts.get(r["status"], 0) + 1
    return counts


# --------------------------------------------------------------------------- main


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(
        prog="medialcad batch",
        description=_DESCRIPTION,
        epilog=_EPILOG,
        formatter_class=argparse.RawDescriptionHelpFormatter,
    )
    p.add_argument("in_dir", metavar="IN_DIR", help="folder searched recursively for STEP files")
    p.add_argument("-o", "--output", metavar="OUT_DIR", required=True, help="output folder")
    p.add_argument(
        "-j",
        "--jobs",
        metavar="N",
        type=int,
        default=None,
        help="parallel worker processes (default: the number of CPUs)",
    )
    p.add_argument(
        "--scheduler",
        metavar="ADDRESS",
        default=None,
        help="run on this Dask distributed scheduler (e.g. tcp://host:8786) instead of "
        "local processes; --jobs is then ignored. Its workers need medialcad installed and "
        "must see IN_DIR and OUT_DIR at the same paths",
    )
    p.add_argument(
        "--tol",
        metavar="T",
        type=float,
        default=None,
        help="absolute fit tolerance (default 1e-5 x each solid's bounding-box diagonal)",
    )
    p.add_argument(
        "--force", action="store_true", help="recompute files whose outputs are up to date"
    )
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    return p


def _one_line(text: object) -> str:
    return " ".join(str(text).split())


def main(argv: list[str] | None = None) -> int:
    """Entry point of ``medialcad batch``."""
    args = _parser().parse_args(argv)
    logging.basicConfig(level=logging.WARNING)
    try:
        return _run(args)
    except KeyboardInterrupt:
        print("medialcad batch: interrupted", file=sys.stderr)
        return 130
    except InputError as err:
        print(f"medialcad batch: error: {_one_line(err)}", file=sys.stderr)
        return 2
    except Exception as err:  # noqa: BLE001 -- one line, not a traceback
        print(f"medialcad batch: failed: {type(err).__name__}: {_one_line(err)}", file=sys.stderr)
        return 1


def _run(args: argparse.Namespace) -> int:
    from tqdm import tqdm  # type: ignore[import-untyped]

    from medialcad.occ.io import atomic_text

    t_start = time.perf_counter()
    in_dir, out_dir = Path(args.in_dir), Path(args.output)
    if not in_dir.is_dir():
        raise InputError(f"{in_dir}: no such folder")
    if args.tol is not None and not (math.isfinite(args.tol) and args.tol > 0):
        raise InputError(f"--tol must be a positive number, got {args.tol!r}")
    workers = args.jobs if args.jobs is not None else (os.cpu_count() or 1)
    if workers < 1:
        raise InputError(f"--jobs must be at least 1, got {workers}")
    if out_dir.exists() and not out_dir.is_dir():
        raise InputError(f"{out_dir}: exists and is not a folder")
    jobs = plan_jobs(find_inputs(in_dir, out_dir), in_dir, out_dir, args.tol)
    if not jobs:
        raise InputError(f"{in_dir}: no STEP files (*.step, *.stp) found")
    out_dir.mkdir(parents=True, exist_ok=True)

    rows: dict[str, dict[str, Any]] = {}
    todo = []
    for job in jobs:
        if not args.force and up_to_date(job):
            rows[job.rel] = _result(job, "skipped", "outputs up to date", None)
        else:
            todo.append(job)

    bar = tqdm(
        total=len(todo),
        unit="file",
        file=sys.stderr,
        disable=args.quiet or not sys.stderr.isatty() or not todo,
        dynamic_ncols=True,
    )

    def on_done(res: dict[str, Any]) -> None:
        rows[res["file"]] = res
        bar.set_postfix_str(f"{res['file']}: {res['status']}", refresh=False)
        bar.update(1)

    interrupted = False
    try:
        if todo:
            if args.scheduler:
                try:
                    run_dask(todo, args.scheduler, on_done)
                except (OSError, TimeoutError) as err:
                    raise MedialCadError(
                        f"cannot use the Dask scheduler {args.scheduler}: {err}"
                    ) from err
            else:
                run_local(todo, workers, on_done)
    except KeyboardInterrupt:
        interrupted = True
    finally:
        bar.close()

    ordered = [rows[j.rel] for j in jobs if j.rel in rows]
    counts = _counts(ordered)
    summary = {
        "format": BATCH_REPORT_FORMAT,
        "input_dir": str(in_dir.resolve()),
        "output_dir": str(out_dir.resolve()),
        "tol": args.tol,
        "runner": f"dask {args.scheduler}" if args.scheduler else f"{workers} local process(es)",
        "interrupted": interrupted,
        "seconds": round(time.perf_counter() - t_start, 3),
        "counts": counts,
        "files": ordered,
    }
    atomic_text(out_dir / BATCH_REPORT, json.dumps(summary, indent=2) + "\n")
    if interrupted:
        raise KeyboardInterrupt
    print(format_table(ordered))
    print(
        f"{len(ordered)} file(s): {counts['ok']} ok, {counts['skipped']} skipped, "
        f"{counts['refused']} refused, {counts['failed']} failed in {summary['seconds']:.1f} s; "
        f"report {out_dir / BATCH_REPORT}"
    )
    return 0 if counts["refused"] == counts["failed"] == 0 else 2


if __name__ == "__main__":  # pragma: no cover
    sys.exit(main())
