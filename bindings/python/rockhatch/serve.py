"""`rockhatch serve DIR`: the web map page over the MBTiles files of a folder.

Every ``*.mbtiles`` in DIR is read: the vector ones (metadata ``format`` = ``pbf``) are the
rock layers, a raster one (PNG or JPEG tiles; ``hillshade.mbtiles`` first) is the base
layer under them. With ``--dem DEM.tif`` and no ``DIR/hillshade.mbtiles``, the hillshade is
made once from the DEM with GDAL (hillshade, warp to EPSG:3857, MBTiles with overviews),
written to a temporary name and renamed.

Served, standard library only (http.server, sqlite3):

- ``/`` and the page's files: the ``web`` folder (index.html, app.js, style.css and MapLibre
  GL JS from ``web/node_modules``), found in the source tree, beside a build (its
  CMakeCache.txt names the sources) or under ``share/rockhatch/web`` of an installed prefix;
  ``--web DIR`` names another;
- ``/tiles.json``: the TileJSON of every tileset, as {"vector": [...], "raster": [...]};
- ``/tiles/NAME.json``: the TileJSON 3.0.0 of DIR/NAME.mbtiles;
- ``/tiles/NAME/Z/X/Y`` (any extension): one tile, XYZ row order (MBTiles rows are TMS,
  flipped here); a gzipped vector tile is sent as stored with ``Content-Encoding: gzip``; a
  tile that is not in the file is 204 (vector) or 404 (raster).

Errors are one line on stderr with the exit code of the rockhatch command: 2 usage, 3 a
missing or unreadable input (DIR, the DEM, no vector MBTiles in DIR, a broken MBTiles file,
the web folder), 9 the address cannot be listened on (port in use) or the hillshade cannot be
written.
"""
import http.server
import json
import os
import pathlib
import signal
import socketserver
import sqlite3
import sys
import threading
import urllib.parse

USAGE = "usage: rockhatch serve DIR [--port N] [--host ADDRESS] [--dem DEM.tif] [--web DIR] [--verbose]"

HELP = f"""{USAGE}

Serves the web map page of the MBTiles files in DIR: the vector ones (rockhatch's rock
drawing, format pbf) over a raster base (a hillshade). Open the printed address in a browser.

  DIR              folder of the .mbtiles files
  --port N         port to listen on (default 8080; 0: any free port)
  --host ADDRESS   address to listen on (default 127.0.0.1: this machine only)
  --dem DEM.tif    make DIR/hillshade.mbtiles from this DEM when it is missing
  --web DIR        folder of the page (default: the one of this installation)
  --verbose        log every request on stderr

Ctrl-C stops the server. See docs/web.md.
"""

DEFAULT_PORT = 8080
HILLSHADE = "hillshade.mbtiles"
RASTER_FORMATS = {"png": "image/png", "jpg": "image/jpeg", "jpeg": "image/jpeg", "webp": "image/webp"}
# The page's own files, and MapLibre GL JS's distribution: nothing else of node_modules is served.
MAPLIBRE_DIST = ("node_modules", "maplibre-gl", "dist")
CONTENT_TYPES = {".html": "text/html; charset=utf-8", ".js": "text/javascript; charset=utf-8",
                 ".mjs": "text/javascript; charset=utf-8", ".css": "text/css; charset=utf-8",
                 ".json": "application/json", ".map": "application/json", ".png": "image/png",
                 ".svg": "image/svg+xml", ".txt": "text/plain; charset=utf-8"}


class ServeError(Exception):
    """A one-line error with the command's exit code."""

    def __init__(self, code, message):
        super().__init__(message)
        self.code = code


# ---------------------------------------------------------------------------------------------
# The command line


def parse_args(argv):
    opts = {"dir": None, "port": DEFAULT_PORT, "host": "127.0.0.1", "dem": None, "web": None, "verbose": False}
    valued = {"--port": "port", "--host": "host", "--dem": "dem", "--web": "web"}
    i = 0
    while i < len(argv):
        a = argv[i]
        name, eq, value = a.partition("=")
        if name in valued:
            if not eq:
                if i + 1 >= len(argv):
                    raise ServeError(2, f"{name} needs a value")
                i += 1
                value = argv[i]
            opts[valued[name]] = value
        elif a == "--verbose":
            opts["verbose"] = True
        elif a.startswith("-") and a != "-":
            raise ServeError(2, f"unknown option '{a}' ({USAGE})")
        elif opts["dir"] is None:
            opts["dir"] = a
        else:
            raise ServeError(2, f"one folder only: '{opts['dir']}' and '{a}'")
        i += 1
    if opts["dir"] is None:
        raise ServeError(2, f"the folder of the .mbtiles files is missing ({USAGE})")
    try:
        port = int(opts["port"])
    except ValueError:
        raise ServeError(2, f"--port '{opts['port']}': not a whole number") from None
    if not 0 <= port <= 65535:
        raise ServeError(2, f"--port {port}: not between 0 and 65535")
    opts["port"] = port
    return opts


