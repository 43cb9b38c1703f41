"""Input and output: robot designs as TOML files (:mod:`tcarod.io.design`) and
results as files (:mod:`tcarod.io.results`: a solution as a dict, JSON, CSV
or VTK; :func:`write_shape` picks the format from the suffix)."""

from .results import write_shape

__all__ = ["write_shape"]
