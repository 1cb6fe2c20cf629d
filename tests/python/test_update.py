"""rockhatch update from the command line and from Python (carto.update): the redrawn faces
hold the bytes of a whole run, every other feature stays, the GeoPackage passes GDAL's
validator, the SVG beside it is drawn again from the layers, and an update killed while it
writes leaves the file as it was."""
import shutil
import sqlite3
import subprocess
import sys

import pytest
from osgeo import ogr

from conftest import features_by_face

VALIDATOR = "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py"


def fingerprints(gpkg):
    con = sqlite3.connect(str(gpkg))
    try:
        return dict(con.execute("SELECT face_id, fingerprint FROM rockhatch_faces"))
    finally:
        con.close()


def valid(gpkg):
    r = subprocess.run([sys.executable, VALIDATOR, str(gpkg)], capture_output=True, text=True)
    return r.returncode == 0 and not r.stdout.strip() and not r.stderr.strip()


def move_vertex(partition, fid, dx, dy):
    ds = ogr.Open(str(partition), 1)
    layer = ds.GetLayerByName("faces")
    f = layer.GetFeature(fid)
    g = f.GetGeometryRef()
    ring = g.GetGeometryRef(0)
    k = ring.GetPointCount() // 2
    ring.SetPoint_2D(k, ring.GetX(k) + dx, ring.GetY(k) + dy)
    f.SetGeometry(g)
    layer.SetFeature(f)
    ds = None


@pytest.fixture
def edited(rockhatch_exe, sample_dir, tmp_path):
    """A run on a copy of the sample's partition, then one face of it moved."""
    part = tmp_path / "partition.gpkg"
    shutil.copy(sample_dir / "partition.gpkg", part)
    args = ["-q", "--dem", str(sample_dir / "dem.tif"), "--partition", str(part)]
    out = tmp_path / "h.gpkg"
    subprocess.run([str(rockhatch_exe), *args, "-o", str(out), "-o", str(tmp_path / "h.svg")], check=True)
    before = features_by_face(out)
    move_vertex(part, 12, 8.0, 6.0)
    whole = tmp_path / "whole.gpkg"
    subprocess.run([str(rockhatch_exe), *args, "-o", str(whole)], check=True)
    return {"args": args, "out": out, "before": before, "whole": whole, "part": part}


