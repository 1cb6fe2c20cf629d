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
# Under ASan + UBSan (scripts/sanitize.sh sets RH_SANITIZED=1). Both passes run every test on
# the same data: this is read only where a test cannot do the same thing under ASan at all
# (test_bad_inputs: an address-space limit, which ASan's shadow memory exceeds; test_qgis_plugin's
# cancel: a wall-time bound), each saying why.
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
def real_dem_file() -> pathlib.Path:
    """../shared's real DEM, for the tests that run whole commands or tiled runs on it."""
    if not SHARED_DEM.exists():
        pytest.skip(f"{SHARED_DEM} is absent (../shared is not beside the project)")
    return SHARED_DEM


def finished_tiles(work) -> list:
    """The names of the finished tile files in a tiled run's work folder (tile_NNNNNNN.gpkg),
    not the temporary file of a tile whose worker was stopped while writing it
    (tile_NNNNNNN.gpkg.part-PID-N.gpkg, which a run that resumes removes): the glob
    tile_*.gpkg matches both."""
    return sorted(p.name for p in pathlib.Path(work).glob("tile_*.gpkg") if ".part-" not in p.name)


@pytest.fixture(scope="session")
def rockhatch_exe() -> pathlib.Path:
    exe = build_dir() / "carto" / "rockhatch"
    if not exe.exists():
        pytest.fail(f"{exe} is missing: run scripts/setup.sh first (or set RH_BUILD_DIR)")
    return exe


@pytest.fixture(scope="session")
def sample_dir() -> pathlib.Path:
    return SAMPLE


def data_snapshot() -> dict:
    """The SHA-256 of every file under data/, by path."""
    import hashlib
    return {str(p.relative_to(ROOT)): hashlib.sha256(p.read_bytes()).hexdigest()
            for p in sorted((ROOT / "data").rglob("*")) if p.is_file()}


@pytest.fixture(scope="session", autouse=True)
def data_folder_untouched():
    """No test (nor the QGIS provider, GDAL's .aux.xml side files or an output written to the
    wrong place) may change, add or remove a file under data/: the bundled inputs are read
    only. Checked at the end of every session (each pytest-xdist worker's)."""
    before = data_snapshot()
    yield
    after = data_snapshot()
    if after != before:
        changed = sorted(k for k in before.keys() | after.keys() if before.get(k) != after.get(k))
        pytest.fail(f"files under data/ changed, appeared or went during the tests: {changed}")


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


def land_cover(path, tagged):
    """A GeoPackage of land cover over the sample: its west half bare rock, its east half scree
    (OpenStreetMap's natural=*), or with tagged False one untagged layer of both."""
    from osgeo import ogr, osr
    ds = ogr.GetDriverByName("GPKG").CreateDataSource(str(path))
    srs = osr.SpatialReference()
    srs.ImportFromEPSG(2154)
    layer = ds.CreateLayer("multipolygons", srs, ogr.wkbPolygon)
    if tagged:
        layer.CreateField(ogr.FieldDefn("natural", ogr.OFTString))
    halves = [("POLYGON((1003000 6538800,1004100 6538800,1004100 6541000,1003000 6541000,1003000 6538800))",
               "bare_rock"),
              ("POLYGON((1004100 6538800,1005200 6538800,1005200 6541000,1004100 6541000,1004100 6538800))", "scree")]
    for wkt, natural in halves:
        f = ogr.Feature(layer.GetLayerDefn())
        if tagged:
            f.SetField("natural", natural)
        f.SetGeometry(ogr.CreateGeometryFromWkt(wkt))
        layer.CreateFeature(f)
    ds = None
    return path


def features_by_face(gpkg):
    """{face id: sorted (layer, family, style, width, GeoPackage geometry blob)}: the bytes of
    every hatch feature of a hatch GeoPackage, fids aside (rockhatch update's tests)."""
    import sqlite3
    con = sqlite3.connect(str(gpkg))
    out = {}
    try:
        for (name,) in con.execute("SELECT table_name FROM gpkg_contents WHERE table_name LIKE 'hatch_%'"):
            for row in con.execute(f'SELECT face_id, family, style, width_mm, geom FROM "{name}"'):
                out.setdefault(row[0], []).append((name,) + row[1:])
    finally:
        con.close()
    return {face: sorted(rows) for face, rows in out.items()}
