"""The outputs and figures the guide's pages show come from files the repository keeps.

Beside the tutorial (``test_tutorial_blocks.py``) and the Table 6 quotations
(``test_quoted_numbers.py``), the guide shows outputs of ``check-design``, ``simulate``,
``identify``, ``preview``, ``bound``, ``hydraulics``, ``robustness`` and the quick benchmark. Each
is kept whole in ``docs/measurements/`` (:data:`SHOWN`, :data:`PRINTED`), its first line saying
the command, the date and the machine; every line a page shows after the command must be a line
of the kept file (a line shortened with "…" must hold its pieces in order). Figures quoted in the
pages' prose are rebuilt from the kept outputs and from shipped result files
(``loader_model/data``: the shipped designs and their checks, the scatter study) at the page's
rounding (:func:`quotations`); a page's claim about them ("every preview length ends above the
baseline") is asserted on the source. Blocks that print in well under a second
(:data:`CHEAP_BLOCKS`) are run and their output compared exactly. Cheap: no simulation.
"""

from __future__ import annotations

import csv
import re
from pathlib import Path

import pytest

from tests.docs.test_quoted_numbers import flat
from tests.docs.test_tutorial_blocks import is_excerpt, shown_outputs

ROOT = Path(__file__).resolve().parents[2]
KEPT = ROOT / "docs" / "measurements"
DATA = ROOT / "loader_model" / "data"
MINUS = "\u2212"
#: (page, the last command of a shell block followed by its output) -> the kept output.
SHOWN = {
    ("design_check.md", "loader-model check-design default --conditions env.toml --no-progress"): (
        "check_my_yard.txt"
    ),
    ("simulation.md", "loader-model simulate --course docs/examples/my_yard.toml --speed 9"): (
        "simulate_my_yard.txt"
    ),
    (
        "simulation.md",
        "loader-model simulate --course docs/examples/my_yard.toml --speed 9 --load full --compare",
    ): "simulate_my_yard_full.txt",
    ("identification.md", "loader-model identify friction friction.csv"): "identify_friction.txt",
    ("bound.md", "loader-model preview --no-progress"): "preview_9kmh_empty.txt",
    ("bound.md", "loader-model preview --simulate --no-progress"): (
        "preview_simulated_9kmh_empty.txt"
    ),
    ("bound.md", "loader-model bound --bound constrained --no-progress"): (
        "bound_constrained_9kmh_empty.txt"
    ),
    ("bound.md", "loader-model bound --machine compact_wheel_loader --no-progress"): (
        "bound_compact_wheel_loader_9kmh_empty.txt"
    ),
    (
        "bound.md",
        "loader-model bound --pump-sizing --speed 9 --load empty --duration 6 --factors 0.5,1,2 "
        "--output pump --no-progress",
    ): "bound_pump_sizing_9kmh_empty.txt",
    ("performance.md", ".venv/bin/python docs/measurements/bench_quick.py"): "bench_quick.txt",
    ("simulation.md", ".venv/bin/python docs/measurements/stepping_accuracy.py"): (
        "stepping_accuracy.txt"
    ),
    ("performance.md", ".venv/bin/python docs/measurements/profile_time.py"): "profile_time.txt",
    ("performance.md", "loader-model bound --bound constrained --no-progress"): (
        "bound_constrained_9kmh_empty.txt"
    ),
}
#: (page, the last line of a python block followed by "prints" and its output) -> kept output.
PRINTED = {("robustness.md", "print(report_text(study, table))"): "robustness_guide_study.txt"}
HEADER = re.compile(r"^# .+ \| \d{4}-\d\d-\d\d \| \d+-core .+, shared with other jobs")


def page(name: str) -> str:
    return (ROOT / "docs" / "guide" / name).read_text(encoding="utf-8")


def kept(name: str) -> str:
    return (KEPT / name).read_text(encoding="utf-8")


def minus(text: str) -> str:
    """``text`` with ASCII hyphen-minus signs as the pages write them (U+2212)."""
    return text.replace("-", MINUS)


@pytest.mark.parametrize(("name", "command"), sorted(SHOWN), ids=lambda v: v[:40])
def test_shown_output_is_an_excerpt_of_the_kept_one(name: str, command: str) -> None:
    shown = dict(shown_outputs(page(name)))
    assert command in shown, f"{name} shows no output after `{command}`"
    text = kept(SHOWN[name, command])
    assert HEADER.match(text), f"{SHOWN[name, command]}: first line must say command, date, machine"
    missing = is_excerpt(shown[command], text)
    assert not missing, f"{name}: lines not in {SHOWN[name, command]}: {missing}"