def test_command_redraws_the_changed_faces_with_a_whole_runs_bytes(rockhatch_exe, edited, tmp_path):
    out, before = edited["out"], edited["before"]
    # A hand edit in a face the edit does not reach: one feature deleted.
    changed = {f for f, fp in fingerprints(edited["whole"]).items() if fingerprints(out)[f] != fp}
    assert 12 in changed and len(changed) < 20
    kept = min(set(before) - changed)
    con = sqlite3.connect(str(out))
    con.execute("DELETE FROM hatch_fill WHERE fid = (SELECT min(fid) FROM hatch_fill WHERE face_id = ?)", (kept,))
    con.commit()
    con.close()
    hand = features_by_face(out)
    r = subprocess.run([str(rockhatch_exe), "update", *edited["args"], "-o", str(out), "-o", str(tmp_path / "h.svg")],
                       capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    assert f"20 faces, {len(changed)} redrawn (0 new), 0 removed" in r.stderr
    after, full = features_by_face(out), features_by_face(edited["whole"])
    for face in full:
        assert after[face] == (full[face] if face in changed else hand[face]), face
    assert len(after[kept]) == len(full[kept]) - 1
    assert fingerprints(out) == fingerprints(edited["whole"])
    assert valid(out)
    # The SVG drawn again from the updated layers.
    from rockhatch import carto
    carto.write_svg(carto.read_gpkg(str(out), 10000), str(tmp_path / "again.svg"))
    assert (tmp_path / "h.svg").read_bytes() == (tmp_path / "again.svg").read_bytes()
    # Nothing more to do.
    r = subprocess.run([str(rockhatch_exe), "update", *edited["args"], "-o", str(out)], capture_output=True, text=True)
    assert "0 redrawn" in r.stderr and features_by_face(out) == after
    # --reset: a whole run's features, the hand edit gone.
    r = subprocess.run([str(rockhatch_exe), "update", "--reset", *edited["args"], "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "20 redrawn" in r.stderr
    assert features_by_face(out) == full and valid(out)


def test_python_update_takes_runs_arguments(sample_dir, edited):
    from rockhatch import carto
    report = carto.update(sample_dir / "dem.tif", edited["part"], [edited["out"]])
    assert report.faces == 20 and 12 in report.redrawn_ids and report.removed == 0
    assert report.written + report.kept > 0
    assert features_by_face(edited["out"]) == features_by_face(edited["whole"])
    with pytest.raises(carto.RockhatchError, match="style rock"):
        carto.update(sample_dir / "dem.tif", edited["part"], [edited["out"]], style="noisy")


KILL = """
import os, sys, threading, time
from rockhatch import carto
def progress(fraction, stage):
    if stage == "writing":
        threading.Thread(target=lambda: (time.sleep(float(sys.argv[4])), os._exit(3)), daemon=True).start()
    return True
carto.update(sys.argv[1], sys.argv[2], [sys.argv[3]], progress=progress, reset=True)
"""


def test_an_update_killed_while_writing_leaves_the_file_as_it_was(sample_dir, edited, tmp_path):
    from conftest import python_env
    out = edited["out"]
    before = features_by_face(out)
    prints = fingerprints(out)
    r = subprocess.run([sys.executable, "-c", KILL, str(sample_dir / "dem.tif"), str(edited["part"]), str(out), "0.3"],
                       env=python_env(), capture_output=True, text=True, timeout=300)
    assert r.returncode == 3, r.stderr  # killed, mid-transaction: SQLite's journal is left beside the file
    assert (tmp_path / "h.gpkg-journal").exists() or (tmp_path / "h.gpkg-wal").exists()
    assert features_by_face(out) == before  # rolled back when next opened
    assert fingerprints(out) == prints
    assert valid(out)


def test_a_moved_ridge_line_redraws_exactly_the_faces_it_reaches(rockhatch_exe, sample_dir, tmp_path):
    from rockhatch import carto
    part = tmp_path / "partition.gpkg"
    shutil.copy(sample_dir / "partition.gpkg", part)
    out = tmp_path / "h.gpkg"
    carto.run(sample_dir / "dem.tif", part, [out])
    # The middle vertex of ridge line 3 moved 12 m: its two segments before and after.
    ds = ogr.Open(str(part), 1)
    lines = ds.GetLayerByName("lines")
    f = lines.GetFeature(3)
    assert f.GetField("kind") == "ridge"
    g = f.GetGeometryRef()
    k = g.GetPointCount() // 2
    moved = [(g.GetX(i), g.GetY(i)) for i in (k - 1, k, k + 1)]
    g.SetPoint_2D(k, g.GetX(k) + 12.0, g.GetY(k))
    moved.append((g.GetX(k), g.GetY(k)))
    f.SetGeometry(g)
    lines.SetFeature(f)
    ds = None
    plan = carto.make_plan(carto.make_options(sample_dir / "dem.tif", part, [out], overwrite=True))
    gt = carto.working_grid(carto.raster_info(str(sample_dir / "dem.tif"))).grid.geotransform
    margin = carto.tile_context_margin(plan, min(abs(gt[1]), abs(gt[5])))
    xs, ys = [p[0] for p in moved], [p[1] for p in moved]
    reached = set()
    ds = ogr.Open(str(part))
    for face in ds.GetLayerByName("faces"):
        x0, x1, y0, y1 = face.GetGeometryRef().GetEnvelope()
        if x0 - margin <= max(xs) and min(xs) <= x1 + margin and y0 - margin <= max(ys) and min(ys) <= y1 + margin:
            reached.add(face.GetFID())
    ds = None
    report = carto.update(sample_dir / "dem.tif", part, [out])
    assert set(report.redrawn_ids) == reached and 0 < len(reached) < 20
    assert fingerprints(out) == fingerprints_of_a_run(sample_dir, part, tmp_path)


def fingerprints_of_a_run(sample_dir, part, tmp_path):
    from rockhatch import carto
    carto.run(sample_dir / "dem.tif", part, [tmp_path / "whole.gpkg"], overwrite=True)
    return fingerprints(tmp_path / "whole.gpkg")


@pytest.mark.parametrize("key, value, words", [("RH_RUN_VERSION", "0.0.9", "program version 0.0.9"),
                                               ("RH_RUN_CRS", "EPSG:32632", "CRS EPSG:32632")])
def test_another_version_or_crs_is_refused_unless_reset(rockhatch_exe, sample_dir, tmp_path, key, value, words):
    out = tmp_path / "h.gpkg"
    args = ["-q", "--dem", str(sample_dir / "dem.tif"), "--partition", str(sample_dir / "partition.gpkg")]
    subprocess.run([str(rockhatch_exe), *args, "-o", str(out)], check=True)
    ds = ogr.Open(str(out), 1)
    ds.SetMetadataItem(key, value)
    ds = None
    before = out.read_bytes()
    r = subprocess.run([str(rockhatch_exe), "update", *args, "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 2 and words in r.stderr and "--reset" in r.stderr, r.stderr
    assert out.read_bytes() == before
    r = subprocess.run([str(rockhatch_exe), "update", "--reset", *args, "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0 and "20 redrawn" in r.stderr, r.stderr
    assert ogr.Open(str(out)).GetMetadataItem(key) != value and valid(out)


def test_update_with_a_style_script(rockhatch_exe, sample_dir, tmp_path):
    """--script: the command hands over to Python (python3 -m rockhatch update), which updates
    with the script's style; the script's bytes are part of the fingerprints."""
    from conftest import STYLES
    script = tmp_path / "noisy.py"
    shutil.copy(STYLES / "noisy.py", script)
    args = ["-q", "--script", str(script), "--dem", str(sample_dir / "dem.tif"), "--partition",
            str(sample_dir / "partition.gpkg")]
    out = tmp_path / "s.gpkg"
    subprocess.run([str(rockhatch_exe), *args, "-o", str(out)], check=True, capture_output=True)
    before = features_by_face(out)
    r = subprocess.run([str(rockhatch_exe), "update", *args, "--face", "3", "-o", str(out)],
                       capture_output=True, text=True)
    assert r.returncode == 0 and "20 faces, 1 redrawn" in r.stderr, r.stderr
    assert features_by_face(out) == before
    # An edit of the script (a comment) changes every fingerprint: every face is redrawn.
    script.write_text(script.read_text() + "\n# edited\n")
    r = subprocess.run([str(rockhatch_exe), "update", *args, "-o", str(out)], capture_output=True, text=True)
    assert r.returncode == 0 and "20 faces, 20 redrawn" in r.stderr, r.stderr
    assert features_by_face(out) == before


STYLE_A = '''
from rockhatch.carto import StyleInfo, python_style
from rockhatch.tex import Constant, Curves, Polyline

def draw(fields, params):
    return Constant(Polyline([(0, 0), (1, 1)]))

STYLE = python_style(StyleInfo("mine", "", "a style given as a function", []), draw)
'''


def test_a_python_function_style_is_fingerprinted_by_its_source(sample_dir, tmp_path):
    """A style given as a Python object (python_style) is part of the fingerprints by its
    module's source: an unchanged style redraws nothing, an edited one every face."""
    import importlib.util
    from rockhatch import carto

    def load(text, name):
        path = tmp_path / f"{name}.py"
        path.write_text(text)
        spec = importlib.util.spec_from_file_location(name, path)
        module = importlib.util.module_from_spec(spec)
        spec.loader.exec_module(module)
        return module.STYLE

    out = tmp_path / "f.gpkg"
    args = (sample_dir / "dem.tif", sample_dir / "partition.gpkg", [out])
    carto.run(*args, style=load(STYLE_A, "style_a"))
    assert carto.update(*args, style=load(STYLE_A, "style_a_again")).redrawn_ids == []
    edited = STYLE_A.replace("(1, 1)", "(2, 1)")
    report = carto.update(*args, style=load(edited, "style_b"))
    assert len(report.redrawn_ids) == report.faces == 20
