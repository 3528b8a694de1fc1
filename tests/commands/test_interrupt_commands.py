"""``reproduce`` and ``robustness`` interrupted as real processes (issue 19, item 3).

Each command runs in its own session (``start_new_session``: its process group is its pid), so
Ctrl-C is what a terminal sends: SIGINT to the whole group. A test waits until the command's pool
workers run (they ignore SIGINT once started), then signals. After SIGINT (or SIGTERM): one line
on stderr, no traceback, exit 130 (143), nothing written, no staging entry left, no process of the
group left. After SIGKILL of the command: none of its processes left within 5 s, and the next run
removes the staging entries it left. Waits are bounds against hanging (polled), never measured.
"""

from __future__ import annotations

import os
import signal
import subprocess
import sys
from pathlib import Path

import pytest

from loader_model.io import staging
from tests.process_scan import command_line, group_members, ignores_sigint, wait_until

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")

#: A study far longer than the tests let it run (5000 samples of 30 s).
STUDY = """
[study]
name = "interrupted"
seed = 1
samples = 5000
duration_s = 30.0
batch_size = 1
[conditions]
speeds_kmh = [18.0]
[controllers]
compare = ["passive"]
[parameters]
"hydraulics.bulk_modulus" = { distribution = "uniform", low = 0.8e9, high = 1.8e9, unit = "Pa" }
"""


class Command:
    """A ``loader-model`` run in its own session; stderr goes to a file (workers inherit it)."""

    def __init__(self, tmp_path: Path, *arguments: str) -> None:
        self.stderr_path = tmp_path / f"stderr-{len(list(tmp_path.glob('stderr-*')))}.txt"
        with open(self.stderr_path, "wb") as stderr:
            self.process = subprocess.Popen(
                [sys.executable, "-m", "loader_model.cli", *arguments],
                stdout=subprocess.DEVNULL,
                stderr=stderr,
                start_new_session=True,
            )
        self.pgid = self.process.pid

    def workers(self) -> list[int]:
        """Pool workers that have started (ignore SIGINT; not multiprocessing's tracker)."""
        return [
            pid
            for pid in group_members(self.pgid)
            if ignores_sigint(pid) and "resource_tracker" not in command_line(pid)
        ]

    def wait_for_workers(self, count: int) -> list[int]:
        def started() -> list[int]:
            assert self.process.poll() is None, self.stderr()
            return self.workers() if len(self.workers()) >= count else []

        return wait_until(started, 120.0, "the command's workers started")

    def end(self, number: int) -> int:
        """Send signal ``number`` (SIGINT to the group, as a terminal does) and wait; the exit
        code. Then wait until no process of the group is left."""
        if number == signal.SIGINT:
            os.killpg(self.pgid, number)
        else:
            os.kill(self.process.pid, number)
        code = self.process.wait(timeout=60)
        wait_until(lambda: not group_members(self.pgid), 5.0, "no process of the command left")
        return code

    def stderr(self) -> str:
        return self.stderr_path.read_text(encoding="utf-8", errors="replace")

    def close(self) -> None:
        if self.process.poll() is None:
            os.killpg(self.pgid, signal.SIGKILL)
            self.process.wait()
        for pid in group_members(self.pgid):
            os.kill(pid, signal.SIGKILL)


@pytest.fixture
def commands(tmp_path: Path):
    started: list[Command] = []

    def start(*arguments: str) -> Command:
        started.append(Command(tmp_path, *arguments))
        return started[-1]

    yield start
    for command in started:
        command.close()


def _hidden(folder: Path) -> list[str]:
    return sorted(p.name for p in folder.rglob(".*"))


def _reproduce(output: Path) -> tuple[str, ...]:
    return ("reproduce", "--output", str(output), "--trials", "2", "--jobs", "2", "--no-progress")


@pytest.mark.parametrize(
    "number",
    [signal.SIGINT, pytest.param(signal.SIGTERM, marks=pytest.mark.slow)],  # 4-4.5 s each
    ids=["SIGINT", "SIGTERM"],
)
def test_interrupted_reproduce_says_so_in_one_line(tmp_path: Path, commands, number) -> None:
    output = tmp_path / "out" / "report"
    run = commands(*_reproduce(output))
    run.wait_for_workers(2)
    assert run.end(number) == 128 + number
    what = "interrupted" if number == signal.SIGINT else "stopped by SIGTERM"
    assert run.stderr() == f"loader-model reproduce: {what}; nothing written to {str(output)!r}\n"
    assert list((tmp_path / "out").iterdir()) == []


# slow: 7 s (a reproduce killed and run again; SIGINT and SIGTERM stay in the fast suite)
@pytest.mark.slow
def test_killed_reproduce_leaves_no_process_and_the_next_run_cleans_up(
    tmp_path: Path, commands
) -> None:
    output = tmp_path / "out" / "report"
    first = commands(*_reproduce(output))
    first.wait_for_workers(2)
    assert first.end(signal.SIGKILL) == -signal.SIGKILL  # end() waits for its workers' end
    (left,) = _hidden(tmp_path / "out")
    assert left.startswith(f".report.tmp-{staging.staging_prefix('x').split('-')[1]}-{first.pgid}-")
    second = commands(*_reproduce(output))
    second.wait_for_workers(2)  # past the start of the report: the stale folder is removed
    (own,) = _hidden(tmp_path / "out")
    assert own.startswith(".report.tmp-") and f"-{second.pgid}-" in own
    assert second.end(signal.SIGINT) == 130
    assert "Traceback" not in second.stderr() and len(second.stderr().splitlines()) == 1
    assert list((tmp_path / "out").iterdir()) == []


def _robustness(tmp_path: Path, output: Path) -> tuple[str, ...]:
    study = tmp_path / "study.toml"
    study.write_text(STUDY, encoding="utf-8")
    return ("robustness", str(study), "--output", str(output), "--jobs", "2", "--no-progress")


def test_interrupted_robustness_says_what_is_saved(tmp_path: Path, commands) -> None:
    output = tmp_path / "results"
    run = commands(*_robustness(tmp_path, output))
    run.wait_for_workers(2)
    assert run.end(signal.SIGINT) == 130
    text = run.stderr()
    saved = len(list((output / "parts").glob("part-*.parquet")))
    assert text == (
        f"loader-model robustness: interrupted; {saved} of 5000 samples are saved in "
        f"{str(output / 'parts')!r}; run the same command again to resume\n"
    )
    assert _hidden(output) == []


@pytest.mark.slow  # 5.7 s: a study started, killed and started again
def test_killed_robustness_leaves_no_process_and_the_next_run_cleans_up(
    tmp_path: Path, commands
) -> None:
    output = tmp_path / "results"
    first = commands(*_robustness(tmp_path, output))
    first.wait_for_workers(2)
    assert first.end(signal.SIGKILL) == -signal.SIGKILL  # end() waits for its workers' end
    host = staging.staging_prefix("x").split("-")[1]
    stale = output / "parts" / f".part-00000007.parquet.tmp-{host}-{first.pgid}-ab_cd012.parquet"
    stale.write_bytes(b"half")  # as if killed while writing a part
    second = commands(*_robustness(tmp_path, output))
    second.wait_for_workers(2)
    assert not stale.exists()
    assert second.end(signal.SIGINT) == 130
    assert "Traceback" not in second.stderr() and len(second.stderr().splitlines()) == 1
    assert _hidden(output) == []
