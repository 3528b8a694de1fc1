"""loader-model: active vibration damping of a pump-controlled skid-steer loader.

Runtime package of the model of Williamson, Lee and Ivantysynova (Int. J. Fluid Power, 2009).
The equations of motion are derived with SymPy by ``derive/`` and emitted as Python source that
builds CasADi functions (the ``loader_model_generated`` package, folder ``generated/``). This
package uses them; it never imports SymPy.

Importing the package is cheap: submodules load on first attribute access.
"""

from __future__ import annotations

import importlib
from importlib import metadata
from typing import Any

try:  # the one version string is pyproject.toml's, read from the installed package's metadata
    __version__ = metadata.version("loader-model")
except metadata.PackageNotFoundError:  # the source tree on sys.path without an install
    __version__ = "0+unknown"

_LAZY_ATTRIBUTES = {
    "LoaderDynamics": "loader_model.vehicle.dynamics",
    "PARAMETER_NAMES": "loader_model.vehicle.dynamics",
}

__all__ = ["PARAMETER_NAMES", "LoaderDynamics", "__version__"]


def __getattr__(name: str) -> Any:
    module_name = _LAZY_ATTRIBUTES.get(name)
    if module_name is None:
        raise AttributeError(f"module 'loader_model' has no attribute {name!r}")
    return getattr(importlib.import_module(module_name), name)