def printed_outputs(text: str) -> dict[str, str]:
    """The last line of each python block followed by a "prints" paragraph and a text block."""
    gap = r"(?:(?!```).)*?"
    pairs = re.findall(rf"```python\n(.*?)```\n\nprints{gap}```text\n(.*?)```", text, flags=re.S)
    return {code.strip().splitlines()[-1]: output for code, output in pairs}


@pytest.mark.parametrize(("name", "line"), sorted(PRINTED), ids=lambda v: v[:40])
def test_printed_output_is_an_excerpt_of_the_kept_one(name: str, line: str) -> None:
    shown = printed_outputs(page(name))
    assert line in shown, f"{name} shows no output after the block ending in `{line}`"
    text = kept(PRINTED[name, line])
    assert HEADER.match(text), f"{PRINTED[name, line]}: first line must say command, date, machine"
    missing = is_excerpt(shown[line], text)
    assert not missing, f"{name}: lines not in {PRINTED[name, line]}: {missing}"


@pytest.mark.parametrize("name", sorted({name for name, _ in SHOWN}))
def test_every_shown_output_has_a_kept_file(name: str) -> None:
    commands = {command for command, _ in shown_outputs(page(name))}
    assert commands <= {c for n, c in SHOWN if n == name}, commands


def _gains(text: str) -> list[float]:
    return [
        float(v) for v in re.search(r"^k_fb = \{ value = \[([^\]]+)\]", text, re.M)[1].split(",")
    ]


def _check_table(name: str) -> tuple[dict[str, list[str]], list[str]]:
    """A shipped design check (Markdown): its rows by condition, and its other lines."""
    rows, other = {}, []
    for line in (DATA / name).read_text(encoding="utf-8").splitlines():
        cells = [c.strip() for c in line.strip("|").split("|")]
        if line.startswith("| ") and cells[0] != "condition":
            rows[cells[0]] = cells
        elif not line.startswith("|"):
            other.append(line)
    return rows, other


def _design_check_quotations() -> list[tuple[str, str]]:
    quotes = []
    refined = _gains((DATA / "controller_refined.toml").read_text(encoding="utf-8"))
    machine_file = (DATA / "controller_machine.toml").read_text(encoding="utf-8")
    machine = _gains(machine_file)
    quotes.append("K_fb = (" + ", ".join(minus(f"{g:.2f}") for g in refined) + ")")
    quotes.append(
        "to K_fb = (" + ", ".join(minus(f"{g:.2f}") for g in machine[:3]) + f", {machine[3]:.3f})"
    )
    j = re.search(r"J (\d\.\d+) -> (\d\.\d+)", machine_file)
    quotes.append(f"lowers J from {float(j[1]):.3f} to {float(j[2]):.3f}")
    margin = re.search(r"worst margin (-\d\.\d+) rad/s", kept("tutorial/check_refined.txt"))[1]
    quotes.append(f"(margin {minus(f'{float(margin):.2f}')} rad/s)")
    rows, other = _check_table("design_check_skid_steer.md")
    change = {k: float(r[4]) for k, r in rows.items()}
    boards = [v for k, v in change.items() if "boards" in k]
    quotes.append(f"every condition {-max(change.values()):.1f} % to {-min(change.values()):.1f} %")
    quotes.append(f"(the boards {-max(boards):.1f} % to {-min(boards):.1f} %)")
    limit = max(max(float(r[6]), float(r[7])) for r in rows.values())
    quotes.append(f"at a limit for more than {limit:.1f} % of the run")
    text = "\n".join(other)
    empty, full = re.findall(r"loop margin (\d\.\d{3}) rad/s", text)
    worst = min(float(v) for v in re.findall(r"worst margin (\d\.\d{3}) rad/s", text))
    quotes.append(f"the loop's margin {empty} / {full} rad/s")
    quotes.append(f"at least {worst:.3f} rad/s on the 16 sampled ones")
    closest = sorted(change, key=change.get, reverse=True)[:2]
    assert closest == ["empty, ISO D 30 km/h", "full, boards 9 km/h"], closest
    quotes.append(
        f"class D road at 30 km/h with the empty bucket ({minus(f'{change[closest[0]]:.1f}')} %)"
    )
    quotes.append(f"at 9 km/h with the full bucket ({minus(f'{change[closest[1]]:.1f}')} %)")
    wheel = (DATA / "controller_machine_compact_wheel_loader.toml").read_text(encoding="utf-8")
    j = re.search(r"J (\d\.\d+) -> (\d\.\d+) over (\d+) scenarios", wheel)
    quotes.append(f"lowers J from {float(j[1]):.3f} to {float(j[2]):.3f} over {j[3]} scenarios")
    rows, other = _check_table("design_check_compact_wheel_loader.md")
    change = [float(r[4]) for r in rows.values()]
    quotes.append(f"{len(rows)} conditions, {-max(change):.1f} % to {-min(change):.1f} % better")
    text = "\n".join(other)
    quotes.append("loop margins " + " / ".join(re.findall(r"loop margin (\d\.\d{3})", text)))
    rest = re.search(r"pitch acceleration empty (\d\.\d{3}), full (\d\.\d{3})", text)
    quotes.append(f"keeps {rest[1]} (empty) and {rest[2]} (full) rad/s²")
    return [("design_check.md", q) for q in quotes]


