"""`rockhatch serve` and the web map page (web/): the server alone (TileJSON, tiles, the y
flip, gzip, the hillshade from --dem, bad input) and the page in Debian's headless Chromium
driven by web/test/shoot.mjs (playwright-core), which must draw the rock tiles over the
hillshade.

The browser tests need /usr/bin/chromium and web/node_modules (scripts/setup.sh installs
both); without them they are skipped, except under CI=true, where they fail.
RH_WRITE_DOCS=1 writes the screenshots at z13 and z16 to docs/web-z13.png and
docs/web-z16.png; otherwise they stay in pytest's temporary folder.
"""
import contextlib
import fcntl
import gzip
import importlib.util
import json
import os
import pathlib
import select
import shutil
import signal
import socket
import sqlite3
import subprocess
import sys
import time
import urllib.error
import urllib.request

import pytest

from conftest import ROOT, SAMPLE, python_env

WEB = ROOT / "web"
SHOOT = WEB / "test" / "shoot.mjs"
CHROMIUM = pathlib.Path(os.environ.get("RH_CHROMIUM", "/usr/bin/chromium"))
IN_CI = os.environ.get("CI") == "true"

def tool_env():
    """For the system's programs (node and Chromium): without the sanitizer pass's
    LD_PRELOAD of the ASan runtime, which only this build's programs and module need."""
    return {k: v for k, v in os.environ.items() if k != "LD_PRELOAD"}


def make_rock_mbtiles(rockhatch_exe, out_dir) -> pathlib.Path:
    """out_dir/rock.mbtiles: the sample drawn by `rockhatch` as vector tiles, levels 12 to
    16 each drawn at its own scale, with crest ornaments (polygons). The one place that makes
    the tiles the tests serve."""
    out = pathlib.Path(out_dir) / "rock.mbtiles"
    subprocess.run([str(rockhatch_exe), "--dem", str(SAMPLE / "dem.tif"), "--partition", str(SAMPLE / "partition.gpkg"),
                    "--crest-ornament", "default", "--zoom", "12-16", "-q", "-o", str(out)],
                   check=True, capture_output=True, timeout=600)
    return out


def need_page():
    """Skips (fails under CI=true) when the page cannot be served: no web/node_modules."""
    if not (WEB / "node_modules" / "maplibre-gl" / "dist" / "maplibre-gl.js").is_file():
        message = "web/node_modules is missing: run `npm ci` in web/ (scripts/setup.sh does)"
        if IN_CI:
            pytest.fail(message)
        pytest.skip(message)


def need_browser():
    need_page()
    missing = []
    if not CHROMIUM.exists():
        missing.append(f"{CHROMIUM} (apt-get install chromium)")
    if shutil.which("node") is None:
        missing.append("node (apt-get install nodejs)")
    if not (WEB / "node_modules" / "playwright-core").is_dir():
        missing.append("web/node_modules/playwright-core (npm ci in web/)")
    if missing:
        message = "the browser test needs " + ", ".join(missing)
        if IN_CI:
            pytest.fail(message)
        pytest.skip(message)


