"""Every result the README and the user guide quote matches the result file it comes from.

The pages quote Table 6 cells, designed gains' changes, the fidelity budget and the bound. Each
quotation below is rebuilt from its source, a file a command wrote and the repository keeps:

- ``docs/measurements/table6.csv`` and ``designed.csv``: ``loader-model reproduce --seed 0`` (the run
  ``docs/measurements/reproduce.toml`` describes; ``test_shipped_reproduction.py`` reruns it, slow);
- ``docs/measurements/machine_*.csv``: the second machine's section of the same run;
- ``loader_model/data/fidelity_budget.json``: ``loader-model fidelity`` (its own slow currency test);
- ``loader_model/data/bound_table6.toml``: ``make bound`` (its own slow currency test);
- ``docs/measurements/bound_9kmh_empty.txt`` (``full``): the output of ``loader-model bound
  --course paper --speed 9 --load empty`` (``full``);
- ``docs/measurements/check_refined.csv`` and ``tutorial/check_refined.txt``: ``loader-model
  check-design`` of the shipped refined gains with ``--output`` (the tutorial's step 5);
  ``check_table3_boards9.txt``: ``check-design default`` on ``check_table3_boards9.toml``.

Each quotation is compared as text at the page's rounding: when a source file changes, the test
names the page and the quotation to update. Cheap: it reads files only.
"""

from __future__ import annotations

import csv
import json
import re
import tomllib
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
RESULTS = ROOT / "docs" / "measurements"
DATA = ROOT / "loader_model" / "data"
MINUS = "\u2212"


def minus(text: str) -> str:
    """``text`` with ASCII hyphen-minus signs as the pages write them (U+2212)."""
    return text.replace("-", MINUS)


def number(value: float, digits: int = 1, plus: bool = False) -> str:
    """``value`` rounded to ``digits`` as a page writes it (U+2212 minus, ``+`` if asked)."""
    return minus(f"{value:{'+' if plus else ''}.{digits}f}")


def interval(low: float, high: float) -> str:
    """A 95 % interval in percent as the pages write it: ``[−22.7, +18.4]``."""
    return f"[{number(low, plus=True)}, {number(high, plus=True)}]"


def table6() -> dict[tuple[int, str, str], dict[str, str]]:
    """``docs/measurements/table6.csv`` by (speed in km/h, load, controller), signs as on the pages."""
    rows = {}
    with (RESULTS / "table6.csv").open(encoding="utf-8") as handle:
        for row in csv.DictReader(handle):
            speed = int(re.search(r"(\d+) km/h", row["speed"]).group(1))
            load = re.search(r"\((empty|full)\)", row["load"]).group(1)
            rows[speed, load, row["controller"]] = {k: minus(v) for k, v in row.items()}
    return rows


def designed() -> dict[tuple[int, str, str], tuple[str, str]]:
    """``docs/measurements/designed.csv``: (change, interval) by (speed, load, gain set)."""
    cells = {}
    with (RESULTS / "designed.csv").open(encoding="utf-8") as handle:
        for row in csv.DictReader(handle):
            speed = int(row["speed"].split()[0])
            for name, value in row.items():
                if name.endswith("[95 % CI]"):
                    change, ci = value.split(" ", 1)
                    cells[speed, row["load"], name.split(" ")[0]] = (minus(change), minus(ci))
    return cells


def budget() -> dict:
    """The shipped fidelity budget (``loader-model fidelity``)."""
    return json.loads((DATA / "fidelity_budget.json").read_text(encoding="utf-8"))


def budget_step(label: str) -> dict:
    """One step of the fidelity budget by its label."""
    (step,) = [s for s in budget()["steps"] if s["label"] == label]
    return step


def bound_table() -> dict:
    """The shipped bound of the Table 6 conditions (``make bound``)."""
    return tomllib.loads((DATA / "bound_table6.toml").read_text(encoding="utf-8"))


def bound_output(load: str) -> list[str]:
    """The lines of ``loader-model bound``'s output kept in ``docs/measurements``."""
    return (RESULTS / f"bound_9kmh_{load}.txt").read_text(encoding="utf-8").splitlines()


def bound_rows(load: str) -> dict[str, float]:
    """a_total [m/s²] per controller row of :func:`bound_output`."""
    rows = {}
    for line in bound_output(load):
        match = re.match(r"^(\S.*?)\s+(-?\d+\.\d{4})\s+[+-]\d+\.\d\s+-?\d+\.\d{2}$", line)
        if match:
            rows[match.group(1)] = float(match.group(2))
    return rows