def _controllers_quotations() -> list[tuple[str, str]]:
    rows = {}
    for line in kept("tutorial/design.txt").splitlines():
        match = re.match(
            r"^  (.+?)\s+\[([^\]]+)\]\s+a_total empty: (\d\.\d+)\s+full: (\d\.\d+)", line
        )
        if match:
            rows[match[1]] = (
                [float(g) for g in match[2].split()],
                float(match[3]),
                float(match[4]),
            )

    def pair(name: str) -> str:
        return f"{rows[name][1]:.3f} / {rows[name][2]:.3f}"

    gains = ", ".join(minus(f"{g:.2f}") for g in rows["optimised (ISO 2631)"][0])
    return [
        ("controllers.md", f"k_φ = +0.22: {pair('Table 3 (k_φ = +0.22)')};"),
        ("controllers.md", f"output-feedback LQR per load: {pair('LQR (empty)')} (designed"),
        ("controllers.md", f"and {pair('LQR (full)')} (full)"),
        ("controllers.md", f"({gains}): {pair('optimised (ISO 2631)')}, the lowest sum"),
    ]


def _bound_quotations() -> list[tuple[str, str]]:
    passive_closed = re.search(r"^passive\s+(\d\.\d{4})", kept("tutorial/compare.txt"), re.M)[1]
    passive_open = re.search(r"^passive\s+(\d\.\d{4})", kept("bound_9kmh_empty.txt"), re.M)[1]
    quotes = [f"(passive: {float(passive_closed):.3f} there, {float(passive_open):.3f} here)"]
    table = {}
    for line in kept("preview_9kmh_empty.txt").splitlines():
        match = re.match(
            r"^\s+(\d\.\d\d)\s+(\d\.\d{4})\s+(?:not run|\d+\.\d{4})\s+(\d+\.\d\d)$", line
        )
        if match:
            table[float(match[1])] = (float(match[2]), float(match[3]))
    bound = float(
        re.search(
            r"non-causal LQ bound \(linear plant\)\s+(\d\.\d{4})", kept("preview_9kmh_empty.txt")
        )[1]
    )
    half, one = (100.0 * (table[length][0] / bound - 1.0) for length in (0.5, 1.0))
    quotes.append(f"within {half:.0f} % of the bound, 1 m within {one:.1f} %")
    quotes.append(f"from {table[0.0][1]:.0f} to about {table[4.0][1]:.0f} times the pump's limit")
    refined = re.search(
        r"^skyhook-refined\s+(\d\.\d{4})\s+\S+\s+(\d\.\d\d)$",
        kept("bound_constrained_9kmh_empty.txt"),
        re.M,
    )
    assert float(refined[2]) > 1.0, "the page says the refined skyhook beats the constrained bound"
    quotes.append(
        f"the refined skyhook in the simulator ({float(refined[1]):.3f}) does better than the "
        f"constrained linear bound (share {refined[2]})"
    )
    simulated = re.findall(
        r"^\s+\d\.\d\d\s+\d\.\d{4}\s+(\d+\.\d{4})\s+\d+\.\d\d$",
        kept("preview_simulated_9kmh_empty.txt"),
        re.M,
    )
    with_preview = sorted(float(v) for v in simulated[1:])
    text = kept("preview_simulated_9kmh_empty.txt")
    baseline = float(re.search(r"baseline \(simulated\)\s+(\d\.\d{4})", text)[1])
    refined = float(re.search(r"skyhook-refined \(simulated\)\s+(\d\.\d{4})", text)[1])
    assert with_preview[0] > baseline > refined, "the page says every preview length ends above"
    quotes.append(
        f"({with_preview[0]:.2f} to {with_preview[-1]:.2f} m/s² against {baseline:.3f}) and "
        f"the refined skyhook ({refined:.3f})"
    )
    sizes = {}
    for line in kept("bound_pump_sizing_9kmh_empty.txt").splitlines():
        cells = line.split()
        if len(cells) == 7 and cells[0] in ("V_p_max", "omega_p", "Vd_p_max"):
            sizes[cells[0], float(cells[1])] = [float(c) for c in cells[2:6]]
    shipped = sizes["V_p_max", 1.0]
    doubled = max(
        abs(sizes[name, 2.0][2] / shipped[2] - 1.0) for name in ("V_p_max", "omega_p", "Vd_p_max")
    )
    assert doubled < 0.003, "the page says doubling moves the bound by less than 0.3 %"
    half = sizes["V_p_max", 0.5]
    quotes.append(
        f"halving V_p_max costs {100.0 * (half[2] / shipped[2] - 1.0):.1f} % of the bound and "
        f"{100.0 * (half[3] / shipped[3] - 1.0):.1f} % of the refined skyhook"
    )
    quotes.append(
        f"The linear plant's own baseline ({shipped[1]:.3f}) lies far above the simulated"
    )
    quotes.append(f"one ({shipped[0]:.3f})")
    return [("bound.md", q) for q in quotes]


