"""Slope hachures per second: rockhatch's slope-hachures style against Daniel Huffman's QGIS
"Hachure Generator" script (github.com/pinakographos/Hachures), on the same DEM.

Huffman's script is not part of rockhatch: fetch it yourself and give its path with --huffman;
it is run headless (QGIS >= 3.22 Python bindings, QT_QPA_PLATFORM=offscreen) with a stand-in
for the `iface` of the QGIS console, its own parameters left as published.

    /usr/bin/python3 bench/bench_hachures.py --rockhatch build/carto/rockhatch \
        --dem SampleDEM.tif [--huffman "Hachure Generator.py"] [--repeat 3]

Prints, for each tool, the median wall time over --repeat runs, the number of lines, their
total length (ground units) and lines and length per second. rockhatch's lines are the
strokes of one contour band each (Lehmann), Huffman's run across many bands: compare the
length per second as well as the lines per second.
"""
import argparse
import os
import statistics
import subprocess
import sys
import tempfile
import time

from osgeo import ogr


def rockhatch_once(exe, dem, scale, interval, out):
    # Huffman's script draws hachures everywhere: no rock faces here either.
    args = [exe, "--dem", dem, "--partition", "none", "--style", "slope-hachures", "--scale", str(scale),
            "--param", f"interval={interval}", "--threads", "1", "-q", "--overwrite", "-o", out]
    t0 = time.perf_counter()
    r = subprocess.run(args, capture_output=True, text=True)
    seconds = time.perf_counter() - t0
    if r.returncode != 0:
        sys.exit(f"rockhatch failed: {r.stderr.strip()}")
    ds = ogr.Open(out)  # kept open while its layer is read
    layer = ds.GetLayerByName("hatch_hachure")
    n, length = 0, 0.0
    for f in layer:
        n += 1
        # A stroke's length: half the perimeter of its thin ring.
        length += f.GetGeometryRef().Boundary().Length() / 2
    return seconds, n, length


HUFFMAN_DRIVER = r'''
import sys, time
from qgis.core import *
from qgis.core import QgsApplication
app = QgsApplication([], False)
app.initQgis()
sys.path.append("/usr/share/qgis/python/plugins")
from processing.core.Processing import Processing
Processing.initialize()
from qgis import processing
dem = QgsRasterLayer(sys.argv[1], "DEM")
assert dem.isValid(), sys.argv[1]
QgsProject.instance().addMapLayer(dem)

class Bar:
    def pushMessage(self, *a, **k):
        print("message:", *a[:2], file=sys.stderr)

class Iface:
    def activeLayer(self):
        return dem
    def messageBar(self):
        return Bar()

import qgis.utils
qgis.utils.iface = Iface()
with open(sys.argv[2]) as f:
    code = f.read()
env = dict(globals())
env["iface"] = qgis.utils.iface
t0 = time.perf_counter()
exec(compile(code, sys.argv[2], "exec"), env)
seconds = time.perf_counter() - t0
layer = [l for l in QgsProject.instance().mapLayers().values() if l.name() == "Main Hachures"][0]
n = layer.featureCount()
length = sum(f.geometry().length() for f in layer.getFeatures())
print(f"RESULT {seconds} {n} {length}")
'''


def huffman_once(script, dem):
    with tempfile.NamedTemporaryFile("w", suffix=".py", delete=False) as f:
        f.write(HUFFMAN_DRIVER)
        driver = f.name
    env = dict(os.environ, QT_QPA_PLATFORM="offscreen")
    try:
        r = subprocess.run(["/usr/bin/python3", driver, dem, script], capture_output=True, text=True, env=env)
    finally:
        os.unlink(driver)
    for line in r.stdout.splitlines():
        if line.startswith("RESULT "):
            s, n, length = line.split()[1:]
            return float(s), int(n), float(length)
    sys.exit(f"Huffman's script did not finish:\n{r.stderr[-2000:]}")


def report(name, runs):
    seconds = statistics.median(r[0] for r in runs)
    n, length = runs[0][1], runs[0][2]
    print(f"{name:>10}: median {seconds:.2f} s over {len(runs)} runs, {n} lines, {length:.0f} units long: "
          f"{n / seconds:.0f} lines/s, {length / seconds:.0f} units/s")
    return n / seconds, length / seconds


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--rockhatch", required=True)
    ap.add_argument("--dem", required=True)
    ap.add_argument("--huffman", help="path of Huffman's 'Hachure Generator.py' (not shipped)")
    ap.add_argument("--scale", type=float, default=5000)
    ap.add_argument("--interval", type=float, default=5)
    ap.add_argument("--repeat", type=int, default=3)
    a = ap.parse_args()
    with tempfile.TemporaryDirectory() as tmp:
        ours = [rockhatch_once(a.rockhatch, a.dem, a.scale, a.interval, os.path.join(tmp, "h.gpkg"))
                for _ in range(a.repeat)]
    lines_ours, length_ours = report("rockhatch", ours)
    if a.huffman:
        theirs = [huffman_once(a.huffman, a.dem) for _ in range(a.repeat)]
        lines_theirs, length_theirs = report("Huffman", theirs)
        print(f"   ratio: {lines_ours / lines_theirs:.1f}x lines/s, {length_ours / length_theirs:.1f}x length/s")


if __name__ == "__main__":
    main()
