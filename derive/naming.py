"""Names and units of a machine's coordinates and signals as the generated docstrings print them."""

from __future__ import annotations

import unicodedata

from derive.description import Machine
from derive.symbols import MachineSymbols

__all__ = ["Naming"]

_GREEK = {"theta": "θ", "phi": "φ", "psi": "ψ"}


def _pretty(name: str) -> str:
    head, _, tail = name.partition("_")
    return f"{_GREEK[head]}{tail}" if head in _GREEK else name


def _dotted(name: str) -> str:
    pretty = _pretty(name)
    return unicodedata.normalize("NFC", pretty[0] + "\u0307" + pretty[1:])


def listing(items: list[str] | tuple[str, ...]) -> str:
    """``a, b and c``."""
    return items[0] if len(items) == 1 else ", ".join(items[:-1]) + " and " + items[-1]


class Naming:
    """Display names and units of one machine."""

    def __init__(self, sym: MachineSymbols) -> None:
        self.sym = sym
        self.machine: Machine = sym.machine
        root = self.machine.root
        self.reference = root.centre_of_gravity
        angles = {b.angle for b in self.machine.bodies if b.angle}
        self.is_angle = [symbol.name in angles for symbol in sym.coordinates]
        self.n = len(sym.coordinates)

    def units(self, linear: str, angular: str) -> str:
        """``[m, m, rad, rad]``-style list over the coordinates."""
        return "[" + ", ".join(angular if a else linear for a in self.is_angle) + "]"

    @property
    def coordinates(self) -> str:
        return "(" + ", ".join(_pretty(s.name) for s in self.sym.coordinates) + ")"

    @property
    def state(self) -> str:
        names = []
        for symbol in self.sym.coordinates:
            names += [_pretty(symbol.name), _dotted(symbol.name)]
        return "(" + ", ".join(names) + ")"

    @property
    def forces(self) -> str:
        return self.units("N", "N·m")

    def per_axle(self, pattern: str) -> str:
        return ", ".join(pattern.format(axle=axle) for axle in self.machine.axles)

    def joint_angle(self, body_name: str) -> tuple[str, str]:
        """(symbol, pretty) of the joint angle of a pinned body, e.g. ("phi", "φ")."""
        body = self.machine.body(body_name)
        name = body.joint_angle or f"phi_{body.name}"
        return name, _pretty(name)

    def angle(self, body_name: str) -> str:
        """Pretty absolute angle of a body (a mount's is its parent's)."""
        body = self.machine.body(body_name)
        while body.angle is None:
            body = self.machine.body(body.parent)  # type: ignore[arg-type]
        return _pretty(body.angle)
