"""``medialcad batch``: a folder of STEP files, in parallel, resumable, crash-proof."""

from __future__ import annotations

import json
import os
import shutil
import signal
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from medialcad.batch import Job, find_inputs, main, plan_jobs, run_local

SOLIDS = Path(__file__).resolve().parent.parent / "fixtures" / "step" / "solids"
BROKEN = "ISO-10303-21; garbage"


def _batch(*args: object) -> subprocess.CompletedProcess[str]:
    return subprocess.run(
        [sys.executable, "-m", "medialcad", "batch", *map(str, args)],
        capture_output=True,
        text=True,
        check=False,
        timeout=600,
    )


def _table(stdout: str) -> dict[str, tuple[str, str]]:
    """``{file: (status, reason)}`` from the final table."""
    lines = stdout.splitlines()
    assert lines[0].split() == ["FILE", "STATUS", "SECONDS", "REASON"], stdout
    rows = {}
    for line in lines[1:-1]:
        file, status, _seconds, reason = line.split(maxsplit=3)
        rows[file] = (status, reason)
    return rows


def _hidden(folder: Path) -> list[Path]:
    return [p for p in folder.rglob(".*")]


@pytest.fixture(scope="module")
def first_run(
    tmp_path_factory: pytest.TempPathFactory,
) -> tuple[Path, subprocess.CompletedProcess[str]]:
    root = tmp_path_factory.mktemp("batch")
    src = root / "in"
    (src / "sub").mkdir(parents=True)
    shutil.copy(SOLIDS / "cylinder.step", src / "cylinder.step")
    shutil.copy(SOLIDS / "faces_only.step", src / "sub" / "faces_only.stp")
    shutil.copy(SOLIDS / "loft.step", src / "sub" / "loft.step")
    (src / "broken.step").write_text(BROKEN)
    (src / "notes.txt").write_text("not a STEP file: ignored")
    proc = _batch(src, "-o", root / "out", "--jobs", "2")
    return root, proc


def test_batch_table_outputs_and_exit_code(
    first_run: tuple[Path, subprocess.CompletedProcess[str]],
) -> None:
    root, proc = first_run
    out = root / "out"
    assert proc.returncode == 2, proc.stderr
    rows = _table(proc.stdout)
    assert {f: s for f, (s, _) in rows.items()} == {
        "broken.step": "failed",
        "cylinder.step": "ok",
        "sub/faces_only.stp": "ok",
        "sub/loft.step": "refused",
    }
    assert "could not be parsed" in rows["broken.step"][1]
    assert "neither an extrusion nor a revolution" in rows["sub/loft.step"][1]
    assert "1 failed" in proc.stdout.splitlines()[-1]
    assert proc.stderr == ""  # no progress bar without a terminal

    for name in ("cylinder.mat.step", "cylinder.radius.json", "cylinder.report.json"):
        assert (out / name).stat().st_size > 0, name
    report = json.loads((out / "cylinder.report.json").read_text())
    assert report["solids"][0]["status"] == "ok"
    assert (out / "sub" / "faces_only.mat.step").exists()
    assert not (out / "sub" / "faces_only.radius.json").exists()  # faces: no sidecar
    assert not (out / "sub" / "loft.mat.step").exists()  # refused: only its report
    assert json.loads((out / "sub" / "loft.report.json").read_text())["status"] == "refused"
    assert not list(out.glob("broken*"))
    assert _hidden(out) == []

    summary = json.loads((out / "batch_report.json").read_text())
    assert summary["counts"] == {"ok": 2, "skipped": 0, "refused": 1, "failed": 1}
    by_file = {f["file"]: f for f in summary["files"]}
    assert by_file["cylinder.step"]["output"] == str((out / "cylinder.mat.step").resolve())
    assert by_file["broken.step"]["output"] is None


def test_rerun_skips_up_to_date_files(
    first_run: tuple[Path, subprocess.CompletedProcess[str]],
) -> None:
    root, _ = first_run
    src, out = root / "in", root / "out"
    before = (out / "cylinder.mat.step").stat().st_mtime_ns
    # the 2D file was edited since: it is recomputed
    later = (out / "sub" / "faces_only.mat.step").stat().st_mtime + 10
    os.utime(src / "sub" / "faces_only.stp", (later, later))
    proc = _batch(src, "-o", out, "--jobs", "1")
    assert proc.returncode == 2, proc.stderr
    rows = _table(proc.stdout)
    assert rows["cylinder.step"] == ("skipped", "outputs up to date")
    assert rows["sub/faces_only.stp"][0] == "ok"
    assert rows["sub/loft.step"][0] == "refused"  # not a success: tried again
    assert rows["broken.step"][0] == "failed"
    assert (out / "cylinder.mat.step").stat().st_mtime_ns == before
    summary = json.loads((out / "batch_report.json").read_text())
    assert summary["counts"] == {"ok": 1, "skipped": 1, "refused": 1, "failed": 1}


