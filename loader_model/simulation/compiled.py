"""Compile a CasADi Function to a shared library once per machine, not once per process.

CasADi's JIT (``"jit": True``) compiles a Function's C code in every process that builds it:
about 0.6 s per closed-loop period on these machines, paid again by every pool worker, every
Dask worker and every ``loader-model`` call. Here the C code is generated with
:class:`casadi.CodeGenerator`, named by the SHA-256 of its text together with the compiler,
its flags, CasADi's version and the platform, compiled once into a cache folder and loaded with
:func:`casadi.external` everywhere after that (a few milliseconds). Like Numba's
``cache=True`` or a ccache, a library in the cache is only ever the compilation of exactly the
source that names it.

The cache folder is ``$LOADER_MODEL_CACHE_DIR`` if set, else ``$XDG_CACHE_HOME/loader-model``,
else ``~/.cache/loader-model``; ``LOADER_MODEL_CACHE_DIR=off`` (or a folder that cannot be
written) compiles into a temporary folder of the process instead, removed at exit. Libraries
are written under a temporary name and renamed into place, so processes that compile the same
source at once never load a half-written file; a library that fails to load is compiled again.
"""

from __future__ import annotations

import hashlib
import os
import platform
import shutil
import subprocess
import sys
import tempfile
from multiprocessing import util
from pathlib import Path

import casadi as ca

__all__ = [
    "COMPILER_FLAGS",
    "CompilationError",
    "cache_directory",
    "cached_function",
    "compiled_function",
]

#: Flags of the C compiler (``-O1`` compiles the closed-loop period in about 0.5 s and runs it as
#: fast as ``-O3`` did, measured on the 9 km/h course run).
COMPILER_FLAGS: tuple[str, ...] = ("-O1", "-fPIC", "-shared")

_PROCESS_FOLDERS: dict[int, Path] = {}


class CompilationError(RuntimeError):
    """No working C compiler, or it failed on the generated code."""


def cache_directory() -> Path | None:
    """The machine's cache folder of compiled libraries, or None when disabled (module notes)."""
    setting = os.environ.get("LOADER_MODEL_CACHE_DIR")
    if setting is not None:
        return None if setting.strip().lower() in ("", "off", "0", "none") else Path(setting)
    base = os.environ.get("XDG_CACHE_HOME") or str(Path.home() / ".cache")
    return Path(base) / "loader-model"


def _process_folder() -> Path:
    """A temporary folder of this process, removed at exit (also in pool workers)."""
    pid = os.getpid()
    if pid not in _PROCESS_FOLDERS:
        folder = Path(tempfile.mkdtemp(prefix="loader-model-compiled-"))
        util.Finalize(None, shutil.rmtree, args=(str(folder), True), exitpriority=0)
        _PROCESS_FOLDERS[pid] = folder
    return _PROCESS_FOLDERS[pid]


def _writable_folder() -> Path:
    folder = cache_directory()
    if folder is not None:
        try:
            folder.mkdir(parents=True, exist_ok=True)
            if os.access(folder, os.W_OK | os.X_OK):
                return folder
        except OSError:
            pass
    return _process_folder()


def _compiler() -> str:
    compiler = os.environ.get("CC") or shutil.which("cc") or shutil.which("gcc")
    if not compiler:
        raise CompilationError("no C compiler found (set CC or install cc/gcc)")
    return compiler


def _source(function: ca.Function) -> str:
    generator = ca.CodeGenerator(f"{function.name()}.c", {"with_header": False})
    generator.add(function)
    return generator.dump()


def _compile(source: str, library: Path, compiler: str) -> None:
    """Compile ``source`` into ``library`` through a temporary name in the same folder."""
    with tempfile.TemporaryDirectory(dir=library.parent, prefix=".build-") as build:
        c_file = Path(build) / "source.c"
        c_file.write_text(source)
        output = Path(build) / library.name
        command = [compiler, *COMPILER_FLAGS, str(c_file), "-o", str(output), "-lm"]
        try:
            completed = subprocess.run(command, capture_output=True, text=True, check=False)
        except OSError as error:
            raise CompilationError(f"{compiler} could not run: {error}") from error
        if completed.returncode != 0:
            raise CompilationError(
                f"{' '.join(command)} failed ({completed.returncode}): {completed.stderr[-2000:]}"
            )
        os.replace(output, library)


def _library(function: ca.Function) -> tuple[str, str, Path]:
    """(C source, compiler, library path in the cache) of ``function`` (module notes)."""
    compiler = _compiler()
    source = _source(function)
    identity = "\n".join(
        [source, compiler, *COMPILER_FLAGS, ca.__version__, sys.platform, platform.machine()]
    )
    digest = hashlib.sha256(identity.encode()).hexdigest()[:32]
    return source, compiler, _writable_folder() / f"{function.name()}-{digest}.so"


def _load(function: ca.Function, library: Path) -> ca.Function | None:
    if not library.exists():
        return None
    try:
        return ca.external(function.name(), str(library))
    except RuntimeError:  # a damaged file (e.g. a disk that filled up): compile it again
        return None


def cached_function(function: ca.Function) -> ca.Function | None:
    """``function``'s compiled library if the cache already holds it, else None (nothing is
    compiled: for callers whose one use would not repay the compilation)."""
    try:
        _, _, library = _library(function)
    except CompilationError:
        return None
    return _load(function, library)


def compiled_function(function: ca.Function) -> ca.Function:
    """``function`` as C, compiled once into the cache and loaded from there (module notes).

    Parameters
    ----------
    function : casadi.Function
        Any code-generatable Function (SX or MX with code-generatable nodes).

    Returns
    -------
    casadi.Function
        The loaded library, same name, inputs and outputs as ``function``.

    Raises
    ------
    CompilationError
        Without a working C compiler.
    """
    source, compiler, library = _library(function)
    loaded = _load(function, library)
    if loaded is not None:
        return loaded
    _compile(source, library, compiler)
    return ca.external(function.name(), str(library))
