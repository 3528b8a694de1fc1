"""Generated packages of machine descriptions outside the package.

A description ``path/to/<stem>.toml`` outside ``derive/machines`` is derived by
``python -m derive path/to/<stem>.toml`` into ``path/to/<stem>_generated/`` beside it
(:func:`generated_folder`, the convention). :func:`register_external` checks that folder's
``DESCRIPTION_HASH`` against the file, imports it under a unique module name
(``loader_model_machine_<name>_<12 hex of the hash>``) and registers the machine under its
``[machine] name`` for the rest of the process; :func:`external` looks a registered machine up.
The registration is per process: a worker process resolves the file again. Standard library
only (no SymPy, no CasADi): :mod:`loader_model.machines` uses it.
"""

from __future__ import annotations

import hashlib
import importlib.util
import os
import sys
from pathlib import Path

__all__ = ["description_hash", "external", "generated_folder", "register_external"]

_EXTERNAL_SUFFIX = "_generated"
_EXTERNAL_PREFIX = "loader_model_machine_"
#: Machines loaded from description files outside the package in this process:
#: name -> (resolved description path, module name of its generated package, description hash).
_EXTERNAL: dict[str, tuple[Path, str, str]] = {}


def external(name: str) -> tuple[Path, str] | None:
    """(description path, module name of its generated package) of a registered machine."""
    known = _EXTERNAL.get(name)
    return None if known is None else (known[0], known[1])


def description_hash(path: str | os.PathLike[str]) -> str:
    """``sha256:<hex>`` of a description file (line endings normalised, as ``derive`` does)."""
    data = Path(path).read_bytes().replace(b"\r\n", b"\n")
    return "sha256:" + hashlib.sha256(data).hexdigest()


def generated_folder(description: str | os.PathLike[str]) -> Path:
    """Where the generated package of a description outside the package lives (convention).

    ``path/to/<stem>.toml`` -> ``path/to/<stem>_generated/``, the folder that
    ``python -m derive path/to/<stem>.toml`` writes.
    """
    path = Path(description)
    return path.with_name(path.stem + _EXTERNAL_SUFFIX)


def _derive_command(path: Path) -> str:
    return f"python -m derive {path}"


def register_external(path: Path, name: str) -> str:
    """Import the generated package beside the description ``path`` of machine ``name`` under a
    unique module name and register it (module notes); returns ``name``.

    Raises
    ------
    ValueError
        Naming the file and the ``python -m derive`` command when the folder is missing, was
        derived from another version of the file or does not import; or when another file (or
        this file's earlier version) is already registered under ``name`` in this process.
    """
    folder = generated_folder(path)
    wanted = description_hash(path)
    init = folder / "__init__.py"
    if not init.is_file():
        raise ValueError(
            f"{path}: machine {name!r} has no generated package in {folder}/; derive it with "
            f"`{_derive_command(path)}` (needs the derive extra: pip install -e '.[derive]')"
        )
    header = init.read_text(encoding="utf-8")
    if f'DESCRIPTION_HASH = "{wanted}"' not in header:
        raise ValueError(
            f"{path}: the generated package {folder}/ was derived from another version of this "
            f"description (its DESCRIPTION_HASH is not {wanted}); derive it again with "
            f"`{_derive_command(path)}`"
        )
    known = _EXTERNAL.get(name)
    if known is not None:
        if known[0] == path.resolve() and known[2] != wanted:
            raise ValueError(
                f"{path}: the description of machine {name!r} changed since this process "
                "loaded it; start a new process to use the new version"
            )
        if known[0] != path.resolve():
            raise ValueError(
                f"{path}: machine {name!r} is already loaded from {known[0]} in this process; "
                "give the description another [machine] name"
            )
        return name
    module_name = f"{_EXTERNAL_PREFIX}{name}_{wanted.removeprefix('sha256:')[:12]}"
    spec = importlib.util.spec_from_file_location(
        module_name, init, submodule_search_locations=[str(folder)]
    )
    if spec is None or spec.loader is None:  # pragma: no cover - a readable __init__.py loads
        raise ValueError(f"{path}: cannot import the generated package {folder}/")
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module
    try:
        spec.loader.exec_module(module)
    except Exception as error:
        del sys.modules[module_name]
        raise ValueError(
            f"{path}: the generated package {folder}/ does not import ({error}); derive it "
            f"again with `{_derive_command(path)}`"
        ) from None
    _EXTERNAL[name] = (path.resolve(), module_name, wanted)
    return name
