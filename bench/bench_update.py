#!/usr/bin/python3
"""The edit loop measured (docs/edit-loop.md): rockhatch update on a DEM (Chamonix.tif) at
1:10000 with a saved partition, on 2 threads.

    /usr/bin/python3 bench/bench_update.py [--dem DEM] [--scale 10000] [--edits 10] [--qgis 100]

1. the partition (rockhatch partition) and a whole run, timed;
2. one face edited at a time (its middle vertex moved 5 m), then `rockhatch update`: wall
   time, faces redrawn, features removed, written and left as they were;
3. a ridge line moved (its middle vertex, 10 m): the faces redrawn against the faces whose
   reach (tile_context_margin around their box) meets the line before or after;
4. ten rounds of a random face edited, a random feature deleted by hand and an update; then a
   whole run of the final partition: every face never redrawn holds its features as they
   were (less the hand deletions), every redrawn face a whole run's (less the deletions made
   after its last redraw), byte for byte;
5. with --qgis N: N faces edited one after the other in QGIS's edit buffer and re-hatched by
   the plugin's action (edit_loop.EditLoop, as the toolbar button calls it): the median time.
Nothing is written into the repository.
"""
import argparse
import collections
import os
import pathlib
import random
import re
import shutil
import sqlite3
import statistics
import subprocess
import sys
import tempfile
import time

ROOT = pathlib.Path(__file__).resolve().parents[1]
BUILD = pathlib.Path(os.environ.get("RH_BUILD_DIR", ROOT / "build"))
sys.path.insert(0, str(BUILD / "python"))
sys.path.insert(0, str(ROOT / "tests" / "python"))
sys.path.insert(0, str(ROOT / "qgis_plugin"))

from osgeo import ogr  # noqa: E402

from conftest import features_by_face  # noqa: E402

ogr.UseExceptions()
EXE = BUILD / "carto" / "rockhatch"
REPORT = re.compile(r"(\d+) faces, (\d+) redrawn \((\d+) new\), (\d+) removed; features: (\d+) removed, (\d+) written, "
                    r"(\d+) unchanged; ([\d.]+) s")


def move_vertex(path, layer_name, fid, dx, dy):
    """Moves the middle vertex of a face's outer ring (or of a line); returns the box (old
    and new geometry) it touched."""
    ds = ogr.Open(str(path), 1)
    layer = ds.GetLayerByName(layer_name)
    f = layer.GetFeature(fid)
    g = f.GetGeometryRef()
    before = g.GetEnvelope()
    line = g.GetGeometryRef(0) if g.GetGeometryType() in (ogr.wkbPolygon, ogr.wkbMultiPolygon) else g
    if line.GetGeometryType() == ogr.wkbPolygon:
        line = line.GetGeometryRef(0)
    k = line.GetPointCount() // 2
    line.SetPoint_2D(k, line.GetX(k) + dx, line.GetY(k) + dy)
    f.SetGeometry(g)
    layer.SetFeature(f)
    after = g.GetEnvelope()
    ds = None
    return (min(before[0], after[0]), min(before[2], after[2]), max(before[1], after[1]), max(before[3], after[3]))


def update(args):
    t = time.perf_counter()
    r = subprocess.run([str(EXE), "update", *args], capture_output=True, text=True)
    wall = time.perf_counter() - t
    if r.returncode:
        sys.exit(f"rockhatch update failed: {r.stderr}")
    m = REPORT.search(r.stderr)
    return {"wall": wall, "redrawn": int(m[2]), "removed": int(m[5]), "written": int(m[6]), "kept": int(m[7])}