def _performance_quotations() -> list[tuple[str, str]]:
    text = kept("tutorial/timings.txt")
    assert HEADER.match(text), "tutorial/timings.txt: first line must say command, date, machine"
    seconds = [float(s) for s in re.findall(r": (\d+\.\d) s$", text, re.M)]
    quote = (
        f"deriving the machine {seconds[0]:.1f} s, `design` with its check over 26 conditions "
        f"{seconds[1]:.1f} s, `check-design` of one condition {seconds[2]:.1f} s"
    )
    before = kept("profile_time_before_road_cache.txt")
    assert HEADER.match(before), "profile_time_before_road_cache.txt: first line as the others"
    check = before[before.index("check-design") :]
    share = re.search(r"road tables \(tyre envelopes\)\s+\S+ s\s+(\d+\.\d) %", check)[1]
    return [
        ("performance.md", quote),
        ("performance.md", f"the same profile spent {share} % of the check in them"),
    ]


def _hydraulics_quotations() -> list[tuple[str, str]]:
    empty, full = kept("hydraulics_empty.txt"), kept("hydraulics_full.txt")
    wheel = kept("hydraulics_compact_wheel_loader.txt")

    def pressure(text: str) -> str:
        return re.search(r"static piston pressure p_A\s+(\d+\.\d\d) bar", text)[1]

    def k_eq(text: str) -> str:
        return re.search(r"k_eq \(chambers closed\)\s+(\S+) N/m", text)[1]

    def dc_direct(text: str) -> str:
        return re.search(r"direct p_A feedback: DC gain (\S+),", text)[1]

    quotes = [
        f"static piston pressure {pressure(empty)} bar (340 kg) and {pressure(full)} bar (770 kg) "
        f"gauge, k_eq {k_eq(empty)} N/m",
        f"positive DC gain ({dc_direct(empty)} with direct p_A feedback)",
        "DC gain " + minus(re.search(r"Eq. 43: DC gain (\S+),", empty)[1]),
        f"p_A {pressure(wheel)} bar, k_eq {k_eq(wheel)} N/m, pressure loop DC gain "
        f"{dc_direct(wheel)} with direct p_A feedback",
    ]
    modes = re.findall(r"^    ((?:\d+\.\d\d/\d\.\d{3}(?:, )?)+)$", empty, re.M)
    labels = (
        "chambers closed (Eq. 28)",
        "pump through open load-holding valves (virtual accumulator, skyhook)",
        "closed load-holding valves, pump idle (baseline)",
        "accumulator behind closed valves (passive, 50 bar precharge)",
    )
    rows = []
    for label, line in zip(labels, modes, strict=True):
        pairs = [m.split("/") for m in line.split(", ") if float(m.split("/")[0]) < 20.0]
        rows.append(pairs)
        quotes.append(f"| {label} | " + " | ".join(f"{f} / {z}" for f, z in pairs) + " |")
    opened, closed = rows[1][1], rows[2][1]
    quotes.append(f"The {opened[0]} Hz boom mode's damping of {opened[1]} with open valves")
    quotes.append(f"the sealed oil column ({closed[1]})")
    return [("hydraulics.md", q) for q in quotes]


