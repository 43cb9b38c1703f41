"""The paper's experiments (Section V), one module each, and their registry.

Each experiment is a frozen dataclass holding what the paper specifies (the
actuators, the loads, the temperatures, and the published data -- ``None``
where the paper prints none; numbers are never invented). Its prediction is a
result object with the :class:`ExperimentResult` interface (``table()``,
``to_json()``, ``plot(path)``).

=========  =================================  ===========================
name       experiment                         module
=========  =================================  ===========================
fig5       extension TCAs under dead weights  :mod:`tcarod.paper.fig5`
fig6       bending radius vs temperature      :mod:`tcarod.paper.fig6`
fig8       blocked-tip force                  :mod:`tcarod.paper.fig8`
table1     grip temperatures (eq 44)          :mod:`tcarod.paper.table1`
fig1b      3-TCA manipulator workspace        :mod:`tcarod.paper.fig1b`
buckling   loss of stability (beyond paper)   :mod:`tcarod.paper.buckling`
=========  =================================  ===========================

:data:`REGISTRY` (the names of ``tcarod reproduce NAME``) is written out
here: a new experiment is a new module plus one line below.
"""

from __future__ import annotations

from typing import Callable, Final

from . import buckling, fig1b, fig5, fig6, fig8, table1
from ._common import ExperimentResult


def _table1() -> table1.Table1Result:
    return table1.predict_table1(study=True, identification=True)


#: Experiment name -> zero-argument callable returning its predicted result.
REGISTRY: Final[dict[str, Callable[[], ExperimentResult]]] = {
    "fig5": fig5.predict_fig5,
    "fig6": fig6.predict_fig6,
    "fig8": fig8.predict_fig8,
    "table1": _table1,
    "fig1b": fig1b.predict_fig1b,
    "buckling": buckling.predict_buckling,
}

__all__ = ["REGISTRY", "ExperimentResult", "buckling", "fig1b", "fig5", "fig6", "fig8", "table1"]
