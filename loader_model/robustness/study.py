"""The study description (TOML): what varies, over which roads, speeds, loads and controllers.

A study file names the uncertain parameters by their parameter-file paths (``hydraulics.bulk_modulus``
of ``data/default_loader.toml``, ``load.mass`` of the bucket-load file), each with a distribution in
the field's SI unit. Everything is checked before anything runs: unknown keys and parameter names
(with the closest valid name), the unit (must equal the parameter file's unit, no conversion), the
distribution's support (must lie inside the field's validated range, with its reason), the sample
count, the road, speeds, loads and controllers. Errors name the key, the value and what is allowed.
The format is documented in the README and shipped as ``data/robustness_example.toml``.
"""

from __future__ import annotations

import difflib
import math
import tomllib
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any

from loader_model.robustness.distributions import Distribution, parse_distribution
from loader_model.robustness.machine_study import (
    machine_parameter_field,
    study_machine,
    study_params,
)

if TYPE_CHECKING:
    from loader_model.plant.layout import PlantLayout

__all__ = [
    "COMPARED_CONTROLLERS",
    "GAIN_METHODS",
    "SAMPLING_METHODS",
    "Study",
    "load_study",
    "parameter_field",
    "parse_study",
]

#: Sampling designs (scipy.stats.qmc), by their study-file name.
SAMPLING_METHODS: tuple[str, ...] = ("latin-hypercube", "sobol")
#: Controllers of section 5.3 a study can compare with the baseline (skyhook: Table 3 gains).
COMPARED_CONTROLLERS: tuple[str, ...] = ("passive", "virtual-accumulator", "skyhook")
#: Computed skyhook gains: output-feedback LQR per load (Eq. 41, 42), ISO 2631 optimisation over
#: both nominal loads, and the same optimisation over plants sampled from the study (robust).
GAIN_METHODS: tuple[str, ...] = ("table3", "table3-printed", "lqr", "optimised", "robust")
_ROAD_KINDS = ("course", "iso8608")
_ISO_CLASSES = tuple("ABCDEFGH")
_SECTIONS = ("study", "road", "conditions", "controllers", "parameters")


@dataclass(frozen=True)
class Study:
    """A validated robustness study (module notes; README "Robustness study").

    Attributes
    ----------
    name : str
        Label of the study.
    seed : int
        Seed of the sampling design and of every sample's road (with the sample index).
    samples : int
        Number of samples (plant, road, speed and load draws); each runs every controller.
    sampling : str
        ``"latin-hypercube"`` or ``"sobol"``.
    duration_s : float
        Simulated time of each run in s.
    batch_size : int
        Samples per task of the execution engine.
    road : str
        ``"course"`` (the paper's five 4 cm boards, section 5.3) or ``"iso8608"``.
    road_class : str
        ISO 8608 class A-H (random road; also the road of the gain design plants).
    road_length_m, position_jitter_m : float
        Length of the ISO 8608 road; standard deviation of each board's position on the course.
    speeds_kmh : tuple of float
        Nominal speeds, drawn with equal probability (course: 9 or 18 km/h, section 5.3).
    speed_spread : float
        The driven speed is uniform within ± this fraction of the nominal speed.
    loads : tuple of str
        Bucket-load cases (``"empty"`` 340 kg, ``"full"`` 770 kg), drawn with equal probability.
    compare : tuple of str
        Controllers of :data:`COMPARED_CONTROLLERS` run beside the baseline.
    gains : tuple of (str, str or tuple of float)
        Further skyhook variants: name and a method of :data:`GAIN_METHODS` or four gains K_fb.
    robust_plants : int
        Number of sampled plants the ``"robust"`` gains are optimised over.
    parameters : tuple of (str, Distribution)
        Uncertain parameters by parameter-file path, in the study file's order.
    machine : str
        The machine (``[study] machine``, default the skid-steer); another machine's parameters
        are its flat file's paths (:mod:`~loader_model.robustness.machine_study`); a
        description file outside the package is held as its absolute path.
    params : str or None
        ``[study] params``: another machine's flat parameter file, resolved against the working
        folder (default the machine's shipped file; required for a machine from a description
        file, which ships none).
    layout : PlantLayout
        The machine resolved once when the study is read (a worker process that unpickles the
        study resolves it again through the verified machine registry); default: resolved from
        ``machine``.
    """

    name: str
    seed: int
    samples: int
    sampling: str
    duration_s: float
    batch_size: int
    road: str
    road_class: str
    road_length_m: float
    position_jitter_m: float
    speeds_kmh: tuple[float, ...]
    speed_spread: float
    loads: tuple[str, ...]
    compare: tuple[str, ...]
    gains: tuple[tuple[str, str | tuple[float, ...]], ...]
    robust_plants: int
    parameters: tuple[tuple[str, Distribution], ...]
    machine: str = "skid_steer"
    params: str | None = None
    layout: PlantLayout = field(default=None, compare=False, repr=False)  # type: ignore[assignment]

    def __post_init__(self) -> None:
        if self.layout is None:
            from loader_model.plant.layout import plant_layout

            object.__setattr__(self, "layout", plant_layout(self.machine))

    @property
    def controllers(self) -> tuple[str, ...]:
        """Every controller run on each sample, baseline first."""
        return ("baseline", *self.compare, *(name for name, _ in self.gains))


