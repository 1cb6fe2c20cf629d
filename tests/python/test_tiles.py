"""Tiled runs on a real Dask cluster (rockhatch.tiles): the merged tiles are the whole run's
hatches, feature for feature and bit for bit, whatever the tile size, the number of workers
or a worker killed in the middle; an interrupted job resumes; bad input is refused."""
import os
import signal
import socket
import subprocess
import sys
import time

import pytest
from conftest import SAMPLE, SAMPLE_SW_QUARTER, finished_tiles, python_env

from osgeo import gdal, ogr

from rockhatch import carto, tiles
from rockhatch._rockhatch import RockhatchError

gdal.UseExceptions()
ogr.UseExceptions()

DEM = str(SAMPLE / "dem.tif")
FACES = str(SAMPLE / "partition.gpkg")


class Hatches(dict):
    """A hatch GeoPackage's features, and its frame (the drawing's extent, which SVG and PNG
    outputs drawn from it use): equal when both are."""
    frame = None

    def __eq__(self, other):
        return dict.__eq__(self, other) and self.frame == getattr(other, "frame", None)

    def __ne__(self, other):
        return not self == other


def features(path):
    """(layer, face id, rank in its face) -> (geometry WKB, style, width) of every hatch; for the
    crest layer, (layer, ridge id, rank) -> (geometry WKB, style, None). The elements of a terrain
    style (face id -1) are ranked in the order of their WKB: tiles write them tile by tile. The
    frame is the file's RH_FRAME metadata item, as written."""
    ds = ogr.Open(str(path))
    groups = {}
    for i in range(ds.GetLayerCount()):
        layer = ds.GetLayer(i)
        if layer.GetName() == "rockhatch_faces":
            continue  # a whole run's fingerprints (rockhatch update), not drawn features
        crest = layer.GetName() == "crest"
        for f in layer:
            face = f.GetField("ridge_id" if crest else "face_id")
            groups.setdefault((layer.GetName(), face), []).append(
                (bytes(f.GetGeometryRef().ExportToWkb()), f.GetField("style"), None if crest else f.GetField("width_mm")))
    out = Hatches()
    for (name, face), items in groups.items():
        if face == -1:
            items.sort()
        for k, item in enumerate(items):
            out[(name, face, k)] = item
    out.frame = ds.GetMetadataItem("RH_FRAME")
    assert out.frame, f"{path}: no frame"
    return out


def whole_run(args, out):
    cl = carto.parse_command_line(list(args) + ["-o", str(out), "-q"])
    carto.run_options(cl.options)
    return features(out)


@pytest.fixture(scope="module")
def sample_whole(tmp_path_factory):
    return whole_run(["--dem", DEM, "--partition", FACES, "--seed", "3"], tmp_path_factory.mktemp("whole") / "w.gpkg")


@pytest.mark.parametrize("tile_size,workers", [(600, 2), (1700, 1)])
def test_tiled_run_equals_the_whole_run(tmp_path, sample_whole, tile_size, workers):
    out = tmp_path / "tiled.gpkg"
    calls = []
    s = tiles.run(DEM, FACES, tile_size, [out], seed=3, workers=workers,
                  progress=lambda f, stage: calls.append((f, stage)) or True)
    assert s.tiles == (16 if tile_size == 600 else 4)
    assert s.hatches == len(sample_whole)
    assert features(out) == sample_whole
    # Progress: tiles done / total with a rate and the time left, then the merge.
    assert any(st.startswith(f"tiles {s.tiles}/{s.tiles}") and "/s" in st and "left" in st for _, st in calls)
    assert calls[-1] == (1.0, "done")
    assert not (tmp_path / "tiled.gpkg.tiles").exists()  # the tile files go once merged
    # No worker process of the run's local cluster outlives it.
    import psutil
    assert not [p for p in psutil.Process().children() if "spawn_main" in " ".join(p.cmdline())]
    # One R-tree per layer in the merged GeoPackage.
    ds = ogr.Open(str(out))
    for name in ("hatch_fill", "hatch_ridge"):
        assert ds.ExecuteSQL(f"SELECT HasSpatialIndex('{name}', 'geom')").GetNextFeature().GetField(0) == 1