# ---------------------------------------------------------------------------------------------
# The page's folder


def _source_dir_of_build(build):
    """The source folder a CMake build folder was configured from, or None."""
    cache = build / "CMakeCache.txt"
    try:
        for line in cache.read_text(errors="replace").splitlines():
            if line.startswith("CMAKE_HOME_DIRECTORY:"):
                return pathlib.Path(line.split("=", 1)[1])
    except OSError:
        pass
    return None


def web_dir_candidates(module_file=__file__):
    """Where the page may be, in order: the source tree holding this module
    (bindings/python/rockhatch), the sources of the build holding it (build/python/rockhatch),
    share/rockhatch/web under each folder above it (an installed prefix)."""
    here = pathlib.Path(module_file).resolve().parent
    out = []
    if len(here.parents) >= 3:
        out.append(here.parents[2] / "web")  # <repo>/bindings/python/rockhatch
    if len(here.parents) >= 2:
        src = _source_dir_of_build(here.parents[1])  # <build>/python/rockhatch
        if src is not None:
            out.append(src / "web")
    for p in here.parents:
        out.append(p / "share" / "rockhatch" / "web")
    return out


def find_web_dir(explicit=None):
    """The folder of the page, checked to hold index.html and MapLibre GL JS."""
    if explicit:
        web = pathlib.Path(explicit)
        if not (web / "index.html").is_file():
            raise ServeError(3, f"--web '{explicit}': no index.html there")
    else:
        web = next((c for c in web_dir_candidates() if (c / "index.html").is_file()), None)
        if web is None:
            raise ServeError(3, "the web page's folder was not found (no web/index.html beside the sources, "
                                "nor share/rockhatch/web under the prefix); name it with --web")
    if not web.joinpath(*MAPLIBRE_DIST, "maplibre-gl.js").is_file():
        raise ServeError(3, f"MapLibre GL JS is missing in '{web}': run `npm ci` in that folder "
                            "(scripts/setup.sh does)")
    return web.resolve()


# ---------------------------------------------------------------------------------------------
# MBTiles


def _connect(path):
    return sqlite3.connect(f"file:{urllib.parse.quote(str(path))}?mode=ro", uri=True, check_same_thread=False)


