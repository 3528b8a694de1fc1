"""Staging entries (issue 19): named after their process, removed by the next run only when that
process has ended on this host; report folders and files get the umask's permissions."""

from __future__ import annotations

import os
import stat
import subprocess
import sys
from pathlib import Path

import pytest

from loader_model.experiments.report import write_report
from loader_model.io import staging
from loader_model.io.export import write_atomically

HOST = staging.staging_prefix("x").split("-")[1]


def _ended_pid() -> int:
    """The pid of a process that has ended and been reaped."""
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    process.wait()
    return process.pid


@pytest.fixture
def live_pid():
    """The pid of another running process."""
    process = subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)"])
    yield process.pid
    process.kill()
    process.wait()


def _entry(folder: Path, name: str, pid: int, host: str = HOST, kind: str = "tmp") -> Path:
    path = folder / f".{name}.{kind}-{host}-{pid}-ab_cd012"
    path.mkdir()
    (path / "report.md").write_text("half")
    return path


def test_the_prefix_names_result_host_and_process() -> None:
    assert staging.staging_prefix("report") == f".report.tmp-{HOST}-{os.getpid()}-"
    assert staging.staging_prefix("report", "old").startswith(".report.old-")
    with pytest.raises(ValueError, match=r"kind must be one of \['tmp', 'old'\]; got 'new'"):
        staging.staging_prefix("report", "new")


def test_only_entries_of_ended_processes_of_this_host_are_removed(tmp_path: Path, live_pid) -> None:
    dead = _ended_pid()
    stale = [_entry(tmp_path, "report", dead), _entry(tmp_path, "report", dead, kind="old")]
    stale_file = tmp_path / f".g.toml.tmp-{HOST}-{dead}-zz99zz99.toml"
    stale_file.write_text("half")
    kept = [
        _entry(tmp_path, "report", os.getpid()),  # this process: a write under way
        _entry(tmp_path, "report", live_pid),  # a concurrent run
        _entry(tmp_path, "report", dead, host="0123abcd" if HOST != "0123abcd" else "0123abce"),
        _entry(tmp_path, "other", dead),  # another result's (name given below)
    ]
    for name in (".report.tmp-k2j3l4m5", "report", ".report.tmp-x-1-ab_cd012", ".report.tmp-"):
        (tmp_path / name).mkdir()  # an old unnamed staging folder, the report, near misses
        kept.append(tmp_path / name)
    removed = staging.remove_stale(tmp_path, "report")
    assert sorted(removed) == sorted(stale)
    assert staging.remove_stale(tmp_path, "g.toml") == [stale_file]
    assert sorted(p for p in tmp_path.iterdir()) == sorted(kept)
    assert staging.remove_stale(tmp_path) == [tmp_path / f".other.tmp-{HOST}-{dead}-ab_cd012"]


def test_a_zombie_owner_has_ended(tmp_path: Path) -> None:
    process = subprocess.Popen([sys.executable, "-c", "pass"])
    os.waitid(os.P_PID, process.pid, os.WEXITED | os.WNOWAIT)  # ended, not reaped: a zombie
    try:
        entry = _entry(tmp_path, "report", process.pid)
        assert staging.is_stale(entry.name, "report")
    finally:
        process.wait()


def test_a_stale_link_is_removed_not_followed(tmp_path: Path) -> None:
    target = tmp_path / "elsewhere"
    target.mkdir()
    (target / "keep.txt").write_text("keep")
    link = tmp_path / f".report.tmp-{HOST}-{_ended_pid()}-ab_cd012"
    link.symlink_to(target, target_is_directory=True)
    assert staging.remove_stale(tmp_path, "report") == [link]
    assert (target / "keep.txt").read_text() == "keep"


def test_a_missing_folder_has_nothing_to_remove(tmp_path: Path) -> None:
    assert staging.remove_stale(tmp_path / "missing") == []


@pytest.mark.parametrize("umask", [0o022, 0o027, 0o002, 0o077])
def test_the_umask_is_read_without_changing_it(umask: int) -> None:
    old = os.umask(umask)
    try:
        assert staging.current_umask() == umask
        assert staging.current_umask() == umask
    finally:
        os.umask(old)


@pytest.mark.parametrize("umask", [0o022, 0o027, 0o002])
def test_report_folder_and_files_get_the_umask_permissions(tmp_path: Path, umask: int) -> None:
    seen = []

    def build(folder: Path) -> None:
        seen.append(stat.S_IMODE(folder.stat().st_mode))
        (folder / "report.md").write_text("complete\n")

    old = os.umask(umask)
    try:
        for _ in range(2):  # a new report, then one replacing it
            target = write_report(tmp_path / "results" / "report", build)
    finally:
        os.umask(old)
    assert seen == [0o777 & ~umask] * 2
    assert stat.S_IMODE(target.stat().st_mode) == 0o777 & ~umask
    assert stat.S_IMODE((target / "report.md").stat().st_mode) == 0o666 & ~umask
    assert [p.name for p in target.parent.iterdir()] == ["report"]


def test_write_report_removes_stale_staging_not_live(tmp_path: Path, live_pid) -> None:
    stale = _entry(tmp_path, "report", _ended_pid())
    live = _entry(tmp_path, "report", live_pid)
    names = []
    write_report(tmp_path / "report", lambda folder: names.append(folder.name))
    assert not stale.exists() and live.exists()
    assert names[0].startswith(staging.staging_prefix("report"))
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["report", live.name])


def test_interrupted_report_leaves_no_staging_folder(tmp_path: Path) -> None:
    def interrupted(folder: Path) -> None:
        (folder / "report.md").write_text("half")
        raise KeyboardInterrupt

    with pytest.raises(KeyboardInterrupt):
        write_report(tmp_path / "report", interrupted)
    assert list(tmp_path.iterdir()) == []


def test_write_atomically_names_its_temporary_and_removes_stale_ones(tmp_path: Path) -> None:
    dead = _ended_pid()
    stale = tmp_path / f".g.toml.tmp-{HOST}-{dead}-ab_cd012.toml"
    other = tmp_path / f".h.toml.tmp-{HOST}-{dead}-ab_cd012.toml"
    for path in (stale, other):
        path.write_text("half")
    names = []

    def write(path: Path) -> None:
        names.append(path.name)
        path.write_text("x = 1\n")

    write_atomically(tmp_path / "g.toml", write, (".toml",))
    assert names[0].startswith(staging.staging_prefix("g.toml")) and names[0].endswith(".toml")
    assert sorted(p.name for p in tmp_path.iterdir()) == sorted(["g.toml", other.name])
    write_atomically(tmp_path / "h.toml", write, (".toml",), remove_stale=False)
    assert other.exists()
