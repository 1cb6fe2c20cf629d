"""The QGIS plugin (qgis_plugin/rockhatch_qgis) in a real headless QGIS from Debian's packages:
plugin loading, the provider's algorithms through processing.run, errors, cancellation, and
qgis_process on the command line with a throwaway profile."""
import json
import pathlib
import os
import shutil
import subprocess
import sys
import time
import zipfile

import pytest

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
# QGIS computes raster statistics: keep them out of data/ (no dem.tif.aux.xml).
os.environ["GDAL_PAM_ENABLED"] = "NO"
import qgis.core as qgis_core  # noqa: E402  (python3-qgis: scripts/setup.sh installs it)

from conftest import (PYTHON_DIR, ROOT, SANITIZED, features_by_face, finished_tiles, land_cover,  # noqa: E402
                      partition_with_scree, python_env)
from osgeo import gdal, ogr  # noqa: E402

from qgis.core import (QgsApplication, QgsProcessingException, QgsProcessingFeedback, QgsProject,  # noqa: E402
                       QgsRasterLayer, QgsVectorLayer)

PLUGINS = ROOT / "qgis_plugin"
QGIS_PROCESS = "/usr/bin/qgis_process.bin"  # Debian's /usr/bin/qgis_process wrapper is broken, see the README
# The default style's layers on the sample (rock: no couloir there).
FAMILIES = ["hatch_fill", "hatch_ridge", "hatch_valley", "hatch_cross", "hatch_ridgeline", "hatch_cliff"]


@pytest.fixture(scope="session")
def qgis(tmp_path_factory):
    """A headless QgsApplication with Processing and the plugin started by QGIS's own plugin
    machinery (as qgis_process does), in a throwaway settings folder."""
    config = tmp_path_factory.mktemp("qgis_config")
    os.environ["QGIS_CUSTOM_CONFIG_PATH"] = str(config)
    os.environ.setdefault("XDG_RUNTIME_DIR", str(config))
    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], False)
    app.initQgis()
    sys.path.append("/usr/share/qgis/python/plugins")
    from processing.core.Processing import Processing
    Processing.initialize()
    import qgis.utils
    qgis.utils.plugin_paths.insert(0, str(PLUGINS))
    sys.path.insert(0, str(PLUGINS))
    qgis.utils.updateAvailablePlugins()
    assert qgis.utils.loadPlugin("rockhatch_qgis")
    assert qgis.utils.startProcessingPlugin("rockhatch_qgis")
    yield app
    qgis.utils.unloadPlugin("rockhatch_qgis")


def run(alg, params, feedback=None):
    import processing
    return processing.run(alg, params, feedback=feedback or QgsProcessingFeedback())


def drawn_layers(ds):
    """The layers of drawn features: the table of the faces' fingerprints (rockhatch update's,
    in a whole run's GeoPackage) aside."""
    return [ds.GetLayer(i) for i in range(ds.GetLayerCount()) if ds.GetLayer(i).GetName() != "rockhatch_faces"]


def layer_counts(gpkg):
    ds = ogr.Open(str(gpkg))
    return {layer.GetName(): layer.GetFeatureCount() for layer in drawn_layers(ds)}


def layer_features(gpkg):
    """Every layer's features, face and geometry in order, and the counts of its other
    attributes' values (one SQL query; reading each feature's fields in Python cost 3 times
    more): equal when the hatches are."""
    ds = ogr.Open(str(gpkg))
    out = {}
    for layer in drawn_layers(ds):
        name = layer.GetName()
        out[name] = [(f.GetField("face_id"), f.GetGeometryRef().ExportToWkb()) for f in layer]
        rows = ds.ExecuteSQL(f"SELECT family, style, width_mm, count(*) FROM {name} GROUP BY 1, 2, 3 ORDER BY 1, 2, 3")
        out[name + " attributes"] = [tuple(f.GetField(j) for j in range(4)) for f in rows]
        ds.ReleaseResultSet(rows)
    return out


@pytest.fixture(scope="session")
def reference(rockhatch_exe, sample_dir, tmp_path_factory):
    """The rockhatch command's outputs on the sample (default style, seed 0)."""
    out = tmp_path_factory.mktemp("reference")
    subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition",
                    str(sample_dir / "partition.gpkg"), "-o", str(out / "ref.gpkg"), "-o", str(out / "ref.svg")],
                   check=True)
    counts = layer_counts(out / "ref.gpkg")
    assert sum(counts.values()) > 10000
    return {"gpkg": out / "ref.gpkg", "svg": out / "ref.svg", "counts": counts, "features": layer_features(out / "ref.gpkg")}


def sample_params(sample_dir, output, **extra):
    return {"DEM": str(sample_dir / "dem.tif"), "FACES": f"{sample_dir / 'partition.gpkg'}|layername=faces",
            "OUTPUT": str(output), **extra}


# ---- loading


def test_plugin_loads_and_registers_provider(qgis):
    import qgis.utils
    assert "rockhatch_qgis" in qgis.utils.active_plugins
    assert qgis.utils.pluginMetadata("rockhatch_qgis", "qgisMinimumVersion") == "3.22"
    assert qgis.utils.pluginMetadata("rockhatch_qgis", "hasProcessingProvider") == "yes"
    registry = QgsApplication.processingRegistry()
    provider = registry.providerById("rockhatch")
    assert provider is not None and provider.name() == "Rock hatching"
    assert os.path.isfile(provider.svgIconPath()) and provider.svgIconPath().endswith("icon.svg")
    ids = ["rockhatch:rockhatching", "rockhatch:rockhatchingtiled", "rockhatch:rockpartition",
           "rockhatch:terrainfields", "rockhatch:updatehatching"]
    assert sorted(a.id() for a in provider.algorithms()) == ids
    for alg_id in ids:
        alg = registry.algorithmById(alg_id)
        assert alg.canExecute()[0]
        assert "default" in alg.shortHelpString().lower() or "NoData" in alg.shortHelpString()
        for p in alg.parameterDefinitions():
            assert p.help(), f"{alg_id} {p.name()} has no help"


def test_style_choices_are_the_modules(qgis):
    from rockhatch import carto
    alg = QgsApplication.processingRegistry().algorithmById("rockhatch:rockhatching")
    style = alg.parameterDefinition("STYLE")
    assert style.options() == [s.name for s in carto.styles()]
    assert style.defaultValue() == carto.default_style()
    for s in carto.styles():
        assert s.name in alg.shortHelpString()


# ---- rock hatching


def test_rock_hatching_equals_the_command(qgis, sample_dir, reference, tmp_path):
    t = time.perf_counter()
    result = run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "h.gpkg", SVG=str(tmp_path / "h.svg")))
    seconds = time.perf_counter() - t
    print(f"rock hatching on the sample through processing.run: {seconds:.2f} s")
    assert layer_features(tmp_path / "h.gpkg") == reference["features"]
    assert (tmp_path / "h.svg").read_bytes() == reference["svg"].read_bytes()
    assert result["PDF"] is None
    assert result["HATCHES"] == sum(reference["counts"].values()) and result["FACES_HATCHED"] == 20
    assert result["LAYERS"] == [f"{tmp_path / 'h.gpkg'}|layername={f}" for f in FAMILIES]
    for uri in result["LAYERS"]:
        layer = QgsVectorLayer(uri, "h", "ogr")
        assert layer.isValid() and layer.crs().authid() == "EPSG:2154"
        assert [f.name() for f in layer.fields()][1:] == ["face_id", "family", "style", "width_mm"]


