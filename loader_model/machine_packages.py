"""Generated packages of machine descriptions outside the package: a private cache, verified.

Generated code is Python: it runs as the user. So the runtime imports the package of a
description ``path/to/<stem>.toml`` only from a folder of its own, never from beside the file:
``python -m derive path/to/<stem>.toml`` writes it into the per-user cache
(:func:`generated_folder`: ``$XDG_CACHE_HOME/loader-model/machines/<key>/``, ``~/.cache`` when
``XDG_CACHE_HOME`` is unset), where ``<key>`` is the SHA-256 of the description's bytes and of the
version of the deriving code (the ``INPUT_HASH`` of the shipped generated package). Beside the
package the folder holds a copy of the description and ``MANIFEST.json``, the SHA-256 of every
file. :func:`register_external` imports the folder only after :func:`verify` checked that the
folder and the cache folders above it are real folders (no symbolic link), owned by the user and
not writable by the group or others, that the folder holds exactly the files of its manifest with
those hashes, and that the manifest names this description. A worker process (a robustness
study's pool) resolves the file again and so checks and imports the same folder. Standard library
only (no SymPy, no CasADi): :mod:`loader_model.machines` uses it.
"""

from __future__ import annotations

import hashlib
import importlib.util
import json
import os
import shlex
import shutil
import stat
import sys
from pathlib import Path

__all__ = [
    "MANIFEST",
    "cache_root",
    "derive_command",
    "derive_extra_command",
    "description_hash",
    "external",
    "external_source",
    "generated_folder",
    "prepare_cache",
    "register_external",
    "verify",
    "write_manifest",
]

MANIFEST = "MANIFEST.json"
_COPY = "description.toml"
_PREFIX = "loader_model_machine_"
_FORMAT = 1
#: Owners and permission bits are checked where they exist (not on Windows).
_POSIX = os.name == "posix" and hasattr(os, "getuid")
#: Machines loaded from description files in this process: name -> (resolved description path,
#: module name of its generated package, description hash, the verified cache folder).
_EXTERNAL: dict[str, tuple[Path, str, str, Path]] = {}


def external(name: str) -> tuple[Path, str] | None:
    """(the verified copy of the description, module name of its package) of a loaded machine."""
    known = _EXTERNAL.get(name)
    return None if known is None else (known[3] / _COPY, known[1])


def external_source(name: str) -> Path | None:
    """The description file a machine loaded in this process was read from (None: not loaded)."""
    known = _EXTERNAL.get(name)
    return None if known is None else known[0]


def description_hash(path: str | os.PathLike[str] | bytes) -> str:
    """``sha256:<hex>`` of a description file or its bytes (line endings normalised, as derive)."""
    data = path if isinstance(path, bytes) else Path(path).read_bytes()
    return "sha256:" + hashlib.sha256(data.replace(b"\r\n", b"\n")).hexdigest()


def _derive_version() -> str:
    import loader_model_generated

    return str(loader_model_generated.INPUT_HASH)


def cache_root() -> Path:
    """``$XDG_CACHE_HOME/loader-model/machines`` (``~/.cache/...`` without an absolute one)."""
    base = os.environ.get("XDG_CACHE_HOME", "")
    root = Path(base) if os.path.isabs(base) else Path.home() / ".cache"
    return root / "loader-model" / "machines"


def generated_folder(description: str | os.PathLike[str] | bytes) -> Path:
    """The cache folder of the generated package of a description (a file or its bytes).

    Named by the SHA-256 of the description's bytes and of the deriving code's version, so an
    edit of the file (even of a comment) or a new version of loader-model names another folder.
    """
    key = f"{description_hash(description)}\n{_derive_version()}\n".encode()
    return cache_root() / hashlib.sha256(key).hexdigest()[:40]


