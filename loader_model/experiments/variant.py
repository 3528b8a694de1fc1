"""Which model a Table 6 trial runs on: the steps of the fidelity budget and the calibration.

The report's Table 6 runs the model as built (:data:`AS_BUILT`). The fidelity budget (
:mod:`~loader_model.experiments.fidelity`) adds one step at a time from the model as it was before
(:data:`AS_IT_WAS`), and the calibration (:mod:`~loader_model.experiments.calibration_table6`) varies
the estimated parameters; each is a :class:`ModelVariant`, a frozen value every trial carries, so a
worker process builds the plant and scenario of a variant once and the seeds stay the trials'.

What a variant switches (errata 11-13):

- ``holding_valves``: baseline and passive on closed load-holding valves, the virtual accumulator
  and skyhook with them open (:meth:`~loader_model.plant.plant_parameters.PlantOptions.
  for_controller`); off: the pump holds the boom for every controller, Table 5's flow acting as
  before (the accumulator still connected for ``passive``);
- ``occupant``: the seat pad under a seated occupant (:mod:`loader_model.plant.occupant`); off: the
  seat is read on the rigid chassis at S;
- ``envelope``: the tyres' effective road (``"tandem-cam"`` or ``"rigid"``,
  :mod:`loader_model.simulation.tandem_cam`, :mod:`loader_model.simulation.envelope`);
- ``table3_gain``: the gains of the ``skyhook`` row (Table 3 with k_φ = +0.22, or as printed);
- ``values``: parameter-file values by dotted path (``"accumulator.gas_volume"``; ``load.<field>``
  of the bucket-load file), validated by the parameter files' own checks.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Any

__all__ = [
    "AS_BUILT",
    "AS_IT_WAS",
    "ENVELOPES",
    "ModelVariant",
]

#: Effective-road models of the tyres.
ENVELOPES: tuple[str, ...] = ("tandem-cam", "rigid")
#: Table 3's gains with k_φ's sign corrected (errata 12) and as printed.
_TABLE3 = (2.75, 5.10, -4.0, 0.22)
_TABLE3_PRINTED = (2.75, 5.10, -4.0, -0.22)


@dataclass(frozen=True)
class ModelVariant:
    """The model of a trial (module notes).

    Attributes
    ----------
    label : str
        Name in tables.
    holding_valves : bool
        Circuit states: the load-holding valves closed while the pump is idle.
    occupant : bool
        Seat pad under a seated occupant (else the rigid chassis at S).
    envelope : str
        One of :data:`ENVELOPES`.
    table3_gain : tuple of 4 float
        K_fb of the ``skyhook`` row.
    values : tuple of (str, float)
        Parameter-file values by dotted path, SI units; ``load.<field>`` applies to both loads.
    """

    label: str = "as built"
    holding_valves: bool = True
    occupant: bool = True
    envelope: str = "tandem-cam"
    table3_gain: tuple[float, ...] = _TABLE3
    values: tuple[tuple[str, float], ...] = ()

    def __post_init__(self) -> None:
        if self.envelope not in ENVELOPES:
            raise ValueError(f"envelope {self.envelope!r}: allowed: {list(ENVELOPES)}")
        if len(self.table3_gain) != 4:
            raise ValueError(f"table3_gain must hold 4 gains; got {self.table3_gain!r}")

    def with_values(self, values: dict[str, float], label: str | None = None) -> ModelVariant:
        """This variant with parameter values ``values`` (path -> SI value), sorted by path."""
        merged = dict(self.values) | {str(k): float(v) for k, v in values.items()}
        return replace(self, label=label or self.label, values=tuple(sorted(merged.items())))

    def plant_options(self, controller: str) -> Any:
        """The plant's switches for ``controller`` (a ride controller's name, module notes)."""
        from loader_model.plant.plant_parameters import PlantOptions

        if self.holding_valves:
            return PlantOptions.for_controller(controller, occupant=self.occupant)
        return PlantOptions(accumulator=controller == "passive", occupant=self.occupant)

    def parameter_sets(self, load: str) -> tuple[Any, Any]:
        """The loader and bucket load ``load`` with :attr:`values` applied (each validated)."""
        from loader_model import parameters

        loader, bucket = parameters.default_loader(), parameters.bucket_load(load)
        loader_values = {p: v for p, v in self.values if not p.startswith("load.")}
        load_values = {p.removeprefix("load."): v for p, v in self.values if p.startswith("load.")}
        if loader_values:
            loader = parameters.replace(loader, loader_values)
        if load_values:
            bucket = parameters.replace(bucket, load_values)
        return loader, bucket


#: The model as built: circuit states, seat pad and occupant, tandem-cam tyres, Table 3 with
#: k_φ = +0.22, the shipped parameter files.
AS_BUILT = ModelVariant()
#: The model before the fidelity budget's steps: Table 5's flow as a cylinder leak for every
#: controller, the seat on the rigid chassis, rigid-wheel tyres, Table 3 as printed.
AS_IT_WAS = ModelVariant(
    label="as it was",
    holding_valves=False,
    occupant=False,
    envelope="rigid",
    table3_gain=_TABLE3_PRINTED,
)
