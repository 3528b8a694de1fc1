"""``loader-model fidelity --update``: only the calibrated steps and the machines' mean-and-scatter
study are recomputed; the other steps and the sign study are kept (fast: the runs are replaced)."""

from __future__ import annotations

import json

import pytest

from loader_model.cli import main
from loader_model.experiments import fidelity, machine_agreement
from loader_model.experiments.fidelity_report import shipped_budget

#: Scatter counts the replaced budget run reports (made up; the test follows them through).
COUNTS = {"scatter_within": 5, "both_within": 3, "held_out_scatter_within": 2}


@pytest.fixture
def previous(tmp_path, monkeypatch) -> tuple:
    budget = shipped_budget()
    path = tmp_path / "budget.json"
    path.write_text(json.dumps(budget), encoding="utf-8")
    ran: list[str] = []

    shipped = {step["label"]: step for step in budget["steps"]}

    def run_budget(steps, **options):
        ran.extend(step.label for step in steps)
        return [shipped[s.label] | COUNTS | {"fresh": options["trials"]} for s in steps]

    def run_machines(machines, trials, seed, jobs, progress):
        cells = {"9/empty/passive": {"both_share": 0.25}}
        return {"machines": machines, "trials": trials, "cells": cells}

    monkeypatch.setattr(fidelity, "run_budget", run_budget)
    monkeypatch.setattr(machine_agreement, "run_machines", run_machines)
    return path, budget, ran


def test_update_recomputes_the_calibrated_steps_only(previous, capsys) -> None:
    path, budget, ran = previous
    argv = ["fidelity", "--trials", "80", "--machines", "3", "--machine-trials", "2"]
    assert main([*argv, "--update", "--output", str(path), "--no-progress"]) == 0
    assert ran == ["+ calibrated to 9 km/h", "+ calibrated to 18 km/h"]
    updated = json.loads(path.read_text(encoding="utf-8"))
    assert [s["label"] for s in updated["steps"]] == [s["label"] for s in budget["steps"]]
    for old, new in zip(budget["steps"], updated["steps"], strict=True):
        assert new == (old | COUNTS | {"fresh": 80} if old["label"] in ran else old)
    assert updated["uncertainty"] == budget["uncertainty"]
    assert updated["machines"]["machines"] == 3 and updated["machines"]["trials"] == 2
    assert updated["command"] == budget["command"] and updated["date"] == budget["date"]
    assert len(updated["updates"]) == len(budget.get("updates", [])) + 1
    update = updated["updates"][-1]
    assert update["command"].endswith(
        "--machines 3 --machine-trials 2 --update calibrated,machines"
    )
    assert update["recomputed"] == [*ran, "machines"]


def test_update_of_the_machines_alone_keeps_every_step(previous, capsys) -> None:
    path, budget, ran = previous
    argv = ["fidelity", "--trials", "80", "--machines", "3", "--update", "machines"]
    assert main([*argv, "--output", str(path), "--no-progress"]) == 0
    updated = json.loads(path.read_text(encoding="utf-8"))
    assert not ran and updated["steps"] == budget["steps"]
    assert updated["machines"]["machines"] == 3
    assert updated["updates"][-1]["recomputed"] == ["machines"]
    argv = ["fidelity", "--trials", "80", "--update", "calibrated-18", "--output", str(path)]
    assert main([*argv, "--no-progress"]) == 0
    again = json.loads(path.read_text(encoding="utf-8"))
    assert again["machines"] == updated["machines"]
    assert len(again["updates"]) == len(budget.get("updates", [])) + 2
    assert ran == ["+ calibrated to 18 km/h"]
    assert main(["fidelity", "--update", "steps", "--output", str(path)]) == 2
    assert "--update 'steps': allowed: calibrated, calibrated-9" in capsys.readouterr().err


def test_update_needs_the_files_own_trials(previous, capsys) -> None:
    path, budget, ran = previous
    assert main(["fidelity", "--trials", "4", "--update", "--output", str(path)]) == 2
    assert "allowed: the same --trials 80 and --seed" in capsys.readouterr().err
    assert not ran and json.loads(path.read_text(encoding="utf-8")) == budget
    missing = path.with_name("none.json")
    assert main(["fidelity", "--trials", "80", "--update", "--output", str(missing)]) == 2
    assert f"--update: {missing} does not exist" in capsys.readouterr().err
    assert main(["fidelity", "--machines", "1", "--output", str(missing)]) == 2
    assert "--machines 1: allowed: an integer >= 2" in capsys.readouterr().err