def check_rows() -> dict[tuple[str, str, str, str], dict[str, str]]:
    """``docs/measurements/check_refined.csv`` by (load, road, speed, run)."""
    with (RESULTS / "check_refined.csv").open(encoding="utf-8") as handle:
        rows = csv.DictReader(handle)
        return {(r["load"], r["road"], r["speed [km/h]"], r["run"]): r for r in rows}


def closed_valve_baselines() -> list[float]:
    """The simulator's baseline (valves closed) at 9 km/h on the boards, empty and full."""
    check = check_rows()
    return [
        float(check[load, "boards", "9", "baseline"]["a_total [m/s^2]"])
        for load in ("empty", "full")
    ]


def _readme_quotations() -> list[tuple[str, str]]:
    t6, des = table6(), designed()
    sky, pas = t6[9, "empty", "skyhook"], t6[18, "full", "passive"]
    calibrated = budget_step("+ calibrated to 9 km/h")
    cal = calibrated["cells"]["9/empty/skyhook"]
    refined = des[18, "empty", "skyhook-refined"]
    run = tomllib.loads((RESULTS / "reproduce.toml").read_text(encoding="utf-8"))
    within = sum(float(row["|Δ−Δ_paper| [pp]"]) <= 10.0 for row in t6.values())
    return [
        (
            "README.md",
            f"| 9 km/h, 340 kg | skyhook (Table 3, k_φ = +0.22) | {sky['model Δ [%]']} "
            f"({sky['95 % CI [%]']}) | {sky['paper Δ [%]']} ({sky['paper p']}) |",
        ),
        (
            "README.md",
            f"| 18 km/h, 770 kg | passive accumulator | {pas['model Δ [%]']} "
            f"({pas['95 % CI [%]']}) | {pas['paper Δ [%]']} ({pas['paper p']}) |",
        ),
        (
            "README.md",
            f"| 18 km/h, 340 kg | skyhook, gains refined on the course | {refined[0]} "
            f"({refined[1]}) | — |",
        ),
        (
            "README.md",
            f"| 9 km/h, 340 kg | skyhook, calibrated to the 9 km/h cells (fidelity budget) | "
            f"{number(cal['change'])} ({interval(cal['low'], cal['high'])}) | "
            f"{sky['paper Δ [%]']} ({sky['paper p']}) |",
        ),
        ("README.md", f"the report took {run['report_wall_time_s']:.0f} s"),
        ("README.md", f"{within} of Table 6's 12 cells lie within 10 percentage points"),
        (
            "README.md",
            f"9 km/h cells (`make calibrate-table6`, one parameter set inside plausible ranges) "
            f"{calibrated['within']} of 12, but only {calibrated['held_out_within']} of the "
            f"{calibrated['held_out_count']} held-out 18 km/h cells",
        ),
    ]


