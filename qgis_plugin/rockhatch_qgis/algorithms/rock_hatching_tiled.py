"""Processing algorithm "Rock hatching, tiled": `rockhatch tiles` (Dask) from QGIS.

The tiled run starts Dask worker processes. Inside QGIS the interpreter is QGIS itself, and a
local cluster started there would launch copies of it (or require changing multiprocessing's
process-wide settings), so the run goes to a child process: the system's Python running
`python3 -m rockhatch tiles`, with this plugin's rockhatch module on its path. Its progress
bar is read from its standard error; cancelling stops it, and the tiles it finished stay in
the work folder, so running again with the same inputs resumes.
"""
import os
import queue
import re
import signal
import subprocess
import sys
import threading

from qgis.core import (QgsProcessingException, QgsProcessingOutputMultipleLayers,
                       QgsProcessingOutputNumber, QgsProcessingParameterBoolean,
                       QgsProcessingParameterFile, QgsProcessingParameterFileDestination,
                       QgsProcessingParameterFolderDestination, QgsProcessingParameterNumber,
                       QgsProcessingParameterRasterLayer, QgsProcessingParameterString)

from .common import RockhatchAlgorithm
from .rock_hatching import load_hatch_layers, parse_params, style_parameter

# "\r[#####      ]  21% tiles 3/14, 0.50/s, 0m22s left": percent and stage of the bar.
_BAR = re.compile(r"\]\s+(\d+)% (.*?)\s*$")
_SUMMARY = re.compile(r"rockhatch tiles: (\d+) tiles \((\d+) done before\), (\d+) faces, (\d+) hatches")


def system_python():
    """The interpreter of the Python QGIS embeds, as a program (QGIS's own sys.executable is
    QGIS)."""
    for candidate in (os.path.join(sys.base_prefix, "bin", "python3"), "/usr/bin/python3"):
        if os.access(candidate, os.X_OK):
            return candidate
    raise QgsProcessingException("no python3 next to QGIS's Python to run the Dask workers")


def stop(proc, grace=30.0):
    """Stops a child run and every process of its group. SIGTERM first: the command closes its
    Dask cluster, so no worker writes a tile after it has exited. A run that does not stop
    within `grace` seconds, and any worker left behind, is killed."""
    proc.terminate()
    try:
        proc.wait(timeout=grace)
    except subprocess.TimeoutExpired:
        pass
    try:
        os.killpg(proc.pid, signal.SIGKILL)
    except (ProcessLookupError, PermissionError):
        pass  # the group is empty: everything has exited
    proc.wait()


