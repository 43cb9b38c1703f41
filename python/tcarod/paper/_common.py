"""What the paper's experiments share: the result interface, TCA and load
specifications, published data, the onset temperature.

Units: SI inside (m, N, kg), temperatures in degrees C; every name says its
unit. Sign convention (paper eq 2): force > 0 is tension (pulls the TCA
longer), displacement > 0 is extension; a compressive dead weight is a
negative force.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Literal, Protocol

import numpy as np
import numpy.typing as npt

from ..models.manipulators import GRAVITY_M_PER_S2
from ..tca import Material, Tca

__all__ = [
    "GRAVITY_M_PER_S2",
    "PAPER_TEMPERATURES_C",
    "DeadWeight",
    "ExperimentResult",
    "FloatArray",
    "PAPER_SOURCE",
    "PublishedCurve",
    "TcaSpec",
    "identity_json",
    "onset_temperature_c",
    "published_json",
]

FloatArray = npt.NDArray[np.float64]

#: The temperature axis [C] of Figs. 5, 6 and 8: 25 to 160 C in 5 C steps.
PAPER_TEMPERATURES_C: tuple[float, ...] = tuple(float(t) for t in range(25, 161, 5))


class ExperimentResult(Protocol):
    """What ``tcarod reproduce`` needs from an experiment's prediction.

    A protocol: ``name``, ``table()``, ``to_json()`` and ``plot(path)``.

    Examples
    --------
    >>> import dataclasses
    >>> from tcarod.paper.fig5 import FIG5
    >>> result = dataclasses.replace(FIG5, temperatures_c=(25.0, 160.0)).predict()   # a Fig5Result
    >>> result.name, result.table().splitlines()[0][:7], result.to_json()["name"]
    ('fig5', 'Fig. 5:', 'fig5')
    >>> result.plot("fig5.png").name
    'fig5.png'
    """

    @property
    def name(self) -> str:
        """Registry name.

        Returns
        -------
        str
            E.g. ``"fig5"``.
        """
        ...

    def table(self) -> str:
        """Human-readable table of the prediction (units in the headers)."""
        ...

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable dict; every key names its unit (``temperature_c``, ``displacement_m``)."""
        ...

    def plot(self, path: str | os.PathLike[str]) -> Path:
        """Write the figure as PNG to ``path``; return the path written."""
        ...


@dataclass(frozen=True)
class TcaSpec:
    """A TCA as fabricated, described by what a user measures.

    Lengths in m; ``turns`` is the inserted twist ``N`` [turns].
    """

    label: str
    threads: int
    fibre_length_m: float
    coiled_length_m: float
    coil_diameter_m: float
    turns: float
    chirality: Literal["extension", "contraction"] = "extension"

    def build(self, material: Material | None = None) -> Tca:
        """The whole TCA (default material: :meth:`Material.silver_coated_nylon`)."""
        return Tca(
            self.fibre_length_m,
            self.coiled_length_m,
            self.coil_diameter_m,
            self.turns,
            self.chirality,
            material,
        )


@dataclass(frozen=True)
class DeadWeight:
    """A hanging mass [kg] plus the paper's friction-equivalent mass [kg]."""

    mass_kg: float
    friction_equivalent_kg: float = 0.0

    @property
    def effective_mass_kg(self) -> float:
        """Mass [kg] whose weight the actuator carries: hanging mass + friction equivalent."""
        return self.mass_kg + self.friction_equivalent_kg

    @property
    def weight_n(self) -> float:
        """Weight [N] of the effective mass, ``effective_mass_kg * GRAVITY_M_PER_S2`` (> 0)."""
        return self.effective_mass_kg * GRAVITY_M_PER_S2

    @property
    def label(self) -> str:
        """E.g. ``"5 g"`` (the hanging mass, as the paper labels its curves)."""
        return f"{self.mass_kg * 1e3:g} g"


@dataclass(frozen=True)
class PublishedCurve:
    """Digitised experimental data of one curve: mean and standard deviation
    of the measured quantity [SI unit of the experiment] at each temperature [C]."""

    label: str
    temperatures_c: tuple[float, ...]
    mean: tuple[float, ...]
    std: tuple[float, ...]

    def to_json(self) -> dict[str, Any]:
        """JSON-serialisable curve (temperatures in C, values in the experiment's SI unit)."""
        return {
            "label": self.label,
            "temperature_c": list(self.temperatures_c),
            "mean": list(self.mean),
            "std": list(self.std),
        }


#: The paper every experiment of this package reproduces; each experiment's
#: ``source`` adds its section and figure.
PAPER_SOURCE = "Pawlowski et al., IEEE/ASME T-Mech 24(1), 2019"


def identity_json(experiment: object) -> dict[str, Any]:
    """The head of every experiment's JSON: its ``name``, ``title`` and ``source``."""
    return {key: getattr(experiment, key) for key in ("name", "title", "source")}


def published_json(data: tuple[PublishedCurve, ...] | None) -> list[dict[str, Any]] | None:
    """An experiment's ``published_data`` as JSON (``None`` where the paper prints none)."""
    return None if data is None else [p.to_json() for p in data]


def onset_temperature_c(tca: Tca, force_n: float) -> float | None:
    """Temperature [C] at which the coils of ``tca`` separate under ``force_n``
    [N] (< 0: compressive), or ``None`` if that does not happen inside the
    material's temperature range (never opens, or already open at its lowest
    temperature). Computed with :meth:`Tca.onset_temperature`."""
    material = tca.material
    t_lo, t_hi = material.t_min, material.t_max
    if tca.displacement(force_n, t_hi) == 0.0:
        return None  # coils still touching at the top of the range
    if tca.displacement(force_n, t_lo) > 0.0:
        return None  # already open at the bottom of the range: no onset inside it
    # Coils closed at t_lo and open at t_hi: the onset is bracketed.
    return tca.onset_temperature(force_n)


def mm_text(x: float) -> str:
    """A length [m] as text in mm (two decimals), ``"inf"`` if infinite."""
    return "inf" if not math.isfinite(x) else f"{x * 1e3:.2f}"


def finite_or_none(x: float) -> float | None:
    """``x`` for JSON: ``None`` where it is infinite (a straight body's radius)."""
    return float(x) if math.isfinite(x) else None


def relative_difference(a: FloatArray, b: FloatArray) -> float:
    """Largest relative difference of two radius arrays [-]: 0 where both are
    infinite (straight), infinite where only one is."""
    both_inf = np.isinf(a) & np.isinf(b)
    ok = np.isfinite(a) & np.isfinite(b)
    if not np.all(ok | both_inf):
        return math.inf  # one straight, the other not
    if not ok.any():
        return 0.0
    return float(np.max(np.abs(a[ok] - b[ok]) / np.abs(b[ok])))
