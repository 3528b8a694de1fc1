"""Hash of the derivation's inputs, recorded in every generated file.

Kept free of SymPy so that a fast test can tell whether ``derive/`` changed since ``generated/``
was last written, without running the derivation.
"""

from __future__ import annotations

import hashlib
from pathlib import Path

__all__ = ["DERIVE_DIR", "SYMPY_VERSION", "input_hash"]

DERIVE_DIR = Path(__file__).resolve().parent

#: The SymPy version that owns the bytes of generated/ (pinned in pyproject.toml's derive extra).
SYMPY_VERSION = "1.14.0"


def input_hash(derive_dir: Path = DERIVE_DIR) -> str:
    """Return ``sha256:<hex>`` over the sources of ``derive/`` and the pinned SymPy version."""
    digest = hashlib.sha256(f"sympy=={SYMPY_VERSION}\n".encode())
    for path in sorted(derive_dir.glob("*.py")):
        digest.update(path.name.encode() + b"\n")
        digest.update(path.read_bytes().replace(b"\r\n", b"\n"))
    return "sha256:" + digest.hexdigest()