def _machines_quotations() -> list[tuple[str, str]]:
    quotes = []
    for load, suffix in (("empty", ""), ("full", "_full")):
        hydraulics = kept(f"hydraulics_compact_wheel_loader{suffix}.txt")
        model = kept(f"model_compact_wheel_loader_{load}.txt")
        p_a = re.search(r"static piston pressure p_A\s+(\d+\.\d\d) bar", hydraulics)[1]
        force = re.search(r"static cylinder force\s+(\d+\.\d\d) kN", hydraulics)[1]
        hold = re.search(r"pump displacement to hold\s+(\d+\.\d{3}) cm", hydraulics)[1]
        tyres = [
            float(re.search(rf"tyre load\s+F_{axle}y0\s+(\d+\.\d) N", model)[1]) / 1e3
            for axle in ("A", "B")
        ]
        quotes.append(f"| {load} | {p_a} | {force} | {tyres[0]:.2f} / {tyres[1]:.2f} | {hold} |")
    k_eq = re.search(r"k_eq \(chambers closed\)\s+(\S+) N/m", hydraulics)[1]
    quotes.append(f"(k_eq = {k_eq.replace('e+0', 'e')} N/m)")
    return [("machines.md", q) for q in quotes]


def _reproduction_quotations() -> list[tuple[str, str]]:
    """The scatter study's table and means from ``loader_model/data/table6_scatter.csv``."""
    lines = (DATA / "table6_scatter.csv").read_text(encoding="utf-8").splitlines()
    rows = list(csv.DictReader(line for line in lines if not line.startswith("#")))
    quotes = []
    for speed, load in (("9", "empty"), ("9", "full"), ("18", "empty"), ("18", "full")):
        cell = [r for r in rows if (r["speed_kmh"], r["load"]) == (speed, load)]
        pooled = sorted(float(r["sd_pct"]) for r in cell)
        own = sorted(float(r["sd_controller_pct"]) for r in cell)
        quotes.append(
            f"| {speed} km/h, {load} | {pooled[0]:.1f}-{pooled[-1]:.1f} | "
            f"{float(cell[0]['sd_baseline_pct']):.1f} / {own[0]:.1f}-{own[-1]:.1f} |"
        )
    nine = {r["controller"]: r for r in rows if (r["speed_kmh"], r["load"]) == ("9", "empty")}
    order = ("passive", "virtual-accumulator", "skyhook")
    four = " / ".join(minus(f"{float(nine[c]['four_change_pct']):.1f}") for c in order)
    many = " / ".join(f"{float(nine[c]['change_pct']):+.1f}" for c in order)
    quotes.append(f"the report's four give {four} % at 9 km/h empty")
    quotes.append(f"150 give {many} %")
    quotes.append(f"at most {max(float(r['se_pp']) for r in rows):.1f} pp")
    factors = ("0.9600", "0.9800", "1.0000", "1.0075", "1.0100", "1.0125", "1.0200", "1.0400")
    for name, label in (
        ("scatter_cause_empty.txt", "a_total as built [m/s²]"),
        ("scatter_cause_empty_damped.txt", "a_total, tyres' c_y = 20 kN s/m [m/s²]"),
    ):
        totals = dict(re.findall(r"^\s+(\d\.\d{4})\s+(\d\.\d{3})\s+\d+$", kept(name), re.M))
        cells = " | ".join(f"{float(totals[f]):.2f}" for f in factors)
        quotes.append(f"| {label} | {cells} |")
    return [("reproduction.md", q) for q in quotes]


