"""rockhatch.tex.WriteImage: a raster of a tiled map written through OpenImageIO (PNG, TIFF,
EXR), read back pixel for pixel, and OpenImageIO loaded only when an image is written."""
import os
import shutil
import subprocess
import sys
import textwrap

import numpy as np
import pytest

from conftest import python_env
from rockhatch.tex import (GridPartition, Rasterize, Region, StripesProperties, TexError, Tiled, WriteImage,
                           pi)

PIL = pytest.importorskip("PIL.Image", reason="Pillow (python3-pil) reads the images back")


def raster():
    grid = GridPartition(StripesProperties(0.3, 12), StripesProperties(pi / 2 + 0.2, 17), Tiled())
    return Rasterize(grid, Region.rectangle(0, 0, 90, 70), 0.5, 1.0)


@pytest.mark.parametrize("ext", [".png", ".tif"])
def test_written_pixels_are_the_raster(tmp_path, ext):
    image = raster()
    assert image.min() == 0 and image.max() == 255  # ink and paper both there
    path = tmp_path / ("grid" + ext)
    WriteImage(image, path)
    back = np.asarray(PIL.open(path))
    assert back.dtype == np.uint8 and back.shape == image.shape
    assert np.array_equal(back, image)


def test_a_strided_view_is_written_as_it_looks(tmp_path):
    image = raster()[::2, ::3]  # not contiguous
    WriteImage(image, tmp_path / "view.png")
    assert np.array_equal(np.asarray(PIL.open(tmp_path / "view.png")), image)


@pytest.mark.skipif(shutil.which("oiiotool") is None, reason="oiiotool (openimageio-tools) reads EXR back")
def test_exr_round_trip(tmp_path):
    image = raster()
    WriteImage(image, tmp_path / "grid.exr")
    # EXR stores half floats: 0..255 / 255 comes back exactly at 8 bits.
    subprocess.run(["oiiotool", str(tmp_path / "grid.exr"), "-d", "uint8", "-o", str(tmp_path / "back.png")],
                   check=True)
    assert np.array_equal(np.asarray(PIL.open(tmp_path / "back.png")), image)


def test_bad_input_is_a_clear_error(tmp_path):
    with pytest.raises(TexError, match="WriteImage.*no-such-format"):
        WriteImage(raster(), tmp_path / "x.no-such-format")
    with pytest.raises(TexError, match="WriteImage.*/no/such/dir/x.png"):
        WriteImage(raster(), "/no/such/dir/x.png")
    with pytest.raises(TexError, match="WriteImage.*uint8"):
        WriteImage(raster().astype(np.float32), tmp_path / "x.png")
    with pytest.raises(TexError, match="WriteImage.*2 dimensions"):
        WriteImage(np.zeros((3, 4, 2), np.uint8), tmp_path / "x.png")
    with pytest.raises(TexError, match="WriteImage.*empty"):
        WriteImage(np.zeros((0, 4), np.uint8), tmp_path / "x.png")


def run_python(code):
    """Run code in a fresh interpreter (this one may have loaded OpenImageIO already)."""
    out = subprocess.run([sys.executable, "-c", textwrap.dedent(code)], capture_output=True, text=True,
                         env=python_env(), check=True)
    return out.stdout.strip()


MAPS = """
def oiio_loaded():
    with open("/proc/self/maps") as f:
        return "libOpenImageIO" in f.read()
"""


@pytest.mark.skipif(not os.path.exists("/proc/self/maps"), reason="needs /proc/self/maps (Linux)")
def test_openimageio_is_loaded_only_by_the_first_write(tmp_path):
    out = run_python(MAPS + f"""
import rockhatch, rockhatch.tex, rockhatch.carto
from rockhatch.tex import *
image = Rasterize(GridPartition(StripesProperties(0, 5), StripesProperties(1, 5), Tiled()),
                  Region.rectangle(0, 0, 20, 20), 1.0, 1.0)
before = oiio_loaded()
WriteImage(image, {str(tmp_path / 'a.png')!r})
print(before, oiio_loaded())
""")
    assert out == "False True"