def parameter_field(path: str) -> tuple[str, Any]:
    """The SI unit and validated range (:class:`~loader_model.parameters.fields.Range`) of a study
    parameter path.

    ``load.<field>`` is a field of the bucket-load file, ``sensors.<name>.gain|offset|noise_std``
    a sensor error (:mod:`~loader_model.robustness.sensors`), anything else a dotted path of the loader
    file. Only scalar real fields can vary (not points, vectors or counts).

    Raises
    ------
    ValueError
        Naming the path, with the closest valid path.
    """
    from loader_model.parameters.schema import BucketLoad, LoaderParameters
    from loader_model.parameters.toml_format import iter_leaves, leaf_metadata
    from loader_model.robustness.sensors import SENSOR_ERROR_FIELDS

    if path in SENSOR_ERROR_FIELDS:
        return SENSOR_ERROR_FIELDS[path]
    leaves = {p: (c, n) for p, c, n in iter_leaves(LoaderParameters)}
    leaves |= {f"load.{p}": (c, n) for p, c, n in iter_leaves(BucketLoad)}
    scalar = [p for p, (c, n) in leaves.items() if _is_scalar(leaf_metadata(c, n))]
    if path not in scalar:
        if path in leaves:
            raise ValueError(
                f"parameters.{path}: only scalar real parameters can vary (not points, vectors "
                "or counts)"
            )
        close = difflib.get_close_matches(path, [*scalar, *SENSOR_ERROR_FIELDS], n=1, cutoff=0.5)
        hint = f"; did you mean {close[0]!r}?" if close else ""
        raise ValueError(
            f"parameters.{path}: unknown parameter{hint} (names are the parameter files' "
            "dotted paths, e.g. 'hydraulics.bulk_modulus', 'tyres.front.k_y', 'load.mass', or "
            "'sensors.<f_Hx|f_Hy|f_Ny|phi|p_A>.<gain|offset|noise_std>')"
        )
    metadata = leaf_metadata(*leaves[path])
    return metadata["unit"], metadata["allowed"]


def _is_scalar(metadata: Mapping[str, Any]) -> bool:
    return metadata.get("shape", 0) == 0 and not metadata.get("integer", False)


def _keys(table: Mapping[str, Any], allowed: tuple[str, ...], where: str) -> None:
    for key in table:
        if key not in allowed:
            close = difflib.get_close_matches(key, allowed, n=1, cutoff=0.5)
            hint = f"did you mean {close[0]!r}?" if close else f"allowed keys: {list(allowed)}"
            raise ValueError(f"{where}{key}: unknown key; {hint}")


