"""Build the plant FMU: CasADi C code generation, a hand-written FMI 2.0 wrapper, gcc, zip.

Route (see the README's FMU section): the plant Function of :mod:`loader_model.plant.plant` and
its static equilibrium are emitted as C by ``casadi.CodeGenerator``; ``fmi2_wrapper.c`` (beside
this module) implements the FMI 2.0 Model Exchange interface on top of them; the FMI 2.0 headers
(2-clause BSD, from the Modelica Association via FMPy) ship in ``include/``. Everything is built
in a temporary folder and the finished ``.fmu`` is renamed over the target at the end, so a
failed build leaves no partial file.
"""

from __future__ import annotations

import hashlib
import os
import platform
import shutil
import subprocess
import sys
import tempfile
import uuid
import zipfile
from pathlib import Path

import casadi as ca
import numpy as np

from loader_model.control.controllers import controller_state_names
from loader_model.control.settings import SETTINGS_NAMES
from loader_model.fmu.closed_loop import closed_loop_functions, closed_loop_variables
from loader_model.fmu.model_description import MODEL_IDENTIFIER, model_description_xml
from loader_model.fmu.variables import fmu_parameter_names, fmu_variables
from loader_model.io.export import check_output_path, write_atomically
from loader_model.plant.equilibrium import equilibrium_function, static_state
from loader_model.plant.layout import (
    SKID_STEER,
    MachineSource,
    PlantLayout,
    resolve_layout,
)
from loader_model.plant.plant import plant_function

__all__ = ["export_plant_fmu", "find_compiler", "fmu_functions"]

_HERE = Path(__file__).resolve().parent
_COMPILERS = ("gcc", "cc")


def find_compiler() -> str:
    """Path of a C compiler (``gcc``, else ``cc``; ``$CC`` first if set).

    Raises
    ------
    ValueError
        If none is found, saying what to install.
    """
    candidates = ([os.environ["CC"]] if os.environ.get("CC") else []) + list(_COMPILERS)
    for name in candidates:
        found = shutil.which(name)
        if found:
            return found
    raise ValueError(
        f"no C compiler found (looked for {', '.join(candidates)} on PATH); building an FMU "
        "compiles C code: install gcc (e.g. `apt-get install gcc`) or set CC"
    )


def _platform_folder() -> str:
    machine = platform.machine().lower()
    if sys.platform.startswith("linux") and machine in ("x86_64", "amd64"):
        return "linux64"
    raise ValueError(
        f"FMU export builds binaries for linux64 only; this is {sys.platform}/{machine}"
    )


def fmu_functions(layout: PlantLayout = SKID_STEER) -> tuple[ca.Function, ca.Function]:
    """``fmu_ode(x, in, p) -> (xdot, y)`` and ``fmu_start(p) -> x0`` over the FMU's parameters.

    ``in`` is (V_p_ref, w); ``p`` is ordered as :func:`~loader_model.fmu.variables.
    fmu_parameter_names` of the machine ``layout`` (default the skid-steer; the parameters the plant
    completes, its static tyre loads and preloads, are fixed at 0).
    """
    names = fmu_parameter_names(layout)
    p = ca.SX.sym("p", len(names))
    given = dict(zip(names, ca.vertsplit(p), strict=True))
    full = ca.vertcat(*[given.get(n, ca.SX(0)) for n in layout.parameter_names])
    x = ca.SX.sym("x", len(layout.state_names))
    inputs = ca.SX.sym("in", len(layout.input_names) + len(layout.exogenous_names))
    xdot, y = plant_function(layout)(x, inputs[0], inputs[1:], full)
    ode = ca.Function("fmu_ode", [x, inputs, p], [xdot, y], ["x", "in", "p"], ["xdot", "y"])
    x0 = equilibrium_function(layout)(full)[0]
    start = ca.Function("fmu_start", [p], [x0], ["p"], ["x0"])
    return ode, start


def _names(variables: list) -> list[str]:
    return [v.name for v in variables]


def _c_array(values: np.ndarray) -> str:
    return "{" + ", ".join(repr(float(v)) for v in values) + "}"


def _write_sources(
    folder: Path,
    params: np.ndarray,
    controller: str | None,
    settings: np.ndarray | None,
    layout: PlantLayout = SKID_STEER,
) -> tuple[bytes, str]:
    """Write the C sources into ``folder``; return (modelDescription.xml, model identifier)."""
    info = layout.machine
    n_p = len(fmu_parameter_names(layout))
    ode, start = fmu_functions(layout)
    generator = ca.CodeGenerator("fmu_model.c", {"with_header": True})
    generator.add(ode)
    generator.add(start)
    x0, u0 = static_state(params, layout)
    variables = fmu_variables(params, x0, u0, layout)
    identifier, n_set, n_z = MODEL_IDENTIFIER, 0, 0
    if controller is not None:
        sample, init = closed_loop_functions(controller, ode, start, layout)
        generator.add(sample)
        generator.add(init)
        variables = closed_loop_variables(variables, controller, settings, layout)
        identifier = f"loader_{controller}"
        n_set, n_z = sample.size1_in(2) - n_p, sample.size1_in(3)
    generator.generate(str(folder) + os.sep)
    source = (folder / "fmu_model.c").read_bytes()
    digest = hashlib.sha256(source + repr(variables).encode()).hexdigest()
    guid = "{" + str(uuid.uuid5(uuid.NAMESPACE_URL, f"loader-model:fmu:{digest}")) + "}"
    starts = np.array([0.0 if v.start is None else v.start for v in variables])
    nominals = np.array([v.nominal for v in variables if v.nominal is not None])
    config = (
        "/* written by loader_model.fmu.build; do not edit */\n"
        + ("#define CLOSED_LOOP 1\n" if controller is not None else "")
        + f'#define MODEL_GUID "{guid}"\n'
        f"#define N_P {n_p}\n"
        f"#define N_SET {n_set}\n"
        f"#define N_IN {len(layout.input_names) + len(layout.exogenous_names)}\n"
        f"#define N_X {len(layout.state_names)}\n"
        f"#define N_Y {len(layout.output_names)}\n"
        f"#define N_Z {n_z}\n"
        + (f"#define VR_TS {_names(variables).index('controller.T_s')}\n" if n_set else "")
        + f"#define START_VALUES {_c_array(starts)}\n"
        f"#define NOMINAL_VALUES {_c_array(nominals)}\n"
    )
    (folder / "fmu_config.h").write_text(config)
    shutil.copy(_HERE / "fmi2_wrapper.c", folder / "fmi2_wrapper.c")
    from loader_model import __version__ as version

    what = "the plant alone" if controller is None else f"plant and {controller} controller"
    title = "skid-steer loader" if info.is_default else info.title
    xml = model_description_xml(
        variables,
        guid,
        f"Nonlinear {title} (loader-model): {what}; states start at the static equilibrium",
        f"loader-model {version} (CasADi {ca.__version__} code generation, FMI 2.0 wrapper)",
        model_identifier=identifier,
    )
    return xml, identifier