def test_rock_hatching_writes_the_commands_geopdf(qgis, sample_dir, tmp_path):
    result = run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "h.gpkg", PDF=str(tmp_path / "h.pdf")))
    assert result["PDF"] == str(tmp_path / "h.pdf")
    pdf = QgsRasterLayer(str(tmp_path / "h.pdf"), "pdf")
    assert pdf.isValid() and pdf.crs().authid() == "EPSG:2154"
    assert round(pdf.extent().width()) == 1900


def test_two_files_and_memory_layers(qgis, sample_dir, reference, tmp_path):
    """Faces, lines and orientation from three files, or the faces as a memory layer: the
    layers are copied into one GeoPackage and the hatches stay the command's."""
    gpkg = sample_dir / "partition.gpkg"
    for name in ("faces", "lines", "orientation"):
        gdal.VectorTranslate(str(tmp_path / f"{name}.shp"), str(gpkg), layers=[name])
    params = {"DEM": str(sample_dir / "dem.tif"), "FACES": str(tmp_path / "faces.shp"),
              "LINES": str(tmp_path / "lines.shp"), "ORIENTATION_LAYER": str(tmp_path / "orientation.shp"),
              "OUTPUT": str(tmp_path / "a.gpkg")}
    run("rockhatch:rockhatching", {**params, "SVG": str(tmp_path / "a.svg")})
    # The same hatches; the faces are numbered by their feature ids, which OGR counts from 0
    # in a shapefile and from 1 in a GeoPackage.
    from_shp = {name: [(face + 1, wkb) for face, wkb in feats] if not name.endswith(" attributes") else feats
                for name, feats in layer_features(tmp_path / "a.gpkg").items()}
    assert from_shp == reference["features"]
    assert (tmp_path / "a.svg").read_bytes() == reference["svg"].read_bytes()

    faces = QgsVectorLayer(f"{gpkg}|layername=faces", "faces", "ogr").materialize(
        qgis_core.QgsFeatureRequest())
    assert faces.providerType() == "memory"
    QgsProject.instance().addMapLayer(faces)
    try:
        run("rockhatch:rockhatching", {**params, "FACES": faces.id(), "OUTPUT": str(tmp_path / "b.gpkg"),
                                       "SVG": str(tmp_path / "b.svg")})
        assert layer_features(tmp_path / "b.gpkg") == reference["features"]
        assert (tmp_path / "b.svg").read_bytes() == reference["svg"].read_bytes()
        with pytest.raises(QgsProcessingException, match="give the labelled lines layer"):
            run("rockhatch:rockhatching", {"DEM": params["DEM"], "FACES": faces.id(),
                                           "OUTPUT": str(tmp_path / "c.gpkg")})
    finally:
        QgsProject.instance().removeMapLayer(faces.id())


def test_style_seed_params_and_script(qgis, sample_dir, tmp_path):
    from rockhatch import carto
    kwargs = dict(style="noisy", seed=3, scale=5000, params={"spacing_min": 0.5})
    carto.run(str(sample_dir / "dem.tif"), str(sample_dir / "partition.gpkg"), [str(tmp_path / "m.svg")], **kwargs)
    run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "q.gpkg", STYLE="noisy", SEED=3, SCALE=5000,
                                                PARAMS="spacing_min=0.5", SVG=str(tmp_path / "q.svg")))
    assert (tmp_path / "q.svg").read_bytes() == (tmp_path / "m.svg").read_bytes()
    # The style script twin of a built-in gives its hatches.
    run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "s.gpkg", STYLE_SCRIPT=str(
        ROOT / "styles" / "noisy.py"), SEED=3, SCALE=5000, PARAMS="spacing_min=0.5", SVG=str(tmp_path / "s.svg")))
    assert layer_features(tmp_path / "s.gpkg") == layer_features(tmp_path / "q.gpkg")
    assert (tmp_path / "s.svg").read_bytes() == (tmp_path / "q.svg").read_bytes()


@pytest.mark.parametrize("style,layer", [("scree", "hatch_stone"), ("slope-hachures", "hatch_hachure")])
def test_terrain_styles_through_the_algorithm(qgis, sample_dir, tmp_path, style, layer):
    # The same drawing as carto.run, and the filled layer loaded as a polygon layer.
    from rockhatch import carto
    carto.run(str(sample_dir / "dem.tif"), str(sample_dir / "partition.gpkg"), [str(tmp_path / "m.svg")], style=style)
    result = run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "q.gpkg", STYLE=style,
                                                         SVG=str(tmp_path / "q.svg")))
    assert (tmp_path / "q.svg").read_bytes() == (tmp_path / "m.svg").read_bytes()
    uri = f"{tmp_path / 'q.gpkg'}|layername={layer}"
    # In the families' order: the terrain's layer before rock's structure layers.
    rock_layers = [f"{tmp_path / 'q.gpkg'}|layername={f}" for f in FAMILIES]
    assert result["LAYERS"] == rock_layers[:4] + [uri] + rock_layers[4:]
    loaded = QgsVectorLayer(uri, layer, "ogr")
    assert loaded.isValid() and loaded.geometryType() == qgis_core.QgsWkbTypes.PolygonGeometry
    assert loaded.featureCount() > 1000


def test_scree_areas_parameter(qgis, sample_dir, tmp_path):
    # A scree polygon layer in the partition's file: the stones stay inside it.
    part = tmp_path / "partition.gpkg"
    box = partition_with_scree(sample_dir, part)
    run("rockhatch:rockhatching", {"DEM": str(sample_dir / "dem.tif"), "FACES": f"{part}|layername=faces",
                                   "SCREE": f"{part}|layername=scree", "STYLE": "scree",
                                   "OUTPUT": str(tmp_path / "s.gpkg")})
    out = ogr.Open(str(tmp_path / "s.gpkg"))
    stones = [g.GetGeometryRef().Clone() for g in out.GetLayerByName("hatch_stone")]
    assert len(stones) > 100 and all(box.Buffer(1.0).Contains(g) for g in stones)


def test_an_operator_style_of_the_tests_through_the_algorithm(qgis, rockhatch_exe, sample_dir, tmp_path):
    # A style none of the seven, from libtex operators only (style_scripts/framed_tiles.py):
    # the algorithm draws what `rockhatch --script` draws.
    script = pathlib.Path(__file__).resolve().parent / "style_scripts" / "framed_tiles.py"
    subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition",
                    str(sample_dir / "partition.gpkg"), "--script", str(script), "--param", "tile=5",
                    "-o", str(tmp_path / "cli.svg"), "-o", str(tmp_path / "cli.gpkg")], check=True, env=python_env())
    run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "q.gpkg", STYLE_SCRIPT=str(script),
                                                PARAMS="tile=5", SVG=str(tmp_path / "q.svg")))
    assert (tmp_path / "q.svg").read_bytes() == (tmp_path / "cli.svg").read_bytes()
    assert layer_features(tmp_path / "q.gpkg") == layer_features(tmp_path / "cli.gpkg")
    assert layer_counts(tmp_path / "q.gpkg")["hatch_ridge"] > 50