def test_dask_scheduler(tmp_path: Path) -> None:
    from dask.distributed import LocalCluster

    src = tmp_path / "in"
    src.mkdir()
    shutil.copy(SOLIDS / "cylinder.step", src / "cylinder.step")
    (src / "broken.step").write_text(BROKEN)
    with LocalCluster(
        n_workers=1,
        threads_per_worker=1,
        processes=False,
        protocol="tcp",
        dashboard_address=None,
    ) as cluster:
        proc = _batch(src, "-o", tmp_path / "out", "--scheduler", cluster.scheduler_address)
    assert proc.returncode == 2, proc.stderr
    rows = _table(proc.stdout)
    assert rows["cylinder.step"][0] == "ok" and rows["broken.step"][0] == "failed"
    assert (tmp_path / "out" / "cylinder.mat.step").exists()
    summary = json.loads((tmp_path / "out" / "batch_report.json").read_text())
    assert summary["runner"].startswith("dask tcp://")


def _crashy(job: Job) -> dict[str, Any]:
    """Stands in for :func:`process_file`: segfaults on files named ``crash*``."""
    if Path(job.src).name.startswith("crash"):
        os.kill(os.getpid(), signal.SIGSEGV)
    return {"file": job.rel, "status": "ok", "reason": "", "seconds": 0.0}


def test_a_crashing_worker_fails_only_its_own_file(tmp_path: Path) -> None:
    names = ["a.step", "b.step", "crash.step", "c.step", "d.step", "e.step"]
    for n in names:
        (tmp_path / n).write_text(BROKEN)
    jobs = plan_jobs(find_inputs(tmp_path), tmp_path, tmp_path / "out")
    results: list[dict[str, Any]] = []
    run_local(jobs, 2, results.append, fn=_crashy)
    status = {r["file"]: r["status"] for r in results}
    assert status == {n: "failed" if n == "crash.step" else "ok" for n in names}
    (crash,) = (r for r in results if r["file"] == "crash.step")
    assert "worker process died" in crash["reason"]


def test_inputs_and_output_names(tmp_path: Path) -> None:
    src = tmp_path / "in"
    for rel in ["a.step", "b.STP", "dup.step", "dup.stp", "x/y/c.step", ".hidden.step"]:
        (src / rel).parent.mkdir(parents=True, exist_ok=True)
        (src / rel).write_text(BROKEN)
    (src / ".git").mkdir()
    (src / ".git" / "g.step").write_text(BROKEN)
    out = src / "out"  # inside the input folder: never read back as input
    (out / "old").mkdir(parents=True)
    (out / "old" / "a.mat.step").write_text(BROKEN)
    found = find_inputs(src, out)
    rels = [p.relative_to(src).as_posix() for p in found]
    assert rels == ["a.step", "b.STP", "dup.step", "dup.stp", "x/y/c.step"]
    jobs = {j.rel: j for j in plan_jobs(found, src, out, tol=0.01)}
    assert jobs["a.step"].output == str(out.resolve() / "a.mat.step")
    assert jobs["b.STP"].radius == str(out.resolve() / "b.radius.json")
    assert jobs["x/y/c.step"].report == str(out.resolve() / "x" / "y" / "c.report.json")
    assert jobs["dup.step"].output.endswith("dup.step.mat.step")  # same stem: keep suffix
    assert jobs["dup.stp"].output.endswith("dup.stp.mat.step")
    assert jobs["a.step"].tol == 0.01


def test_bad_arguments_exit_2(tmp_path: Path, capsys: pytest.CaptureFixture[str]) -> None:
    assert main([str(tmp_path / "nope"), "-o", str(tmp_path / "out")]) == 2
    assert "no such folder" in capsys.readouterr().err
    assert main([str(tmp_path), "-o", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err
    assert len(err.strip().splitlines()) == 1 and "no STEP files" in err
    assert main([str(tmp_path), "-o", str(tmp_path / "out"), "--jobs", "0"]) == 2
    assert not (tmp_path / "out").exists()
