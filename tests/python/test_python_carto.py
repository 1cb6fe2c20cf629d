"""rockhatch.carto: rasters as numpy arrays with NoData, geotransform and CRS; control
fields from numpy, rasters and callables; the pipeline from Python, with progress,
cancellation, Python styles and their errors."""
import math
import subprocess
import sys
import traceback

import numpy as np
import pytest
from osgeo import ogr

import rockhatch
from rockhatch import carto, tex
from conftest import SAMPLE_SW_QUARTER
from rockhatch.tex import (CROP, KEEP_OUTSIDE, Arrangement, Crop, GridPartition, HasLabel, Inside, JitterEdges,
                           MapToEdges, MapToFaces, Nothing, Outline, Point, Region, SetEdgeLabels, StripesPartition,
                           StripesProperties, ToCurve, pi)

GT = [1000.0, 5.0, 0.0, 2000.0, 0.0, -5.0]


def test_numpy_round_trip_with_nodata():
    a = np.arange(12, dtype=np.float64).reshape(3, 4)
    a[1, 2] = -9999
    r = carto.Raster.from_array(a, GT, "EPSG:2154", nodata=-9999)
    assert (r.width, r.height) == (4, 3)
    assert r.geotransform == GT
    assert r.crs_name == "EPSG:2154"
    view = r.array
    assert view.dtype == np.float32 and view.shape == (3, 4)
    assert math.isnan(view[1, 2]) and np.isnan(view).sum() == 1
    np.testing.assert_array_equal(r.to_array(nodata=-9999), a)
    # The view shares the raster's memory.
    view[0, 0] = 42
    assert r.nearest(Point(1002.5, 1997.5)) == 42


def test_geotiff_round_trip(tmp_path):
    a = np.random.default_rng(1).normal(1000, 50, (20, 30)).astype(np.float32)
    a[3, 4] = np.nan
    r = carto.Raster.from_array(a, GT, "EPSG:32632")
    path = str(tmp_path / "r.tif")
    carto.write_geotiff(r, path)
    back = carto.read_raster(path)
    assert back.geotransform == GT and carto.same_crs(back.crs, r.crs)
    np.testing.assert_array_equal(np.isnan(back.array), np.isnan(a))
    np.testing.assert_allclose(np.nan_to_num(back.array), np.nan_to_num(a))


def test_terrain_fields_are_numpy_arrays_with_nodata():
    # A plane rising 1 m per metre eastwards: slope 100 %, downhill to the west.
    x = np.arange(40) * 5.0
    a = np.tile(x, (30, 1))
    a[10, 10] = np.nan
    t = carto.compute_terrain(carto.Raster.from_array(a, GT, "EPSG:2154"))
    slope, aspect = t.slope.array, t.aspect.array
    assert slope.shape == (30, 40) and t.slope.geotransform == GT and t.slope.crs_name == "EPSG:2154"
    assert math.isnan(slope[10, 10]) and np.isnan(slope).sum() == 1
    ok = ~np.isnan(slope)
    np.testing.assert_allclose(slope[ok], 100.0, rtol=1e-5)
    np.testing.assert_allclose(np.abs(aspect[ok]), math.pi, atol=1e-5)
    assert np.nanmax(t.roughness.array) < 1e-6
    assert 0 <= np.nanmin(t.hillshade.array) <= np.nanmax(t.hillshade.array) <= 1


def test_fields_from_numpy_rasters_numbers_and_callables():
    a = np.array([[1.0, 2.0], [3.0, -1.0]])
    f = carto.Field.from_array(a, GT, nodata=-1)
    assert f(Point(1002.5, 1997.5)) == 1.0 and f(1007.5, 1992.5) != f(1007.5, 1992.5)  # NaN at NoData
    assert f.kind == "raster"
    r = carto.Raster.from_array(a, GT)
    assert carto.Field(r)(1002.5, 1992.5) == 3.0
    assert carto.Field.from_raster(r, offset=1, range=2)(1002.5, 1992.5) == 1.0
    assert carto.Field(0.25)(0, 0) == 0.25
    g = carto.Field(lambda p: p.x + 2 * p.y)
    assert g(Point(1, 2)) == 5 and g.kind == "python"
    xs, ys = np.array([0.0, 1.0, 2.0]), np.array([1.0, 1.0, 1.0])
    np.testing.assert_array_equal(g.sample(xs, ys), [2, 3, 4])
    fields = carto.ControlFields(orientation=0.5, density=g, height=r, roughness=f)
    assert fields.orientation(Point(0, 0)) == 0.5 and fields.density(Point(1, 1)) == 3
    with pytest.raises(TypeError, match="a field is"):
        carto.Field("steep")
    with pytest.raises(ValueError, match="2-D"):
        carto.Raster.from_array(np.zeros(3), GT)


