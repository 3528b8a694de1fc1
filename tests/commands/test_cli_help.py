"""The command line's help, usage errors, exit codes and version (the guide's command page)."""

from __future__ import annotations

import argparse
import re
from pathlib import Path

import pytest

import loader_model
from loader_model.cli import COMMANDS, EXIT_OUTSIDE_VALIDITY, EXIT_USAGE, build_parser, main
from loader_model.commands.check_design_command import EXIT_CHECK_FAILED

GUIDE = Path(__file__).resolve().parents[2] / "docs" / "guide"

#: What a user's help text must not show: reST markup, tracker numbers, development notes.
FORBIDDEN = re.compile(
    r"``|:(?:mod|func|class|meth|data|attr|ref):|\bissues? \d|\bsession\b|DESIGN\.md|README",
    re.IGNORECASE,
)


def _parsers() -> dict[str, argparse.ArgumentParser]:
    """Every (sub)command's parser by its command line, nested ones (identify friction) too."""
    found: dict[str, argparse.ArgumentParser] = {}

    def walk(name: str, parser: argparse.ArgumentParser) -> None:
        found[name] = parser
        for action in parser._actions:
            if isinstance(action, argparse._SubParsersAction):
                for sub_name, sub in action.choices.items():
                    walk(f"{name} {sub_name}", sub)

    walk("loader-model", build_parser())
    return found


PARSERS = _parsers()


def test_every_command_is_reached() -> None:
    assert {f"loader-model {name}" for name in COMMANDS} <= set(PARSERS)
    assert "loader-model identify friction" in PARSERS


@pytest.mark.parametrize("name", sorted(PARSERS))
def test_help_is_plain_text(name: str, capsys: pytest.CaptureFixture[str]) -> None:
    """--help of every (sub)command: no reST markup, issue numbers, sessions or files a user
    cannot open; its guide page exists; every option with a default shows it one way."""
    with pytest.raises(SystemExit) as exit_info:
        main([*name.split()[1:], "--help"])
    assert exit_info.value.code == 0
    text = capsys.readouterr().out
    assert FORBIDDEN.search(text) is None, FORBIDDEN.search(text)
    for page in re.findall(r"docs/guide/([\w-]+\.md)", text):
        assert (GUIDE / page).is_file(), page
    assert re.search(r"\(default \d|; default[: ]|\(\d+(\.\d+)?\)$", text, re.MULTILINE) is None
    for action in PARSERS[name]._actions:
        default = action.default
        if not action.option_strings or default in (None, argparse.SUPPRESS, []):
            continue
        if isinstance(default, bool) or action.help == argparse.SUPPRESS:
            continue
        option = action.option_strings[-1]
        options = text[text.index("\noptions:") :]
        entry = options[re.search(rf"\n  (-\w, )?{re.escape(option)}\b", options).start() + 1 :]
        entry = entry[: entry.find("\n  -") % (len(entry) + 1)]  # to the next option or the end
        assert "(default: " in " ".join(entry.split()), (name, option)


@pytest.mark.parametrize("name", sorted(f"loader-model {name}" for name in COMMANDS))
def test_each_command_points_to_its_guide_page(name: str, capsys) -> None:
    with pytest.raises(SystemExit):
        main([*name.split()[1:], "--help"])
    assert re.search(r"Guide: docs/guide/[\w-]+\.md", capsys.readouterr().out)


def test_one_name_per_concept() -> None:
    """Worker processes are --jobs and the progress bar --no-progress wherever they exist."""
    for name, parser in PARSERS.items():
        options = {option for action in parser._actions for option in action.option_strings}
        visible = {
            option
            for action in parser._actions
            if action.help != argparse.SUPPRESS
            for option in action.option_strings
        }
        assert "--workers" not in visible and "--processes" not in visible, name
        if "--jobs" in options or "--simulate" in options or name.endswith(("bound", "design")):
            assert "--no-progress" in options, name


def test_a_misspelt_option_prints_the_subcommand_usage(capsys) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["simulate", "--sped", "9"])
    assert exit_info.value.code == EXIT_USAGE
    error = capsys.readouterr().err
    assert error.startswith("usage: loader-model simulate ")
    assert "unrecognized arguments: --sped 9 (did you mean --speed?)" in error


def test_a_misspelt_option_of_a_nested_command_names_it(capsys) -> None:
    with pytest.raises(SystemExit) as exit_info:
        main(["identify", "friction", "data.csv", "--plt", "fit.png"])
    assert exit_info.value.code == EXIT_USAGE
    error = capsys.readouterr().err
    assert error.startswith("usage: loader-model identify friction ")
    assert "(did you mean --plot?)" in error


def test_bad_input_is_exit_code_2_with_one_line(capsys) -> None:
    assert main(["simulate", "--speed", "-1"]) == EXIT_USAGE
    error = capsys.readouterr().err
    assert error == "loader-model simulate: error: --speed must be in (0, 40] km/h; got -1.0\n"


def test_exit_codes_are_distinct_and_documented() -> None:
    assert (EXIT_USAGE, EXIT_OUTSIDE_VALIDITY, EXIT_CHECK_FAILED) == (2, 3, 4)
    page = (GUIDE / "commands.md").read_text(encoding="utf-8")
    for code in (0, 1, EXIT_USAGE, EXIT_OUTSIDE_VALIDITY, EXIT_CHECK_FAILED, 130, 143):
        assert re.search(rf"^\| `{code}` \|", page, re.MULTILINE), code


def test_version_is_the_package_s(capsys) -> None:
    from importlib import metadata

    with pytest.raises(SystemExit) as exit_info:
        main(["--version"])
    assert exit_info.value.code == 0
    assert capsys.readouterr().out == f"loader-model {metadata.version('loader-model')}\n"
    assert loader_model.__version__ == metadata.version("loader-model")


def test_the_former_workers_option_still_runs_as_jobs() -> None:
    args = build_parser().parse_args(["robustness", "study.toml", "--workers", "3"])
    assert args.jobs == 3