def _private(path: Path, what: str, inside: bool = False) -> None:
    """Refuse a folder or file that is a link, not the user's, or writable by others (a file
    ``inside`` the package's folder, which only its owner can enter, may have any mode)."""
    try:
        info = path.lstat()
    except OSError as error:
        raise ValueError(f"{path}: {what} cannot be read ({error.strerror})") from None
    if stat.S_ISLNK(info.st_mode):
        raise ValueError(f"{path}: {what} is a symbolic link; the runtime does not follow it")
    if _POSIX and info.st_uid != os.getuid():
        raise ValueError(f"{path}: {what} belongs to another user (uid {info.st_uid})")
    if _POSIX and not inside and info.st_mode & (stat.S_IWGRP | stat.S_IWOTH):
        raise ValueError(
            f"{path}: {what} is writable by the group or others (mode {oct(info.st_mode & 0o777)})"
        )


def prepare_cache() -> Path:
    """Make the cache folders (mode 0o700) and check them; returns :func:`cache_root`."""
    root = cache_root()
    for folder in (root.parent, root):
        folder.mkdir(mode=0o700, parents=True, exist_ok=True)
        _private(folder, "the machine cache folder")
    return root


def _sha256(path: Path) -> str:
    return hashlib.sha256(path.read_bytes()).hexdigest()


def write_manifest(folder: Path, description: bytes) -> None:
    """Add the copy of ``description`` and ``MANIFEST.json`` to a package ``folder``."""
    (folder / _COPY).write_bytes(description)
    files = {path.name: _sha256(path) for path in sorted(folder.iterdir()) if path.is_file()}
    manifest = {
        "format": _FORMAT,
        "description_hash": description_hash(description),
        "derive_version": _derive_version(),
        "files": files,
    }
    (folder / MANIFEST).write_text(json.dumps(manifest, indent=1) + "\n", encoding="utf-8")


def _manifest(folder: Path) -> dict[str, str]:
    path = folder / MANIFEST
    _private(path, "the manifest", inside=True)
    try:
        manifest = json.loads(path.read_text(encoding="utf-8"))
        files = manifest["files"]
        assert isinstance(files, dict) and all(isinstance(v, str) for v in files.values())
        assert manifest["format"] == _FORMAT
    except (OSError, ValueError, KeyError, TypeError, AssertionError):
        raise ValueError(f"{path}: not a manifest written by python -m derive") from None
    names = [name for name in files if "/" in name or name in ("", ".", "..", MANIFEST)]
    if names or manifest.get("derive_version") != _derive_version():
        raise ValueError(f"{path}: written by another version of the deriving code")
    return {str(name): str(digest) for name, digest in files.items()}


def verify(folder: Path, description: bytes) -> None:
    """Check a cache folder before anything in it is imported (module notes).

    Raises
    ------
    ValueError
        Naming the folder, file or link that fails a check.
    """
    for parent in (cache_root().parent, cache_root()):
        _private(parent, "the machine cache folder")
    _private(folder, "the generated package's folder")
    if _POSIX and folder.lstat().st_mode & 0o077:
        raise ValueError(f"{folder}: others may enter the generated package's folder (not 0o700)")
    files = _manifest(folder)
    for name, digest in files.items():
        path = folder / name
        _private(path, "a generated file", inside=True)
        if not path.is_file() or _sha256(path) != digest:
            raise ValueError(f"{path}: differs from the manifest (changed after derive wrote it)")
    if description_hash((folder / _COPY).read_bytes()) != description_hash(description):
        raise ValueError(f"{folder}: was derived from another description")
    for entry in folder.iterdir():
        if entry.name == "__pycache__":
            _private(entry, "the bytecode folder", inside=True)
            for item in entry.iterdir():
                _private(item, "a bytecode file", inside=True)
        elif entry.name not in files and entry.name != MANIFEST:
            raise ValueError(f"{entry}: not in the manifest (added after derive wrote the folder)")


def _on_path(name: str) -> bool:
    """Whether ``name`` on the user's ``PATH`` is the file of that name beside this interpreter
    (the same environment: an activated one, or its scripts folder on the ``PATH``)."""
    found = shutil.which(name)
    beside = Path(sys.executable).absolute().with_name(name)
    return found is not None and Path(found).absolute() == beside