def _reproduction_quotations() -> list[tuple[str, str]]:
    page = "docs/guide/reproduction.md"
    t6, des = table6(), designed()
    quotes = []
    for speed, load, controller, label in (
        (9, "empty", "skyhook", "skyhook (Table 3, k_φ = +0.22)"),
        (9, "empty", "passive", "passive accumulator"),
        (18, "full", "passive", "passive accumulator"),
        (18, "full", "skyhook", "skyhook (Table 3)"),
    ):
        row = t6[speed, load, controller]
        kg = {"empty": 340, "full": 770}[load]
        quotes.append(
            (
                page,
                f"| {speed} km/h, {kg} kg | {label} | {row['model Δ [%]']} "
                f"({row['95 % CI [%]']}, {row['model p']}) | {row['paper Δ [%]']} "
                f"({row['paper p']}) |",
            )
        )
    for speed, load, gains, label in (
        (9, "empty", "skyhook-refined", "skyhook, gains refined on the course"),
        (18, "empty", "skyhook-optimised", "skyhook, ISO 2631-optimised gains"),
    ):
        change, ci = des[speed, load, gains]
        kg = {"empty": 340, "full": 770}[load]
        quotes.append((page, f"| {speed} km/h, {kg} kg | {label} | {change} ({ci}) | — |"))
    run = tomllib.loads((RESULTS / "reproduce.toml").read_text(encoding="utf-8"))
    quotes.append((page, f"the report took {run['report_wall_time_s']:.0f} s"))
    within = sum(float(row["|Δ−Δ_paper| [pp]"]) <= 10.0 for row in t6.values())
    quotes.append((page, f"**Table 6 with the sourced parameter files**: {within} of its 12 cells"))
    for step in budget()["steps"]:
        cells = [
            step["cells"][f"9/empty/{c}"]["change"]
            for c in ("passive", "virtual-accumulator", "skyhook")
        ]
        quotes.append(
            (
                page,
                f"| {step['within']} | " + " / ".join(number(c, plus=True) for c in cells) + " |",
            )
        )
    paper = [
        t6[9, "empty", c]["paper Δ [%]"] for c in ("passive", "virtual-accumulator", "skyhook")
    ]
    quotes.append((page, "The paper: " + " / ".join(paper) + "."))
    values = [budget_step(f"+ calibrated to {s} km/h")["values"] for s in (9, 18)]
    precharge = [v["accumulator.precharge_pressure"] / 1e5 for v in values]
    quotes.append((page, f"(precharge {precharge[0]:.0f} bar against {precharge[1]:.0f} bar)"))
    for speed in (9, 18):
        fit = budget_step(f"+ calibrated to {speed} km/h")
        quotes.append(
            (
                page,
                f"| {speed} km/h | {fit['within']} of 12 ({fit['held_out_within']} of 6) | "
                f"{fit['scatter_within']} of 12 ({fit['held_out_scatter_within']} of 6) | "
                f"{fit['both_within']} of 12 ({fit['held_out_both_within']} of 6) | "
                f"{number(fit['largest_se'])} |",
            )
        )
    machines = budget()["machines"]
    both = [cell["both_share"] for cell in machines["cells"].values()]
    quotes.append(
        (
            page,
            f"{machines['machines']} plausible machines, {machines['trials']} trials per group "
            f"each: mean and scatter both agree in {100 * min(both):.0f}-{100 * max(both):.0f} % "
            "of them per cell",
        )
    )
    return quotes


def _controllers_quotations() -> list[tuple[str, str]]:
    page = "docs/guide/controllers.md"
    des = designed()

    def pair(gains: str, speed: int) -> str:
        return f"{des[speed, 'empty', gains][0]} % / {des[speed, 'full', gains][0]} %"

    bound = bound_table()
    empty, full = bound_rows("empty"), bound_rows("full")
    closed = closed_valve_baselines()
    refined = (DATA / "controller_refined.toml").read_text(encoding="utf-8")
    recorded = re.search(r"course a_total (\d\.\d{3})/(\d\.\d{3}) m/s", refined)
    return [
        (
            page,
            f"Table 3 {empty['skyhook']:.3f} / {full['skyhook']:.3f}, linear optimum "
            f"{empty['skyhook-optimised']:.3f} / {full['skyhook-optimised']:.3f}",
        ),
        (page, f"0.68) {recorded.group(1)} / {recorded.group(2)} (the figure"),
        (
            page,
            f"`bound` reads {empty['skyhook-refined']:.3f} / {full['skyhook-refined']:.3f} today",
        ),
        (page, f"closed load-holding valves (errata 11): {closed[0]:.3f} / {closed[1]:.3f}"),
        (
            page,
            f"the refined gains give {pair('skyhook-refined', 9)} at 9 km/h (empty / full) "
            f"and {pair('skyhook-refined', 18)} at 18 km/h; Table 3 gives "
            f"{pair('skyhook', 9)} and {pair('skyhook', 18)}; the optimised gains "
            f"{pair('skyhook-optimised', 9)} and {pair('skyhook-optimised', 18)}.",
        ),
        (
            page,
            "another baseline for the same drive, "
            f"{bound['9 km/h empty']['baseline_a_total_m_s2']:.3f} / "
            f"{bound['9 km/h full']['baseline_a_total_m_s2']:.3f}",
        ),
    ]


