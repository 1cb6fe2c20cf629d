"""The discrete operator set of seed 004 (pinning, dart throwing, relaxation, stream lines).

    from rockhatch.discrete import *

gives the seed's operators under their names: elements (Polyline, RegionSet, and
rockhatch.tex's Point and Region), construction (RandomPinning, RegularPinning,
RegularPinning1D, Centroid, TangentFlowField, Contour, Interpolation, VoronoiCells,
ApplyThickness), transformations (Translation, Rotation, Scale), scalars (CountUpTo,
Overlap, RandomR, Distance, MinimalDistance), input / output (Image, ReadPGM, BuiltinHatch,
BuiltinRectangle, BuiltinCircle, UserRegion, ToCurves) and the programs
(greedy_distribution, relaxation, stream_line).

Operators are values: a partial form (``Overlap(hatches)``, ``Translation(BuiltinHatch())``,
``Rotation(RandomR(0, 2 * pi))``) is a callable, and any Python callable may stand where an
operator is expected. ``Not``, ``And``, ``Compose`` and ``Const`` below combine them.
"""
from math import pi  # noqa: F401  (the seed's programs use it bare)

from ._rockhatch import TexError  # noqa: F401
from ._rockhatch.discrete import *  # noqa: F401,F403
from ._rockhatch import discrete as _discrete
from ._rockhatch.tex import BBox, Curves, ExportSVG, ImportSVG, Point, Region, ToSVG  # noqa: F401


def Not(f):
    """Not ∘ f: a callable true where f is false."""
    return lambda *args: not f(*args)


def And(f, g):
    """A callable true where f and g both are (g is not called when f is false)."""
    return lambda *args: bool(f(*args)) and bool(g(*args))


def Compose(f, g):
    """f ∘ g. With a generator g (no argument) the result is a generator."""
    return lambda *args: f(g(*args))


def Const(value):
    """A constant as a generator (∅ -> T)."""
    return lambda: value


__all__ = [n for n in dir(_discrete) if not n.startswith("_")] + [
    "Not", "And", "Compose", "Const", "pi", "TexError", "BBox", "Curves", "ExportSVG", "ImportSVG", "Point",
    "Region", "ToSVG"]
