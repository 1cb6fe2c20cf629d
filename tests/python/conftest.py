"""Shared fixtures: where the built programs and the Python module are."""
import os
import pathlib
import sys

import pytest

ROOT = pathlib.Path(__file__).resolve().parents[2]


def build_dir() -> pathlib.Path:
    return pathlib.Path(os.environ.get("RH_BUILD_DIR", ROOT / "build"))


# The module of this build comes first, whatever another set-up installed.
PYTHON_DIR = build_dir() / "python"
sys.path.insert(0, str(PYTHON_DIR))
STYLES = ROOT / "styles"
# Under the sanitizers (scripts/sanitize.sh sets RH_SANITIZED=1) the slowest tests check their
# property on less work (fewer runs, smaller windows); the normal pass keeps the full versions.
SANITIZED = os.environ.get("RH_SANITIZED") == "1"
GALLERY_PY = ROOT / "bindings" / "examples" / "gallery.py"


def python_env() -> dict:
    """Environment for a child /usr/bin/python3 that must import this build's module."""
    env = dict(os.environ)
    env["PYTHONPATH"] = str(PYTHON_DIR) + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    return env


@pytest.fixture(scope="session")
def gallery_exe() -> pathlib.Path:
    exe = build_dir() / "libtex" / "rh_gallery"
    if not exe.exists():
        pytest.fail(f"{exe} is missing: run scripts/setup.sh first (or set RH_BUILD_DIR)")
    return exe


SAMPLE = ROOT / "data" / "sample_montblanc"
# The south-west quarter of the sample (xmin, ymin, xmax, ymax), for a run on less work.
SAMPLE_SW_QUARTER = (1002900, 6538700, 1004100, 6539900)
SHARED_DEM = ROOT.parent / "shared" / "data" / "montblanc" / "Chamonix.tif"

# The tests on ../shared's real DEM: skipped, with the reason, when it is absent.
real_dem = pytest.mark.skipif(not SHARED_DEM.exists(),
                              reason=f"{SHARED_DEM} is absent (../shared is not beside the project)")


@pytest.fixture(scope="session")
def real_dem_file(tmp_path_factory) -> pathlib.Path:
    """../shared's real DEM, for the tests that run whole commands or tiled runs on it. Under
    the sanitizers, its middle quarter (322 x 252 cells of 1 arc-second, about 7.8 x 7 km), cut
    with gdal_translate, so still in degrees and with the same NoData value: the same code paths
    on a quarter of the cells (on the whole DEM those tests took 27 to 66 s each under ASan)."""
    if not SHARED_DEM.exists():
        pytest.skip(f"{SHARED_DEM} is absent (../shared is not beside the project)")
    if not SANITIZED:
        return SHARED_DEM
    from osgeo import gdal
    out = tmp_path_factory.mktemp("real_dem") / "chamonix_middle.tif"
    src = gdal.Open(str(SHARED_DEM))
    w, h = src.RasterXSize, src.RasterYSize
    gdal.Translate(str(out), src, srcWin=[w // 4, h // 4, w // 2, h // 2])
    return out


@pytest.fixture(scope="session")
def quarter_under_sanitizers(tmp_path_factory) -> str:
    """The sample's DEM; under the sanitizers, its south-west quarter (SAMPLE_SW_QUARTER, a file
    cut by gdal_translate), on which a tiled test takes tiles of half the size
    (half_under_sanitizers): as many tiles, on a quarter of the cells."""
    dem = SAMPLE / "dem.tif"
    if not SANITIZED:
        return str(dem)
    from osgeo import gdal
    out = str(tmp_path_factory.mktemp("sw_quarter") / "dem_sw_quarter.tif")
    x0, y0, x1, y1 = SAMPLE_SW_QUARTER
    gdal.Translate(out, str(dem), projWin=[x0, y1, x1, y0])
    return out


def half_under_sanitizers(metres):
    """A tile size for quarter_under_sanitizers: half of it under the sanitizers."""
    return metres // 2 if SANITIZED else metres


def finished_tiles(work) -> list:
    """The names of the finished tile files in a tiled run's work folder (tile_NNNNNNN.gpkg),
    not the temporary file of a tile whose worker was stopped while writing it
    (tile_NNNNNNN.gpkg.part-PID-N.gpkg, which a run that resumes removes): the glob
    tile_*.gpkg matches both."""
    return sorted(p.name for p in pathlib.Path(work).glob("tile_*.gpkg") if ".part-" not in p.name)


def one_under_sanitizers(values):
    """Values of a parametrized test: all of them in the normal pass, the first only under the
    sanitizers, for a test whose other values take the same code path on other sizes or counts."""
    return values[:1] if SANITIZED else values


@pytest.fixture(scope="session")
def rockhatch_exe() -> pathlib.Path:
    exe = build_dir() / "carto" / "rockhatch"
    if not exe.exists():
        pytest.fail(f"{exe} is missing: run scripts/setup.sh first (or set RH_BUILD_DIR)")
    return exe


@pytest.fixture(scope="session")
def sample_dir() -> pathlib.Path:
    return SAMPLE


def partition_with_scree(sample_dir, path):
    """Copies the sample's partition to `path` with a polygon layer "scree": a 600 m square at
    the south-west corner of the faces. Returns the square (an OGR geometry)."""
    from osgeo import gdal, ogr
    gdal.VectorTranslate(str(path), str(sample_dir / "partition.gpkg"))
    ds = ogr.Open(str(path), 1)  # kept open while its layers are used
    faces = ds.GetLayerByName("faces")
    xmin, _, ymin, _ = faces.GetExtent()
    box = ogr.CreateGeometryFromWkt(
        f"POLYGON(({xmin} {ymin},{xmin + 600} {ymin},{xmin + 600} {ymin + 600},{xmin} {ymin + 600},{xmin} {ymin}))")
    layer = ds.CreateLayer("scree", faces.GetSpatialRef(), ogr.wkbPolygon)
    f = ogr.Feature(layer.GetLayerDefn())
    f.SetGeometry(box)
    layer.CreateFeature(f)
    return box


def pytest_collection_modifyitems(items):
    """test_tiles first: its Dask runs are 60% of the normal pass's test time (326 of 533
    test-seconds), and as the last file by name its longest tests could end the run on one
    worker while the other had finished (that run took 281 s of wall time for 533 / 2). The
    order within each file is kept."""
    items.sort(key=lambda item: item.path.name != "test_tiles.py")
