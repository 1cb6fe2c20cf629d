"""The libtex operators under the thesis's names (tables 3.2 to 3.6).

    from rockhatch.tex import *

gives partitions (StripesProperties, GridPartition, UniformPartition...), label setters,
the border constants, MapToVertices / MapToEdges / MapToFaces with Python mappers (a Python
call per cell) or the engine's stock mappers (MapToEdges(JitterEdges(...), a): native, no
Python call per edge), every table 3.4 built-in, Union / Inside / Outside / Crop / Outline,
ImportSVG / ExportSVG, Point, Scale, Rotate, Translate, Labelled, Nothing, Random, SeedScope,
StreamScope, pi, and the names of `math` the thesis's scripts use bare
(cos, sin, tan, acos, asin, atan, atan2, sqrt, hypot, exp, log, pow, fabs, floor, ceil:
`curves[floor(Random(edge, 0, len(curves), 0))]` runs as written). `pow` is math.pow: after
the star import it shadows the built-in pow (always a float, no modulus argument).
"""
from math import (acos, asin, atan, atan2, ceil, cos, exp, fabs, floor, hypot, log,  # noqa: F401
                  pow, sin, sqrt, tan)  # (the scripts' math)

from ._rockhatch import Lines, Points, TexError  # noqa: F401
from ._rockhatch.tex import *  # noqa: F401,F403
from ._rockhatch import tex as _tex

_MATH_NAMES = ["cos", "sin", "tan", "acos", "asin", "atan", "atan2", "sqrt", "hypot", "exp", "log", "pow",
               "fabs", "floor", "ceil"]



def WriteImage(image, path):
    """Write a grey image (a 2-D uint8 array, as ``Rasterize`` returns) to a file through
    OpenImageIO; the extension of ``path`` chooses the format (``.png``, ``.tif``, ``.exr``...).

    OpenImageIO is loaded on the first call only (it lives in the separate compiled module
    ``rockhatch._rockhatch_image``), so scripts that write no image do not pay its start-up.

    Raises
    ------
    TexError
        When the array is not a 2-D uint8 image, or the file cannot be written (the message
        names it), or this build has no OpenImageIO.
    """
    try:
        from ._rockhatch_image import WriteImage as write
    except ImportError as e:
        raise TexError("WriteImage: this build of rockhatch has no OpenImageIO (" + str(e) + ")") from None
    write(image, str(path))


__all__ = ([n for n in dir(_tex) if not n.startswith("_")] + _MATH_NAMES +
           ["Points", "Lines", "TexError", "WriteImage"])
