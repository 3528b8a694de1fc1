"""Fuzz run over every parameter field and every CLI option (issue 9, "Must show").

``python -m tests.fuzz_cli`` runs each bad input through ``loader_model.cli.main`` in this
process and classifies the outcome:

- clear: exit code 2, a message on stderr that names the field, option or file, no traceback,
  and no output file created or changed;
- unnamed: exit 2 but the message names none of them;
- traceback: an exception escaped ``main``;
- silent: exit 0 for an input outside the field's range or of the wrong type;
- hang: no answer within the time limit;
- valid: exit 0 for an input that is in fact valid (a value inside the range, a BOM file).

It prints the counts per class and the failures, and exits 1 if any input was not handled.
"""

from __future__ import annotations

import contextlib
import io
import math
import os
import signal
import sys
import tempfile
import tomllib
from collections import Counter
from collections.abc import Callable
from pathlib import Path

import numpy as np

from loader_model.cli import main
from loader_model.parameters.schema import BucketLoad, LoaderParameters
from loader_model.parameters.toml_format import iter_leaves, leaf_metadata
from tests.mutations import (
    BAD_VALUES,
    LOAD_TEXT,
    LOADER_PATHS,
    LOADER_TEXT,
    mutate_leaf,
    valid_csv_rows,
    write_csv,
)

TIME_LIMIT_S = 60


class _Timeout(Exception):
    pass


def _alarm(signum: int, frame: object) -> None:
    raise _Timeout


def run(argv: list[str], watch: list[Path]) -> tuple[str, str]:
    """Run ``main(argv)``; return (kind, stderr) with kind exit code text, 'traceback' or 'hang'."""
    before = {p: (p.read_bytes() if p.is_file() else None) for p in watch}
    err = io.StringIO()
    signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(TIME_LIMIT_S)
    try:
        with contextlib.redirect_stderr(err), contextlib.redirect_stdout(io.StringIO()):
            code = main(argv)
    except SystemExit as exit_:
        code = exit_.code
    except _Timeout:
        return "hang", err.getvalue()
    except Exception as error:  # this is what is being counted
        return "traceback", f"{type(error).__name__}: {error}"
    finally:
        signal.alarm(0)
    after = {p: (p.read_bytes() if p.is_file() else None) for p in watch}
    if code != 0 and after != before:
        return "partial", err.getvalue()
    return str(code), err.getvalue()


def classify(kind: str, stderr: str, names: list[str], valid: bool) -> str:
    if kind in ("hang", "traceback", "partial"):
        return kind
    if kind == "0":
        return "valid" if valid else "silent"
    if "Traceback" in stderr:
        return "traceback"
    return "clear" if any(name in stderr for name in names) else "unnamed"


def _in_range(path: str, literal: str, cls: type) -> bool:
    """Whether a TOML literal is a valid value of the field (type, shape and range)."""
    leaf = {p: (c, n) for p, c, n in iter_leaves(cls)}[path]
    meta = leaf_metadata(*leaf)
    value = tomllib.loads(f"v = {literal}")["v"]
    items = value if meta["shape"] else [value]
    if meta["shape"] and (not isinstance(value, list) or len(value) != meta["shape"]):
        return False
    for item in items:
        if isinstance(item, bool) or not isinstance(item, int | float):
            return False
        if meta["integer"] and not isinstance(item, int):
            return False
        try:
            if not meta["allowed"].contains(float(item)):
                return False
        except OverflowError:
            return False
    return True