def _integer(value: Any, key: str, low: int, high: int) -> int:
    if isinstance(value, bool) or not isinstance(value, int) or not low <= value <= high:
        raise ValueError(f"{key} = {value!r}: allowed: an integer from {low} to {high}")
    return int(value)


def _number(value: Any, key: str, low: float, high: float) -> float:
    ok = not isinstance(value, bool) and isinstance(value, int | float)
    if not ok or not math.isfinite(value) or not low <= value <= high:
        raise ValueError(f"{key} = {value!r}: allowed: a number from {low:g} to {high:g}")
    return float(value)


def _choices(value: Any, key: str, allowed: tuple[Any, ...]) -> tuple[Any, ...]:
    if not isinstance(value, list) or not value:
        raise ValueError(f"{key} = {value!r}: allowed: a non-empty list of {list(allowed)}")
    for item in value:
        if item not in allowed or isinstance(item, bool):
            raise ValueError(f"{key}: {item!r} is not allowed; allowed: {list(allowed)}")
    if len(set(value)) != len(value):
        raise ValueError(f"{key} = {value!r}: entries must be distinct")
    return tuple(value)


def _gains(table: Any) -> tuple[tuple[str, str | tuple[float, ...]], ...]:
    if not isinstance(table, dict):
        raise ValueError(f"controllers.gains = {table!r}: allowed: a table name = method or K_fb")
    gains: list[tuple[str, str | tuple[float, ...]]] = []
    for name, spec in table.items():
        key = f"controllers.gains.{name}"
        if name in ("baseline", *COMPARED_CONTROLLERS):
            raise ValueError(f"{key}: the name is taken by a controller; choose another")
        if isinstance(spec, str):
            if spec not in GAIN_METHODS:
                raise ValueError(f"{key} = {spec!r}: allowed: one of {list(GAIN_METHODS)}")
            gains.append((name, spec))
            continue
        bad = not isinstance(spec, list) or len(spec) != 4
        if bad or any(isinstance(g, bool) or not isinstance(g, int | float) for g in spec):
            raise ValueError(
                f"{key} = {spec!r}: allowed: one of {list(GAIN_METHODS)} or four gains K_fb"
            )
        if not all(math.isfinite(g) and abs(g) <= 1e4 for g in spec):
            raise ValueError(f"{key} = {spec!r}: gains must be finite, |K| <= 1e4")
        gains.append((name, tuple(float(g) for g in spec)))
    return tuple(gains)


def parse_study(text: str, origin: str = "study file") -> Study:
    """Parse and validate a study file's text (module notes).

    Parameters
    ----------
    text : str
        TOML text of the study.
    origin : str
        Where it came from, for messages.

    Returns
    -------
    Study

    Raises
    ------
    ValueError
        Naming the origin, the key, the value and what is allowed; raised before anything runs.
    """
    from loader_model.parameters.sets import LOAD_CASES
    from loader_model.simulation.courses import PAPER_SPACING_M

    try:
        data = tomllib.loads(text)
    except tomllib.TOMLDecodeError as error:
        raise ValueError(f"{origin}: not valid TOML: {error}") from None
    try:
        return _build(data, LOAD_CASES, tuple(PAPER_SPACING_M))
    except ValueError as error:
        raise ValueError(f"{origin}: {error}") from None


def _table(data: Mapping[str, Any], name: str) -> dict[str, Any]:
    table = data.get(name, {})
    if not isinstance(table, dict):
        raise ValueError(f"{name}: must be a table [{name}]")
    return table


