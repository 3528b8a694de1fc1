"""Worker pools whose workers end with their parent (issue 19), interrupts as one line.

The parent-death tests run a small driver script as a real process, SIGKILL it and check that its
workers are gone within 5 s (a bound against hanging, polled; no timing is asserted).
"""

from __future__ import annotations

import ctypes
import signal
import subprocess
import sys
import textwrap
import time
from concurrent.futures.process import BrokenProcessPool

import pytest

from loader_model.cli import main
from loader_model.processes import (
    Interrupted,
    files_note,
    interrupt_message,
    interrupted,
    sigterm_interrupts,
    worker_pool,
)
from tests.process_scan import running, wait_until

pytestmark = pytest.mark.skipif(not sys.platform.startswith("linux"), reason="reads /proc")

DRIVER = """
import os, sys, time
from loader_model.processes import worker_pool

def pid_after(delay_s):
    time.sleep(delay_s)
    return os.getpid()

def busy():
    while True:  # Python bytecode: the GIL passes to the watchdog between them
        pass

if __name__ == "__main__":
    with worker_pool(2, death_signal={death_signal}) as pool:
        for future in [pool.submit(pid_after, 0.3) for _ in range(2)]:
            future.result()  # the workers have started (initializer run)
        print(*pool._processes, flush=True)
        pool.submit(time.sleep, 600)
        pool.submit(busy)
        time.sleep(600)
"""


@pytest.mark.parametrize("death_signal", [True, False], ids=["pdeathsig", "watchdog"])
def test_workers_end_when_the_parent_is_killed(tmp_path, death_signal: bool) -> None:
    script = tmp_path / "driver.py"
    script.write_text(textwrap.dedent(DRIVER.format(death_signal=death_signal)))
    parent = subprocess.Popen([sys.executable, str(script)], stdout=subprocess.PIPE, text=True)
    try:
        workers = [int(pid) for pid in parent.stdout.readline().split()]
        assert len(workers) == 2 and all(running(pid) for pid in workers)
        parent.kill()
        parent.wait()
        wait_until(lambda: not any(running(pid) for pid in workers), 5.0, "workers ended")
    finally:
        parent.kill()
        parent.wait()
        parent.stdout.close()


def _death_signal() -> int:
    """The signal Linux sends this process when its parent ends (PR_GET_PDEATHSIG; 0: none)."""
    value = ctypes.c_int()
    ctypes.CDLL(None).prctl(2, ctypes.byref(value), 0, 0, 0)
    return value.value


@pytest.mark.parametrize("death_signal", [None, False])
def test_workers_ignore_sigint_die_on_sigterm_and_on_parent_death(death_signal) -> None:
    with worker_pool(1, death_signal=death_signal) as pool:
        assert pool.submit(signal.getsignal, signal.SIGINT).result() == signal.SIG_IGN
        assert pool.submit(signal.getsignal, signal.SIGTERM).result() == signal.SIG_DFL
        expected = signal.SIGKILL if death_signal is None else 0  # made in the main thread
        assert pool.submit(_death_signal).result() == expected


def test_an_exception_in_the_block_stops_running_workers_at_once() -> None:
    with pytest.raises(KeyboardInterrupt), worker_pool(2) as pool:
        futures = [pool.submit(time.sleep, 60) for _ in range(3)]
        wait_until(lambda: sum(f.running() for f in futures) >= 1, 30.0, "a task running")
        processes = list(pool._processes.values())
        raise KeyboardInterrupt
    assert processes and not any(p.is_alive() for p in processes)
    for future in futures:  # cancelled if queued, broken if it was running: none finished
        assert future.cancelled() or isinstance(future.exception(timeout=30), BrokenProcessPool)


def test_a_normal_end_waits_for_the_results() -> None:
    with worker_pool(2) as pool:
        futures = [pool.submit(pow, 2, n) for n in range(5)]
    assert [f.result() for f in futures] == [1, 2, 4, 8, 16]


def test_sigterm_raises_an_interrupt_inside_the_block_only() -> None:
    before = signal.getsignal(signal.SIGTERM)
    with pytest.raises(Interrupted) as caught, sigterm_interrupts():
        signal.raise_signal(signal.SIGTERM)
    assert caught.value.signal_number == signal.SIGTERM
    assert signal.getsignal(signal.SIGTERM) is before


def test_interrupt_messages_and_exit_codes() -> None:
    assert interrupt_message(KeyboardInterrupt()) == ("interrupted; no partial file was left", 130)
    term = interrupted(Interrupted(signal.SIGTERM), "nothing written to 'out'")
    assert interrupt_message(term) == ("stopped by SIGTERM; nothing written to 'out'", 143)
    assert files_note(("a.toml", None, "b.png"), ["a.toml"]) == (
        "wrote 'a.toml'; nothing written to 'b.png'"
    )
    assert files_note((None,), []) == "nothing written"
    assert files_note(("a",), []) == "nothing written to 'a'"


def _interrupt_after(written_path: str | None):
    def run(args, written):
        if written_path is not None:
            written.append(getattr(args, written_path))
        raise KeyboardInterrupt

    return run


def test_design_and_identify_say_which_files_were_written(tmp_path, monkeypatch, capsys) -> None:
    from loader_model.commands import design_command, identify_command

    plot, settings = str(tmp_path / "f.png"), str(tmp_path / "g.toml")
    monkeypatch.setattr(design_command, "_design", _interrupt_after("output"))
    assert main(["design", "--output", settings, "--plot", plot]) == 130
    assert capsys.readouterr().err == (
        f"loader-model design: interrupted; wrote {settings!r}; nothing written to {plot!r}\n"
    )
    monkeypatch.setattr(identify_command, "_fit", _interrupt_after(None))
    assert main(["identify", "leakage", "x.csv", "--plot", plot]) == 130
    assert capsys.readouterr().err == (
        f"loader-model identify: interrupted; nothing written to {plot!r}\n"
    )
    monkeypatch.setattr(identify_command, "_synthesize", _interrupt_after("output"))
    assert main(["identify", "synthesize", settings]) == 130
    assert capsys.readouterr().err == f"loader-model identify: interrupted; wrote {settings!r}\n"


def test_an_interrupt_of_any_command_is_one_line(monkeypatch, capsys) -> None:
    from loader_model.commands import modes_command

    def stop(args):
        raise KeyboardInterrupt

    monkeypatch.setattr(modes_command, "run", stop)
    assert main(["modes"]) == 130
    assert capsys.readouterr().err == "loader-model modes: interrupted; no partial file was left\n"