def test_layers_load_styled(qgis, sample_dir, tmp_path):
    """runAndLoadResults (what the Toolbox does on completion): every non-empty family is
    loaded with black lines as wide as width_mm."""
    import processing
    project = QgsProject.instance()
    before = set(project.mapLayers())
    processing.runAndLoadResults("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "l.gpkg"),
                                 feedback=QgsProcessingFeedback())
    loaded = [project.mapLayer(i) for i in set(project.mapLayers()) - before]
    try:
        counts = layer_counts(tmp_path / "l.gpkg")
        assert loaded and sum(counts.values()) > 10000
        assert sorted(lay.name() for lay in loaded) == sorted(f for f in FAMILIES if counts[f])
        for lay in loaded:
            symbol = lay.renderer().symbol()
            assert symbol.color().name() == "#000000"
            prop = symbol.symbolLayer(0).dataDefinedProperties().property(qgis_core.QgsSymbolLayer.PropertyStrokeWidth)
            assert prop.isActive() and "width_mm" in prop.expressionString()
    finally:
        project.removeMapLayers([lay.id() for lay in loaded])


def test_crest_ornaments_through_the_algorithm(qgis, rockhatch_exe, sample_dir, tmp_path):
    """CREST draws what `rockhatch --crest-ornament default` draws, and the crest layer is
    loaded filled."""
    import processing
    subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition",
                    str(sample_dir / "partition.gpkg"), "--crest-ornament", "default", "--crest-height", "3",
                    "-o", str(tmp_path / "cli.svg")], check=True)
    project = QgsProject.instance()
    before = set(project.mapLayers())
    processing.runAndLoadResults("rockhatch:rockhatching", sample_params(
        sample_dir, tmp_path / "q.gpkg", CREST=True, CREST_HEIGHT=3, SVG=str(tmp_path / "q.svg")),
        feedback=QgsProcessingFeedback())
    loaded = [project.mapLayer(i) for i in set(project.mapLayers()) - before]
    try:
        assert (tmp_path / "q.svg").read_bytes() == (tmp_path / "cli.svg").read_bytes()
        crest = [lay for lay in loaded if lay.name() == "crest"]
        assert len(crest) == 1 and crest[0].featureCount() >= 5
        assert crest[0].renderer().symbol().color().name() == "#000000"
    finally:
        project.removeMapLayers([lay.id() for lay in loaded])
    (tmp_path / "junk.svg").write_text("not SVG <<<")
    with pytest.raises(QgsProcessingException, match="--crest-ornament .*junk.svg"):
        run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "b.gpkg",
                                                    CREST_EXEMPLAR=str(tmp_path / "junk.svg")))


# ---- tiled runs (Dask, in a child process)


def test_tiled_algorithm_writes_what_the_tiles_command_writes(qgis, sample_dir, tmp_path):
    """rockhatch:rockhatchingtiled runs `rockhatch tiles` in a child Python (Dask starts
    worker processes there, not inside QGIS): the same GeoPackage bytes as the command, the
    tile count and hatches reported, the hatch layers loaded, progress moving to 100%. With a
    terrain style (scree), which the tiled run draws as the whole run does."""
    import processing
    dem, tile = str(sample_dir / "dem.tif"), 1200
    cli = tmp_path / "cli.gpkg"
    subprocess.run([sys.executable, "-m", "rockhatch", "tiles", "-q", "--dem", dem,
                    "--partition", str(sample_dir / "partition.gpkg"), "--tile-size", str(tile), "--workers", "1",
                    "--seed", "2", "--style", "scree", "-o", str(cli)], check=True, env=python_env())
    project = QgsProject.instance()
    before = set(project.mapLayers())
    out = tmp_path / "q.gpkg"
    steps = []

    class Feedback(QgsProcessingFeedback):
        def setProgress(self, value):  # noqa: N802 (QGIS's name)
            steps.append(value)
            super().setProgress(value)

    result = processing.runAndLoadResults("rockhatch:rockhatchingtiled", {
        "DEM": dem, "PARTITION": str(sample_dir / "partition.gpkg"), "TILE_SIZE": tile,
        "WORKERS": 1, "SEED": 2, "STYLE": "scree", "OUTPUT": str(out)}, feedback=Feedback())
    loaded = {project.mapLayer(i).name() for i in set(project.mapLayers()) - before}
    try:
        assert out.read_bytes() == cli.read_bytes()
        assert result["TILES"] == 4
        assert result["HATCHES"] == sum(layer_counts(out).values()) > 10000
        assert {"hatch_fill", "hatch_ridge", "hatch_valley", "hatch_stone"} <= loaded
        assert steps and max(steps) == 100
        assert not (tmp_path / "q.gpkg.tiles").exists()  # the work folder goes after the merge
    finally:
        project.removeMapLayers([i for i in set(project.mapLayers()) - before])


def test_tiled_algorithm_cancelled_then_resumed(qgis, sample_dir, tmp_path):
    """Cancelling after the first tile stops the child run and keeps the finished tiles; the
    same job run again resumes from them and writes what an uninterrupted run writes."""
    params = {"DEM": str(sample_dir / "dem.tif"), "PARTITION": str(sample_dir / "partition.gpkg"),
              "TILE_SIZE": 800, "WORKERS": 1, "SEED": 4, "OUTPUT": str(tmp_path / "q.gpkg")}
    info = []

    class Feedback(QgsProcessingFeedback):
        def setProgressText(self, text):  # noqa: N802 (QGIS's name)
            if text.startswith("tiles ") and not text.startswith("tiles 0/"):
                self.cancel()
            super().setProgressText(text)

    with pytest.raises(QgsProcessingException, match="cancelled"):
        run("rockhatch:rockhatchingtiled", params, Feedback())
    work = tmp_path / "q.gpkg.tiles"
    kept, left = finished_tiles(work), sorted(p.name for p in work.iterdir())
    assert 1 <= len(kept) < 9 and not (tmp_path / "q.gpkg").exists()
    # Cancel stopped the Dask workers too: none goes on to finish a tile after the algorithm
    # has returned (a worker orphaned by the cancel did, and the resume count below was off).
    time.sleep(3)
    assert sorted(p.name for p in work.iterdir()) == left

    class Log(QgsProcessingFeedback):
        def pushInfo(self, text):  # noqa: N802
            info.append(text)
            super().pushInfo(text)

    result = run("rockhatch:rockhatchingtiled", params, Log())
    assert result["TILES"] == 9
    assert any(f"({len(kept)} done before)" in line for line in info), info
    whole = tmp_path / "whole.gpkg"
    run("rockhatch:rockhatchingtiled", {**params, "OUTPUT": str(whole)})
    assert (tmp_path / "q.gpkg").read_bytes() == whole.read_bytes()


def test_tiled_algorithm_reports_the_commands_error(qgis, sample_dir, tmp_path):
    """A bad input gets the command's one-line message as the algorithm's error, and no output."""
    out = tmp_path / "q.gpkg"
    with pytest.raises(QgsProcessingException, match="nonsense"):
        run("rockhatch:rockhatchingtiled", {
            "DEM": str(sample_dir / "dem.tif"), "PARTITION": str(sample_dir / "partition.gpkg"),
            "TILE_SIZE": 1200, "PARAMS": "nonsense=1", "OUTPUT": str(out)})
    assert not out.exists()