def _bound_quotations() -> list[tuple[str, str]]:
    page = "docs/guide/bound.md"
    table, t6, des = bound_table(), table6(), designed()
    quotes = []
    for speed, load in ((9, "empty"), (9, "full"), (18, "empty"), (18, "full")):
        row = table[f"{speed} km/h {load}"]
        base, linear = row["baseline_a_total_m_s2"], row["linear_bound_a_total_m_s2"]
        constrained = row["constrained_bound_a_total_m_s2"]
        change = number(100.0 * (constrained / base - 1.0))
        quotes.append(
            (
                page,
                f"| {speed} km/h, {load} | {base:.3f} | {linear:.3f} | {constrained:.3f} "
                f"({change} %) |",
            )
        )
        paper = {
            c: float(t6[speed, load, c]["paper Δ [%]"].replace(MINUS, "-"))
            for c in ("passive", "virtual-accumulator", "skyhook")
        }
        best_paper = min(paper, key=paper.get)
        simulated = {
            g: float(des[speed, load, g][0].replace(MINUS, "-"))
            for g in ("skyhook", "skyhook-lqr", "skyhook-optimised", "skyhook-refined")
        }
        simulated.update(
            {
                c: float(t6[speed, load, c]["model Δ [%]"].replace(MINUS, "-"))
                for c in ("passive", "virtual-accumulator")
            }
        )
        best_sim = min(simulated, key=simulated.get)
        quotes.append(
            (
                page,
                f"| {speed} km/h {load} | {change} | {number(paper[best_paper])} "
                f"({best_paper.replace('-', ' ')}) | {number(simulated[best_sim])} (",
            )
        )
    peaks = [table[k]["linear_bound_peak_command_over_limit"] for k in table]
    quotes.append((page, ", ".join(f"{p:.1f}" for p in peaks[:3]) + f" and {peaks[3]:.1f}"))
    quotes += [(page, line) for line in bound_output("empty")]
    closed = closed_valve_baselines()
    open_ = [table[f"9 km/h {load}"]["baseline_a_total_m_s2"] for load in ("empty", "full")]
    quotes.append(
        (
            page,
            f"{open_[0]:.3f} (open) against {closed[0]:.3f} (closed) m/s² with the empty bucket, "
            f"{open_[1]:.3f} against {closed[1]:.3f} with the full one",
        )
    )
    empty = table["9 km/h empty"]
    base, constrained = empty["baseline_a_total_m_s2"], empty["constrained_bound_a_total_m_s2"]
    linear = empty["linear_bound_a_total_m_s2"]
    quotes.append(
        (
            page,
            f"The constrained bound ({constrained:.3f} m/s²) lies "
            f"{100.0 * (1.0 - constrained / base):.1f} % below the baseline, against "
            f"{100.0 * (1.0 - linear / base):.1f} % for the unconstrained one",
        )
    )
    return quotes


def _design_check_quotations() -> list[tuple[str, str]]:
    rows = check_rows()
    conditions = {key[:3] for key in rows}
    total = {key: float(row["a_total [m/s^2]"]) for key, row in rows.items()}
    better = [100.0 * (1.0 - total[(*c, "design")] / total[(*c, "baseline")]) for c in conditions]
    assert not [k for k, r in rows.items() if k[3] == "design" and r["failures"]], (
        "the design check page says every condition passes"
    )
    kept = (RESULTS / "tutorial" / "check_refined.txt").read_text(encoding="utf-8")
    margin = float(re.search(r"empty: .*worst margin (-?\d+\.\d+) rad/s", kept).group(1))
    table3 = (RESULTS / "check_table3_boards9.txt").read_text(encoding="utf-8")
    worse = float(
        re.search(r"^empty, boards 9 km/h(?:\s+\S+){3}\s+\+(\d+\.\d)", table3, re.M).group(1)
    )
    page = "docs/guide/design_check.md"
    return [
        (
            page,
            f"pass every one of the {len(conditions)} nonlinear conditions of the default "
            f"envelope, {min(better):.1f} % to {max(better):.1f} %",
        ),
        (page, f"margin {number(margin, 2)} rad/s"),
        (page, f"with the empty bucket {worse:.1f} % worse than the baseline"),
    ]


