"""Python functions behind methods of API objects whose work lives in a
layer above the API, registered when tcarod is imported.

* ``Solution.to_dict``, ``to_json``, ``to_csv``, ``to_vtk``: the bindings
  call :func:`tcarod.io.results.export` (they never import Python modules
  themselves);
* ``BatchResult.plot_tips``: :func:`tcarod.plotting.batch.plot_tips`,
  imported on first use (it needs the ``plot`` extra, matplotlib).

The API modules (``tcarod.rod``, ``tcarod.batch``, ...) import neither
``tcarod.io`` nor ``tcarod.plotting``; this module points them there.
"""

from __future__ import annotations

from typing import Any

from . import _batch_result, _core
from .io import results


def _plot_tips(result: Any, **kwargs: Any) -> Any:
    from .plotting.batch import plot_tips

    return plot_tips(result, **kwargs)


_core._register_exporter(results.export)
_batch_result._register_tip_plotter(_plot_tips)