class RockHatchingTiled(RockhatchAlgorithm):
    DEM, PARTITION, TILE_SIZE, WORKERS, SCHEDULER = "DEM", "PARTITION", "TILE_SIZE", "WORKERS", "SCHEDULER"
    STYLE, PARAMS, SCALE, SEED, WORKDIR, KEEP_TILES = "STYLE", "PARAMS", "SCALE", "SEED", "WORKDIR", "KEEP_TILES"
    OUTPUT, SVG = "OUTPUT", "SVG"

    def name(self):
        return "rockhatchingtiled"

    def displayName(self):  # noqa: N802
        return "Rock hatching, tiled (Dask)"

    def tags(self):
        return ["hatching", "rock", "tiles", "dask", "distributed", "cluster", "large", "national"]

    def initAlgorithm(self, config=None):  # noqa: N802
        self.add(QgsProcessingParameterRasterLayer(self.DEM, "DEM"),
            "Elevation raster in a projected CRS, read window by window (a GeoTIFF or a VRT mosaic of many "
            "files, e.g. from gdalbuildvrt). A layer that is not a GDAL file is first written to a GeoTIFF.")
        self.add(QgsProcessingParameterFile(self.PARTITION, "Partition (GeoPackage of faces and lines)",
                                            extension="gpkg"),
            "The partition file: rock-face polygons and lines labelled ridge / valley / other, as "
            "'Rock partition from DEM' writes it or as drawn by hand.")
        self.add(QgsProcessingParameterNumber(self.TILE_SIZE, "Tile size (ground units)",
                                              QgsProcessingParameterNumber.Double, 2000, minValue=1),
            "Side of a tile in the DEM's CRS units (metres). Each tile reads its DEM window with a halo and "
            "hatches the faces whose anchor it holds; the result is the same whatever the tile size.")
        self.add(QgsProcessingParameterNumber(self.WORKERS, "Local workers", QgsProcessingParameterNumber.Integer,
                                              1, minValue=1),
            "Worker processes of the local Dask cluster (ignored with a scheduler). Default: 1.")
        self.add(QgsProcessingParameterString(self.SCHEDULER, "Dask scheduler address", optional=True),
            "tcp://HOST:8786 of an existing Dask cluster whose workers can import rockhatch and read the "
            "inputs and the work folder. Default: a local cluster.", advanced=True)
        names, default = self.style_names()
        style_parameter(self, self.STYLE, names, default, f"Built-in style: a rock style, or a terrain style (scree, slope-hachures), tiled as the whole run "
                        f"draws it. Default: {default}.")
        self.add(QgsProcessingParameterString(self.PARAMS, "Style parameters", optional=True),
            "NAME=VALUE separated by ';', lengths in mm on paper at the map scale. Default: the style's values.",
            advanced=True)
        self.add(QgsProcessingParameterNumber(self.SCALE, "Map scale 1:", QgsProcessingParameterNumber.Double,
                                              10000, minValue=100),
            "Scale denominator of the map. Default: 10000.")
        self.add(QgsProcessingParameterNumber(self.SEED, "Random seed", QgsProcessingParameterNumber.Integer, 0,
                                              minValue=0),
            "Seed of the styles' jitter: the same seed gives the same hatches. Default: 0.")
        self.add(QgsProcessingParameterFolderDestination(self.WORKDIR, "Work folder (tiles)", optional=True,
                                                         createByDefault=False),
            "Where the tiles are written before the merge; a run that was cancelled or failed resumes from "
            "the tiles found there. Default: next to the output (OUTPUT.tiles).", advanced=True)
        self.add(QgsProcessingParameterBoolean(self.KEEP_TILES, "Keep the tiles", False),
            "Keep the work folder after the merge. Default: no.", advanced=True)
        self.add(QgsProcessingParameterFileDestination(self.OUTPUT, "Hatches (GeoPackage)", "GeoPackage (*.gpkg)"),
            "The merged hatches, one layer per family with one R-tree each: the same features as one whole "
            "run. An existing file is replaced.")
        self.add(QgsProcessingParameterFileDestination(self.SVG, "Hatches (SVG)", "SVG files (*.svg)", optional=True,
                                                       createByDefault=False),
            "Optional SVG drawn from the merged hatches.")
        self.addOutput(QgsProcessingOutputMultipleLayers("LAYERS", "Hatch layers"))
        self.addOutput(QgsProcessingOutputNumber("TILES", "Tiles"))
        self.addOutput(QgsProcessingOutputNumber("FACES_HATCHED", "Faces hatched"))
        self.addOutput(QgsProcessingOutputNumber("HATCHES", "Hatches"))

    def style_names(self):
        try:
            carto = self.carto()
        except QgsProcessingException:
            return ["rock"], "rock"
        return [s.name for s in carto.styles()], carto.default_style()

    def shortHelpString(self):  # noqa: N802
        return ("Hatches a large area tile by tile on a Dask cluster and merges the tiles (the rockhatch tiles "
                "command): the same hatches as one whole run, whatever the tile size and the number of workers. "
                "A local cluster by default, or an existing one with its scheduler address. The run goes to a "
                "separate Python process (Dask starts worker processes, which it cannot do inside QGIS); "
                "cancelling stops it and keeps the finished tiles in the work folder, so running the same "
                "job again resumes. The partition is a file (extract one with 'Rock partition from DEM'); the "
                "DEM may be geographic (worked in the UTM zone of its centre, as a whole run does); the terrain styles "
                "are tiled too.")

    def command(self, parameters, context, feedback):
        """The `rockhatch tiles` arguments of these parameters."""
        dem = self.raster_path(parameters, self.DEM, context, feedback)
        partition = self.parameterAsFile(parameters, self.PARTITION, context)
        output = self.parameterAsFileOutput(parameters, self.OUTPUT, context)
        svg = self.parameterAsFileOutput(parameters, self.SVG, context)
        argv = ["--dem", dem, "--partition", partition, "-o", output, "--overwrite",
                "--tile-size", repr(self.parameterAsDouble(parameters, self.TILE_SIZE, context)),
                "--style", self.parameterAsEnumString(parameters, self.STYLE, context),
                "--scale", repr(self.parameterAsDouble(parameters, self.SCALE, context)),
                "--seed", str(self.parameterAsInt(parameters, self.SEED, context))]
        if svg:
            argv += ["-o", svg]
        for name, value in parse_params(self.parameterAsString(parameters, self.PARAMS, context)).items():
            argv += ["--param", f"{name}={value!r}"]
        scheduler = self.parameterAsString(parameters, self.SCHEDULER, context)
        if scheduler:
            argv += ["--scheduler", scheduler]
        else:
            argv += ["--workers", str(self.parameterAsInt(parameters, self.WORKERS, context))]
        if parameters.get(self.WORKDIR) not in (None, ""):
            argv += ["--workdir", self.parameterAsString(parameters, self.WORKDIR, context)]
        if self.parameterAsBool(parameters, self.KEEP_TILES, context):
            argv.append("--keep-tiles")
        return argv, output, svg

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        carto = self.carto()
        argv, output, svg = self.command(parameters, context, feedback)
        package = os.path.dirname(os.path.dirname(os.path.abspath(carto.__file__)))
        env = dict(os.environ)
        env["PYTHONPATH"] = os.pathsep.join([package] + [p for p in env.get("PYTHONPATH", "").split(os.pathsep) if p])
        cmd = [system_python(), "-m", "rockhatch", "tiles", *argv]
        feedback.pushInfo("running: " + " ".join(cmd))
        # Its own process group, so that a cancel reaches the Dask workers it starts too.
        proc = subprocess.Popen(cmd, stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                                env=env, start_new_session=True)
        lines = []  # what the run wrote, the bar's redraws apart
        chunks = queue.Queue()

        def pump(stream, sink):
            for chunk in iter(lambda: stream.read1(4096), b""):
                sink.put(chunk)
            sink.put(None)

        readers = [threading.Thread(target=pump, args=(proc.stderr, chunks), daemon=True),
                   threading.Thread(target=proc.stdout.read, daemon=True)]  # nothing expected; never blocks it
        for t in readers:
            t.start()

        def close():
            proc.wait()
            for t in readers:
                t.join(timeout=10)
            proc.stdout.close()
            proc.stderr.close()
        buf, stage = b"", None
        while True:
            try:
                chunk = chunks.get(timeout=0.2)
            except queue.Empty:
                chunk = b""
            if feedback.isCanceled():
                stop(proc)
                close()
                raise QgsProcessingException("cancelled: the finished tiles are kept in the work folder; run the "
                                             "same job again to resume")
            if chunk is None:
                break
            buf += chunk
            parts = re.split(rb"[\r\n]", buf)
            buf = parts.pop()
            for raw in parts:
                text = raw.decode(errors="replace").strip()
                m = _BAR.search(text)
                if m:
                    feedback.setProgress(int(m.group(1)))
                    if m.group(2) != stage:
                        stage = m.group(2)
                        feedback.setProgressText(stage)
                elif text:
                    lines.append(text)
                    feedback.pushInfo(text)
        if buf.strip():
            lines.append(buf.decode(errors="replace").strip())
        close()
        code = proc.returncode
        if code != 0:
            message = next((t for t in reversed(lines) if t.startswith("rockhatch")), lines[-1] if lines else "")
            raise QgsProcessingException(message.replace("rockhatch tiles: ", "", 1) or f"rockhatch tiles exited "
                                                                                          f"with {code}")
        summary = next((m for m in map(_SUMMARY.search, lines) if m), None)
        tiles, faces, hatches = (int(summary.group(1)), int(summary.group(3)), int(summary.group(4))) if summary \
            else (0, 0, 0)
        uris = load_hatch_layers(output, context, self.OUTPUT)
        return {self.OUTPUT: output, self.SVG: svg or None, "LAYERS": uris, "TILES": tiles,
                "FACES_HATCHED": faces, "HATCHES": hatches}