@pytest.fixture(scope="session")
def tiles_dir(tmp_path_factory, rockhatch_exe):
    """A folder with rock.mbtiles, and hillshade.mbtiles made by `rockhatch serve --dem`:
    made once for all pytest-xdist workers (in their shared temporary folder, under a lock)."""
    need_page()
    root = tmp_path_factory.getbasetemp()
    if os.environ.get("PYTEST_XDIST_WORKER"):
        root = root.parent
    folder = root / "web_tiles"
    folder.mkdir(exist_ok=True)
    with open(root / "web_tiles.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if not (folder / "rock.mbtiles").exists():
            make_rock_mbtiles(rockhatch_exe, folder)
        if not (folder / "hillshade.mbtiles").exists():
            with serve(folder, "--dem", SAMPLE / "dem.tif") as url:
                assert url.startswith("http://127.0.0.1:")
        fcntl.flock(lock, fcntl.LOCK_UN)
    return folder


def serve_cmd(*args):
    return [sys.executable, "-m", "rockhatch", "serve", *map(str, args)]


@contextlib.contextmanager
def serve(folder, *args, timeout=120):
    """`rockhatch serve FOLDER --port 0 ...` (this checkout's web/ page) running; yields its
    URL. Stopped by Ctrl-C (SIGINT) at the end, which must end it cleanly."""
    proc = subprocess.Popen(serve_cmd(folder, "--port", "0", "--web", WEB, *args), env=python_env(),
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        ready, _, _ = select.select([proc.stdout], [], [], timeout)
        line = proc.stdout.readline() if ready else ""
        if "http://" not in line:
            proc.kill()
            raise AssertionError(f"rockhatch serve did not start: {line!r} {proc.stderr.read()!r}")
        url = line.split()[2]
        yield url
    finally:
        if proc.poll() is None:
            proc.send_signal(signal.SIGINT)
            try:
                proc.wait(timeout=10)
            except subprocess.TimeoutExpired:
                proc.kill()
                proc.wait()
                raise AssertionError("rockhatch serve did not stop on Ctrl-C")
    assert proc.returncode == 0, proc.stderr.read()
    assert "stopped" in proc.stderr.read()


def get(url):
    """(status, headers, body) of a GET, the body as sent (not decompressed)."""
    try:
        with urllib.request.urlopen(url, timeout=30) as r:
            return r.status, r.headers, r.read()
    except urllib.error.HTTPError as e:
        return e.code, e.headers, e.read()


def stored_tiles(path, zoom):
    """{(column, tms row): bytes} of one level of an MBTiles file, read directly."""
    con = sqlite3.connect(f"file:{path}?mode=ro", uri=True)
    try:
        return {(c, r): d for c, r, d in con.execute(
            "SELECT tile_column, tile_row, tile_data FROM tiles WHERE zoom_level=?", (zoom,))}
    finally:
        con.close()


# ---------------------------------------------------------------------------------------------
# The server alone


def test_tilejson(tiles_dir):
    with serve(tiles_dir) as url:
        status, headers, body = get(url + "tiles/rock.json")
        assert status == 200 and headers["Content-Type"] == "application/json"
        tj = json.loads(body)
        assert tj["tilejson"] == "3.0.0" and tj["format"] == "pbf"
        assert tj["tiles"] == [url + "tiles/rock/{z}/{x}/{y}.pbf"]
        assert (tj["minzoom"], tj["maxzoom"]) == (12, 16)
        assert (tj["pixel_mm"], tj["tile_px"]) == (0.28, 256)  # the scales of rockhatch's writer
        names = {layer["id"] for layer in tj["vector_layers"]}
        assert {"fill", "ridge", "valley", "cross", "crest"} <= names
        assert "width_mm" in next(layer for layer in tj["vector_layers"] if layer["id"] == "fill")["fields"]
        w, s, e, n = tj["bounds"]
        assert 6.85 < w < e < 7.0 and 45.85 < s < n < 45.95  # the sample, at the Aiguille du Moine

        everything = json.loads(get(url + "tiles.json")[2])
        assert [t["tiles"] for t in everything["vector"]] == [tj["tiles"]]
        assert len(everything["raster"]) == 1 and everything["raster"][0]["format"] == "png"
        assert everything["raster"][0]["tiles"] == [url + "tiles/hillshade/{z}/{x}/{y}.png"]

        assert get(url + "tiles/nothing.json")[0] == 404


def test_vector_tile_gzip_and_y_flip(tiles_dir):
    """A tile asked for in XYZ rows is the MBTiles (TMS) row 2^z - 1 - y, sent as stored
    (gzipped PBF) with Content-Encoding: gzip; the row not flipped is another tile."""
    z = 15
    stored = stored_tiles(tiles_dir / "rock.mbtiles", z)
    assert len(stored) >= 4
    # A tile whose unflipped row holds no tile, so a server that forgot the flip fails.
    (x, row), data = next(((k, d) for k, d in sorted(stored.items()) if (k[0], (1 << z) - 1 - k[1]) not in stored))
    y = (1 << z) - 1 - row
    with serve(tiles_dir) as url:
        status, headers, body = get(f"{url}tiles/rock/{z}/{x}/{y}.pbf")
        assert status == 200
        assert headers["Content-Encoding"] == "gzip"
        assert headers["Content-Type"] == "application/vnd.mapbox-vector-tile"
        assert body == data and body[:2] == b"\x1f\x8b"
        assert len(gzip.decompress(body)) > 0
        # Every stored tile of the level comes back at its flipped row.
        for (c, r), d in stored.items():
            assert get(f"{url}tiles/rock/{z}/{c}/{(1 << z) - 1 - r}")[2] == d
        # The row as stored (TMS) is empty in XYZ: 204, no body.
        status, _, body = get(f"{url}tiles/rock/{z}/{x}/{row}.pbf")
        assert (status, body) == (204, b"")
        assert get(f"{url}tiles/rock/{z}/{1 << z}/0.pbf")[0] == 204  # outside the level
        assert get(f"{url}tiles/rock/{z}/{x}/abc.pbf")[0] == 400


def test_raster_tiles_and_hillshade(tiles_dir):
    """`--dem` made hillshade.mbtiles once (PNG, EPSG:3857 levels with overviews, nothing
    left behind); a second start with --dem does not make it again."""
    hs = tiles_dir / "hillshade.mbtiles"
    con = sqlite3.connect(f"file:{hs}?mode=ro", uri=True)
    meta = dict(con.execute("SELECT name, value FROM metadata"))
    levels = [z for (z,) in con.execute("SELECT DISTINCT zoom_level FROM tiles ORDER BY 1")]
    z = levels[-1]
    (x, row, data), = con.execute("SELECT tile_column, tile_row, tile_data FROM tiles WHERE zoom_level=? LIMIT 1",
                                  (z,)).fetchall()
    con.close()
    assert meta["format"] == "png"
    assert len(levels) >= 4 and levels == list(range(levels[0], z + 1)) and z >= 14  # a 5 m DEM
    assert not [p.name for p in tiles_dir.iterdir() if ".part" in p.name]
    before = hs.stat().st_mtime_ns
    with serve(tiles_dir, "--dem", SAMPLE / "dem.tif") as url:
        status, headers, body = get(f"{url}tiles/hillshade/{z}/{x}/{(1 << z) - 1 - row}.png")
        assert status == 200 and headers["Content-Type"] == "image/png" and "Content-Encoding" not in headers
        assert body == data and body[:4] == b"\x89PNG"
        assert get(f"{url}tiles/hillshade/{z}/0/0.png")[0] == 404
    assert hs.stat().st_mtime_ns == before


def test_page_files(tiles_dir):
    """The page and MapLibre's distribution are served; nothing else of web/."""
    with serve(tiles_dir) as url:
        status, headers, body = get(url)
        assert status == 200 and headers["Content-Type"].startswith("text/html") and b"app.js" in body
        assert get(url + "app.js")[0] == 200
        status, headers, _ = get(url + "node_modules/maplibre-gl/dist/maplibre-gl.js")
        assert status == 200 and headers["Content-Type"].startswith("text/javascript")
        for path in ("package.json", "node_modules/playwright-core/package.json", "test/shoot.mjs", "../README.md",
                     "%2e%2e/README.md"):
            assert get(url + path)[0] == 404, path


def run_serve(*args, timeout=60):
    return subprocess.run(serve_cmd(*args), env=python_env(), capture_output=True, text=True, timeout=timeout)


def one_line_error(r, code, words):
    assert r.returncode == code, (r.returncode, r.stderr)
    lines = r.stderr.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("rockhatch serve: "), r.stderr
    assert words in lines[0], lines[0]


def test_bad_input(tmp_path, tiles_dir):
    web = ["--web", WEB]
    one_line_error(run_serve(tmp_path / "none", *web), 3, "no such folder")
    empty = tmp_path / "empty"
    empty.mkdir()
    one_line_error(run_serve(empty, *web), 3, "no vector MBTiles")
    shutil.copy(tiles_dir / "hillshade.mbtiles", empty / "hillshade.mbtiles")  # a raster only
    one_line_error(run_serve(empty, *web), 3, "no vector MBTiles")
    (tmp_path / "junk").mkdir()
    (tmp_path / "junk" / "rock.mbtiles").write_bytes(b"not sqlite" * 100)
    one_line_error(run_serve(tmp_path / "junk", *web), 3, "not an MBTiles file")
    one_line_error(run_serve(tiles_dir, "--port", "http", *web), 2, "--port 'http'")
    one_line_error(run_serve(tiles_dir, "--port", "70000", *web), 2, "--port 70000")
    one_line_error(run_serve(tiles_dir, "--bogus", *web), 2, "unknown option '--bogus'")
    one_line_error(run_serve(*web), 2, "folder of the .mbtiles files is missing")
    one_line_error(run_serve(tiles_dir, "--web", tmp_path), 3, "no index.html")
    no_hillshade = tmp_path / "rock_only"
    no_hillshade.mkdir()
    os.symlink(tiles_dir / "rock.mbtiles", no_hillshade / "rock.mbtiles")
    one_line_error(run_serve(no_hillshade, "--dem", tmp_path / "none.tif", *web), 3, "--dem")
    (tmp_path / "junk.tif").write_bytes(b"junk")
    one_line_error(run_serve(no_hillshade, "--dem", tmp_path / "junk.tif", *web), 3, "not a raster")
    assert sorted(p.name for p in no_hillshade.iterdir()) == ["rock.mbtiles"]  # nothing left behind
    with socket.socket() as taken:
        taken.bind(("127.0.0.1", 0))
        taken.listen()
        port = taken.getsockname()[1]
        one_line_error(run_serve(tiles_dir, "--port", port, *web), 9, f"cannot listen on 127.0.0.1:{port}")


def test_help():
    r = run_serve("--help")
    assert r.returncode == 0 and r.stdout.startswith("usage: rockhatch serve DIR")


def test_command_dispatches_serve(rockhatch_exe, tmp_path):
    """`rockhatch serve` is the Python command's, like `rockhatch tiles`."""
    r = subprocess.run([str(rockhatch_exe), "serve", "--help"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 0 and r.stdout.startswith("usage: rockhatch serve DIR"), r.stdout + r.stderr
    r = subprocess.run([str(rockhatch_exe), "serve", tmp_path / "none"], capture_output=True, text=True, timeout=60)
    assert r.returncode == 3 and "no such folder" in r.stderr


def _load_serve_source():
    spec = importlib.util.spec_from_file_location("rh_serve_source", ROOT / "bindings/python/rockhatch/serve.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_web_folder_found(tmp_path):
    """The page is found beside the sources, beside a build (its CMakeCache.txt names the
    sources) and under share/rockhatch/web of an installed prefix."""
    m = _load_serve_source()
    assert m.web_dir_candidates(ROOT / "bindings/python/rockhatch/serve.py")[0] == ROOT / "web"
    build = tmp_path / "build"
    (build / "python" / "rockhatch").mkdir(parents=True)
    (build / "CMakeCache.txt").write_text(f"CMAKE_HOME_DIRECTORY:INTERNAL={ROOT}\n")
    assert ROOT / "web" in m.web_dir_candidates(build / "python" / "rockhatch" / "serve.py")
    prefix = tmp_path / "usr"
    module = prefix / "lib" / "python3" / "dist-packages" / "rockhatch" / "serve.py"
    (prefix / "share" / "rockhatch" / "web").mkdir(parents=True)
    found = [c for c in m.web_dir_candidates(module) if c.is_dir()]
    assert found == [prefix / "share" / "rockhatch" / "web"]


# ---------------------------------------------------------------------------------------------
# The page in Chromium


def dark_pixels(png, threshold=96):
    from PIL import Image
    hist = Image.open(png).convert("L").histogram()
    return sum(hist[:threshold])


def darker_pixels(png, base_png, by=48):
    """Pixels at least `by` grey levels darker than in the render without the rock."""
    import numpy as np
    from PIL import Image
    a = np.asarray(Image.open(png).convert("L"), dtype=np.int16)
    b = np.asarray(Image.open(base_png).convert("L"), dtype=np.int16)
    return int(((b - a) >= by).sum())


def test_page_draws_rock(tiles_dir, tmp_path):
    need_browser()
    with serve(tiles_dir) as url:
        t0 = time.monotonic()
        r = subprocess.run(["node", str(SHOOT), url, str(tmp_path), "13", "16"], capture_output=True, text=True,
                           timeout=300, cwd=WEB, env=tool_env())
        wall = time.monotonic() - t0
    out = json.loads(r.stdout.strip().splitlines()[-1]) if r.stdout.strip() else {}
    assert r.returncode == 0, f"{out.get('failure')} {out.get('console')} {r.stderr[-2000:]}"
    assert out["errors"] == [], out["errors"]
    assert not [c for c in out["console"] if c.startswith(("error", "pageerror"))], out["console"]
    assert out["requests"]["failed"] == [] and out["requests"]["tiles"] > 10, out["requests"]

    measures = {"renderer": out["renderer"], "first_rock_drawn_ms": round(out["firstRockDrawnMs"]),
                "first_idle_ms": round(out["firstIdleMs"]), "page_load_ms": round(out["pageLoadMs"]),
                "shoot_wall_s": round(wall, 1), "views": {}}
    for view in ("fitted", "z13", "z16"):
        v = out["views"][view]
        assert v["features"] > 1000, (view, v)  # the rock layers are drawn there
        # Strokes as wide as the drawing's pixels make them (rockhatch's writer: 0.28 mm
        # pixels of 256-pixel tiles, shown by MapLibre in 512-pixel tiles), magnified between levels.
        assert len(v["widths"]) >= 4, v["widths"]
        zoom = v["zoom"]
        for layer, (width_mm, px) in v["widths"].items():
            assert px == pytest.approx(width_mm / 0.28 * 2 * 2 ** (zoom - int(zoom)), rel=1e-6), (view, layer)
        rock, base = tmp_path / f"{view}.png", tmp_path / f"{view}-base.png"
        d_rock, d_base, darker = dark_pixels(rock), dark_pixels(base), darker_pixels(rock, base)
        measures["views"][view] = {"zoom": round(v["zoom"], 2), "scale": v["scale"], "features": v["features"],
                                   "dark_with_rock": d_rock, "dark_hillshade_only": d_base, "darker": darker}
        # Clearly more dark stroke pixels with the rock than on the hillshade alone.
        assert d_rock > 3 * d_base + 2000, (view, d_rock, d_base)
        assert darker > 5000, (view, darker)
    # The map fitted the tiles' bounds: the whole sample at about 1:10000 in 1024 x 768.
    assert 13.5 < out["fittedZoom"] < 15.5
    assert out["views"]["z16"]["scale"].startswith("zoom 16.0")
    assert out["firstRockDrawnMs"] < 30000
    print("web page measures:", json.dumps(measures))
    (tmp_path / "measures.json").write_text(json.dumps(measures, indent=1))
    if os.environ.get("RH_WRITE_DOCS") == "1":  # in 64 colours: half the bytes, the same look
        from PIL import Image
        for z in ("z13", "z16"):
            Image.open(tmp_path / f"{z}.png").convert("RGB").quantize(64).save(ROOT / "docs" / f"web-{z}.png",
                                                                                optimize=True)


def test_make_hillshade_leaves_gdals_exceptions_as_the_caller_had_them(tmp_path):
    # In a fresh interpreter: the test processes' other modules have their own GDAL settings.
    for setting, expected in (("DontUseExceptions", 0), ("UseExceptions", 1)):
        out = tmp_path / f"hillshade{expected}.mbtiles"
        code = ("from osgeo import gdal\n"
                "from rockhatch import serve\n"
                f"gdal.{setting}()\n"
                f"serve.make_hillshade({str(SAMPLE / 'dem.tif')!r}, {str(out)!r}, log=lambda *a: None)\n"
                "print(gdal.GetUseExceptions())\n")
        p = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=python_env(),
                           timeout=300)
        assert p.returncode == 0, p.stderr
        assert out.exists()
        assert p.stdout.split()[-1] == str(expected), p.stdout