def _robustness_quotations() -> list[tuple[str, str]]:
    """The shipped example study's report (``loader-model robustness``), per controller."""
    report = kept("robustness_example_report.txt")
    sections = dict(re.findall(r"^## (\S+)\n(.*?)(?=^## |\Z)", report, re.M | re.S))

    def figures(name: str) -> dict[str, str]:
        text = sections[name]
        over_all, among = re.findall(r"(\d\.\d{3}) (?:over all|among the)", text)
        return {
            "mean": re.search(r"mean ([+-]\d+\.\d) %", text)[1].replace("-", MINUS),
            "all": over_all,
            "among": among,
            "unstable": ([*re.findall(r"unstable on (\d+\.\d)% of the samples", text), ""])[0],
            "limit": re.search(r"pump at its limit on (\d+\.\d)% of the runs", text)[1],
            "evaluated": re.search(r"samples: 64: (\d+) evaluated, (\d+) unstable", text).groups(),
            "ci": re.search(r"over all 64 samples.*?\(95 % CI (\S+)\)", text)[1],
            "spearman": float(re.search(r"speed_kmh \(driven\) (-\d\.\d\d)", text)[1]),
        }

    rows = {name: figures(name) for name in sections}
    labels = {
        "passive": "passive",
        "virtual-accumulator": "virtual accumulator",
        "skyhook": "skyhook with Table 3",
        "lqr": "output-feedback LQR",
        "optimised": "optimised for the nominal loads",
        "robust": "plants",
    }
    quotes = [f"{labels[n]} {rows[n]['mean']} % / {rows[n]['all']}" for n in labels]
    lqr, optimised = rows["lqr"], rows["optimised"]
    quotes.append(f"unstable on {lqr['unstable']} % of the samples, the pump at its limit in")
    quotes.append(f"{lqr['limit']} % of the runs), optimised")
    quotes.append(
        f"loads {optimised['mean']} % / {optimised['all']} (unstable on {optimised['unstable']} %)"
    )
    for name in ("skyhook", "robust"):
        assert rows[name]["evaluated"][1] == "0", f"the page says {name} is stable on every sample"
    spearman = sorted(row["spearman"] for row in rows.values())
    quotes.append(f"(Spearman {minus(f'{spearman[-1]:.2f}')} to {minus(f'{spearman[0]:.2f}')}:")
    quotes.append(
        f"unstable on the linearised plant of {lqr['evaluated'][1]} samples; filed as failures, the "
        f"report gives a probability of worse comfort of {lqr['all']} (95 % CI {lqr['ci']}) over "
        f"all 64 samples and {lqr['among']} among the {lqr['evaluated'][0]} evaluated, mean change "
        f"{lqr['mean']} % over those {lqr['evaluated'][0]}"
    )
    quotes.append(
        f"{optimised['evaluated'][1]} unstable, {optimised['all']} over all, {optimised['among']} "
        f"among the {optimised['evaluated'][0]} evaluated"
    )
    quotes.append(f"stable on every sample ({rows['robust']['all']} either way)")
    return [("robustness.md", q) for q in quotes]


def quotations() -> list[tuple[str, str]]:
    """Every (page, quoted text) rebuilt from its kept output or shipped result file."""
    return [
        *_design_check_quotations(),
        *_controllers_quotations(),
        *_bound_quotations(),
        *_performance_quotations(),
        *_hydraulics_quotations(),
        *_machines_quotations(),
        *_reproduction_quotations(),
        *_robustness_quotations(),
    ]


@pytest.mark.parametrize(("name", "quote"), quotations(), ids=lambda v: v[:50])
def test_quoted_figure_matches_its_source(name: str, quote: str) -> None:
    assert flat(quote) in flat(page(name)), f"{name} should quote, from its source: {quote!r}"


#: Pages whose block before "prints" is cheap (no simulation): a marker of that block's code.
CHEAP_BLOCKS = {
    "parameters.md": "default_loader()",
    "simulation.md": "validity_bounds(",
}


@pytest.mark.parametrize("name", sorted(CHEAP_BLOCKS))
def test_a_cheap_block_prints_what_its_page_shows(name: str, tmp_path, monkeypatch, capsys) -> None:
    """A cheap block with its output on the page: run it and compare the output exactly."""
    pairs = re.findall(r"```python\n(.*?)```\n\nprints\n\n```text\n(.*?)```", page(name), re.S)
    ((code, shown),) = [pair for pair in pairs if CHEAP_BLOCKS[name] in pair[0]]
    monkeypatch.chdir(tmp_path)
    exec(compile(code, name, "exec"), {"__name__": "__guide__"})
    assert capsys.readouterr().out == shown