# ---- partition from the DEM


def test_rock_partition_equals_the_command(qgis, rockhatch_exe, sample_dir, tmp_path):
    """rockhatch:rockpartition writes what `rockhatch partition` writes, loads faces and lines
    (ridges red, valleys blue), and its output feeds rockhatch:rockhatching."""
    import processing
    cli = tmp_path / "cli.gpkg"
    subprocess.run([str(rockhatch_exe), "partition", "-q", "--dem", str(sample_dir / "dem.tif"), "-o", str(cli)],
                   check=True)
    project = QgsProject.instance()
    before = set(project.mapLayers())
    out = tmp_path / "p.gpkg"
    result = processing.runAndLoadResults("rockhatch:rockpartition", {
        "DEM": str(sample_dir / "dem.tif"), "OUTPUT": str(out), "PREVIEW": str(tmp_path / "p.png")},
        feedback=QgsProcessingFeedback())
    loaded = {project.mapLayer(i).name(): project.mapLayer(i) for i in set(project.mapLayers()) - before}
    try:
        assert out.read_bytes() == cli.read_bytes()
        counts = layer_counts(out)
        assert result["FACES_COUNT"] == counts["faces"] > 10
        assert set(loaded) == {"faces", "lines"}
        lines = loaded["lines"]
        assert lines.crs().authid() == "EPSG:2154"
        colours = {c.value(): c.symbol().color().name() for c in lines.renderer().categories()}
        assert colours["ridge"] == "#c81e1e" and colours["valley"] == "#1e3cc8"
        assert (tmp_path / "p.png").stat().st_size > 10000
    finally:
        project.removeMapLayers([lay.id() for lay in loaded.values()])
    hatched = run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "h.gpkg",
                                                          FACES=f"{out}|layername=faces"))
    assert hatched["FACES_HATCHED"] == counts["faces"] and hatched["HATCHES"] > 10000


def test_rock_partition_mask_keeps_the_bare_rock_of_a_land_cover_layer(qgis, rockhatch_exe, sample_dir, tmp_path):
    """The MASK parameter is the command's --mask: an OpenStreetMap land-cover layer keeps the
    rock inside its natural=bare_rock polygons only, the same file as `rockhatch partition`."""
    mask = land_cover(tmp_path / "osm.gpkg", True)
    cli = tmp_path / "cli.gpkg"
    subprocess.run([str(rockhatch_exe), "partition", "-q", "--dem", str(sample_dir / "dem.tif"), "--mask", str(mask),
                    "-o", str(cli)], check=True)
    out = tmp_path / "q.gpkg"
    result = run("rockhatch:rockpartition", {"DEM": str(sample_dir / "dem.tif"), "MASK": str(mask),
                                             "OUTPUT": str(out)})
    assert out.read_bytes() == cli.read_bytes()
    assert result["FACES_COUNT"] > 0
    ds = ogr.Open(str(out))
    east = max(f.GetGeometryRef().GetEnvelope()[1] for f in ds.GetLayerByName("faces"))
    assert east <= 1004100 + 1e-6  # west of the scree


def test_rock_partition_fixed_controls_equals_the_command(qgis, rockhatch_exe, sample_dir, tmp_path):
    """FIXED_CONTROLS writes what `rockhatch partition --fixed-controls` writes: the faces carry
    orientation and density (taken as given by the hatching) instead of fall_line and shade."""
    cli = tmp_path / "cli.gpkg"
    subprocess.run([str(rockhatch_exe), "partition", "-q", "--dem", str(sample_dir / "dem.tif"), "-o", str(cli),
                    "--fixed-controls"], check=True)
    out = tmp_path / "p.gpkg"
    run("rockhatch:rockpartition", {"DEM": str(sample_dir / "dem.tif"), "OUTPUT": str(out), "FIXED_CONTROLS": True})
    assert out.read_bytes() == cli.read_bytes()
    layer = QgsVectorLayer(f"{out}|layername=faces", "faces", "ogr")
    names = set(layer.fields().names())
    assert {"orientation", "density"} <= names and not {"fall_line", "shade"} & names
    derived = tmp_path / "d.gpkg"
    run("rockhatch:rockpartition", {"DEM": str(sample_dir / "dem.tif"), "OUTPUT": str(derived)})
    assert {"fall_line", "shade"} <= set(QgsVectorLayer(f"{derived}|layername=faces", "f", "ogr").fields().names())


def test_a_graphical_model_from_dem_to_hatching(qgis, rockhatch_exe, sample_dir, tmp_path):
    """The algorithms chain in a Processing model: DEM -> Rock partition -> Rock hatching,
    with the partition in a temporary file of the model; same hatches as the two commands."""
    dem = str(sample_dir / "dem.tif")
    from qgis.core import (QgsProcessingModelAlgorithm, QgsProcessingModelChildAlgorithm,
                           QgsProcessingModelChildParameterSource, QgsProcessingModelOutput,
                           QgsProcessingModelParameter, QgsProcessingParameterRasterLayer)
    model = QgsProcessingModelAlgorithm("dem_to_hatching", "rockhatch tests")
    model.addModelParameter(QgsProcessingParameterRasterLayer("dem", "DEM"), QgsProcessingModelParameter("dem"))
    dem_source = QgsProcessingModelChildParameterSource.fromModelParameter("dem")
    part = QgsProcessingModelChildAlgorithm("rockhatch:rockpartition")
    part.setChildId("partition")
    part.addParameterSources("DEM", [dem_source])
    model.addChildAlgorithm(part)
    hatch = QgsProcessingModelChildAlgorithm("rockhatch:rockhatching")
    hatch.setChildId("hatching")
    hatch.addParameterSources("DEM", [dem_source])
    hatch.addParameterSources("FACES", [QgsProcessingModelChildParameterSource.fromChildOutput("partition", "OUTPUT")])
    output = QgsProcessingModelOutput("hatches", "Hatches")
    output.setChildId("hatching")
    output.setChildOutputName("OUTPUT")
    hatch.setModelOutputs({"hatches": output})
    model.addChildAlgorithm(hatch)
    model.updateDestinationParameters()
    result = run(model, {"dem": dem, "hatching:hatches": str(tmp_path / "m.gpkg")})
    assert result["hatching:hatches"] == str(tmp_path / "m.gpkg")

    part_gpkg, cli = tmp_path / "p.gpkg", tmp_path / "cli.gpkg"
    subprocess.run([str(rockhatch_exe), "partition", "-q", "--dem", dem, "-o", str(part_gpkg)], check=True)
    subprocess.run([str(rockhatch_exe), "-q", "--dem", dem, "--partition", str(part_gpkg),
                    "-o", str(cli)], check=True)
    assert layer_counts(tmp_path / "m.gpkg") == layer_counts(cli)
    assert layer_features(tmp_path / "m.gpkg") == layer_features(cli)


