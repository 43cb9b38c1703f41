"""Optional dependencies: import them on first use, with one clear line when missing.

The core install needs NumPy only. Plots need the ``plot`` extra (matplotlib),
fits and the brute-force baseline need ``fit`` (scipy), progress bars need
``progress`` (tqdm), cluster batches need ``dask``, table export needs
``pandas``, design files need ``io`` (tomli-w; tomli before Python 3.11),
VTK shape files need ``export`` (meshio), interactive figures need
``interactive`` (plotly).
Every optional import goes through :func:`require`.
"""

from __future__ import annotations

import importlib
from types import ModuleType

#: Top-level module -> the extra of ``tcarod`` that installs it.
EXTRAS: dict[str, str] = {
    "matplotlib": "plot",
    "scipy": "fit",
    "tqdm": "progress",
    "dask": "dask",
    "distributed": "dask",
    "pandas": "pandas",
    "tomli": "io",
    "tomli_w": "io",
    "meshio": "export",
    "plotly": "interactive",
}


class MissingDependencyError(ImportError):
    """An optional dependency of tcarod is not installed."""


def require(module: str) -> ModuleType:
    """Import ``module`` (dotted names allowed) or raise
    :class:`MissingDependencyError` naming the extra that installs it."""
    try:
        return importlib.import_module(module)
    except ImportError as exc:
        top = module.split(".")[0]
        extra = EXTRAS.get(top, "all")
        raise MissingDependencyError(
            f"{top} is needed for this feature and is not installed: pip install 'tcarod[{extra}]'"
        ) from exc