def _compile(compiler: str, folder: Path, library: Path) -> None:
    command = [
        compiler,
        "-shared",
        "-fPIC",
        "-O1",
        "-fvisibility=default",
        f"-I{_HERE / 'include'}",
        f"-I{folder}",
        str(folder / "fmu_model.c"),
        str(folder / "fmi2_wrapper.c"),
        "-o",
        str(library),
        "-lm",
    ]
    done = subprocess.run(command, capture_output=True, text=True, check=False)
    if done.returncode != 0:
        raise ValueError(
            f"compiling the FMU's C code with {compiler} failed (exit {done.returncode}):\n"
            + done.stderr[-2000:]
        )


def export_plant_fmu(
    path: str | os.PathLike[str],
    params: np.ndarray,
    *,
    controller: str | None = None,
    settings: np.ndarray | None = None,
    include_sources: bool = True,
    machine: MachineSource = SKID_STEER,
) -> Path:
    """Build a Model Exchange FMU (FMI 2.0, linux64) of the nonlinear plant and write ``path``.

    Parameters
    ----------
    path : str or os.PathLike
        Target ``.fmu`` file; checked before any work, written atomically.
    params : numpy.ndarray
        Plant parameter vector (order ``PLANT_PARAMETER_NAMES``, from
        :func:`~loader_model.plant.plant_parameters.plant_parameter_vector`): the parameters'
        start values; the states start at its static equilibrium.
    controller : str, optional
        One of :data:`~loader_model.control.controllers.CONTROLLER_NAMES` to close the loop
        inside the FMU (:mod:`loader_model.fmu.closed_loop`); None: the plant alone.
    settings : numpy.ndarray, optional
        The controller's settings vector (:func:`~loader_model.control.settings.
        settings_vector_for_plant`); required with ``controller``.
    include_sources : bool
        Also put the C sources into ``sources/`` of the FMU (for inspection and rebuilding).
    machine : PlantLayout, str or pathlib.Path
        The machine resolved (:func:`~loader_model.plant.layout.plant_layout`), or a machine of
        :func:`~loader_model.machines.list_machines` or its description file resolved once here
        (default the skid-steer); ``params`` is then in its plant layout's order
        (:func:`~loader_model.plant.layout.plant_layout`); a controller reads the same named
        sensors on every machine (:mod:`loader_model.fmu.closed_loop`).

    Returns
    -------
    pathlib.Path
        The written FMU.

    Raises
    ------
    ValueError
        Bad path, no C compiler, unsupported platform or a failed compilation; nothing is
        written then.
    """
    target = check_output_path(path, (".fmu",), "FMU")
    layout = resolve_layout(machine)
    n_params = len(layout.parameter_names)
    params = np.asarray(params, dtype=float)
    if params.shape != (n_params,) or not np.all(np.isfinite(params)):
        raise ValueError(
            f"params must be {n_params} finite plant parameters; got shape {params.shape}"
        )
    if controller is not None:
        controller_state_names(controller)  # ValueError naming the allowed ones
        if settings is None or np.shape(settings) != (len(SETTINGS_NAMES),):
            raise ValueError(
                f"settings: controller {controller!r} needs its {len(SETTINGS_NAMES)} settings "
                f"(settings_vector_for_plant); got shape {np.shape(settings)}"
            )
    compiler = find_compiler()
    folder_name = _platform_folder()
    with tempfile.TemporaryDirectory(prefix="loader_fmu_") as temporary:
        build = Path(temporary)
        sources = build / "sources"
        sources.mkdir()
        xml, identifier = _write_sources(sources, params, controller, settings, layout)
        library = build / f"{identifier}.so"
        _compile(compiler, sources, library)

        def write(archive_path: Path) -> None:
            with zipfile.ZipFile(archive_path, "w", zipfile.ZIP_DEFLATED) as archive:
                archive.writestr("modelDescription.xml", xml)
                archive.write(library, f"binaries/{folder_name}/{identifier}.so")
                if include_sources:
                    for item in sorted(sources.iterdir()):
                        archive.write(item, f"sources/{item.name}")
                    for header in sorted((_HERE / "include").glob("*.h")):
                        archive.write(header, f"sources/{header.name}")

        return write_atomically(target, write, (".fmu",), "FMU")