@pytest.mark.parametrize("tile_size", [500, 1300])
def test_crest_ornaments_tiled_equal_the_whole_run(tmp_path, tile_size):
    # Each ridge is drawn by the tile holding its anchor, with the ridges around it read so
    # that ends are cut back where ridges meet as in the whole run: the same crest polygons,
    # bit for bit. Many ridges cross the 500 m tiles' borders.
    args = ["--crest-ornament", "default", "--crest-height", "3"]
    whole = whole_run(["--dem", DEM, "--partition", FACES, "--seed", "3"] + args, tmp_path / "w.gpkg")
    crests = {k: v for k, v in whole.items() if k[0] == "crest"}
    assert len(crests) >= 5
    out = tmp_path / "tiled.gpkg"
    tiles.run(DEM, FACES, tile_size, [out, tmp_path / "tiled.svg"], seed=3, workers=1, args=args)
    assert features(out) == whole
    # The SVG drawn from the merged file carries the crest group.
    assert '<g id="crest"' in (tmp_path / "tiled.svg").read_text()


def test_the_dashboard_serves_the_cluster_pages(tmp_path, sample_whole):
    import socket
    import urllib.request

    with socket.socket() as sk:
        sk.bind(("127.0.0.1", 0))
        port = sk.getsockname()[1]
    pages = []

    def progress(fraction, stage):
        if stage.startswith("tiles 1/") and not pages:
            with urllib.request.urlopen(f"http://127.0.0.1:{port}/info/main/workers.html", timeout=10) as r:
                pages.append((r.status, r.read().decode()))
        return True

    out = tmp_path / "t.gpkg"
    tiles.run(DEM, FACES, 1200, [out], seed=3, workers=1, args=["--dashboard", f"127.0.0.1:{port}"], progress=progress)
    assert pages and pages[0][0] == 200 and "Workers" in pages[0][1]
    assert features(out) == sample_whole


def test_an_unreachable_scheduler_is_one_line(tmp_path):
    # Dask retries a refused connection until --connect-timeout (default 15 s); 1 s here.
    t0 = time.monotonic()
    r = subprocess.run([sys.executable, "-m", "rockhatch", "tiles", "--dem", DEM, "--partition", FACES,
                        "--tile-size", "1000", "--scheduler", "tcp://127.0.0.1:9", "--connect-timeout", "1",
                        "-q", "-o", str(tmp_path / "o.gpkg")],
                       capture_output=True, text=True, env=python_env(), timeout=120)
    assert r.returncode == 1
    assert "127.0.0.1:9" in r.stderr and "after 1 s" in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert time.monotonic() - t0 < 12
    assert not (tmp_path / "o.gpkg").exists()


@pytest.mark.parametrize("extra, message", [
    (["--connect-timeout", "5"], "--connect-timeout is for --scheduler"),
    (["--scheduler", "tcp://127.0.0.1:9", "--connect-timeout", "0"], "--connect-timeout: 0 is not a positive number"),
    (["--scheduler", "tcp://127.0.0.1:9", "--connect-timeout", "soon"], "--connect-timeout: 'soon' is not a number"),
])
def test_a_bad_connect_timeout_is_refused_before_any_work(tmp_path, extra, message):
    r = subprocess.run([sys.executable, "-m", "rockhatch", "tiles", "--dem", DEM, "--partition", FACES,
                        "--tile-size", "1000", *extra, "-q", "-o", str(tmp_path / "o.gpkg")],
                       capture_output=True, text=True, env=python_env(), timeout=60)
    assert r.returncode == 2 and message in r.stderr, r.stderr
    assert not list(tmp_path.iterdir())


