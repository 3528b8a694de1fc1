"""Hash of the derivation's inputs, recorded in every generated file.

Kept free of SymPy so that a fast test can tell whether ``derive/`` or a machine description
changed since ``generated/`` was last written, without running the derivation.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["DERIVE_DIR", "SYMPY_VERSION", "description_hash", "input_hash"]

DERIVE_DIR = Path(__file__).resolve().parent

#: The SymPy version that owns the bytes of generated/ (pinned in pyproject.toml's derive extra).
SYMPY_VERSION = "1.14.0"


def _description_path(machine: str, derive_dir: Path) -> Path:
    """``derive/machines/<machine>.toml``, or ``machine`` itself when it is a ``.toml`` path."""
    if str(machine).endswith(".toml"):
        return Path(machine)
    return derive_dir / "machines" / f"{machine}.toml"


def description_hash(machine: str = "skid_steer", derive_dir: Path = DERIVE_DIR) -> str:
    """``sha256:<hex>`` of the machine description ``derive/machines/<machine>.toml`` (or of the
    description file ``machine``, a ``.toml`` path)."""
    path = _description_path(machine, derive_dir)
    return "sha256:" + hashlib.sha256(path.read_bytes().replace(b"\r\n", b"\n")).hexdigest()


def input_hash(machine: str = "skid_steer", derive_dir: Path = DERIVE_DIR) -> str:
    """``sha256:<hex>`` over the sources of ``derive/`` (its code and the description schema),
    the machine's description (a name in ``derive/machines`` or a ``.toml`` path) and the pinned
    SymPy version."""
    digest = hashlib.sha256(f"sympy=={SYMPY_VERSION}\n".encode())
    sources = [*derive_dir.glob("*.py"), *derive_dir.glob("*.json")]
    for path in sorted(sources):
        digest.update(path.name.encode() + b"\n")
        digest.update(path.read_bytes().replace(b"\r\n", b"\n"))
    name = _description_path(machine, derive_dir).stem
    digest.update(f"machine {name} {description_hash(machine, derive_dir)}\n".encode())
    return "sha256:" + digest.hexdigest()