class Tileset:
    """One MBTiles file: its metadata, read once, and its tiles, read per request."""

    def __init__(self, path):
        self.path = pathlib.Path(path)
        self.name = self.path.stem
        try:
            con = _connect(self.path)
            try:
                meta = dict(con.execute("SELECT name, value FROM metadata").fetchall())
                first = con.execute("SELECT tile_data FROM tiles LIMIT 1").fetchone()
                zooms = con.execute("SELECT MIN(zoom_level), MAX(zoom_level) FROM tiles").fetchone()
            finally:
                con.close()
        except sqlite3.Error as e:
            raise ServeError(3, f"'{self.path}': not an MBTiles file SQLite can read ({e})") from None
        self.meta = meta
        fmt = (meta.get("format") or "").lower()
        if not fmt and first is not None:  # sniffed from the first tile when the metadata omits it
            data = first[0] or b""
            fmt = "png" if data[:4] == b"\x89PNG" else "jpg" if data[:2] == b"\xff\xd8" else "pbf"
        if fmt not in RASTER_FORMATS and fmt != "pbf":
            raise ServeError(3, f"'{self.path}': tile format '{fmt or '?'}' is neither pbf nor an image")
        self.format = fmt
        self.vector = fmt == "pbf"
        # The levels the file holds (its metadata may claim more: GDAL's raster writer says 0).
        try:
            self.minzoom = int(zooms[0]) if zooms[0] is not None else int(meta.get("minzoom", 0))
            self.maxzoom = int(zooms[1]) if zooms[1] is not None else int(meta.get("maxzoom", 0))
        except ValueError:
            raise ServeError(3, f"'{self.path}': bad minzoom or maxzoom in the metadata") from None
        try:
            self.bounds = [float(v) for v in meta.get("bounds", "-180,-85.0511,180,85.0511").split(",")]
            if len(self.bounds) != 4:
                raise ValueError
        except ValueError:
            raise ServeError(3, f"'{self.path}': bad bounds in the metadata: '{meta.get('bounds')}'") from None
        self.vector_layers = []
        if self.vector and meta.get("json"):
            try:
                self.vector_layers = json.loads(meta["json"]).get("vector_layers", [])
            except ValueError:
                raise ServeError(3, f"'{self.path}': the metadata's json is not JSON") from None
        # The CSS pixels a tile spans at its own zoom: 512 for vector tiles (MapLibre's only
        # size: a level-z tile is shown at its own scale at map zoom z), 256 for GDAL's PNG
        # tiles unless the file says otherwise.
        self.tile_size = 512
        # The scale each level was drawn at, for the page's line widths: the writer of
        # `rockhatch -o x.mbtiles` (carto::zoom_scale) takes level z at the ground of a pixel
        # of a 256-pixel Web Mercator tile over OGC's 0.28 mm pixel; the metadata keys
        # pixel_mm and tile_px say otherwise for tiles drawn another way.
        self.pixel_mm, self.tile_px = 0.28, 256
        try:
            self.pixel_mm = float(meta.get("pixel_mm", self.pixel_mm))
            self.tile_px = int(meta.get("tile_px", self.tile_px))
        except ValueError:
            raise ServeError(3, f"'{self.path}': bad pixel_mm or tile_px in the metadata") from None
        if not (self.pixel_mm > 0 and self.tile_px > 0):
            raise ServeError(3, f"'{self.path}': pixel_mm and tile_px must be positive")
        if not self.vector:
            try:
                self.tile_size = int(meta.get("tile_size", 256))
            except ValueError:
                self.tile_size = 256
        self._local = threading.local()

    def tilejson(self, base_url):
        tj = {
            "tilejson": "3.0.0",
            "name": self.meta.get("name", self.name),
            "description": self.meta.get("description", ""),
            "attribution": self.meta.get("attribution", ""),
            "scheme": "xyz",
            "tiles": [f"{base_url}/tiles/{urllib.parse.quote(self.name)}/{{z}}/{{x}}/{{y}}.{self.format}"],
            "minzoom": self.minzoom,
            "maxzoom": self.maxzoom,
            "bounds": self.bounds,
            "format": self.format,
            "tile_size": self.tile_size,
        }
        if "center" in self.meta:
            try:
                tj["center"] = [float(v) for v in self.meta["center"].split(",")]
            except ValueError:
                pass
        if self.vector:
            tj["vector_layers"] = self.vector_layers
            tj["pixel_mm"], tj["tile_px"] = self.pixel_mm, self.tile_px
        return tj

    def tile(self, z, x, y):
        """The stored bytes of tile z/x/y (XYZ row order), or None."""
        if not (0 <= z <= 30 and 0 <= x < (1 << z) and 0 <= y < (1 << z)):
            return None
        con = getattr(self._local, "con", None)
        if con is None:
            con = self._local.con = _connect(self.path)
        row = con.execute("SELECT tile_data FROM tiles WHERE zoom_level=? AND tile_column=? AND tile_row=?",
                          (z, x, (1 << z) - 1 - y)).fetchone()
        return row[0] if row else None


def load_tilesets(folder):
    folder = pathlib.Path(folder)
    if not folder.is_dir():
        raise ServeError(3, f"'{folder}': no such folder")
    sets = [Tileset(p) for p in sorted(folder.glob("*.mbtiles")) if p.is_file()]
    vector = [t for t in sets if t.vector]
    raster = [t for t in sets if not t.vector]
    if not vector:
        raise ServeError(3, f"'{folder}': no vector MBTiles (format pbf) there")
    raster.sort(key=lambda t: t.path.name != HILLSHADE)  # the hillshade first, then by name
    return vector, raster


# ---------------------------------------------------------------------------------------------
# The hillshade


def make_hillshade(dem, out, log=print):
    """DIR/hillshade.mbtiles from a DEM: GDAL's hillshade, warped to EPSG:3857, PNG tiles at
    the zoom level nearest the DEM's cell size with overviews down to a few tiles. Written to
    a temporary name in the same folder and renamed, so a stopped run leaves no half file."""
    from osgeo import gdal

    # GDAL's exceptions for this call only: the caller's choice is put back.
    used = gdal.GetUseExceptions()
    gdal.UseExceptions()
    try:
        _make_hillshade(gdal, dem, out, log)
    finally:
        if not used:
            gdal.DontUseExceptions()