def _python() -> str:
    """How to call this interpreter from the user's shell: ``python`` when that is it on the
    ``PATH`` (an activated environment), else its full path."""
    return "python" if _on_path("python") else shlex.quote(str(Path(sys.executable).absolute()))


def derive_command(path: str | os.PathLike[str]) -> str:
    """The command that derives the description ``path`` where the user is.

    ``python -m derive path`` when ``python`` on the ``PATH`` is this interpreter (an activated
    environment), else ``loader-model-derive path`` when that console script of this environment
    is on the ``PATH``, else this interpreter's full path with ``-m derive``; ``path`` as the
    user gave it (relative to the working folder), quoted for a POSIX shell where it needs it.
    """
    quoted = shlex.quote(str(path))
    if not _on_path("python") and _on_path("loader-model-derive"):
        return f"loader-model-derive {quoted}"
    return f"{_python()} -m derive {quoted}"


def derive_extra_command() -> str:
    """The command that installs the derive extra (SymPy) into this interpreter's environment:
    from the source folder of an editable install (a clone), else from the package index."""
    import loader_model

    root = Path(loader_model.__file__).resolve().parents[1]
    source = root / "pyproject.toml"
    if source.is_file() and 'name = "loader-model"' in source.read_text(encoding="utf-8"):
        target = "-e " + shlex.quote(f"{root}[derive]")
    else:
        target = shlex.quote("loader-model[derive]")
    return f"{_python()} -m pip install {target}"


def _extra_note() -> str:
    """Where SymPy is missing: how to install the derive extra, else nothing."""
    if importlib.util.find_spec("sympy") is not None:
        return ""
    return f" (needs the derive extra: `{derive_extra_command()}`)"


def _import(path: Path, name: str, folder: Path, digest: str) -> str:
    """Import the verified package in ``folder`` under a unique module name."""
    module_name = f"{_PREFIX}{name}_{digest.removeprefix('sha256:')[:12]}"
    spec = importlib.util.spec_from_file_location(
        module_name, folder / "__init__.py", submodule_search_locations=[str(folder)]
    )
    if spec is None or spec.loader is None:  # pragma: no cover - a readable __init__.py loads
        raise ValueError(f"{path}: cannot import the generated package {folder}/")
    module = importlib.util.module_from_spec(spec)
    sys.modules[module_name] = module
    try:
        spec.loader.exec_module(module)
    except (Exception, SystemExit) as error:
        del sys.modules[module_name]
        raise ValueError(
            f"{path}: the generated package {folder}/ does not import "
            f"({type(error).__name__}: {error}); derive it again with `{derive_command(path)}`"
        ) from None
    return module_name


def register_external(path: Path, name: str) -> str:
    """Verify and import the generated package of the description ``path`` of machine ``name``
    from the cache (module notes) and register it; returns ``name``.

    Raises
    ------
    ValueError
        Naming the file and the ``python -m derive`` command when its package is missing from the
        cache (never derived, or derived from another version of the file or of loader-model),
        fails :func:`verify` or does not import; or when another file (or this file's earlier
        version) is already registered under ``name`` in this process.
    """
    data = Path(path).read_bytes()
    wanted = description_hash(data)
    folder = generated_folder(data)
    if not folder.exists() and not folder.is_symlink():
        raise ValueError(
            f"{path}: machine {name!r} has no generated package for this version of the file "
            f"(none in {folder}/); derive it with `{derive_command(path)}`{_extra_note()}"
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
    try:
        verify(folder, data)
    except ValueError as error:
        raise ValueError(
            f"{path}: the generated package is refused: {error}; derive it again with "
            f"`{derive_command(path)}`"
        ) from None
    module_name = _import(path, name, folder, wanted)
    _EXTERNAL[name] = (path.resolve(), module_name, wanted, folder)
    return name
