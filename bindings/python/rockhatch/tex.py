"""The libtex operators under the thesis's names (tables 3.2 to 3.6).

    from rockhatch.tex import *

gives partitions (StripesProperties, GridPartition, UniformPartition...), label setters,
the border constants, MapToVertices / MapToEdges / MapToFaces with Python mappers, every
table 3.4 built-in, Union / Inside / Outside, ImportSVG / ExportSVG, Point, Scale, Rotate,
Translate, Nothing, Random, pi, and cos / sin / sqrt / atan2 from math as the thesis's
scripts use them.
"""
from math import atan2, cos, sin, sqrt  # noqa: F401  (the scripts' math)

from ._rockhatch import Lines, Points, TexError  # noqa: F401
from ._rockhatch.tex import *  # noqa: F401,F403
from ._rockhatch import tex as _tex

__all__ = [n for n in dir(_tex) if not n.startswith("_")] + [
    "cos", "sin", "sqrt", "atan2", "Points", "Lines", "TexError"]