def test_run_from_python_equals_the_command(rockhatch_exe, sample_dir, tmp_path):
    cli = tmp_path / "cli.gpkg"
    r = subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition",
                        str(sample_dir / "partition.gpkg"), "--style", "balanced", "--seed", "3", "-o", str(cli)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    stages = []

    def progress(fraction, stage):
        stages.append((fraction, stage))

    py = tmp_path / "py.gpkg"
    stats = carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [py], style="balanced", seed=3,
                      progress=progress)
    assert py.read_bytes() == cli.read_bytes()
    assert stats.faces == 20 and stats.hatches > 1000 and stats.crs == "EPSG:2154"
    fractions = [f for f, _ in stages]
    assert fractions == sorted(fractions) and fractions[-1] == 1.0
    assert {"reading the DEM", "hatching", "writing", "done"} <= {s for _, s in stages}


def test_a_window_from_python_is_the_commands_window(rockhatch_exe, sample_dir, tmp_path):
    # Regression: window= raised NameError (make_options named BBox, which carto does not
    # export). The south-west quarter of the sample, as a tuple and as a tex.BBox, gives the
    # bytes of `rockhatch --window`, and fewer hatches than the whole run.
    box = SAMPLE_SW_QUARTER
    cli = tmp_path / "cli.svg"
    r = subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition",
                        str(sample_dir / "partition.gpkg"), "--window", ",".join(map(str, box)), "-o", str(cli)],
                       capture_output=True, text=True, timeout=300)
    assert r.returncode == 0, r.stderr
    for name, window in (("tuple", box), ("bbox", tex.BBox(*box))):
        stats = carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / f"{name}.svg"],
                          window=window)
        assert (tmp_path / f"{name}.svg").read_bytes() == cli.read_bytes(), name
        assert 1000 < stats.hatches < 60000, stats.hatches


def test_cancelling_from_the_progress_callback(sample_dir, tmp_path):
    out = tmp_path / "never.svg"
    with pytest.raises(rockhatch.RockhatchError, match="cancelled during hatching") as e:
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [out],
                  progress=lambda f, stage: stage != "hatching")
    assert e.value.code == 10
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_pipeline_errors_carry_the_exit_code(sample_dir, tmp_path):
    with pytest.raises(rockhatch.RockhatchError, match="--dem 'missing.tif'") as e:
        carto.run("missing.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"])
    assert e.value.code == 3
    with pytest.raises(rockhatch.RockhatchError, match="unknown style 'nope'") as e:
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"], style="nope")
    assert e.value.code == 7
    with pytest.raises(TypeError, match="unknown option 'colour'"):
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"], colour="red")


def test_prepare_hatch_write_in_steps(sample_dir, tmp_path):
    prepared = carto.prepare(sample_dir / "dem.tif", sample_dir / "partition.gpkg")
    assert len(prepared.partition.faces) == 20
    dem = prepared.terrain.elevation
    assert dem.array.shape == (dem.height, dem.width)
    drawing = carto.hatch(prepared, style="noisy")
    assert drawing.style == "noisy" and len(drawing.faces) == 20 and drawing.hatch_count() > 500
    carto.write_svg(drawing, str(tmp_path / "d.svg"))
    assert (tmp_path / "d.svg").stat().st_size > 10000