def _build(data: dict[str, Any], load_cases: tuple[str, ...], course_speeds: tuple) -> Study:
    _keys(data, _SECTIONS, "")
    study = _table(data, "study")
    keys = ("name", "seed", "samples", "sampling", "duration_s", "batch_size", "machine", "params")
    _keys(study, keys, "study.")
    from loader_model.plant.layout import plant_layout

    machine = study_machine(study.get("machine", "skid_steer"))
    layout = plant_layout(machine)
    params = study_params(study.get("params"), machine)
    if "samples" not in study:
        raise ValueError("study.samples: missing key (the number of samples, >= 1)")
    samples = _integer(study["samples"], "study.samples", 1, 10_000_000)
    sampling = study.get("sampling", "latin-hypercube")
    if sampling not in SAMPLING_METHODS:
        raise ValueError(f"study.sampling = {sampling!r}: allowed: {list(SAMPLING_METHODS)}")
    road = _table(data, "road")
    _keys(road, ("kind", "class", "length_m", "position_jitter_m"), "road.")
    kind = road.get("kind", "course")
    if kind not in _ROAD_KINDS:
        raise ValueError(f"road.kind = {kind!r}: allowed: {list(_ROAD_KINDS)}")
    road_class = road.get("class", "C")
    if road_class not in _ISO_CLASSES:
        raise ValueError(f"road.class = {road_class!r}: allowed: ISO 8608 class {_ISO_CLASSES}")
    conditions = _table(data, "conditions")
    _keys(conditions, ("speeds_kmh", "speed_spread", "loads"), "conditions.")
    default_speeds = list(course_speeds) if kind == "course" else [9.0]
    speeds = conditions.get("speeds_kmh", default_speeds)
    if kind == "course":
        speeds = _choices(speeds, "conditions.speeds_kmh", course_speeds)
    else:
        if not isinstance(speeds, list) or not speeds:
            raise ValueError(f"conditions.speeds_kmh = {speeds!r}: allowed: a non-empty list")
        speeds = tuple(_number(s, "conditions.speeds_kmh", 1.0, 60.0) for s in speeds)
    controllers = _table(data, "controllers")
    _keys(controllers, ("compare", "gains", "robust_plants"), "controllers.")
    gains = _gains(controllers.get("gains", {}))
    parameters = _table(data, "parameters")
    varied = []
    for path, spec in parameters.items():
        if machine == "skid_steer":
            unit, allowed = parameter_field(path)
        else:
            unit, allowed = machine_parameter_field(path, layout.machine)
        varied.append((path, parse_distribution(spec, f"parameters.{path}", unit, allowed)))
    return Study(
        name=str(study.get("name", "robustness study")),
        seed=_integer(study.get("seed", 0), "study.seed", 0, 2**63 - 1),
        samples=samples,
        sampling=sampling,
        duration_s=_number(study.get("duration_s", 10.0), "study.duration_s", 3.0, 600.0),
        batch_size=_integer(study.get("batch_size", 16), "study.batch_size", 1, 100_000),
        road=kind,
        road_class=road_class,
        road_length_m=_number(road.get("length_m", 200.0), "road.length_m", 10.0, 10_000.0),
        position_jitter_m=_number(
            road.get("position_jitter_m", 0.05), "road.position_jitter_m", 0.0, 1.0
        ),
        speeds_kmh=tuple(float(s) for s in speeds),
        speed_spread=_number(
            conditions.get("speed_spread", 0.05), "conditions.speed_spread", 0, 0.5
        ),
        loads=_choices(conditions.get("loads", list(load_cases)), "conditions.loads", load_cases),
        compare=_choices(
            controllers.get("compare", list(COMPARED_CONTROLLERS)),
            "controllers.compare",
            COMPARED_CONTROLLERS,
        ),
        gains=gains,
        robust_plants=_integer(
            controllers.get("robust_plants", 8), "controllers.robust_plants", 1, 200
        ),
        parameters=tuple(varied),
        machine=machine,
        params=params,
        layout=layout,
    )


def load_study(path: str | Path) -> Study:
    """Read and validate the study file at ``path`` (ValueError naming file, key and value)."""
    path = Path(path)
    try:
        text = path.read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as error:
        reason = getattr(error, "strerror", None) or str(error)
        raise ValueError(f"study file {str(path)!r} cannot be read: {reason}") from None
    return parse_study(text, f"study file {str(path)!r}")
