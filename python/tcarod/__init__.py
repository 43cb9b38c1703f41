"""tcarod: soft robots actuated by twisted-and-coiled actuators (TCAs).

Implements Pawlowski et al., "Modeling of Soft Robots Actuated by
Twisted-and-Coiled Actuators", IEEE/ASME T-Mech 24(1), 2019, on a Rust core.
SI units throughout (m, N, Pa, kg, s) except temperatures, in degrees C.

Layers (imports run one way, cli -> paper / models -> API -> _core): the API
over the Rust core here (``tca``, ``rod``, ``inverse``, ``batch``);
:mod:`tcarod.models` built on it; :mod:`tcarod.paper`, one module per
experiment of the paper; :mod:`tcarod.io`, design files and JSON;
:mod:`tcarod.plotting`, every plot; :mod:`tcarod.cli`, the command line.
"""

from __future__ import annotations

from ._core import (
    ConvergenceError,
    UnitsWarning,
    UnstableEquilibriumError,
    UnstableEquilibriumWarning,
    __version__,
)
from . import rod
from .rod import *  # noqa: F403  the rod API (Robot, Body, ...): the names of rod.__all__
from .tca import Material, Tca
from .materials import BodyMaterial, body_material, body_materials
from .batch import BatchResult, solve_batch
from .models.grasp import grasp_temperature
from .inverse import (
    BlockedResult,
    InverseResult,
    blocked_force,
    blocked_temperature,
    blocked_temperature_direct,
    jacobian_and_compliance,
    tip_position,
)
from . import _display  # noqa: F401  registers notebook display formatters inside IPython
from . import _hooks  # noqa: F401  registers Solution.to_dict/to_json/to_csv/to_vtk and BatchResult.plot_tips

__all__ = [
    "ConvergenceError",
    "UnitsWarning",
    "UnstableEquilibriumError",
    "UnstableEquilibriumWarning",
    "Material",
    "Tca",
    "BodyMaterial",
    "body_material",
    "body_materials",
    "__version__",
    "BatchResult",
    "BlockedResult",
    "InverseResult",
    "blocked_force",
    "blocked_temperature",
    "blocked_temperature_direct",
    "grasp_temperature",
    "jacobian_and_compliance",
    "solve_batch",
    "tip_position",
]
__all__ += rod.__all__  # Robot, Body, ... (tcarod.rod)
