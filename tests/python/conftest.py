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


def left_to_the_normal_pass(twin, what):
    """Marks a test the sanitizer pass skips (scripts/sanitize.sh sets RH_SANITIZED=1): `what`
    says why it is costly there, and `twin`, named in the reason, runs the C++ code it reaches
    under the sanitizers. RH_SANITIZE_PYTEST=all (sets RH_SANITIZE_EVERY=1) runs it there too."""
    skip = SANITIZED and os.environ.get("RH_SANITIZE_EVERY") != "1"
    return pytest.mark.skipif(skip, reason=f"{what}, left to the normal pass; its code paths run under the "
                                           f"sanitizers in {twin}")


# A real-DEM test whose code paths a sample test also takes, on 10 to 40 times the data: the
# normal pass runs it; under the sanitizers (27 and 44 s each, the two longest Python tests
# there) its sample twin, named in the reason, covers those paths. With them the test command
# took 1,575 s from a fresh clone here, and 1,895 s in CI.
def heavy_real_dem(twin):
    return left_to_the_normal_pass(twin, "a heavy real-DEM test")


# A test of the Dask tiled runs or of the QGIS plugin whose own work under ASan is Python (Dask's
# scheduling, resuming, QGIS's processing framework) around C++ entry points that other tests
# run under the sanitizers: 20 to 115 s each there (a Dask worker or QGIS loads the instrumented
# module; the whole of test_tiles and test_qgis_plugin took 595 s of the pass's wall time, for
# 1,178 test-seconds). The rest of those two files runs under the sanitizers.
def dask_or_qgis_heavy(twin):
    return left_to_the_normal_pass(twin, "a tiled-run or QGIS test costly under ASan")


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