def _make_hillshade(gdal, dem, out, log):
    from osgeo import osr

    dem = pathlib.Path(dem)
    if not dem.is_file():
        raise ServeError(3, f"--dem '{dem}': no such file")
    try:
        src = gdal.Open(str(dem))
    except RuntimeError:
        src = None
    if src is None or src.RasterCount < 1:
        raise ServeError(3, f"--dem '{dem}': not a raster GDAL can read")
    wkt = src.GetProjection()
    if not wkt:
        raise ServeError(4, f"--dem '{dem}': the raster has no CRS")
    srs = osr.SpatialReference(wkt=wkt)
    # Ground units per horizontal unit: degrees of a geographic DEM are ~111 km.
    scale = 111120.0 if srs.IsGeographic() else 1.0
    out = pathlib.Path(out)
    tag = f".part-{os.getpid()}"
    shade = str(out) + tag + ".hs.tif"
    merc = str(out) + tag + ".3857.tif"
    part = str(out) + tag  # not *.mbtiles: never taken for a tileset if left behind
    log(f"rockhatch serve: making {out} from {dem} (once)")
    try:
        gdal.DEMProcessing(shade, src, "hillshade", format="GTiff", computeEdges=True, scale=scale,
                           azimuth=315, altitude=45, zFactor=1.0, creationOptions=["COMPRESS=DEFLATE", "TILED=YES"])
        gdal.Warp(merc, shade, dstSRS="EPSG:3857", resampleAlg="bilinear", srcNodata=0, dstAlpha=True,
                  creationOptions=["COMPRESS=DEFLATE", "TILED=YES"])
        ds = gdal.Translate(part, merc, format="MBTiles",
                            creationOptions=["TILE_FORMAT=PNG", "RESAMPLING=BILINEAR", "ZOOM_LEVEL_STRATEGY=UPPER",
                                             f"NAME={dem.stem} hillshade"])
        # Overviews (lower zoom levels): at least four, and down to the level where the DEM
        # is a few dozen pixels wide.
        width, height = ds.RasterXSize, ds.RasterYSize
        factors, f = [], 2
        while (max(width, height) / f >= 32 or len(factors) < 4) and len(factors) < 16:
            factors.append(f)
            f *= 2
        if factors:
            ds.BuildOverviews("AVERAGE", factors)
        ds = None
        os.replace(part, out)
    except (RuntimeError, OSError) as e:
        raise ServeError(9, f"cannot make '{out}' from --dem '{dem}': {e}") from None
    finally:  # on an error or Ctrl-C too: no temporary file is left (the part is gone once renamed)
        for p in (shade, merc, part):
            if os.path.exists(p):
                os.remove(p)


# ---------------------------------------------------------------------------------------------
# The server