def _machines_quotations() -> list[tuple[str, str]]:
    page = "docs/guide/machines.md"
    quotes = []
    with (RESULTS / "machine_comparison.csv").open(encoding="utf-8") as handle:
        rows = {row["controller"]: row for row in csv.DictReader(handle)}
    labels = {
        "baseline": "baseline",
        "passive": "passive",
        "virtual-accumulator": "virtual accumulator",
        "skyhook": "skyhook, Table 3 gains",
        "skyhook (designed)": "skyhook, designed",
    }
    for name, label in labels.items():
        cells = []
        for load in ("full", "empty"):
            value, change = re.match(
                r"(\S+) \((\S+) %\)", rows[name][f"{load} a_total [m/s²] (Δ)"]
            ).groups()
            cells += [value, "" if name == "baseline" else f"{minus(change)} %"]
        quotes.append((page, f"| {label} | " + " | ".join(cells) + " |"))
    with (RESULTS / "machine_modes.csv").open(encoding="utf-8") as handle:
        modes = {row["load"]: row["undamped modes [Hz]"] for row in csv.DictReader(handle)}
    quotes.append((page, f"with the full bucket: {modes['full']} Hz"))
    gains = (RESULTS / "machine_gains.csv").read_text(encoding="utf-8").splitlines()[1]
    values = [minus(v) for v in gains.split(",")[0].split()]
    quotes.append((page, "K_fb = (" + ", ".join(values) + ")"))
    return quotes


def _tutorial_quotations() -> list[tuple[str, str]]:
    t6 = table6()
    cells = [t6[9, "empty", c] for c in ("passive", "virtual-accumulator", "skyhook")]
    model = sorted(float(c["model Δ [%]"].replace(MINUS, "-")) for c in cells)
    paper = sorted(float(c["paper Δ [%]"].replace(MINUS, "-")) for c in cells)
    return [
        (
            "docs/guide/tutorial.md",
            f"the paper measured {number(paper[-1])} % to {number(paper[0])} % at this speed",
        ),
        (
            "docs/guide/tutorial.md",
            f"the model's changes average {number(model[0])} % to {number(model[-1])} %",
        ),
    ]


def quotations() -> list[tuple[str, str]]:
    """Every (page, quoted text) rebuilt from its source file."""
    return [
        *_readme_quotations(),
        *_reproduction_quotations(),
        *_controllers_quotations(),
        *_bound_quotations(),
        *_design_check_quotations(),
        *_tutorial_quotations(),
        *_machines_quotations(),
    ]


def flat(text: str) -> str:
    """``text`` with every run of white space as one space (quotations may wrap)."""
    return " ".join(text.split())


@pytest.mark.parametrize(("page", "quote"), quotations(), ids=lambda v: v[:60])
def test_quoted_number_matches_its_source(page: str, quote: str) -> None:
    text = flat((ROOT / page).read_text(encoding="utf-8"))
    assert flat(quote) in text, f"{page} should quote, from its source file: {quote!r}"


def test_number_formats_as_the_pages_do() -> None:
    assert number(-2.25) == f"{MINUS}2.2" and number(18.35, plus=True) == "+18.4"
    assert interval(-22.74, 18.36) == f"[{MINUS}22.7, +18.4]"
    assert flat("a\n  b") == "a b"


def test_a_changed_source_is_caught(tmp_path, monkeypatch) -> None:
    """A source cell that differs from the page by one unit of the page's rounding fails."""
    text = (RESULTS / "table6.csv").read_text(encoding="utf-8")
    row = next(line for line in text.splitlines() if ",skyhook," in line and "(empty)" in line)
    fields = next(csv.reader([row]))
    fields[3] = f"{float(fields[3]) + 0.1:+.1f}"
    changed = text.replace(row, ",".join(f'"{f}"' if "," in f else f for f in fields))
    (tmp_path / "table6.csv").write_text(changed, encoding="utf-8")
    for name in ("designed.csv", "reproduce.toml"):
        (tmp_path / name).write_text((RESULTS / name).read_text(encoding="utf-8"), "utf-8")
    monkeypatch.setattr(f"{__name__}.RESULTS", tmp_path)
    readme = flat((ROOT / "README.md").read_text(encoding="utf-8"))
    assert any(flat(q) not in readme for page, q in _readme_quotations() if page == "README.md")


@pytest.mark.parametrize("page", ["README.md", "docs/guide/reproduction.md"])
def test_about_a_third_of_plausible_machines(page: str) -> None:
    """ "About a third" of the sampled machines show the paper's sign at 9 km/h empty: each of
    the three controllers' shares in the shipped uncertainty study lies within 1/3 ± 0.1."""
    cells = budget()["uncertainty"]["cells"]
    shares = [cells[f"9/empty/{c}"]["share"] for c in ("passive", "virtual-accumulator", "skyhook")]
    assert "about a third" in flat((ROOT / page).read_text(encoding="utf-8"))
    assert all(abs(share - 1.0 / 3.0) <= 0.1 for share in shares), shares