def stripes_style(fields, params):
    """A minimal Python style: horizontal hatches cut to the face, broken every five
    spacings (one arrangement for every face)."""
    hatch_lines = StripesProperties(0.0, params["spacing"])
    SetEdgeLabels(hatch_lines, "fill")
    grid = GridPartition(hatch_lines, StripesProperties(pi / 2, 5 * params["spacing"]), KEEP_OUTSIDE)
    return Crop(MapToEdges(lambda e: ToCurve(e) if HasLabel(e, "fill") else Nothing(), grid), CROP)


def make_style(fn, name="test-stripes"):
    return carto.python_style(carto.StyleInfo(name, "", "test", [carto.StyleParam("spacing", 1.0, "mm")]), fn)


def test_a_python_style_on_any_thread_count(sample_dir, tmp_path):
    outs = []
    for threads in (1, 2):
        out = tmp_path / f"t{threads}.svg"
        s = carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [out], style=make_style(stripes_style),
                      threads=threads)
        assert s.hatches > 100
        outs.append(out.read_bytes())
    assert outs[0] == outs[1]
    with pytest.raises(rockhatch.RockhatchError, match="has no parameter 'gap'"):
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"],
                  style=make_style(stripes_style), params={"gap": 1})


def test_errors_inside_a_python_style(sample_dir, tmp_path):
    # An exception raised while a face is drawn stops the run; the pipeline reports it with
    # the style, the face, the Python exception and its traceback (where it was raised).
    drawn = []

    def failing_style(fields, params):
        def face_fn(region):
            drawn.append(region.area())
            if len(drawn) == 8:
                raise ZeroDivisionError("face 8 is cursed")
            return Nothing()

        return Arrangement(face_fn)

    with pytest.raises(rockhatch.RockhatchError,
                       match=r"style 'test-stripes', face \d+: ZeroDivisionError: face 8 is cursed") as e:
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"],
                  style=make_style(failing_style), threads=2)
    assert "face_fn" in str(e.value) and e.value.code == 1
    assert not (tmp_path / "x.svg").exists()

    def failing_mapper(fields, params):
        def cell_fn(cell):
            raise KeyError("no such cell")

        return MapToFaces(cell_fn, StripesPartition(StripesProperties(0.0, params["spacing"])))

    with pytest.raises(rockhatch.RockhatchError, match="KeyError: 'no such cell'") as e:
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"],
                  style=make_style(failing_mapper), threads=2)
    assert "cell_fn" in str(e.value)

    with pytest.raises(rockhatch.RockhatchError, match="Arrangement: the function returned str, not Curves"):
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"],
                  style=make_style(lambda fields, params: Arrangement(lambda region: "hatches")))

    with pytest.raises(rockhatch.RockhatchError, match="MapToEdges: the mapper returned int"):
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"],
                  style=make_style(lambda fields, params: MapToEdges(lambda e: 1, Outline())))

    with pytest.raises(TypeError, match="style 'test-stripes': it returned int; a style returns the arrangement"):
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"],
                  style=make_style(lambda fields, params: 42))
    assert not (tmp_path / "x.svg").exists()


def test_faces_and_controls_seen_by_a_python_style(sample_dir, tmp_path):
    """A style sees each face as a region whose border edges carry their kind (ridge,
    valley, other) and "owned" where this face draws what lies on a shared border; the
    fields read inside it are in range."""
    seen = []

    def probe(fields, params):
        def face_fn(region):
            inside = carto.interior_point(region)
            assert region.has_edges() and region.contains(inside)
            edges = Outline()(region).curves
            kinds = [[k for k in ("ridge", "valley", "other") if k in e.labels] for e in edges]
            assert all(len(k) == 1 for k in kinds), kinds
            seen.append((fields.orientation(inside), fields.density(inside), fields.height(inside),
                         sum(k == ["ridge"] for k in kinds), sum("owned" in e.labels for e in edges), len(edges)))
            return Nothing()

        return Arrangement(face_fn)

    carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"], style=make_style(probe))
    assert len(seen) == 20
    assert all(not math.isnan(o) and 0 <= d <= 1 and 0 <= h <= 1 for o, d, h, *_ in seen)
    assert sum(r for *_, r, _, _ in seen) > 0, "some faces border ridges"
    # A border shared by two faces is owned by one of them: some edges are not owned.
    assert 0 < sum(o for *_, o, _ in seen) < sum(n for *_, n in seen)


