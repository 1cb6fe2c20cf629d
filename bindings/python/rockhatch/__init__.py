"""rockhatch: programmable element arrangements and rock hatching for topographic maps.

The compiled part (rockhatch._rockhatch) is re-exported by three modules:

- rockhatch.tex: the arrangement operators of the thesis (partitions, mappers, merges,
  table 3.4 built-ins), under their names, for scripts starting with
  ``from rockhatch.tex import *``;
- rockhatch.discrete: the discrete operator set of seed 004 (dart throwing, relaxation,
  Voronoi cells of regions, stream lines);
- rockhatch.carto: rasters as numpy arrays, control fields, the partition of rock areas,
  the hatching building blocks, styles and the pipeline of the rockhatch command.
"""
from . import _rockhatch
from ._rockhatch import Lines, Points, RockhatchError, TexError

__version__ = "0.1.0"
__all__ = ["tex", "discrete", "carto", "Points", "Lines", "TexError", "RockhatchError", "__version__"]


def __getattr__(name):
    # rockhatch.tex and rockhatch.carto load on first use.
    if name in ("tex", "discrete", "carto", "cli"):
        import importlib

        return importlib.import_module(f".{name}", __name__)
    raise AttributeError(f"module 'rockhatch' has no attribute '{name}'")