class Handler(http.server.BaseHTTPRequestHandler):
    server_version = "rockhatch-serve"
    protocol_version = "HTTP/1.1"

    def log_message(self, fmt, *args):
        if self.server.verbose:
            sys.stderr.write("rockhatch serve: %s %s\n" % (self.address_string(), fmt % args))

    def _send(self, status, body=b"", content_type=None, headers=None):
        self.send_response(status)
        if content_type:
            self.send_header("Content-Type", content_type)
        for k, v in (headers or {}).items():
            self.send_header(k, v)
        self.send_header("Content-Length", str(len(body)))
        self.send_header("Access-Control-Allow-Origin", "*")
        self.end_headers()
        if self.command != "HEAD" and body:
            self.wfile.write(body)

    def _json(self, obj):
        self._send(200, json.dumps(obj).encode(), "application/json", {"Cache-Control": "no-cache"})

    def _base_url(self):
        host = self.headers.get("Host") or f"{self.server.server_address[0]}:{self.server.server_address[1]}"
        return f"http://{host}"

    def do_HEAD(self):
        self.do_GET()

    def do_GET(self):
        path = urllib.parse.urlsplit(self.path).path
        parts = [urllib.parse.unquote(p) for p in path.split("/") if p]
        try:
            if parts[:1] == ["tiles"]:
                return self._tiles(parts[1:])
            if parts == ["tiles.json"]:
                base = self._base_url()
                return self._json({"vector": [t.tilejson(base) for t in self.server.vector],
                                   "raster": [t.tilejson(base) for t in self.server.raster]})
            return self._static(parts)
        except (BrokenPipeError, ConnectionResetError):
            pass
        except sqlite3.Error as e:
            self._send(500, f"tile read failed: {e}\n".encode(), "text/plain")

    def _tiles(self, parts):
        sets = self.server.tilesets
        if len(parts) == 1 and parts[0].endswith(".json") and parts[0][:-5] in sets:
            return self._json(sets[parts[0][:-5]].tilejson(self._base_url()))
        if len(parts) == 4 and parts[0] in sets:
            ts = sets[parts[0]]
            try:
                z, x, y = int(parts[1]), int(parts[2]), int(parts[3].split(".", 1)[0])
            except ValueError:
                return self._send(400, b"bad tile address\n", "text/plain")
            data = ts.tile(z, x, y)
            if data is None:
                return self._send(204 if ts.vector else 404)
            headers = {"Cache-Control": "no-cache"}
            if ts.vector:
                ctype = "application/vnd.mapbox-vector-tile"
                if data[:2] == b"\x1f\x8b":
                    headers["Content-Encoding"] = "gzip"
            else:
                ctype = RASTER_FORMATS[ts.format]
            return self._send(200, data, ctype, headers)
        return self._send(404, b"no such tileset or tile\n", "text/plain")

    def _static(self, parts):
        web = self.server.web
        if not parts:
            parts = ["index.html"]
        if any(p in ("..", ".") or p.startswith(".") for p in parts):
            return self._send(404, b"not found\n", "text/plain")
        # The page's top-level files, and MapLibre's distribution folder; nothing else.
        if len(parts) > 1 and tuple(parts[:3]) != MAPLIBRE_DIST:
            return self._send(404, b"not found\n", "text/plain")
        if len(parts) == 1 and pathlib.Path(parts[0]).suffix not in (".html", ".js", ".css", ".png", ".svg"):
            return self._send(404, b"not found\n", "text/plain")
        f = web.joinpath(*parts)
        if not f.is_file():
            return self._send(404, b"not found\n", "text/plain")
        ctype = CONTENT_TYPES.get(f.suffix, "application/octet-stream")
        self._send(200, f.read_bytes(), ctype, {"Cache-Control": "no-cache"})


class Server(socketserver.ThreadingMixIn, http.server.HTTPServer):
    daemon_threads = True
    allow_reuse_address = True


def make_server(opts, log=print):
    folder = pathlib.Path(opts["dir"])
    if not folder.is_dir():
        raise ServeError(3, f"'{folder}': no such folder")
    web = find_web_dir(opts["web"])
    try:  # first: a port in use is told before any work
        server = Server((opts["host"], opts["port"]), Handler)
    except OSError as e:
        raise ServeError(9, f"cannot listen on {opts['host']}:{opts['port']}: {e.strerror or e}") from None
    try:
        if opts["dem"] and not (folder / HILLSHADE).exists():
            make_hillshade(opts["dem"], folder / HILLSHADE, log)
        vector, raster = load_tilesets(folder)
    except BaseException:
        server.server_close()
        raise
    server.web = web
    server.vector, server.raster = vector, raster
    server.tilesets = {t.name: t for t in vector + raster}
    server.verbose = opts["verbose"]
    return server


def main(argv=None):
    """`rockhatch serve`: returns the exit code."""
    argv = sys.argv[1:] if argv is None else list(argv)
    if "--help" in argv or "-h" in argv:
        sys.stdout.write(HELP)
        return 0
    try:
        opts = parse_args(argv)
        server = make_server(opts, log=lambda m: print(m, file=sys.stderr, flush=True))
    except ServeError as e:
        sys.stderr.write(f"rockhatch serve: {e}\n")
        return e.code
    except KeyboardInterrupt:
        sys.stderr.write("rockhatch serve: interrupted\n")
        return 130

    # Ctrl-C (SIGINT) and SIGTERM stop the server, from the moment its address is printed: a
    # request being answered is finished, then the socket is closed.
    def _stop(signum, frame):
        threading.Thread(target=server.shutdown, daemon=True).start()

    previous = {sig: signal.signal(sig, _stop) for sig in (signal.SIGINT, signal.SIGTERM)}
    host, port = server.server_address[:2]
    shown = f"[{host}]" if ":" in host else host
    base = server.raster[0].name if server.raster else "none"
    print(f"rockhatch serve: http://{shown}:{port}/  (rock: {', '.join(t.name for t in server.vector)}; "
          f"base: {base}; Ctrl-C stops)", flush=True)
    try:
        server.serve_forever(poll_interval=0.2)
    finally:
        for sig, handler in previous.items():
            signal.signal(sig, handler)
        server.server_close()
    print("rockhatch serve: stopped", file=sys.stderr, flush=True)
    return 0


if __name__ == "__main__":
    sys.exit(main())