def face_ids(partition):
    ds = ogr.Open(str(partition))
    return sorted(f.GetFID() for f in ds.GetLayerByName("faces"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--dem", default="/work/shared/data/montblanc/Chamonix.tif")
    ap.add_argument("--scale", default="10000")
    ap.add_argument("--threads", default="2")
    ap.add_argument("--edits", type=int, default=10, help="one-face edits timed")
    ap.add_argument("--qgis", type=int, default=0, help="faces edited through the QGIS action")
    ap.add_argument("--work", help="folder for the files (default: a temporary one, removed)")
    ap.add_argument("--reuse", action="store_true", help="keep the partition and hatches of --work (skip 1 and 2)")
    a = ap.parse_args()
    if not pathlib.Path(a.dem).exists():
        sys.exit(f"bench_update: {a.dem} is absent")
    work = pathlib.Path(a.work or tempfile.mkdtemp(prefix="rh_bench_update_"))
    work.mkdir(parents=True, exist_ok=True)
    part, out = work / "partition.gpkg", work / "h.gpkg"
    run_args = ["-q", "--threads", a.threads, "--dem", a.dem, "--partition", str(part), "--scale", a.scale]
    if not a.reuse:
        subprocess.run([str(EXE), "partition", "-q", "--overwrite", "--dem", a.dem, "--scale", a.scale, "-o",
                        str(part)], check=True)
        t = time.perf_counter()
        r = subprocess.run([str(EXE), *run_args, "--overwrite", "-o", str(out)], check=True, capture_output=True,
                           text=True)
        whole_seconds = time.perf_counter() - t
        print(f"whole run: {whole_seconds:.2f} s wall ({r.stderr.strip()}); {out.stat().st_size / 1e6:.0f} MB")
    ids = face_ids(part)
    upd = [*run_args, "-o", str(out)]

    # 2. One face at a time.
    rows = []
    for fid in ([] if a.reuse else ids[:: max(1, len(ids) // a.edits)][: a.edits]):
        move_vertex(part, "faces", fid, 5.0, 5.0)
        row = update(upd)
        row["face"] = fid
        rows.append(row)
        print(f"face {fid}: {row['wall']:.2f} s, {row['redrawn']} faces redrawn, features {row['removed']} removed, "
              f"{row['written']} written, {row['kept']} unchanged")
    walls = sorted(r["wall"] for r in rows)
    if rows:
        print(f"one face edited ({len(rows)} faces): median {statistics.median(walls):.2f} s, "
              f"min {walls[0]:.2f} s, max {walls[-1]:.2f} s; faces redrawn median "
              f"{statistics.median(r['redrawn'] for r in rows)}, features rewritten median "
              f"{statistics.median(r['removed'] + r['written'] for r in rows)}")

    # 3. A ridge line moved.
    from rockhatch import carto
    ds = ogr.Open(str(part))  # held: a layer does not keep its dataset alive
    ridges = [f.GetFID() for f in ds.GetLayerByName("lines")
              if f.GetField("kind") == "ridge" and f.GetGeometryRef().GetPointCount() > 4]
    ds = None
    ridge = ridges[len(ridges) // 2]
    box = move_vertex(part, "lines", ridge, 10.0, 0.0)
    options = carto.make_options(a.dem, part, [out], scale=float(a.scale), threads=int(a.threads), overwrite=True)
    plan = carto.make_plan(options)
    gt = carto.working_grid(carto.raster_info(a.dem)).grid.geotransform
    margin = carto.tile_context_margin(plan, min(abs(gt[1]), abs(gt[5])))
    reached = set()
    ds = ogr.Open(str(part))
    for f in ds.GetLayerByName("faces"):
        x0, x1, y0, y1 = f.GetGeometryRef().GetEnvelope()
        if x0 - margin <= box[2] and box[0] <= x1 + margin and y0 - margin <= box[3] and box[1] <= y1 + margin:
            reached.add(f.GetFID())
    ds = None
    t = time.perf_counter()
    rep = carto.update_options(options)
    seconds = time.perf_counter() - t
    redrawn = set(rep.redrawn_ids)
    print(f"ridge line {ridge} moved: {len(redrawn)} faces redrawn in {seconds:.2f} s; faces whose reach "
          f"({margin:.0f} m) meets the line: {len(reached)}; redrawn and not reached: {sorted(redrawn - reached)}; "
          f"reached and not redrawn: {sorted(reached - redrawn)}")

    # 4. Random edits and hand deletions, then a whole run.
    rng = random.Random(41)
    base = features_by_face(out)
    state = {face: ("before", []) for face in base}  # the base of each face's features, and rows deleted since
    for k in range(10):
        move_vertex(part, "faces", rng.choice(ids), rng.uniform(-8, 8), rng.uniform(-8, 8))
        ds = ogr.Open(str(out), 1)
        fill = ds.GetLayerByName("hatch_fill")
        face = rng.choice(sorted(base))
        fill.SetAttributeFilter(f"face_id = {face}")
        fids = [f.GetFID() for f in fill]
        if fids:
            fid = rng.choice(fids)
            con = sqlite3.connect(str(out))
            row = con.execute("SELECT family, style, width_mm, geom FROM hatch_fill WHERE fid = ?", (fid,)).fetchone()
            con.close()
            fill.DeleteFeature(fid)
            state.setdefault(face, ("before", []))[1].append(("hatch_fill",) + row)
        ds = None
        report = carto.update_options(options)
        for face in report.redrawn_ids:
            state[face] = ("whole", [])
    whole = work / "whole.gpkg"
    subprocess.run([str(EXE), *run_args, "--overwrite", "-o", str(whole)], check=True, capture_output=True)
    final, full = features_by_face(out), features_by_face(whole)
    bad = []
    for face, (source, deleted) in state.items():
        rows = collections.Counter((base if source == "before" else full).get(face, []))
        rows.subtract(collections.Counter(deleted))
        if sorted(rows.elements()) != final.get(face, []):
            bad.append(face)
    redrawn_faces = sum(1 for s in state.values() if s[0] == "whole")
    print(f"10 random edits and hand deletions: {redrawn_faces} faces redrawn at least once, "
          f"{len(state) - redrawn_faces} never; faces whose features differ from the expected bytes: {bad or 'none'}")

    # 5. The QGIS action.
    if a.qgis:
        qgis_edits(part, out, ids, a.qgis)
    if not a.work:
        shutil.rmtree(work)


def qgis_edits(part, out, ids, n):
    os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
    from qgis.core import QgsApplication, QgsProject, QgsVectorLayer
    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], False)
    app.initQgis()
    from rockhatch_qgis.edit_loop import EditLoop
    project = QgsProject.instance()
    faces = QgsVectorLayer(f"{part}|layername=faces", "faces", "ogr")
    project.addMapLayer(faces)
    ds = ogr.Open(str(out))
    names = [ds.GetLayer(i).GetName() for i in range(ds.GetLayerCount()) if ds.GetLayer(i).GetName().startswith("hatch_")]
    ds = None
    project.addMapLayers([QgsVectorLayer(f"{out}|layername={name}", name, "ogr") for name in names])
    loop = EditLoop(project)
    times, redrawn = [], []
    for fid in ids[:: max(1, len(ids) // n)][:n]:
        faces.startEditing()
        geom = faces.getFeature(fid).geometry()
        ring = geom.asPolygon()[0] if not geom.isMultipart() else geom.asMultiPolygon()[0][0]
        k = len(ring) // 2
        geom.moveVertex(ring[k].x() + 4, ring[k].y() - 4, k)
        faces.changeGeometry(fid, geom)
        t = time.perf_counter()
        reports = loop.rehatch(faces)
        times.append(time.perf_counter() - t)
        redrawn.append(sum(r.redrawn for r in reports.values()))
    times.sort()
    print(f"QGIS action, {len(times)} faces edited one after the other: median {statistics.median(times):.2f} s per "
          f"edit (min {times[0]:.2f}, max {times[-1]:.2f}); faces redrawn per edit: median "
          f"{statistics.median(redrawn)}")
    project.removeAllMapLayers()
    app.exitQgis()


if __name__ == "__main__":
    main()