def test_command_line_tiles_and_svg(tmp_path, rockhatch_exe, sample_whole):
    gpkg, svg = tmp_path / "t.gpkg", tmp_path / "t.svg"
    r = subprocess.run([str(rockhatch_exe), "tiles", "--dem", DEM, "--partition", FACES, "--seed", "3",
                        "--tile-size", "1000", "--workers", "1", "-o", str(gpkg), "-o", str(svg)],
                       capture_output=True, text=True, env=python_env(), timeout=300)
    assert r.returncode == 0, r.stderr
    assert "9 tiles" in r.stderr and "hatches" in r.stderr
    assert features(gpkg) == sample_whole
    # The SVG drawn from the merged tiles is the whole run's drawing: the same frame and
    # georeference (the tiles keep their frames in their GeoPackages), and in each group the
    # same strokes, one per hatch; only the faces' order follows the tiles.
    whole_svg = tmp_path / "w.svg"
    r = subprocess.run([str(rockhatch_exe), "--dem", DEM, "--partition", FACES, "--seed", "3", "-q", "-o", str(whole_svg)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr

    def svg_parts(path):
        head, *groups = path.read_text().split("<g ")
        return head, [(g.split(">", 1)[0], sorted(g.splitlines()[1:])) for g in groups]

    head, groups = svg_parts(svg)
    assert (head, groups) == svg_parts(whole_svg)
    assert sum(len([x for x in lines if x.startswith("<poly")]) for _, lines in groups) == len(sample_whole)


class ExternalCluster:
    """A real Dask cluster of its own: `dask scheduler` and one `dask worker` process with
    two worker processes under nannies, each importing this build's module."""

    def __init__(self, tmp_path):
        env = python_env()
        self.sched_file = str(tmp_path / "scheduler.json")
        self.procs = [subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_scheduler", "--no-dashboard",
                                        "--port", "0", "--scheduler-file", self.sched_file],
                                       env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
        deadline = time.monotonic() + 60
        while not os.path.exists(self.sched_file) and time.monotonic() < deadline:
            time.sleep(0.2)
        import json

        self.address = json.load(open(self.sched_file))["address"]
        self.procs.append(subprocess.Popen([sys.executable, "-m", "distributed.cli.dask_worker", self.address,
                                            "--nworkers", "2", "--nthreads", "1", "--no-dashboard"],
                                           env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        from distributed import Client

        self.client = Client(self.address, timeout="60s")
        self.client.wait_for_workers(2, timeout=120)

    def worker_pids(self):
        return list(self.client.run(os.getpid).values())

    def close(self):
        self.client.close()
        for p in reversed(self.procs):
            p.terminate()
        for p in self.procs:
            try:
                p.wait(timeout=20)
            except subprocess.TimeoutExpired:
                p.kill()


@pytest.fixture
def cluster(tmp_path):
    c = ExternalCluster(tmp_path)
    yield c
    c.close()


def test_a_killed_worker_loses_nothing(tmp_path, cluster, sample_whole):
    out = tmp_path / "tiled.gpkg"
    killed = []

    def progress(fraction, stage):
        # After the first tile: kill a worker process (its nanny starts a new one; Dask runs
        # the tile it held again).
        if stage.startswith("tiles 1/") and not killed:
            pid = cluster.worker_pids()[0]
            os.kill(pid, signal.SIGKILL)
            killed.append(pid)
        return True

    s = tiles.run(DEM, FACES, 500, [out], seed=3, scheduler=cluster.address, progress=progress)
    assert killed, "no worker was killed: the test did not test anything"
    assert killed[0] not in cluster.worker_pids()
    assert s.tiles == 25
    assert features(out) == sample_whole


def test_an_interrupted_job_resumes(tmp_path, sample_whole):
    out = tmp_path / "tiled.gpkg"
    work = tmp_path / "work"

    def stop_after_4(fraction, stage):
        return not stage.startswith("tiles 4/")

    with pytest.raises(RockhatchError) as e:
        tiles.run(DEM, FACES, 500, [out], seed=3, workers=2, workdir=work, progress=stop_after_4)
    assert e.value.code == 10
    assert not out.exists()
    done = finished_tiles(work)
    assert len(done) >= 4
    stamps = {n: os.stat(work / n).st_mtime_ns for n in done}
    # The same job with other options may not reuse these tiles.
    with pytest.raises(RockhatchError) as e:
        tiles.run(DEM, FACES, 500, [out], seed=4, workers=1, workdir=work)
    assert e.value.code == 9 and "another job" in str(e.value)
    s = tiles.run(DEM, FACES, 500, [out], seed=3, workers=1, workdir=work, keep_tiles=True)
    assert s.done_before == len(done)
    for n in done:  # finished tiles are not computed again
        assert os.stat(work / n).st_mtime_ns == stamps[n]
    assert features(out) == sample_whole


def test_a_terminated_command_stops_its_workers_and_resumes(tmp_path, sample_whole):
    """SIGTERM (QGIS's Cancel, a batch scheduler) stops `rockhatch tiles` in order: it exits
    with code 10 and one line, after closing its cluster, so no worker writes a tile later."""
    out, work = tmp_path / "tiled.gpkg", tmp_path / "work"
    proc = subprocess.Popen([sys.executable, "-m", "rockhatch", "tiles", "--dem", DEM, "--partition", FACES,
                             "--tile-size", "500", "--seed", "3", "--workers", "2", "--workdir", str(work),
                             "-o", str(out)], stderr=subprocess.PIPE, env=python_env(), start_new_session=True)
    seen = b""
    while b"tiles 2/" not in seen:
        chunk = proc.stderr.read1(256)
        assert chunk, seen.decode(errors="replace")  # it ended before two tiles
        seen += chunk
    proc.send_signal(signal.SIGTERM)
    rest = proc.stderr.read().decode()
    assert proc.wait(timeout=60) == 10
    assert rest.strip().splitlines()[-1].startswith("rockhatch tiles: terminated:"), rest
    done, left = finished_tiles(work), sorted(p.name for p in work.iterdir())
    time.sleep(3)  # nothing of the run is left to write a tile
    assert sorted(p.name for p in work.iterdir()) == left and 2 <= len(done) < 25  # 5 x 5 tiles
    assert not out.exists()
    s = tiles.run(DEM, FACES, 500, [out], seed=3, workers=1, workdir=work)
    assert s.done_before == len(done)
    assert features(out) == sample_whole


def test_partial_tile_files_are_never_merged(tmp_path, sample_whole):
    out = tmp_path / "tiled.gpkg"
    work = tmp_path / "work"
    with pytest.raises(RockhatchError):
        tiles.run(DEM, FACES, 1000, [out], seed=3, workers=1, workdir=work, progress=lambda f, s: not s.startswith("tiles 2/"))
    # What a worker killed while writing leaves: a temporary file, and garbage under it.
    (work / "tile_0000008.gpkg.part-999-0.gpkg").write_bytes(b"half a GeoPackage")
    s = tiles.run(DEM, FACES, 1000, [out], seed=3, workers=1, workdir=work)
    assert s.done_before >= 2
    assert features(out) == sample_whole


def test_tiled_equals_whole_on_chamonix(tmp_path, rockhatch_exe, real_dem_file):
    # Chamonix.tif is in degrees, with NoData: both runs work on its UTM 32N reprojection,
    # the tiles reading it window by window.
    faces = tmp_path / "faces.gpkg"
    r = subprocess.run([str(rockhatch_exe), "partition", "--dem", str(real_dem_file), "-o", str(faces), "-q"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    args = ["--dem", str(real_dem_file), "--partition", str(faces), "--scale", "25000"]
    expected = whole_run(args, tmp_path / "whole.gpkg")
    assert len(expected) > 100000
    s = tiles.run(real_dem_file, faces, 2500, [tmp_path / "tiled.gpkg"], scale=25000, workers=2)
    assert s.tiles > 20
    assert features(tmp_path / "tiled.gpkg") == expected


SW_QUARTER = ",".join(map(str, SAMPLE_SW_QUARTER))


@pytest.mark.parametrize("style,params,faces,window", [
    # In the user's --window (the sample's south-west quarter): the tiles draw the window's
    # elements and frame them as the whole run does.
    ("scree", [], FACES, SW_QUARTER),
    ("scree", [], FACES, None),
    # A contour interval of 5 m gives tiles of about 230 m: the 600 m tiles read windows of the
    # DEM (at 20 m, 788 m tiles reach over the whole sample; the defaults are checked in C++,
    # TerrainStyles.WindowsTogetherDrawTheWholeRunsElements).
    ("slope-hachures", ["interval=5"], FACES, None),
    ("slope-hachures", ["interval=5"], "none", None),  # no rock at all
])
def test_terrain_styles_tiled_equal_the_whole_run(tmp_path, style, params, faces, window):
    # The terrain elements are thrown over one grid of tiles of the working CRS, in colour
    # phases: a map tile draws the elements of the grid's tiles whose centre it holds, after
    # those they depend on, reading the DEM and the rock hatches within the style's reach.
    extra = ["--window", window] if window else []
    args = ["--dem", DEM, "--partition", faces, "--seed", "4", "--style", style] + extra
    for p in params:
        args += ["--param", p]
    whole = whole_run(args, tmp_path / "whole.gpkg")
    terrain = [k for k in whole if k[1] == -1]
    assert len(terrain) > 1000
    if window:  # framed by what it drew, not by the DEM (1002900 6538700 1005300 6541100)
        assert float(whole.frame.split()[0]) > 1003000 and float(whole.frame.split()[2]) < 1004500
    s = tiles.run(DEM, faces, 600, [tmp_path / "tiled.gpkg"], style=style, seed=4, workers=2,
                  params=dict(p.split("=") for p in params) or None, args=extra)
    assert s.tiles == 16
    # Faces counted once each (the terrain's entry is not a face), every element once.
    assert s.faces == (0 if faces == "none" else len({k[1] for k in whole if k[1] != -1}))
    assert s.hatches == len(whole)
    assert features(tmp_path / "tiled.gpkg") == whole


def raster_on_another_grid(tmp_path, name, kind):
    """A slope (percent) or roughness (0..1) raster of the sample in its CRS, on a grid of 7 m
    cells whose origin is 2.5 m off the DEM's: the whole run resamples it onto the DEM."""
    import numpy as np
    src = str(tmp_path / f"{name}_dem_grid.tif")
    if kind == "slope":
        gdal.DEMProcessing(src, DEM, "slope", slopeFormat="percent")
    else:
        gdal.DEMProcessing(src, DEM, "roughness")
        ds = gdal.Open(src, gdal.GA_Update)
        a = ds.GetRasterBand(1).ReadAsArray()
        ds.GetRasterBand(1).WriteArray(np.clip(a / max(float(np.nanmax(a)), 1e-9), 0, 1))
        ds = None
    d = gdal.Open(DEM)
    gt, w, h = d.GetGeoTransform(), d.RasterXSize, d.RasterYSize
    out = str(tmp_path / f"{name}.tif")
    gdal.Warp(out, src, xRes=7, yRes=7, resampleAlg="bilinear",
              outputBounds=(gt[0] + 2.5, gt[3] + h * gt[5] + 2.5, gt[0] + w * gt[1] + 2.5, gt[3] + 2.5))
    return out


def test_a_raster_on_another_grid_is_tiled_as_the_whole_run_resamples_it(tmp_path):
    # Each tile resamples the window of the raster that holds its cells' neighbours at its cell
    # centres, placed in the whole grid: the whole run's values, so its hatches. --roughness
    # with print (its cross hatching follows the roughness); --slope takes the same path.
    style, option, kind = "print", "--roughness", "roughness"
    raster = raster_on_another_grid(tmp_path, kind, kind)
    args = ["--dem", DEM, "--partition", FACES, "--seed", "6", "--style", style]
    whole = whole_run(args + [option, raster], tmp_path / "whole.gpkg")
    assert whole != whole_run(args, tmp_path / "plain.gpkg")  # the style reads the raster
    s = tiles.run(DEM, FACES, 1000, [tmp_path / "tiled.gpkg"], style=style, seed=6, workers=2, args=[option, raster])
    assert s.tiles == 9
    assert features(tmp_path / "tiled.gpkg") == whole
    # In another CRS the whole run warps the whole file first, which a tile cannot do: refused
    # before any work, with the command's usage code.
    other = str(tmp_path / "other_crs.tif")
    gdal.Warp(other, raster, dstSRS="EPSG:32632")
    r = subprocess.run([sys.executable, "-m", "rockhatch", "tiles", "--dem", DEM, "--partition", FACES,
                        "--tile-size", "1000", option, other, "-o", str(tmp_path / "refused.gpkg")],
                       capture_output=True, text=True, env=python_env(), timeout=120)
    assert r.returncode == 2 and "CRS the DEM is worked in" in r.stderr, r.stderr
    assert len(r.stderr.strip().splitlines()) == 1 and not (tmp_path / "refused.gpkg").exists()


@pytest.mark.parametrize("args,code,words", [
    (["--partition", "auto", "--extract-halo", "-5"], 2, "--extract-halo"),
    (["--tile-size", "0"], 2, "--tile-size"),
    (["--tile-size", "abc"], 2, "--tile-size"),
    (["--workers", "0"], 2, "--workers"),
    (["--workers", "2", "--scheduler", "tcp://127.0.0.1:1"], 2, "exclude"),
    (["-o", FACES, "--overwrite"], 9, "input"),
    (["--style", "nosuch"], 7, "nosuch"),
    # The extraction's tuning options: with --partition auto only, checked before any work.
    (["--min-slope", "60"], 2, "--min-slope: an option of the extraction, for --partition auto only"),
    (["--partition", "auto", "--min-slope", "abc"], 2, "--min-slope: 'abc' is not a number"),
    (["--partition", "auto", "--simplify", "5"], 2, "--simplify: at most 2 cells"),
    (["--partition", "auto", "--mask", "none.gpkg"], 3, "--mask 'none.gpkg': no such file"),
    (["--partition", "auto", "--mask", FACES, "-o", FACES, "--overwrite"], 9, "input"),
])
def test_bad_input_is_refused_before_any_work(tmp_path, args, code, words):
    base = {"--dem": DEM, "--partition": FACES, "--tile-size": "1000", "-o": str(tmp_path / "o.gpkg")}
    argv = []
    given = {args[i] for i in range(0, len(args), 2) if args[i].startswith("-")}
    for k, v in base.items():
        if k not in given:
            argv += [k, v]
    r = subprocess.run([sys.executable, "-m", "rockhatch", "tiles"] + argv + args, capture_output=True, text=True,
                       env=python_env(), timeout=120)
    assert r.returncode == code, r.stderr
    assert words in r.stderr
    assert len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not (tmp_path / "o.gpkg").exists()


def test_a_geographic_dem_is_tiled_as_the_whole_run_reprojects_it(tmp_path, rockhatch_exe):
    # The sample in degrees (with NoData corners): tiles of the UTM grid the whole run works
    # on, each warped alone from the DEM, give the whole run's hatches bit for bit; so does
    # the partition extracted tile by tile.
    dem = tmp_path / "geo.tif"
    gdal.Warp(str(dem), DEM, dstSRS="EPSG:4326", dstNodata=-9999)
    whole = whole_run(["--dem", str(dem), "--partition", FACES, "--seed", "3"], tmp_path / "w.gpkg")
    assert len(whole) > 1000
    out = tmp_path / "tiled.gpkg"
    s = tiles.run(dem, FACES, 700, [out], seed=3, workers=2)
    assert s.tiles >= 9
    assert features(out) == whole
    assert ogr.Open(str(out)).GetLayer(0).GetSpatialRef().GetAuthorityCode(None) == "32632"
    r = subprocess.run([str(rockhatch_exe), "partition", "--dem", str(dem), "-o", str(tmp_path / "p.gpkg"), "-q"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    work = tmp_path / "work"
    s = tiles.run(dem, "auto", 900, [tmp_path / "auto.gpkg"], seed=3, workers=2, workdir=work,
                  keep_tiles=True)
    assert s.warnings == []
    assert partition_faces(work / "partition.gpkg") == partition_faces(tmp_path / "p.gpkg")


def test_a_vrt_mosaic_of_many_files_gives_the_same_hatches(tmp_path, sample_whole):
    # The sample DEM cut into 3 x 3 files and put together again with gdalbuildvrt: a tiled
    # run over the mosaic draws what a whole run draws over the single file.
    src = gdal.Open(DEM)
    w, h = src.RasterXSize, src.RasterYSize
    parts = []
    for j in range(3):
        for i in range(3):
            x0, y0 = i * w // 3, j * h // 3
            p = str(tmp_path / f"part_{i}_{j}.tif")
            gdal.Translate(p, src, srcWin=[x0, y0, (i + 1) * w // 3 - x0, (j + 1) * h // 3 - y0])
            parts.append(p)
    vrt = str(tmp_path / "mosaic.vrt")
    gdal.BuildVRT(vrt, parts)
    out = tmp_path / "tiled.gpkg"
    tiles.run(vrt, FACES, 900, [out], seed=3, workers=2)
    assert features(out) == sample_whole


def test_faces_without_orientation_follow_the_fall_line_tiled_as_whole(tmp_path):
    # The sample's faces and lines without its orientation layer: every face's direction is
    # derived, and the print style lays its strokes along the smoothed fall line, a field the
    # tiles must compute from the same cells as the whole run.
    src = ogr.Open(FACES)
    faces = str(tmp_path / "faces.gpkg")
    out = ogr.GetDriverByName("GPKG").CreateDataSource(faces)
    for name in ("faces", "lines"):
        out.CopyLayer(src.GetLayerByName(name), name)
    out = None
    expected = whole_run(["--dem", DEM, "--partition", faces, "--style", "print"], tmp_path / "whole.gpkg")
    tiles.run(DEM, faces, 700, [tmp_path / "tiled.gpkg"], style="print", workers=2)
    assert features(tmp_path / "tiled.gpkg") == expected


# ---- --partition auto: the partition extracted tile by tile ----------------------------------


def partition_faces(path):
    """(id, geometry WKB) of every face of a partition GeoPackage, in file order."""
    ds = ogr.Open(str(path))
    return [(f.GetField("id"), bytes(f.GetGeometryRef().ExportToWkb())) for f in ds.GetLayerByName("faces")]


@pytest.fixture(scope="module")
def sample_auto(tmp_path_factory, rockhatch_exe):
    """The whole run with --partition auto, and the whole extraction (rockhatch partition)."""
    dem = DEM
    tmp = tmp_path_factory.mktemp("auto")
    hatches = whole_run(["--dem", dem, "--partition", "auto", "--seed", "3"], tmp / "w.gpkg")
    r = subprocess.run([str(rockhatch_exe), "partition", "--dem", dem, "-o", str(tmp / "faces.gpkg"), "-q"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    return hatches, partition_faces(tmp / "faces.gpkg")


def test_partition_auto_tiled_equals_the_whole_run_with_1_or_2_workers(tmp_path, sample_auto):
    dem = DEM
    hatches, faces = sample_auto
    outs = {}
    for workers in (1, 2):
        out = tmp_path / f"tiled{workers}.gpkg"
        calls = []
        s = tiles.run(dem, "auto", 800, [out], seed=3, workers=workers,
                      workdir=tmp_path / f"work{workers}", keep_tiles=True,
                      progress=lambda f, stage: calls.append((f, stage)) or True)
        assert s.tiles == 9 and s.partition_faces == len(faces)
        assert s.partition_overlaps == 0 and s.warnings == []  # the tiles agree
        # Extracted tile by tile, the partition is the whole extraction's, face for face and bit
        # for bit (ids included), and the hatching is the whole --partition auto run's.
        assert partition_faces(tmp_path / f"work{workers}" / "partition.gpkg") == faces
        assert features(out) == hatches
        assert any(st.startswith("partition tiles 9/9") for _, st in calls)
        assert any(st.startswith("tiles 9/9") for _, st in calls)
        fractions = [f for f, _ in calls]
        assert fractions == sorted(fractions)
        outs[workers] = out.read_bytes()
    # One or two workers: the same bytes, partition and hatching.
    assert (tmp_path / "work1" / "partition.gpkg").read_bytes() == (tmp_path / "work2" / "partition.gpkg").read_bytes()
    assert outs[1] == outs[2]


def test_partition_auto_takes_the_extractions_options(tmp_path, rockhatch_exe):
    dem = DEM
    # rockhatch partition's tuning options, passed to every extraction tile: the tiled
    # partition is the whole extraction's with the same options, and not the default one.
    opts = ["--min-slope", "90", "--no-ridge-extension", "--min-area=25"]
    r = subprocess.run([str(rockhatch_exe), "partition", "--dem", dem, "-o", str(tmp_path / "whole.gpkg"), "-q", *opts],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    whole = partition_faces(tmp_path / "whole.gpkg")
    work = tmp_path / "work"
    s = tiles.run(dem, "auto", 800, [tmp_path / "t.gpkg"], seed=3, workers=2, workdir=work,
                  keep_tiles=True, args=opts)
    assert s.partition_faces == len(whole) and s.warnings == []
    assert partition_faces(work / "partition.gpkg") == whole
    r = subprocess.run([str(rockhatch_exe), "partition", "--dem", dem, "-o", str(tmp_path / "default.gpkg"), "-q"],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0 and partition_faces(tmp_path / "default.gpkg") != whole
    # Other extraction options are another job: the finished tiles are not reused.
    with pytest.raises(RockhatchError) as e:
        tiles.run(dem, "auto", 800, [tmp_path / "t.gpkg"], seed=3, workers=1, workdir=work,
                  overwrite=True, args=["--min-slope", "80"])
    assert e.value.code == 9 and "another job" in str(e.value)


def test_partition_auto_warns_where_the_tiles_disagree(tmp_path):
    # A halo too short for the sample's basins: neighbouring tiles place some faces
    # differently and the merge finds them overlapping; the command says so in one line.
    r = subprocess.run([sys.executable, "-m", "rockhatch", "tiles", "--dem", DEM, "--partition", "auto",
                        "--tile-size", "1300", "--extract-halo", "300", "--workers", "1", "-q",
                        "-o", str(tmp_path / "o.gpkg")], capture_output=True, text=True, env=python_env(), timeout=300)
    assert r.returncode == 0, r.stderr
    warnings = [line for line in r.stderr.splitlines() if "warning:" in line]
    assert len(warnings) == 1 and "partition tiles disagree" in warnings[0] and "--extract-halo (now 300)" in warnings[0]


def test_partition_auto_other_tiles_same_partition(tmp_path, sample_auto):
    dem = DEM
    # Tiles of 500 m (25 tiles; every face larger than a tile, or cut by a tile border, comes
    # out once and whole from the tile holding its anchor) and a shorter halo: still the whole
    # extraction on the sample.
    hatches, faces = sample_auto
    out = tmp_path / "t.gpkg"
    s = tiles.run(dem, "auto", 500, [out], seed=3, workers=2, workdir=tmp_path / "work",
                  keep_tiles=True, extract_halo=1000)
    assert s.tiles == 25
    assert max(s.extract_rounds) >= 2  # some tile had to extract again over a larger window
    assert partition_faces(tmp_path / "work" / "partition.gpkg") == faces
    assert features(out) == hatches


def test_partition_auto_resumes_in_either_stage(tmp_path, sample_auto):
    dem = DEM
    hatches, _ = sample_auto
    out, work = tmp_path / "t.gpkg", tmp_path / "work"
    # Stopped while extracting: the finished partition tiles stay.
    with pytest.raises(RockhatchError) as e:
        tiles.run(dem, "auto", 800, [out], seed=3, workers=1, workdir=work,
                  progress=lambda f, stage: not stage.startswith("partition tiles 3/"))
    assert e.value.code == 10 and not out.exists()
    done = {p.name: p.stat().st_mtime_ns for p in work.glob("partition_*.gpkg")}
    assert len(done) >= 3 and not (work / "partition.gpkg").exists()
    # Stopped while hatching: the partition is merged, the extraction is not run again.
    with pytest.raises(RockhatchError) as e:
        tiles.run(dem, "auto", 800, [out], seed=3, workers=1, workdir=work,
                  progress=lambda f, stage: not stage.startswith("tiles 2/"))
    assert e.value.code == 10
    for name, stamp in done.items():
        assert (work / name).stat().st_mtime_ns == stamp
    s = tiles.run(dem, "auto", 800, [out], seed=3, workers=1, workdir=work)
    assert s.done_before >= 2 and s.partition_faces == 0  # nothing extracted again
    assert features(out) == hatches
    assert not work.exists()


def test_partition_auto_without_rock_is_one_line(tmp_path):
    flat = tmp_path / "flat.tif"
    src = gdal.Open(DEM)
    drv = gdal.GetDriverByName("GTiff")
    ds = drv.Create(str(flat), 60, 60, 1, gdal.GDT_Float32)
    ds.SetGeoTransform(src.GetGeoTransform())
    ds.SetProjection(src.GetProjection())
    ds.GetRasterBand(1).Fill(1000.0)
    ds = None
    # Dask's default dashboard port held by another program (another cluster, a parallel
    # test): a run that asks for no dashboard must not warn about it.
    busy = socket.socket()
    try:
        busy.bind(("0.0.0.0", 8787))
        busy.listen(1)
    except OSError:
        pass  # already held
    try:
        r = subprocess.run([sys.executable, "-m", "rockhatch", "tiles", "--dem", str(flat), "--partition", "auto",
                            "--tile-size", "100", "-q", "-o", str(tmp_path / "o.gpkg")],
                           capture_output=True, text=True, env=python_env(), timeout=300)
    finally:
        busy.close()
    assert r.returncode == 6, r.stderr
    assert "no rock" in r.stderr and len(r.stderr.strip().splitlines()) == 1, r.stderr
    assert not (tmp_path / "o.gpkg").exists()


def test_partition_auto_on_chamonix_within_the_documented_bound(tmp_path, rockhatch_exe, real_dem_file):
    # Chamonix.tif warped to UTM 32N at 30 m, 1:25000, tiles of 3 km, the default halo (4 km):
    # the bound docs/tiles-partition.md states (same face count, no more than 6 faces not bit for
    # bit the whole extraction's, at most 0.05% of the rock area on another face, covered twice
    # or uncovered).
    dem = tmp_path / "chamonix_utm.tif"
    gdal.Warp(str(dem), str(real_dem_file), dstSRS="EPSG:32632", xRes=30, yRes=30, resampleAlg="bilinear")
    r = subprocess.run([str(rockhatch_exe), "partition", "--dem", str(dem), "--scale", "25000", "-o",
                        str(tmp_path / "whole.gpkg"), "-q"], capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    work = tmp_path / "work"
    tiles.run(dem, "auto", 3000, [tmp_path / "t.gpkg"], scale=25000, workers=2, workdir=work,
              keep_tiles=True)
    whole, tiled = partition_faces(tmp_path / "whole.gpkg"), partition_faces(work / "partition.gpkg")
    assert len(tiled) == len(whole)
    assert len(set(w for _, w in whole) - set(w for _, w in tiled)) <= 6
    d = tiles.partition_difference(tmp_path / "whole.gpkg", work / "partition.gpkg")
    assert d["faces"] == (len(whole), len(tiled)) and d["same"] >= len(whole) - 6
    assert d["other"] <= 0.0005 and d["twice"] <= 0.0005 and d["uncovered"] <= 0.0005, d