def test_rock_partition_without_rock_raises(qgis, tmp_path):
    flat = tmp_path / "flat.tif"
    ds = gdal.GetDriverByName("GTiff").Create(str(flat), 50, 50, 1, gdal.GDT_Float32)
    ds.SetGeoTransform([1000000, 5, 0, 6500000, 0, -5])
    ds.SetProjection(carto_epsg_wkt(2154))
    ds.GetRasterBand(1).Fill(1200.0)
    ds = None
    # The extraction's own refusal, naming the DEM ("rock" alone is also in the tmp_path).
    with pytest.raises(QgsProcessingException, match=r"flat\.tif'?: no rock: no area"):
        run("rockhatch:rockpartition", {"DEM": str(flat), "OUTPUT": str(tmp_path / "f.gpkg")})
    assert not (tmp_path / "f.gpkg").exists()


def carto_epsg_wkt(code):
    from rockhatch import carto
    return carto.epsg_wkt(code)


# ---- terrain fields


def test_terrain_fields(qgis, sample_dir, tmp_path):
    import numpy as np
    from rockhatch import carto
    outs = {k: str(tmp_path / f"{k.lower()}.tif") for k in ("SLOPE", "ROUGHNESS", "HILLSHADE")}
    result = run("rockhatch:terrainfields", {"DEM": str(sample_dir / "dem.tif"), **outs})
    assert result == outs
    terrain = carto.compute_terrain(carto.load_dem(str(sample_dir / "dem.tif"))[0])
    for key, path in outs.items():
        layer = QgsRasterLayer(path, key)
        assert layer.isValid() and (layer.width(), layer.height()) == (480, 480)
        assert layer.crs().authid() == "EPSG:2154"
        assert layer.dataProvider().sourceNoDataValue(1) == -9999
        values = gdal.Open(path).ReadAsArray().astype("float32")
        values[values == -9999] = np.nan
        expected = getattr(terrain, key.lower()).array
        assert np.isnan(values).sum() > 0
        assert np.array_equal(np.isnan(values), np.isnan(expected))
        assert np.allclose(values[~np.isnan(values)], expected[~np.isnan(expected)])


# ---- errors


def no_crs_dem(sample_dir, tmp_path):
    path = str(tmp_path / "nocrs.tif")
    src = gdal.Open(str(sample_dir / "dem.tif"))
    dst = gdal.GetDriverByName("GTiff").CreateCopy(path, src)
    dst.SetProjection("")
    dst = None
    assert not gdal.Open(path).GetProjection()
    return path


def shifted_dem(sample_dir, tmp_path):
    path = str(tmp_path / "far.tif")
    dst = gdal.GetDriverByName("GTiff").CreateCopy(path, gdal.Open(str(sample_dir / "dem.tif")))
    gt = list(dst.GetGeoTransform())
    gt[0] += 50000
    dst.SetGeoTransform(gt)
    dst = None
    return path


def script(tmp_path, body):
    path = tmp_path / "bad_style.py"
    path.write_text(body)
    return str(path)


BAD = {
    "dem without CRS": lambda s, t: ({"DEM": no_crs_dem(s, t)}, {"dem": no_crs_dem(s, t)}),
    "partition outside the DEM": lambda s, t: ({"DEM": shifted_dem(s, t)}, {"dem": shifted_dem(s, t)}),
    "unknown label field": lambda s, t: ({"LINES": f"{s / 'partition.gpkg'}|layername=lines", "LABEL_FIELD": "nope"},
                                         {"lines_layer": "lines", "label_field": "nope"}),
    "script without style()": lambda s, t: ({"STYLE_SCRIPT": script(t, "NAME = 'x'\n")},
                                            {"style": script(t, "NAME = 'x'\n")}),
}


@pytest.mark.parametrize("case", sorted(BAD))
def test_bad_inputs_raise_the_pipelines_message(qgis, sample_dir, tmp_path, case):
    from rockhatch import RockhatchError, carto
    qgis_params, run_kwargs = BAD[case](sample_dir, tmp_path)
    kwargs = {"dem": str(sample_dir / "dem.tif"), "partition": str(sample_dir / "partition.gpkg"),
              "faces_layer": "faces", **run_kwargs}
    with pytest.raises(RockhatchError) as expected:
        carto.run(outputs=[str(tmp_path / "direct.gpkg")], **kwargs)
    with pytest.raises(QgsProcessingException) as raised:
        run("rockhatch:rockhatching", {**sample_params(sample_dir, tmp_path / "x.gpkg"), **qgis_params})
    assert str(expected.value) in str(raised.value)
    assert not (tmp_path / "x.gpkg").exists()


def test_style_script_error_raises(qgis, sample_dir, tmp_path):
    body = ("NAME = 'broken'\nPARAMS = []\n\ndef style(fields, params):\n"
            "    raise ValueError('this style is broken')\n")
    with pytest.raises(QgsProcessingException, match="ValueError: this style is broken"):
        run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "x.gpkg",
                                                    STYLE_SCRIPT=script(tmp_path, body)))
    with pytest.raises(QgsProcessingException, match="PARAMS: 'spacing_min' is not NAME=NUMBER"):
        run("rockhatch:rockhatching", sample_params(sample_dir, tmp_path / "x.gpkg", PARAMS="spacing_min"))
    with pytest.raises(QgsProcessingException, match="no CRS"):
        run("rockhatch:terrainfields", {"DEM": no_crs_dem(sample_dir, tmp_path),
                                        "SLOPE": str(tmp_path / "s.tif")})


def test_missing_module_gives_a_clear_error(qgis, sample_dir, tmp_path, monkeypatch):
    from rockhatch_qgis import module
    monkeypatch.setattr(module, "_carto", None)
    monkeypatch.setitem(sys.modules, "rockhatch.carto", None)
    alg = QgsApplication.processingRegistry().createAlgorithmById("rockhatch:terrainfields")
    ok, message = alg.canExecute()
    assert not ok and "rockhatch Python module cannot be imported" in message and "ROCKHATCH_PYTHONPATH" in message
    with pytest.raises(QgsProcessingException, match="rockhatch Python module cannot be imported"):
        run(alg, {"DEM": str(sample_dir / "dem.tif"), "SLOPE": str(tmp_path / "s.tif")})


# ---- never onto an input (issue 17)


