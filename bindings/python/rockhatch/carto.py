"""Rock hatching from Python: rasters as numpy arrays, control fields, the partition, the
hatching building blocks, styles, and the pipeline of the rockhatch command.

The pipeline is the one the command runs (carto::run in C++)::

    from rockhatch import carto
    stats = carto.run(dem="dem.tif", partition="partition.gpkg",
                      outputs=["out.gpkg", "out.svg"], style="noisy",
                      progress=lambda f, stage: print(f, stage))

``style`` is a built-in name (see ``carto.styles()``), a style script (``styles/*.py``),
a module with the script attributes, or a Style from ``python_style``.
"""
import importlib.util
import os
import sys
import traceback

from ._rockhatch import RockhatchError
from ._rockhatch.carto import *  # noqa: F401,F403
from ._rockhatch import carto as _carto
from ._rockhatch import tex as _tex
from ._rockhatch.carto import blocks  # noqa: F401  (the style blocks, also as rockhatch.carto.blocks)

sys.modules[__name__ + ".blocks"] = blocks

__all__ = [n for n in dir(_carto) if not n.startswith("_")] + [
    "run", "run_options", "prepare", "hatch", "make_options", "load_style", "as_style", "error", "partition_from_dem",
    "style_file", "params_help"]


def params_help(params):
    """The parameter section of a style script's header, made from its PARAMS (the lines
    `rockhatch --list-styles` prints)."""
    return ('\nParameters (--param NAME=VALUE; "mm" are millimetres on paper at --scale):\n' +
            params_text(params))  # noqa: F405


def error(code, message):
    """A RockhatchError with the exit code of the rockhatch command."""
    e = RockhatchError(message)
    e.code = code
    return e


def load_style(path):
    """Loads a style script: a Python file defining NAME, PARAMS and style(fields, params),
    which returns the tex.Arrangement drawn in each face (evaluated on the face's labelled
    region; the pipeline sets the seed and random streams around it). Its folder is on
    sys.path while it loads, so a script may import another script; the shared blocks
    are native (rockhatch.carto.blocks)."""
    if not os.path.isfile(path):
        raise error(3, f"--script '{path}': no such file")
    name = "rockhatch_style_" + os.path.splitext(os.path.basename(path))[0].replace("-", "_")
    folder = os.path.dirname(os.path.abspath(path))
    added = folder not in sys.path
    if added:
        sys.path.insert(0, folder)
    try:
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        sys.modules[name] = module
        try:
            with _tex.SavedSeed():  # a script may call SetSeed as it loads: the process keeps its seed
                spec.loader.exec_module(module)
        except SyntaxError as e:  # a bad input: one line naming the script and the line
            sys.modules.pop(name, None)
            raise error(7, f"--script '{path}': line {e.lineno}: {e.msg}") from None
        except Exception as e:
            sys.modules.pop(name, None)
            frames = [f for f in traceback.extract_tb(e.__traceback__) if f.filename == spec.origin]
            where = f"line {frames[-1].lineno}: " if frames else ""
            raise error(7, f"--script '{path}': {where}{type(e).__name__}: {e}") from None
    finally:
        if added:
            sys.path.remove(folder)
    return style_of_module(module, path)


def style_of_module(module, where=None):
    """The Style defined by a script module (NAME, FIGURE, TITLE, PARAMS and
    style(fields, params) -> tex.Arrangement drawn in each face)."""
    where = where or getattr(module, "__file__", repr(module))
    fn = getattr(module, "style", None)
    if not callable(fn):
        raise error(7, f"--script '{where}': defines no style(fields, params) function")
    params = []
    for p in getattr(module, "PARAMS", []):
        if isinstance(p, StyleParam):  # noqa: F405
            params.append(p)
        else:
            params.append(StyleParam(*p))  # noqa: F405
    info = StyleInfo(getattr(module, "NAME", os.path.splitext(os.path.basename(str(where)))[0]),  # noqa: F405
                     getattr(module, "FIGURE", ""), getattr(module, "TITLE", ""), params,
                     bool(getattr(module, "CREST_ORNAMENT", False)))
    return python_style(info, fn)  # noqa: F405


def as_style(style):
    """A Style, or None for a built-in name (the C++ style is used then)."""
    if style is None or isinstance(style, Style):  # noqa: F405
        return style
    if isinstance(style, str):
        if style.endswith(".py"):
            return load_style(style)
        return None
    if hasattr(style, "style"):
        return style_of_module(style)
    raise TypeError(f"style: expected a name, a script path, a module or a Style, got {type(style).__name__}")


def style_file(style):
    """The file a style is read from ('' for a built-in or a Style): an input of the run."""
    if isinstance(style, (str, os.PathLike)) and os.fspath(style).endswith(".py"):
        return os.fspath(style)
    if style is not None and not isinstance(style, (str, Style)) and hasattr(style, "style"):  # noqa: F405
        return getattr(style, "__file__", None) or ""
    return ""


_PARTITION_KEYS = ("faces_layer", "lines_layer", "label_field", "id_field", "orientation_field",
                   "orientation_layer", "density_field", "density_layer", "scree_layer", "repair", "snap")