def field_cases(folder: Path) -> list[tuple[list[str], list[str], bool, list[Path]]]:
    """(argv, names the message may use, valid input?, files to watch) per field and value."""
    cases = []
    export = folder / "good.npz"
    for path in LOADER_PATHS:
        for literal in BAD_VALUES:
            file = folder / f"{path}.{BAD_VALUES.index(literal)}.toml"
            file.write_text(mutate_leaf(LOADER_TEXT, path, literal), encoding="utf-8")
            valid = _in_range(path, literal, LoaderParameters)
            names = [path, path.rsplit(".", 1)[0]] if path.count(".") > 1 else [path]
            for command in ("model", "modes"):
                argv = [command, "--params", str(file)]
                argv += ["--export", str(export)] if command == "model" else []
                cases.append((argv, names, valid, [export]))
    for path in (p for p, _, _ in iter_leaves(BucketLoad)):
        for literal in BAD_VALUES:
            file = folder / f"load.{path}.{BAD_VALUES.index(literal)}.toml"
            file.write_text(mutate_leaf(LOAD_TEXT, path, literal), encoding="utf-8")
            valid = _in_range(path, literal, BucketLoad)
            for command in ("model", "modes"):
                cases.append(([command, "--load", str(file)], [path], valid, []))
    for path in LOADER_PATHS[:: max(1, len(LOADER_PATHS) // 8)]:
        file = folder / f"unit.{path}.toml"
        file.write_text(mutate_leaf(LOADER_TEXT, path, '"furlong"', key="unit"), encoding="utf-8")
        cases.append((["model", "--params", str(file)], [path], False, []))
    return cases


def _files(folder: Path) -> dict[str, Path]:
    good = folder / "good_loader.toml"
    good.write_text(LOADER_TEXT, encoding="utf-8")
    paths = {
        "dir": folder / "adir.toml",
        "fifo": folder / "fifo.toml",
        "missing": folder / "no.toml",
    }
    paths["dir"].mkdir()
    os.mkfifo(paths["fifo"])
    (folder / "latin1.toml").write_bytes(LOADER_TEXT.encode().replace(b"standard", b"\xe4"))
    (folder / "binary.toml").write_bytes(bytes(range(256)) * 4)
    (folder / "empty.toml").write_text("", encoding="utf-8")
    (folder / "syntax.toml").write_text("[chassis\nmass = 1\n", encoding="utf-8")
    (folder / "bom.toml").write_bytes(b"\xef\xbb\xbf" + LOADER_TEXT.encode())
    (folder / "crlf.toml").write_bytes(LOADER_TEXT.replace("\n", "\r\n").encode())
    (folder / "load_as_loader.toml").write_text(LOAD_TEXT, encoding="utf-8")
    return paths


def _csv_files(folder: Path) -> dict[str, tuple[Path, bool]]:
    rows = valid_csv_rows()
    out: dict[str, tuple[Path, bool]] = {}

    def make(name: str, table: list[list[str]], valid: bool = False) -> None:
        out[name] = (write_csv(folder / f"{name}.csv", table), valid)

    make("good", rows, True)
    make("header_only", rows[:1])
    make("unknown_column", [["time", "x", "heave"], *rows[1:]])
    make("duplicate", [["time", "x", "x"], *rows[1:]])
    make("no_time", [["t", "x", "z"], *rows[1:]])
    make("short", rows[:5])
    # a sensor that recorded no vibration and Unix time stamps are ordinary files (issue 19)
    make("zero_axis", [rows[0]] + [[r[0], "0", r[2]] for r in rows[1:]], True)
    make("unix_time", [rows[0]] + [[f"17{float(r[0]):012.3f}", *r[1:]] for r in rows[1:]], True)
    make("backwards", [rows[0], *reversed(rows[1:])])
    make("slow_rate", [rows[0]] + [[f"{i / 150:.4f}", r[1], r[2]] for i, r in enumerate(rows[1:])])
    make(
        "jitter",
        [rows[0]]
        + [
            [f"{float(r[0]) + (0.002 if i == 50 else 0):.3f}", r[1], r[2]]
            for i, r in enumerate(rows[1:])
        ],
    )
    for cell in ("nan", "inf", "1e200", "-1e300", "x", "", "1;2", "0x10"):
        for column in (0, 1, 2):
            table = [list(r) for r in rows]
            table[40][column] = cell
            make(f"cell_{column}_{cell or 'empty'}", table)
    table = [list(r) for r in rows]
    table[40].append("1")
    make("extra_value", table)
    bom = folder / "bom.csv"
    bom.write_bytes(b"\xef\xbb\xbf" + (folder / "good.csv").read_bytes())
    crlf = folder / "crlf.csv"
    crlf.write_bytes((folder / "good.csv").read_bytes().replace(b"\n", b"\r\n"))
    latin = folder / "latin1.csv"
    latin.write_bytes((folder / "good.csv").read_bytes() + b"# \xe4\n")
    out |= {"bom": (bom, True), "crlf": (crlf, True), "latin1": (latin, False)}
    return out


def option_cases(folder: Path) -> list[tuple[list[str], list[str], bool, list[Path]]]:
    paths = _files(folder)
    csvs = _csv_files(folder)
    good_csv = str(csvs["good"][0])
    target = folder / "existing.npz"
    target.write_bytes(b"good file")
    (folder / "sub.npz").mkdir()
    (folder / "plotdir.png").mkdir()
    os.mkfifo(folder / "fifo.npz")
    cases = []
    param_inputs = {
        "''": "",
        "dir": str(paths["dir"]),
        "fifo": str(paths["fifo"]),
        "missing": str(paths["missing"]),
        **{
            name: str(folder / f"{name}.toml")
            for name in ("latin1", "binary", "empty", "syntax", "load_as_loader")
        },
    }
    for command in ("model", "modes", "calibrate"):
        for value in param_inputs.values():
            names = ["--params", "loader parameter file", value or "''"]
            cases.append(([command, "--params", value], names, False, [target]))
        for name in ("bom", "crlf"):
            if command != "calibrate":
                cases.append(([command, "--params", str(folder / f"{name}.toml")], [], True, []))
        for name, value in {**param_inputs, "case": "heavy"}.items():
            names = ["load", value or "''"]
            # a load file given as --params is refused; as --load it is valid
            cases.append(([command, "--load", value], names, name == "load_as_loader", []))
    for value in (
        "",
        str(folder),
        str(folder / "sub.npz"),
        str(folder / "x" / "m.npz"),
        str(folder / "m.txt"),
        str(folder / "fifo.npz"),
        str(folder / "m"),
    ):
        cases.append((["model", "--export", value], ["--export"], False, [target]))
    for value in (
        "",
        str(folder),
        str(folder / "c.npz"),
        str(folder / "x" / "c.toml"),
        str(folder / "sub.npz"),
        str(folder / "c.TOM"),
    ):
        cases.append((["calibrate", "--output", value], ["--output"], False, [target]))
    for path, valid in csvs.values():
        cases.append((["iso2631", str(path)], [path.name], valid, []))
    for name, value in param_inputs.items():
        cases.append(
            (
                ["iso2631", value.replace(".toml", ".csv") if name == "missing" else value],
                ["vibration CSV file", value or "''"],
                False,
                [],
            )
        )
    options = {
        "--weighting": ["z=Wb", "roll=We", "z", "z=", "=Wk", "heave=Wk"],
        "--k-factor": ["z=nan", "z=inf", "z=-1", "z=1e300", "z=x", "yaw=1", "z=3"],
        "--integration-time": ["0", "-1", "nan", "inf", "1e300", "x", "100", "1e-300"],
        "--running-rms": ["median", ""],
        "--exposure-hours": ["0", "-1", "nan", "inf", "1e300", "25", "x"],
        "--plot-weightings": [
            "",
            str(folder / "plotdir.png"),
            str(folder / "w.jpg"),
            str(folder / "x" / "w.png"),
            str(folder / "sub.npz"),
        ],
    }
    for option, values in options.items():
        for value in values:
            names = [
                option,
                option.strip("-").replace("-", "_"),
                "k_factors",
                "weightings",
                "weighting",
                "integration_time_s",
            ]
            cases.append((["iso2631", good_csv, option, value], names, False, [target]))
    cases.append(
        (
            ["iso2631", good_csv, "--weighting", "z=Wk", "--weighting", "z=Wd"],
            ["--weighting"],
            False,
            [],
        )
    )
    cases.append((["iso2631"], ["DATA.csv"], False, []))
    return cases


API_VALUES: list[object] = [
    0,
    -1.0,
    1e-300,
    1e30,
    1e300,
    10**400,
    math.nan,
    math.inf,
    True,
    "1",
    1j,
    [1.0, 2.0],
    None,
]


def _api_call(call: Callable[[], object], names: list[str], valid: bool) -> str:
    """Classify one API call: ValueError naming one of ``names`` is clear."""
    signal.signal(signal.SIGALRM, _alarm)
    signal.alarm(TIME_LIMIT_S)
    try:
        result = call()
    except ValueError as error:
        return "clear" if any(name in str(error) for name in names) else "unnamed"
    except _Timeout:
        return "hang"
    except Exception:  # this is what is being counted
        return "traceback"
    finally:
        signal.alarm(0)
    finite = all(np.all(np.isfinite(np.asarray(v, dtype=float))) for v in _arrays(result))
    if not finite:
        return "nan"
    return "valid" if valid else "silent"


def _plausible(value: object, allowed: object) -> bool:
    if isinstance(value, bool) or not isinstance(value, int | float):
        return False
    try:
        number = float(value)
    except OverflowError:
        return False
    return math.isfinite(number) and allowed.contains(number)  # type: ignore[attr-defined]


def _arrays(result: object) -> list[object]:
    if isinstance(result, dict):
        return list(result.values())
    if hasattr(result, "A"):
        return [result.A, result.B, result.C]
    return [] if result is None or not isinstance(result, np.ndarray | float) else [result]


def api_cases() -> list[tuple[str, str]]:
    """(argument, outcome) of every model parameter and method argument with bad values."""
    from loader_model.parameters.model_checks import MODEL_PARAMETER_RANGES
    from loader_model.parameters.sets import bucket_load, default_loader, model_parameter_values
    from loader_model.vehicle.dynamics import LoaderDynamics

    good = model_parameter_values(default_loader(), bucket_load("empty"))
    model = LoaderDynamics(good)
    outcomes = []
    for name in good:
        for value in API_VALUES:
            if _plausible(value, MODEL_PARAMETER_RANGES[name]) or (name == "g" and value == 0):
                continue  # in range (g = 0: the documented analysis without gravity)
            outcome = _api_call(
                lambda n=name, v=value: LoaderDynamics(good | {n: v}), [name], False
            )
            outcomes.append((f"LoaderDynamics({name}=...)", outcome))
    shapes = {"p": 4, "pd": 4, "force_N": 1, "road_m": 4, "road_rate_m_s": 4, "disturbance": 3}
    for argument, size in shapes.items():
        for value in API_VALUES:
            bad = value if size == 1 else [value] + [0.0] * (size - 1)
            if not isinstance(value, bool) and value in (0, -1.0, 1e-300):
                continue  # plausible values
            arguments = {"p": np.zeros(4), "pd": np.zeros(4)} | {argument: bad}
            for method in ("forward_dynamics", "linearise"):
                default = argument == "force_N" and value is None  # None: the static force
                outcome = _api_call(
                    lambda m=method, a=arguments: getattr(model, m)(**a), [argument], default
                )
                outcomes.append((f"{method}({argument}=...)", outcome))
    for value in API_VALUES:
        outcome = _api_call(
            lambda v=value: LoaderDynamics.from_parameters(v), ["loader"], value is None
        )
        outcomes.append(("from_parameters(loader=...)", outcome))
        outcome = _api_call(
            lambda v=value: LoaderDynamics.from_parameters(None, v), ["load"], False
        )
        outcomes.append(("from_parameters(load=...)", outcome))
    return outcomes


def main_fuzz() -> int:
    counts: Counter[str] = Counter()
    failures = []
    with tempfile.TemporaryDirectory() as name:
        folder = Path(name)
        (folder / "fields").mkdir()
        (folder / "options").mkdir()
        groups = {
            "fields": field_cases(folder / "fields"),
            "options": option_cases(folder / "options"),
        }
        for group, cases in groups.items():
            for argv, names, valid, watch in cases:
                kind, stderr = run(argv, watch)
                outcome = classify(kind, stderr, names, valid)
                counts[(group, outcome)] += 1
                if outcome not in ("clear", "valid"):
                    failures.append((outcome, argv, stderr.strip()[-300:]))
        for call, outcome in api_cases():
            counts[("api", outcome)] += 1
            if outcome not in ("clear", "valid"):
                failures.append((outcome, [call], ""))
    total = sum(counts.values())
    for (group, outcome), count in sorted(counts.items()):
        print(f"{group:<8} {outcome:<10} {count}")
    bad = sum(c for (_, o), c in counts.items() if o not in ("clear", "valid"))
    errors = sum(c for (_, o), c in counts.items() if o != "valid")
    print(
        f"total {total} inputs: {total - sum(c for (_, o), c in counts.items() if o == 'valid')} bad "
        f"inputs, clear errors {errors - bad} ({100 * (errors - bad) / max(errors, 1):.1f} %), "
        f"not handled {bad}"
    )
    for outcome, argv, stderr in failures[:60]:
        print(f"{outcome}: {argv}\n    {stderr}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main_fuzz())