def test_algorithms_refuse_to_write_onto_an_input(qgis, sample_dir, tmp_path):
    """Each algorithm fails cleanly, before any work, when an output is one of its inputs
    (the file itself, another spelling, a symbolic link), and the input keeps its bytes."""
    data = tmp_path / "data"
    (data / "sub").mkdir(parents=True)
    for name in ("dem.tif", "partition.gpkg"):
        shutil.copy(sample_dir / name, data / name)
    gdal.VectorTranslate(str(data / "mask.shp"), str(sample_dir / "partition.gpkg"), layers=["faces"])
    (data / "style.py").write_text((ROOT / "styles" / "noisy.py").read_text())
    (data / "link.gpkg").symlink_to("partition.gpkg")
    before = {p.name: p.read_bytes() for p in data.iterdir() if p.is_file()}
    faces = f"{data / 'partition.gpkg'}|layername=faces"
    cases = [
        ("rockhatch:rockhatching", {"DEM": str(data / "dem.tif"), "FACES": faces,
                                    "OUTPUT": str(data / "partition.gpkg")}, "--partition"),
        ("rockhatch:rockhatching", {"DEM": str(data / "dem.tif"), "FACES": faces,
                                    "OUTPUT": str(data / "link.gpkg")}, "--partition"),
        ("rockhatch:rockhatching", {"DEM": str(data / "dem.tif"), "FACES": faces, "OUTPUT": str(tmp_path / "h.gpkg"),
                                    "SVG": str(data / "sub" / ".." / "dem.tif")}, "--dem"),
        ("rockhatch:rockhatching", {"DEM": str(data / "dem.tif"), "FACES": faces, "OUTPUT": str(tmp_path / "h.gpkg"),
                                    "STYLE_SCRIPT": str(data / "style.py"), "SVG": str(data / "style.py")},
         "--script"),
        ("rockhatch:rockpartition", {"DEM": str(data / "dem.tif"), "MASK": str(data / "mask.shp"),
                                     "OUTPUT": str(data / "." / "mask.shp")}, "--mask"),
        ("rockhatch:rockpartition", {"DEM": str(data / "dem.tif"), "OUTPUT": str(tmp_path / "p.gpkg"),
                                     "PREVIEW": str(data / "dem.tif")}, "--dem"),
        ("rockhatch:terrainfields", {"DEM": str(data / "dem.tif"), "SLOPE": str(tmp_path / "s.tif"),
                                     "HILLSHADE": str(data / "sub" / ".." / "dem.tif")}, "is the input DEM"),
    ]
    for alg, params, fragment in cases:
        with pytest.raises(QgsProcessingException, match="onto an input") as raised:
            run(alg, params)
        assert fragment in str(raised.value), (alg, str(raised.value))
        assert {p.name: p.read_bytes() for p in data.iterdir() if p.is_file()} == before, alg
    assert not list(tmp_path.glob("*.gpkg")) and not list(tmp_path.glob("*.tif"))


# ---- cancellation


class CancelAt(QgsProcessingFeedback):
    """Cancels at the first progress report of at least `percent`."""

    def __init__(self, percent):
        super().__init__()
        self.percent = percent
        self.cancelled_at = None

    def setProgress(self, progress):  # noqa: N802
        super().setProgress(progress)
        if self.cancelled_at is None and progress >= self.percent:
            self.cancelled_at = time.perf_counter()
            self.cancel()


@pytest.mark.parametrize("percent", [0, 30])
def test_cancel_stops_quickly_and_leaves_no_output(qgis, sample_dir, tmp_path, percent):
    """Cancelled at the first progress report, or in the middle of the hatching of a dense
    run (1:5000, fine spacing: several seconds uncancelled)."""
    params = sample_params(sample_dir, tmp_path / "c.gpkg", SVG=str(tmp_path / "c.svg"), SCALE=5000,
                           STYLE="bidirectional", PARAMS="spacing_min=0.15; spacing_max=0.3")
    feedback = CancelAt(percent)
    with pytest.raises(QgsProcessingException, match="cancel"):
        run("rockhatch:rockhatching", params, feedback)
    stopped = time.perf_counter() - feedback.cancelled_at
    print(f"run cancelled at {percent}% stopped {stopped:.2f} s after the cancel")
    # The pipeline stops at its next progress report: while hatching, when a face is done,
    # so the faces in flight finish first. At 1:5000 with 0.15 mm spacing one sample face
    # took up to 1.65 s under a loaded CI run (pytest -n 2); an uncancelled run takes
    # several seconds. The same run in both passes, only the bound differs: under ASan
    # (scripts/sanitize.sh sets RH_SANITIZED=1) every face takes about ten times longer, and
    # so may the face in flight, which 3 s cannot hold.
    assert stopped < (30.0 if SANITIZED else 3.0)
    assert not list(tmp_path.iterdir())


# ---- install command and qgis_process


def test_install_zip(tmp_path):
    out = tmp_path / "rockhatch_qgis.zip"
    subprocess.run(["bash", str(ROOT / "scripts" / "install_qgis_plugin.sh"), "--zip", str(out)], check=True)
    names = zipfile.ZipFile(out).namelist()
    assert "rockhatch_qgis/metadata.txt" in names and "rockhatch_qgis/algorithms/rock_hatching.py" in names
    assert not [n for n in names if "__pycache__" in n or not n.startswith("rockhatch_qgis/")]


def test_qgis_process_runs_rock_hatching(sample_dir, reference, tmp_path):
    """The install command into a throwaway profile, then qgis_process as a cartographer runs it."""
    assert os.path.exists(QGIS_PROCESS), f"{QGIS_PROCESS} is missing: scripts/setup.sh installs QGIS (package qgis)"
    config = tmp_path / "config"
    env = python_env()
    env.update(QGIS_CUSTOM_CONFIG_PATH=str(config), QT_QPA_PLATFORM="offscreen", XDG_RUNTIME_DIR=str(tmp_path),
               GDAL_PAM_ENABLED="NO")
    subprocess.run(["bash", str(ROOT / "scripts" / "install_qgis_plugin.sh"), "--module-path", str(PYTHON_DIR)],
                   check=True, env=env)
    assert (config / "profiles" / "default" / "python" / "plugins" / "rockhatch_qgis").is_symlink()
    out = tmp_path / "qp.gpkg"
    t = time.perf_counter()
    p = subprocess.run([QGIS_PROCESS, "--json", "run", "rockhatch:rockhatching", "--",
                        f"DEM={sample_dir / 'dem.tif'}", f"FACES={sample_dir / 'partition.gpkg'}|layername=faces",
                        "STYLE=rock", f"OUTPUT={out}", f"SVG={tmp_path / 'qp.svg'}"], env=env,
                       capture_output=True, text=True, timeout=120)
    print(f"qgis_process run: {time.perf_counter() - t:.2f} s")
    assert p.returncode == 0, p.stderr + p.stdout
    results = json.loads(p.stdout[p.stdout.index("{"):])["results"]
    assert results["OUTPUT"] == str(out)
    assert layer_features(out) == reference["features"]
    assert (tmp_path / "qp.svg").read_bytes() == reference["svg"].read_bytes()
    # Bad input: a non-zero exit with the pipeline's message.
    p = subprocess.run([QGIS_PROCESS, "run", "rockhatch:rockhatching", "--", f"DEM={sample_dir / 'dem.tif'}",
                        f"FACES={sample_dir / 'partition.gpkg'}|layername=faces", "LABEL_FIELD=nope",
                        f"OUTPUT={tmp_path / 'bad.gpkg'}"], env=env, capture_output=True, text=True, timeout=120)
    assert p.returncode != 0 and "no line layer with a 'nope' field" in p.stdout + p.stderr
    shutil.rmtree(config)



# ---- the edit loop: re-hatching faces in place (edit_loop.py, rockhatch update)


def hatch_layers_of(gpkg, project):
    layers = []
    for name in FAMILIES:
        layer = QgsVectorLayer(f"{gpkg}|layername={name}", name, "ogr")
        assert layer.isValid(), name
        layers.append(layer)
    project.addMapLayers(layers)
    return layers


def hatched_copy(rockhatch_exe, sample_dir, tmp_path):
    """A copy of the sample's partition and the hatch GeoPackage of a run on it."""
    part = tmp_path / "partition.gpkg"
    shutil.copy(sample_dir / "partition.gpkg", part)
    out = tmp_path / "h.gpkg"
    subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition", str(part),
                    "-o", str(out)], check=True)
    return part, out