def make_options(dem="", partition="", outputs=(), style=None, params=None, scale=10000.0, seed=0, threads=0,
                 overwrite=False, slope="", roughness="", window=None, png_pixels=1600, spatial_index=True,
                 relief_radius=1000.0, crest_ornament=None, crest_height_mm=None, mask="", page="", zoom="",
                 **partition_options):
    """The Options of the rockhatch command from keyword arguments (same names as its
    options, partition layer and field options included; crest_ornament is 'default' or an
    SVG file, crest_height_mm the band height in mm on paper; page the page of a .pdf output,
    zoom the zoom levels of a .mbtiles output, e.g. "12-16")."""
    o = Options()  # noqa: F405
    o.dem = os.fspath(dem)
    o.partition.path = os.fspath(partition)
    for key, value in partition_options.items():
        if key not in _PARTITION_KEYS:
            raise TypeError(f"unknown option '{key}'")
        setattr(o.partition, key, value)
    o.outputs = [os.fspath(p) for p in ([outputs] if isinstance(outputs, (str, os.PathLike)) else outputs)]
    o.overwrite = bool(overwrite)
    o.slope = os.fspath(slope) if slope else ""
    o.roughness = os.fspath(roughness) if roughness else ""
    o.mask = os.fspath(mask) if mask else ""
    o.style_file = style_file(style)
    if crest_ornament is not None:
        o.crest_ornament = os.fspath(crest_ornament)
    if crest_height_mm is not None:
        o.crest_height_mm = float(crest_height_mm)
    # Before a style script runs: no output may replace an input (the script included).
    check_files(o)  # noqa: F405
    custom = as_style(style)
    if custom is not None:
        o.custom_style = custom
    elif style:
        o.style = style
    o.params = dict(params or {})
    o.scale = float(scale)
    o.relief_radius = float(relief_radius)
    o.seed = int(seed)
    o.threads = int(threads)
    if window is not None:
        o.window = window if isinstance(window, _tex.BBox) else _tex.BBox(*window)
    o.png_pixels = int(png_pixels)
    o.page = str(page or "")
    o.zoom = str(zoom or "")
    o.spatial_index = bool(spatial_index)
    return o


def run(dem, partition, outputs, progress=None, **kwargs):
    """Everything the rockhatch command does; returns Stats. progress(fraction, stage) may
    return False to cancel (RockhatchError with code 10)."""
    return run_options(make_options(dem, partition, outputs, **kwargs), progress)


def update(dem, partition, outputs, progress=None, reset=False, faces=(), undo="", **kwargs):
    """rockhatch update with the arguments of run (those of the run that wrote the outputs):
    redraws the faces whose fingerprint changed, appeared or went away (also the face ids in
    `faces`; every face with reset=True) in the GeoPackage output, in one transaction, and
    draws the SVG / PNG / PDF outputs again from it; returns UpdateReport. undo: a GeoPackage
    path where what the update replaces is kept, for restore_faces(output, undo)."""
    kwargs["overwrite"] = True  # the outputs are the files to update
    return update_options(make_options(dem, partition, outputs, **kwargs), progress, reset=reset, faces=faces,
                          undo=undo)


def update_options(options, progress=None, reset=False, faces=(), undo=""):
    """carto::update on ready-made Options."""
    return _carto.update(options, bool(reset), [int(f) for f in faces], os.fspath(undo or ""), progress)


def run_options(options, progress=None):
    """carto::run on ready-made Options (what the command line parses into)."""
    return _carto.run(options, progress)


def prepare(dem, partition, progress=None, **kwargs):
    """Reads the DEM (reprojected when geographic), its terrain fields and the partition."""
    o = make_options(dem, partition, **kwargs)
    return _carto.prepare(o, progress)


def hatch(prepared, progress=None, **kwargs):
    """Hatches a prepared partition; returns a Drawing (write it with write_gpkg / write_svg)."""
    return _carto.hatch(prepared, make_options(**kwargs), progress)


def partition_from_dem(dem, output=None, progress=None, overwrite=False, png=None, png_pixels=1600,
                       fixed_controls=False, **options):
    """The partition of the rock areas from the DEM alone (``rockhatch partition``).

    dem: a path or a Raster. options: the fields of ExtractOptions (min_slope in percent,
    min_roughness, min_area_mm2 and scale, thalweg_area and ridge_area in m2, smooth and
    max_fill in m, converge, extend_ridges, simplify in cells, mask: a polygon layer path).
    Writes the GeoPackage `output` (layers faces, lines, mask, network) that ``run`` reads,
    and a PNG preview when `png` is given; returns the ExtractResult. The faces carry their
    fall line and shade as `fall_line` and `shade` (derived: hatching follows the terrain, as
    with ``partition="auto"``), or as `orientation` and `density` with `fixed_controls`
    (read as given: one hatch direction per face)."""
    o = ExtractOptions()  # noqa: F405
    if isinstance(dem, Raster):  # noqa: F405
        o.raster = dem
    else:
        o.dem = os.fspath(dem)
    for key, value in options.items():
        if key.startswith("_") or not hasattr(o, key) or key in ("dem", "raster", "what"):
            raise TypeError(f"unknown option '{key}'")
        setattr(o, key, os.fspath(value) if key == "mask" else value)
    check_extract_files(o, os.fspath(output or ""), os.fspath(png or ""), overwrite)  # noqa: F405
    result = _carto.extract_partition(o, progress)
    if output is not None:
        write_partition_gpkg(result.partition, os.fspath(output), overwrite, result.network,  # noqa: F405
                             fixed_controls)
    if png is not None:
        write_partition_png(result, os.fspath(png), png_pixels)  # noqa: F405
    return result
