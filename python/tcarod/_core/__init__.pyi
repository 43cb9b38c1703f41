"""Type stub of the Rust extension ``tcarod._core`` (hand-written; checked
against the compiled module by ``python -m mypy.stubtest tcarod._core``).

Units: lengths in m, forces in N (tension > 0), torques in N m, moduli in Pa,
temperatures in degrees C. Argument errors raise ``ValueError`` naming the
argument; wrong Python types raise ``TypeError``.
"""

from typing import Final

from ._common import ConvergenceError as ConvergenceError
from ._common import UnstableEquilibriumError as UnstableEquilibriumError
from ._common import UnitsWarning as UnitsWarning
from ._tca import Material as Material
from ._tca import Tca as Tca
from ._rod import Section as Section
from ._rod import Routing as Routing
from ._rod import Body as Body
from ._rod import Actuator as Actuator
from ._rod import Robot as Robot
from ._rod import _restore_section as _restore_section
from ._rod import _restore_routing as _restore_routing
from ._rod import _restore_actuator as _restore_actuator
from ._rod import _experiment_robot as _experiment_robot
from ._solution import Solution as Solution
from ._solution import _register_plotter as _register_plotter
from ._solution import _restore_solution as _restore_solution
from ._solution import _register_exporter as _register_exporter
from ._solution import _restore_solution_verdict as _restore_solution_verdict
from ._inverse import InverseResult as InverseResult
from ._inverse import BlockedResult as BlockedResult
from ._inverse import sensitivities as sensitivities
from ._inverse import tip_position as tip_position
from ._inverse import blocked_force as blocked_force
from ._inverse import blocked_temperature as blocked_temperature
from ._inverse import blocked_temperature_direct as blocked_temperature_direct
from ._inverse import grasp_temperature as grasp_temperature
from ._inverse import _restore_inverse_result as _restore_inverse_result
from ._inverse import _restore_blocked_result as _restore_blocked_result
from ._batch import solve_batch as solve_batch
from ._batch import default_threads as default_threads
from ._batch import bench_rows as bench_rows
from ._batch import bench_time as bench_time
from ._stability import UnstableEquilibriumWarning as UnstableEquilibriumWarning
from ._stability import Continuation as Continuation
from ._stability import Stability as Stability
from ._stability import Branch as Branch
from ._stability import _restore_stability as _restore_stability
from ._stability import _restore_branch as _restore_branch
from ._stability import stability as stability
from ._stability import follow_branch as follow_branch
from ._fixtures import fixture_constants as fixture_constants
from ._fixtures import fixture_manipulator as fixture_manipulator
from ._fixtures import fixture_leg_turns as fixture_leg_turns
from ._fixtures import fixture_fig5_tca as fixture_fig5_tca
from ._fixtures import fixture_fig5_half_tca as fixture_fig5_half_tca
from ._fixtures import fixture_tendon_robot as fixture_tendon_robot

__version__: Final[str]