def test_a_style_built_from_libtex_operators(sample_dir, tmp_path):
    """bindings/examples/appendix_e_noisy.py: grid partition, jitter mapper and Inside merge,
    controlled by the face's fields, as in the thesis's Appendix E."""
    from conftest import ROOT

    script = str(ROOT / "bindings" / "examples" / "appendix_e_noisy.py")
    prepared = carto.prepare(sample_dir / "dem.tif", sample_dir / "partition.gpkg")
    drawings = [carto.hatch(prepared, style=script, threads=t, seed=4) for t in (1, 2)]
    assert drawings[0].hatch_count() > 5000
    # The same faces, in the same order (zip alone would stop at the shorter list).
    assert [f.face_id for f in drawings[0].faces] == [f.face_id for f in drawings[1].faces]
    for a, b in zip(drawings[0].faces, drawings[1].faces):
        assert a.face_id == b.face_id and list(a.hatches) == list(b.hatches)
    # The engine's stock mapper makes the same calls to Random natively: the same hatches.
    example = carto.load_style(script)
    module = sys.modules["rockhatch_style_appendix_e_noisy"]

    def native(fields, params):
        def arrangement(region):
            angle, density = module.face_controls(fields, region)
            spacing = params["spacing_min"] + (params["spacing_max"] - params["spacing_min"]) * (1 - density)
            hatch_lines = StripesProperties(angle, spacing)
            SetEdgeLabels(hatch_lines, "hatches")
            grid = GridPartition(hatch_lines, StripesProperties(angle + pi / 2, params["length"]), KEEP_OUTSIDE)
            jitter = JitterEdges("hatches", angle, spacing, params["length"], params["jitter"])
            return Inside(MapToEdges(jitter, grid), Outline(), CROP)(region)

        return Arrangement(arrangement)

    stock = carto.hatch(prepared, style=carto.python_style(example.info, native), threads=2, seed=4)
    assert [f.face_id for f in stock.faces] == [f.face_id for f in drawings[0].faces]
    for a, b in zip(drawings[0].faces, stock.faces):
        assert a.face_id == b.face_id and list(a.hatches) == list(b.hatches)
    # Cut with CROP: every stroke lies in its face (holes included), to rounding.
    faces = {f.id: f for f in prepared.partition.faces}
    for fh in drawings[0].faces:
        region = faces[fh.face_id].region
        face = ogr.Geometry(ogr.wkbPolygon)
        for ring_points in [region.outer, *region.holes]:
            ring = ogr.Geometry(ogr.wkbLinearRing)
            for q in [*ring_points, ring_points[0]]:
                ring.AddPoint_2D(q.x, q.y)
            face.AddGeometry(ring)
        tolerant = face.Buffer(1e-6)
        for h in fh.hatches:
            line = ogr.Geometry(ogr.wkbLineString)
            for q in h.points:
                line.AddPoint_2D(q.x, q.y)
            assert line.Within(tolerant), (fh.face_id, line.ExportToWkt()[:200])


def test_cancelling_while_the_geopackage_is_written(sample_dir, tmp_path):
    drawing = carto.hatch(carto.prepare(sample_dir / "dem.tif", sample_dir / "partition.gpkg"))
    calls = []
    with pytest.raises(rockhatch.RockhatchError, match="cancelled while writing") as e:
        carto.write_gpkg(drawing, str(tmp_path / "w.gpkg"), progress=lambda f, s: calls.append(f) or len(calls) < 3)
    assert e.value.code == 10 and len(calls) == 3 and calls == sorted(calls)
    assert list(tmp_path.iterdir()) == []


def test_an_exception_in_the_progress_callback_stops_the_run(sample_dir, tmp_path):
    def progress(fraction, stage):
        if stage == "hatching":
            raise ValueError("stop here")

    with pytest.raises(ValueError, match="stop here"):
        carto.run(sample_dir / "dem.tif", sample_dir / "partition.gpkg", [tmp_path / "x.svg"], progress=progress,
                  threads=2)
    assert list(tmp_path.iterdir()) == []