def partition_and_hatches(rockhatch_exe, sample_dir, tmp_path):
    """hatched_copy's files, its faces layer and its hatch layers in the project."""
    part, out = hatched_copy(rockhatch_exe, sample_dir, tmp_path)
    project = QgsProject.instance()
    faces = QgsVectorLayer(f"{part}|layername=faces", "faces", "ogr")
    assert faces.isValid()
    project.addMapLayer(faces)
    return part, out, faces, hatch_layers_of(out, project)


def move_vertex(layer, fid, dx, dy):
    """Moves the middle vertex of a face's outer ring, in the layer's edit buffer."""
    from qgis.core import QgsPointXY
    geom = layer.getFeature(fid).geometry()
    ring = geom.asPolygon()[0]
    k = len(ring) // 2
    assert geom.moveVertex(ring[k].x() + dx, ring[k].y() + dy, k)
    assert layer.changeGeometry(fid, geom)
    return QgsPointXY(ring[k])


def test_rehatch_action_redraws_the_edited_and_selected_faces_and_undo_puts_them_back(
        qgis, rockhatch_exe, sample_dir, tmp_path):
    sys.path.insert(0, str(PLUGINS))
    from rockhatch_qgis.edit_loop import EditLoop, has_edits
    part, out, faces, hatches = partition_and_hatches(rockhatch_exe, sample_dir, tmp_path)
    before = features_by_face(out)
    shutil.copy(out, tmp_path / "before.gpkg")
    project = QgsProject.instance()
    try:
        loop = EditLoop(project)
        # One face edited in the edit buffer, another selected.
        assert faces.startEditing()
        move_vertex(faces, 7, 15.0, -10.0)
        faces.selectByIds([3])
        reports = loop.rehatch(faces)
        assert list(reports) == [str(out.resolve())]
        r = reports[str(out.resolve())]
        redrawn = set(r.redrawn_ids)
        assert {3, 7} <= redrawn and len(redrawn) < 20
        assert r.written + r.deleted > 0
        # The edit was saved for the run to read it; the layer counts as modified for QGIS only
        # through the re-hatching's command on its undo stack (QGIS's Undo).
        assert not has_edits(faces) and faces.isModified() and faces.undoStack().count() == 1
        after = features_by_face(out)
        # Each redrawn face: the bytes of a whole run on the edited partition; every other face untouched.
        whole = tmp_path / "whole.gpkg"
        subprocess.run([str(rockhatch_exe), "-q", "--dem", str(sample_dir / "dem.tif"), "--partition", str(part),
                        "-o", str(whole)], check=True)
        full = features_by_face(whole)
        from rockhatch import carto
        was, now = carto.read_fingerprints(str(whole))[1], carto.read_fingerprints(str(tmp_path / "before.gpkg"))[1]
        changed = {face for face in now if now[face] != was[face]}
        assert 7 in changed and redrawn == changed | {3}
        for face in full:
            assert after[face] == (full[face] if face in redrawn else before[face]), face
        assert after[7] != before[7]
        # The open layers show the file.
        counts = layer_counts(out)
        for layer in hatches:
            assert layer.featureCount() == counts[layer.name()]
        # Undo: the features as they were, the fingerprints too (the face is redrawn again next time).
        assert loop.undo()
        assert features_by_face(out) == before
        assert not loop.undo()
        # The Processing algorithm on the file: the edited face and its neighbours again.
        result = run("rockhatch:updatehatching", {"HATCHES": str(out)})
        assert result["REDRAWN"] == len(changed)
        assert features_by_face(out) == {f: (full[f] if f in changed else before[f]) for f in full}
        result = run("rockhatch:updatehatching", {"HATCHES": str(out), "FACES": "3"})
        assert result["REDRAWN"] == 1 and features_by_face(out) == full
        # The hatch layers stay editable in QGIS after updates: a feature deleted there and saved.
        fill = next(layer for layer in hatches if layer.name() == "hatch_fill")
        fill.reload()
        count = fill.featureCount()
        assert fill.startEditing()
        assert fill.deleteFeature(next(fill.getFeatures()).id())
        with pytest.raises(ValueError, match="unsaved edits"):  # re-hatching waits for them
            loop.rehatch(faces)
        assert fill.commitChanges(), fill.commitErrors()
        assert layer_counts(out)["hatch_fill"] == count - 1
        assert subprocess.run([sys.executable, "/usr/lib/python3/dist-packages/osgeo_utils/samples/validate_gpkg.py",
                               str(out)], capture_output=True).returncode == 0
    finally:
        faces.rollBack()
        project.removeAllMapLayers()


def assert_layers_show(gpkg, layers):
    """The open hatch layers were reloaded: they count the file's features."""
    counts = layer_counts(gpkg)
    assert {layer.name(): layer.featureCount() for layer in layers} == {layer.name(): counts[layer.name()]
                                                                       for layer in layers}


def test_qgis_undo_and_redo_put_back_and_redraw_the_rehatchings(qgis, rockhatch_exe, sample_dir, tmp_path):
    """QGIS's Undo (Ctrl+Z: the active layer's undoStack().undo()) and Redo on the re-hatchings."""
    sys.path.insert(0, str(PLUGINS))
    from rockhatch import carto
    from rockhatch_qgis.edit_loop import EditLoop, RehatchCommand, has_edits, unsaved_edits
    part, out, faces, hatches = partition_and_hatches(rockhatch_exe, sample_dir, tmp_path)
    before, prints = features_by_face(out), carto.read_fingerprints(str(out))[1]
    reported = []
    loop = EditLoop(QgsProject.instance(), report=lambda text, level: reported.append(text))
    # No lasting Python wrapper of the stack (QGIS keeps none): it would keep the commands alive.
    stack = faces.undoStack
    try:
        assert faces.startEditing()
        move_vertex(faces, 7, 15.0, -10.0)
        faces.selectByIds([3])
        redrawn = loop.rehatch(faces)[str(out.resolve())].redrawn_ids
        after = features_by_face(out)
        assert after != before
        # The save took the edit's own command; the re-hatching's is the stack's only one, done.
        assert stack().count() == 1 and stack().index() == 1 and isinstance(stack().command(0), RehatchCommand)
        first = stack().text(0)
        assert first == f"Re-hatch {len(redrawn)} face(s)" and len(redrawn) >= 2
        # QGIS counts the layer as modified; the update algorithm does not refuse for it.
        assert faces.isModified() and not has_edits(faces) and unsaved_edits(str(out)) == []
        stack().undo()  # Ctrl+Z: the features and fingerprints as they were, the open layers reloaded
        assert features_by_face(out) == before and carto.read_fingerprints(str(out))[1] == prints
        assert_layers_show(out, hatches)
        assert loop.undo_stack == [] and not loop.undo()
        stack().redo()  # the same update again: the same features
        assert features_by_face(out) == after and len(loop.undo_stack) == 1
        assert_layers_show(out, hatches)
        # The toolbar's Undo goes through the stack when the command is its last done one.
        assert loop.undo()
        assert stack().index() == 0 and features_by_face(out) == before
        stack().redo()
        assert features_by_face(out) == after
        # A second re-hatching with another edit: its save cleared the stack, the first
        # command is pushed again below the second.
        move_vertex(faces, 17, -10.0, 10.0)
        redrawn = loop.rehatch(faces)[str(out.resolve())].redrawn_ids
        after2 = features_by_face(out)
        assert after2 != after and stack().index() == 2
        assert [stack().text(i) for i in range(stack().count())] == [first, f"Re-hatch {len(redrawn)} face(s)"]
        stack().undo()
        assert features_by_face(out) == after
        stack().undo()
        assert features_by_face(out) == before and not stack().canUndo() and loop.undo_stack == []
        # Redo: the partition file keeps both edits, so the first redo draws them both, and
        # the second draws its faces again the same.
        stack().redo()
        assert features_by_face(out) == after2
        stack().redo()
        assert features_by_face(out) == after2 and stack().index() == 2 and len(loop.undo_stack) == 2
        assert reported == []
    finally:
        faces.rollBack()
        QgsProject.instance().removeAllMapLayers()


