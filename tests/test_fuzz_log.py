"""The long fuzzing run's log (``MEDIALCAD_FUZZ_LOG``): every example is recorded as
passed, refused or failed, and a failure does not stop the run."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from medialcad.errors import ComputationError, NotExtrusionOrRevolutionError
from tests import faces as F


def _entries(path: Path) -> list[dict[str, object]]:
    return [json.loads(line) for line in path.read_text().splitlines()]


def test_without_the_log_a_failure_is_raised_and_the_shape_kept(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    monkeypatch.delenv("MEDIALCAD_FUZZ_LOG", raising=False)
    monkeypatch.setenv("MEDIALCAD_FAILED_FACES", str(tmp_path))
    with (
        pytest.raises(AssertionError),
        F.dump_on_failure(F.square(), "square", env="MEDIALCAD_FAILED_FACES"),
    ):
        raise AssertionError("soundness 3e-3 diag")
    assert len(list(tmp_path.glob("square-*.bbrep"))) == 1


def test_with_the_log_every_outcome_is_recorded_and_the_run_goes_on(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    log = tmp_path / "fuzz.jsonl"
    monkeypatch.setenv("MEDIALCAD_FUZZ_LOG", str(log))
    monkeypatch.setenv("MEDIALCAD_FAILED_SHAPES", str(tmp_path / "shapes"))
    face = F.square()
    with F.dump_on_failure(face, "ok"):
        pass
    with F.dump_on_failure(face, "refused"):
        raise NotExtrusionOrRevolutionError("face 7 (sphere)")
    with F.dump_on_failure(face, "internal"):
        raise ComputationError("the mid sheet's boundary does not close")
    with F.dump_on_failure(face, "wrong"):
        raise AssertionError("completeness 7.6e-3 diag")
    entries = _entries(log)
    assert [e["outcome"] for e in entries] == ["passed", "refused", "failed", "failed"]
    assert entries[2]["error"] == "ComputationError: the mid sheet's boundary does not close"
    assert entries[0]["shape"] is None
    assert all(Path(str(e["shape"])).exists() for e in entries[1:])


def test_hypothesis_control_flow_is_not_an_outcome(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from hypothesis.errors import UnsatisfiedAssumption

    log = tmp_path / "fuzz.jsonl"
    monkeypatch.setenv("MEDIALCAD_FUZZ_LOG", str(log))
    with pytest.raises(UnsatisfiedAssumption), F.dump_on_failure(F.square(), "assume"):
        raise UnsatisfiedAssumption()
    assert not log.exists() or not log.read_text()