def test_qgis_undo_stack_cleared_leaves_the_toolbar_undo(qgis, rockhatch_exe, sample_dir, tmp_path):
    """A save, a rollback, the layer removed or the project cleared delete or pass over the
    commands without a crash; the toolbar's Undo keeps working, also when the layer is not
    being edited; errors in Undo reach the report callback, not Qt."""
    sys.path.insert(0, str(PLUGINS))
    import gc
    from qgis.PyQt import sip
    from rockhatch_qgis.edit_loop import EditLoop
    part, out, faces, hatches = partition_and_hatches(rockhatch_exe, sample_dir, tmp_path)
    before = features_by_face(out)
    project = QgsProject.instance()
    reported = []
    loop = EditLoop(project, report=lambda text, level: reported.append(text))
    stack = faces.undoStack()
    try:
        # A save deletes the command: the toolbar's Undo still undoes the re-hatching.
        assert faces.startEditing()
        move_vertex(faces, 7, 15.0, -10.0)
        loop.rehatch(faces)
        after = features_by_face(out)
        command = stack.command(0)
        assert faces.commitChanges(False)
        assert stack.count() == 0 and sip.isdeleted(command)
        gc.collect()
        assert loop.undo() and features_by_face(out) == before
        # A rollback discards the unsaved edits only: the re-hatching, in the files, stays
        # (the rollback's undo passes over it), and Redo then leaves it as it is.
        faces.selectByIds([3])
        loop.rehatch(faces)
        assert features_by_face(out) == after and stack.count() == 1
        move_vertex(faces, 9, 5.0, 5.0)
        assert faces.rollBack(False) and stack.index() == 0
        assert features_by_face(out) == after
        stack.redo()
        assert features_by_face(out) == after and len(loop.undo_stack) == 1
        assert faces.rollBack() and not faces.isEditable() and stack.count() == 0
        assert features_by_face(out) == after
        assert loop.undo() and features_by_face(out) == before and not loop.undo()
        # Not being edited: no command (QGIS's Undo is off for the layer), the toolbar's Undo works.
        loop.rehatch(faces)
        assert stack.count() == 0 and features_by_face(out) == after
        assert loop.undo() and features_by_face(out) == before
        # An error inside Ctrl+Z (the undo file gone) is reported; the file stays as it was.
        assert faces.startEditing()
        loop.rehatch(faces)
        os.remove(loop.undo_stack[-1].files[-1][1])
        stack.undo()
        assert len(reported) == 1 and "failed" in reported[0] and features_by_face(out) == after
        loop.undo_stack.clear()
        # Older than the last MAX_UNDO: Ctrl+Z says so and drops the command (the failed one,
        # undone for Qt, went with the next push).
        loop.MAX_UNDO = 1
        loop.rehatch(faces)
        loop.rehatch(faces)
        assert stack.count() == 2 and len(loop.undo_stack) == 1
        stack.undo()
        stack.undo()
        assert "cannot be undone" in reported[-1] and stack.count() == 1
        loop.MAX_UNDO = 20
        # The layer removed with a command on its stack, then the project cleared with one:
        # the toolbar's Undo still puts back the files.
        move_vertex(faces, 9, 5.0, 5.0)
        loop.rehatch(faces)
        assert features_by_face(out) != after and stack.count() == 1
        project.removeMapLayer(faces)
        QgsApplication.processEvents()
        gc.collect()
        assert loop.undo() and features_by_face(out) == after
        faces = QgsVectorLayer(f"{part}|layername=faces", "faces", "ogr")
        project.addMapLayer(faces)
        assert faces.startEditing()
        move_vertex(faces, 11, 5.0, 5.0)
        loop.rehatch(faces)
        assert features_by_face(out) != after and faces.undoStack().count() == 1
        project.clear()
        QgsApplication.processEvents()
        gc.collect()
        assert loop.undo() and features_by_face(out) == after
        assert len(reported) == 2
    finally:
        if not sip.isdeleted(faces):
            faces.rollBack()
        project.removeAllMapLayers()


def test_update_algorithm_refuses_while_the_partition_or_the_hatches_have_unsaved_edits(
        qgis, rockhatch_exe, sample_dir, tmp_path):
    part, out = hatched_copy(rockhatch_exe, sample_dir, tmp_path)
    before = features_by_face(out)
    project = QgsProject.instance()
    faces = QgsVectorLayer(f"{part}|layername=faces", "faces", "ogr")
    project.addMapLayer(faces)
    hatches = hatch_layers_of(out, project)
    try:
        # A face moved in QGIS's edit buffer, not saved: the update would read the file as it
        # was and report nothing to redraw. Refused, the file untouched.
        assert faces.startEditing()
        move_vertex(faces, 7, 15.0, -10.0)
        with pytest.raises(QgsProcessingException, match="partition layer 'faces' has unsaved edits"):
            run("rockhatch:updatehatching", {"HATCHES": str(out)})
        assert faces.commitChanges(), faces.commitErrors()
        # A hatch layer being edited: the update would write under it.
        fill = next(layer for layer in hatches if layer.name() == "hatch_fill")
        assert fill.startEditing()
        assert fill.deleteFeature(next(fill.getFeatures()).id())
        with pytest.raises(QgsProcessingException, match="hatch layer 'hatch_fill' has unsaved edits"):
            run("rockhatch:updatehatching", {"HATCHES": str(out)})
        assert features_by_face(out) == before
        fill.rollBack()
        assert run("rockhatch:updatehatching", {"HATCHES": str(out)})["REDRAWN"] >= 1
        assert features_by_face(out)[7] != before[7]
    finally:
        faces.rollBack()
        project.removeAllMapLayers()


def test_update_algorithm_refuses_a_file_without_fingerprints(qgis, sample_dir, tmp_path):
    import processing
    from rockhatch import carto
    drawing = carto.hatch(carto.prepare(sample_dir / "dem.tif", sample_dir / "partition.gpkg"),
                          window=(1003150, 6538950, 1003600, 6539400))
    carto.write_gpkg(drawing, str(tmp_path / "t.gpkg"))
    with pytest.raises(QgsProcessingException, match="keeps no fingerprints"):
        processing.run("rockhatch:updatehatching", {"HATCHES": str(tmp_path / "t.gpkg")})
