"""Processing algorithm "Rock hatching": the rockhatch pipeline on QGIS layers."""
import os

from osgeo import ogr
from qgis.core import (QgsFillSymbol, QgsLineSymbol, QgsProcessing, QgsProcessingContext, QgsProcessingException,
                       QgsProcessingLayerPostProcessorInterface, QgsProcessingOutputMultipleLayers,
                       QgsProcessingOutputNumber, QgsProcessingParameterBoolean, QgsProcessingParameterEnum,
                       QgsProcessingParameterFeatureSource, QgsProcessingParameterField,
                       QgsProcessingParameterFile, QgsProcessingParameterFileDestination,
                       QgsProcessingParameterNumber, QgsProcessingParameterRasterLayer,
                       QgsProcessingParameterString, QgsProcessingUtils, QgsProperty, QgsSingleSymbolRenderer,
                       QgsSymbolLayer, QgsUnitTypes)
from qgis.PyQt.QtCore import Qt

from .common import Progress, RockhatchAlgorithm

# The GeoPackage layers the pipeline writes, one per hatch family, with the line width a
# renderer uses when a feature has no width_mm (mm on paper).
FAMILIES = {"hatch_fill": 0.10, "hatch_ridge": 0.12, "hatch_valley": 0.25, "hatch_cross": 0.08,
            "hatch_ridgeline": 0.12, "hatch_couloir": 0.08, "hatch_cliff": 0.12}
# The polygon layer of the crest ornaments (filled black).
CREST_LAYER = "crest"
# The polygon layers of the terrain styles (scree, slope-hachures), filled black, no outline.
FILLED = ("hatch_stone", "hatch_hachure")
# Vector formats handed to the pipeline as they are; other layers are written to a GeoPackage.
OGR_EXTENSIONS = ["gpkg", "shp", "geojson", "json", "fgb", "sqlite", "gml", "kml", "tab", "mif", "csv"]


def hatch_renderer(family):
    """Black lines as wide as their width_mm attribute (mm on paper), round caps; the terrain
    styles' stones and hachures filled black."""
    if family in FILLED:
        return QgsSingleSymbolRenderer(QgsFillSymbol.createSimple({"color": "0,0,0,255", "outline_style": "no"}))
    symbol = QgsLineSymbol.createSimple({"color": "0,0,0,255", "width": str(FAMILIES.get(family, 0.1)),
                                         "width_unit": "MM", "capstyle": "round", "joinstyle": "round"})
    layer = symbol.symbolLayer(0)
    layer.setDataDefinedProperty(QgsSymbolLayer.PropertyStrokeWidth,
                                 QgsProperty.fromExpression(f'coalesce("width_mm", {FAMILIES.get(family, 0.1)})'))
    layer.setWidthUnit(QgsUnitTypes.RenderMillimeters)
    layer.setPenCapStyle(Qt.RoundCap)
    return QgsSingleSymbolRenderer(symbol)


def crest_renderer():
    """The crest ornaments filled black, with no outline (holes stay open)."""
    return QgsSingleSymbolRenderer(QgsFillSymbol.createSimple({"color": "0,0,0,255", "outline_style": "no"}))


class HatchStyler(QgsProcessingLayerPostProcessorInterface):
    """Gives a hatch layer loaded on completion its line style (its fill for the crests)."""

    def __init__(self, family):
        super().__init__()
        self.family = family

    def postProcessLayer(self, layer, context, feedback):  # noqa: N802 (QGIS's name)
        layer.setRenderer(crest_renderer() if self.family == CREST_LAYER else hatch_renderer(self.family))
        layer.triggerRepaint()


# The layer details take ownership of their post-processor: one new per loaded layer, its
# Python side kept alive here until the next run loads the same layer.
_STYLERS = {}


def styler(uri, family):
    _STYLERS[uri] = HatchStyler(family)
    return _STYLERS[uri]


def gpkg_layers(path):
    """{layer name: feature count} of a GeoPackage."""
    ds = ogr.Open(path)
    if ds is None:
        return {}
    return {ds.GetLayer(i).GetName(): ds.GetLayer(i).GetFeatureCount() for i in range(ds.GetLayerCount())}


def load_hatch_layers(output, context, output_name):
    """Loads the hatch layers of a written GeoPackage when the algorithm completes, each with
    its style (empty ones are not loaded); returns the URIs of all of them."""
    uris = []
    for family, count in gpkg_layers(output).items():
        if family not in FAMILIES and family != CREST_LAYER and family not in FILLED:
            continue
        uri = f"{output}|layername={family}"
        uris.append(uri)
        if count:
            details = QgsProcessingContext.LayerDetails(family, context.project(), output_name)
            details.setPostProcessor(styler(uri, family))
            context.addLayerToLoadOnCompletion(uri, details)
    return uris


def style_parameter(alg, name, names, default, help_text):
    """The style list (static strings: a model or qgis_process names the style itself)."""
    style = QgsProcessingParameterEnum(name, "Style", names, defaultValue=default)
    style.setUsesStaticStrings(True)
    alg.add(style, help_text)


def parse_params(text):
    """'spacing_min=0.3; length=2' -> {'spacing_min': 0.3, 'length': 2.0}."""
    params = {}
    for item in (text or "").replace(",", ";").split(";"):
        if not item.strip():
            continue
        name, sep, value = item.partition("=")
        try:
            if not sep or not name.strip():
                raise ValueError
            params[name.strip()] = float(value)
        except ValueError:
            raise QgsProcessingException(f"PARAMS: '{item.strip()}' is not NAME=NUMBER") from None
    return params


class RockHatching(RockhatchAlgorithm):
    DEM, FACES, LINES, LABEL_FIELD = "DEM", "FACES", "LINES", "LABEL_FIELD"
    ORIENTATION_FIELD, DENSITY_FIELD, ID_FIELD, ORIENTATION_LAYER = (
        "ORIENTATION_FIELD", "DENSITY_FIELD", "ID_FIELD", "ORIENTATION_LAYER")
    SLOPE, ROUGHNESS, STYLE, STYLE_SCRIPT, PARAMS = "SLOPE", "ROUGHNESS", "STYLE", "STYLE_SCRIPT", "PARAMS"
    SCALE, SEED, OUTPUT, SVG, PDF = "SCALE", "SEED", "OUTPUT", "SVG", "PDF"
    RELIEF_RADIUS = "RELIEF_RADIUS"
    CREST, CREST_EXEMPLAR, CREST_HEIGHT = "CREST", "CREST_EXEMPLAR", "CREST_HEIGHT"
    SCREE = "SCREE"

    def name(self):
        return "rockhatching"

    def displayName(self):  # noqa: N802
        return "Rock hatching"

    def tags(self):
        return ["hatching", "hachures", "rock", "relief", "cliff", "topographic", "cartography", "dem"]

    def style_names(self):
        try:
            carto = self.carto()
        except QgsProcessingException:
            return ["rock"], "rock"
        return [s.name for s in carto.styles()], carto.default_style()

    def initAlgorithm(self, config=None):  # noqa: N802
        self.add(QgsProcessingParameterRasterLayer(self.DEM, "DEM"),
            "Elevation raster (metres) in a projected CRS, or a geographic one (then reprojected to its "
            "UTM zone, which becomes the CRS of the hatches). It must have a CRS.")
        self.add(QgsProcessingParameterFeatureSource(self.FACES, "Rock faces (partition polygons)",
                                                [QgsProcessing.TypeVectorPolygon]),
            "Polygons of the rock faces. When the line layer is not given, the lines are taken from the "
            "faces' own file (GeoPackage): a line layer with the label field, or layers named ridges / "
            "valleys; a line layer named orientation* there gives the faces' orientation.")
        self.add(QgsProcessingParameterFeatureSource(self.LINES, "Labelled lines (ridges, valleys)",
                                                [QgsProcessing.TypeVectorLine], optional=True),
            "Lines that label the faces' borders, with a label field holding ridge, valley or other. "
            "Default: found in the faces' file.")
        self.add(QgsProcessingParameterField(self.LABEL_FIELD, "Label field of the lines", "kind", self.LINES,
                                        QgsProcessingParameterField.String, optional=True),
            "Field of the line layer holding ridge / valley / other. Default: kind.")
        self.add(QgsProcessingParameterField(self.ORIENTATION_FIELD, "Orientation field of the faces", None,
                                        self.FACES, QgsProcessingParameterField.Numeric, optional=True),
            "Field of the faces with the hatching direction, azimuth in degrees clockwise from north. "
            "Default: a field named orientation if there is one; faces without it take the orientation "
            "layer or the mean aspect. A field chosen here must exist.")
        self.add(QgsProcessingParameterField(self.DENSITY_FIELD, "Density field of the faces", None, self.FACES,
                                        QgsProcessingParameterField.Numeric, optional=True),
            "Field of the faces with the hatching density, 0 (light) to 1 (dark). Default: a field named "
            "density if there is one; faces without it are shaded from the terrain. A field chosen here must exist.")
        self.add(QgsProcessingParameterField(self.ID_FIELD, "Identifier field of the faces", None, self.FACES,
                                        QgsProcessingParameterField.Numeric, optional=True),
            "Integer field copied to face_id of the hatches. Default: the feature id.", advanced=True)
        self.add(QgsProcessingParameterFeatureSource(self.ORIENTATION_LAYER, "Orientation lines",
                                                [QgsProcessing.TypeVectorLine], optional=True),
            "Lines along the faces' fall lines: a face takes the direction of the line it holds. "
            "Default: a layer named orientation* in the partition's file.", advanced=True)
        self.add(QgsProcessingParameterFeatureSource(self.SCREE, "Scree areas (polygons)",
                                                     [QgsProcessing.TypeVectorPolygon], optional=True),
            "Polygons where the scree style throws its stones (outside the rock faces). Default: the band "
            "below the rock faces where the slope is moderate. Read by the scree style only.", advanced=True)
        self.add(QgsProcessingParameterRasterLayer(self.SLOPE, "Slope raster", optional=True),
            "Slope in percent replacing the one computed from the DEM (resampled onto the DEM's grid). "
            "Default: computed from the DEM (Horn).", advanced=True)
        self.add(QgsProcessingParameterRasterLayer(self.ROUGHNESS, "Roughness raster", optional=True),
            "Roughness 0..1 replacing the one computed from the DEM (vector ruggedness). "
            "Default: computed from the DEM.", advanced=True)
        names, default = self.style_names()
        style_parameter(self, self.STYLE, names, default, f"Built-in style (thesis Fig. 5.4 a to g), or a terrain style drawn around the rock faces "
                   f"(scree: stones below the rock; slope-hachures: Lehmann hachures on the other slopes). "
                   f"Default: {default}. See the algorithm's help for each style's parameters.")
        self.add(QgsProcessingParameterFile(self.STYLE_SCRIPT, "Style script (Python)", extension="py", optional=True),
            "A Python style script (styles/*.py of rockhatch: NAME, PARAMS, style(fields, params) returning a libtex arrangement); "
            "replaces the built-in style when given.")
        self.add(QgsProcessingParameterString(self.PARAMS, "Style parameters", optional=True),
            "Overrides of the style's parameters: NAME=VALUE separated by ';', lengths in mm on paper at the "
            "map scale, e.g. spacing_min=0.3; length=2. Default: the style's values.", advanced=True)
        self.add(QgsProcessingParameterNumber(self.SCALE, "Map scale 1:", QgsProcessingParameterNumber.Double, 10000,
                                         minValue=100),
            "Scale denominator of the map: the style's mm on paper become ground metres at this scale. "
            "Default: 10000.")
        self.add(QgsProcessingParameterNumber(self.RELIEF_RADIUS, "Relief radius (m)",
                                              QgsProcessingParameterNumber.Double, 1000, minValue=1),
            "The styles' height is the elevation between the lowest and the highest ground within this "
            "distance: an edit of the DEM changes the drawing only that far. Default: 1000 m.", advanced=True)
        self.add(QgsProcessingParameterNumber(self.SEED, "Random seed", QgsProcessingParameterNumber.Integer, 0,
                                         minValue=0),
            "Seed of the styles' jitter: the same seed gives the same hatches. Default: 0.")
        self.add(QgsProcessingParameterBoolean(self.CREST, "Crest ornaments on the ridges", False),
            "Draws every ridge line as one connected band pattern synthesised from an exemplar (the "
            "project's, or the SVG below), written as the polygon layer crest. Default: off.")
        self.add(QgsProcessingParameterFile(self.CREST_EXEMPLAR, "Crest exemplar (SVG)", extension="svg",
                                            optional=True),
            "An SVG of polygons (with holes) drawn along the ridges instead of the project's spine with "
            "barbs; giving one turns the crest ornaments on. It must be able to repeat into one connected "
            "band (shapes hanging on a line that runs through it).", advanced=True)
        self.add(QgsProcessingParameterNumber(self.CREST_HEIGHT, "Crest band height (mm)",
                                              QgsProcessingParameterNumber.Double, 2, minValue=0.01, maxValue=50),
            "Height of the crest band centred on the ridge, mm on paper at the map scale. Default: 2.",
            advanced=True)
        self.add(QgsProcessingParameterFileDestination(self.OUTPUT, "Hatches (GeoPackage)", "GeoPackage (*.gpkg)"),
            "GeoPackage written with one LineString layer per hatch family (hatch_fill, hatch_ridge, "
            "hatch_valley, hatch_cross; fields face_id, family, style, width_mm) in the DEM's CRS (UTM "
            "for a geographic DEM), and with a terrain style a Polygon layer of filled shapes (hatch_stone "
            "for scree, hatch_hachure for slope hachures; face_id -1). An existing file is replaced.")
        self.add(QgsProcessingParameterFileDestination(self.SVG, "Hatches (SVG)", "SVG files (*.svg)", optional=True,
                                                  createByDefault=False),
            "Optional SVG drawing of the hatches at the map scale (millimetres on paper).")
        self.add(QgsProcessingParameterFileDestination(self.PDF, "Hatches (GeoPDF)", "PDF files (*.pdf)", optional=True,
                                                  createByDefault=False),
            "Optional georeferenced PDF at the map scale on a page fitted to the drawing, one PDF layer "
            "per hatch family, for print layout (docs/publish.md).")
        self.addOutput(QgsProcessingOutputMultipleLayers("LAYERS", "Hatch layers"))
        self.addOutput(QgsProcessingOutputNumber("FACES_HATCHED", "Faces hatched"))
        self.addOutput(QgsProcessingOutputNumber("HATCHES", "Hatches"))

    def shortHelpString(self):  # noqa: N802
        text = ("Draws rock hatching (H. Loi, 2015, chapter 5) in rock faces: hatch lines whose direction, "
                "spacing and length follow the faces' orientation, density and the terrain. It runs the "
                "pipeline of the rockhatch command (same hatches for the same inputs and seed).\n\n"
                "Inputs: a DEM (metres) with a CRS; the partition: rock-face polygons and lines labelled "
                "ridge / valley / other along their borders, either two layers or one GeoPackage holding "
                "both (then give the faces only); optional slope (percent) and roughness (0..1) rasters.\n"
                "Style: a built-in style or a Python style script; its parameters (mm on paper at the "
                "map scale 1:SCALE, default 1:10000) may be overridden in Style parameters. Seed: 0 by "
                "default.\n"
                "Outputs: a GeoPackage with one layer per hatch family (loaded with black lines as wide "
                "as width_mm) and an optional SVG.\n"
                "Crest ornaments (optional): every ridge line drawn as one connected band synthesised "
                "from an exemplar, in the polygon layer crest (loaded filled black); ridges too short or "
                "too tight for the band are skipped and counted in the log.\n\n")
        try:
            carto = self.carto()
            for s in carto.styles():
                params = ", ".join(f"{p.name} {p.value:g} {p.unit}" for p in s.params)
                where = "terrain, around the rock" if s.terrain else s.figure
                text += f"{s.name} ({where}): {s.title}. Parameters: {params}.\n"
        except QgsProcessingException as e:
            text += str(e)
        return text

    # ---- partition layers to the pipeline's partition options
    def source_path(self, parameters, name, context, feedback):
        """(path, layer name) of a vector parameter: its own file when OGR reads it as is, else
        a GeoPackage written in the temporary folder (memory layers, selections, filters)."""
        if parameters.get(name) in (None, ""):
            return None
        if self.parameterAsSource(parameters, name, context) is None:
            raise QgsProcessingException(f"{name}: '{parameters.get(name)}' is not a vector layer QGIS can read")
        path, layer = self.parameterAsCompatibleSourceLayerPathAndLayerName(
            parameters, name, context, OGR_EXTENSIONS, "gpkg", feedback)
        return path, layer or ""

    def is_copy(self, parameters, name, context, path):
        """True when `path` is a copy Processing wrote of the layer (a memory layer, a
        selection, a filter), not the file the layer is read from."""
        source = self.parameterAsVectorLayer(parameters, name, context)
        if source is None or source.providerType() != "ogr":
            return True
        own = source.source().split("|")[0]
        return os.path.realpath(own) != os.path.realpath(path) or "subset=" in source.source()

    def partition_options(self, parameters, context, feedback):
        """The partition path and layer options: the faces' file when every layer lies in it,
        else a temporary GeoPackage with the layers faces, lines, orientation."""
        roles = {"faces_layer": self.source_path(parameters, self.FACES, context, feedback),
                 "lines_layer": self.source_path(parameters, self.LINES, context, feedback),
                 "orientation_layer": self.source_path(parameters, self.ORIENTATION_LAYER, context, feedback),
                 "scree_layer": self.source_path(parameters, self.SCREE, context, feedback)}
        given = {k: v for k, v in roles.items() if v is not None}
        files = {os.path.realpath(p) for p, _ in given.values()}
        if len(files) == 1:
            path = given["faces_layer"][0]
            if "lines_layer" not in given and self.is_copy(parameters, self.FACES, context, path):
                raise QgsProcessingException(
                    "FACES is not read from its own file (a selection, a filter or a memory layer): give the "
                    "labelled lines layer LINES")
            return path, {k: layer for k, (p, layer) in given.items()}
        merged = QgsProcessingUtils.generateTempFilename("partition.gpkg")
        feedback.pushInfo(f"The partition's layers lie in different files: copying them into {merged}")
        dst = ogr.GetDriverByName("GPKG").CreateDataSource(merged)
        options = {}
        for key, (path, layer) in given.items():
            role = key[:-len("_layer")]
            src = ogr.Open(path)
            lyr = None if src is None else (src.GetLayerByName(layer) if layer else src.GetLayer(0))
            if lyr is None or dst.CopyLayer(lyr, role) is None:
                raise QgsProcessingException(f"{role}: cannot copy layer '{layer}' of {path} to {merged}")
            options[key] = role
        dst = None
        return merged, options

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        carto = self.carto()
        dem = self.raster_path(parameters, self.DEM, context, feedback)
        partition, layers = self.partition_options(parameters, context, feedback)
        fields = {  # an empty orientation / density / id field: not read from the faces
            "label_field": self.parameterAsString(parameters, self.LABEL_FIELD, context) or "kind",
            "orientation_field": self.parameterAsString(parameters, self.ORIENTATION_FIELD, context) or "",
            "density_field": self.parameterAsString(parameters, self.DENSITY_FIELD, context) or "",
            "id_field": self.parameterAsString(parameters, self.ID_FIELD, context) or ""}
        script = self.parameterAsFile(parameters, self.STYLE_SCRIPT, context)
        style = script or self.parameterAsEnumString(parameters, self.STYLE, context)
        output = self.parameterAsFileOutput(parameters, self.OUTPUT, context)
        svg = self.parameterAsFileOutput(parameters, self.SVG, context)
        pdf = self.parameterAsFileOutput(parameters, self.PDF, context)
        outputs = [output] + ([svg] if svg else []) + ([pdf] if pdf else [])
        exemplar = self.parameterAsFile(parameters, self.CREST_EXEMPLAR, context)
        crest = exemplar or ("default" if self.parameterAsBool(parameters, self.CREST, context) else None)
        crest_height = self.parameterAsDouble(parameters, self.CREST_HEIGHT, context) if crest else None
        feedback.pushInfo(f"rockhatch: DEM {dem}, partition {partition} {layers}, style {style}")
        stats = self.call(
            carto.run, dem, partition, outputs, progress=Progress(feedback),
            style=style, params=parse_params(self.parameterAsString(parameters, self.PARAMS, context)),
            scale=self.parameterAsDouble(parameters, self.SCALE, context),
            relief_radius=self.parameterAsDouble(parameters, self.RELIEF_RADIUS, context),
            seed=self.parameterAsInt(parameters, self.SEED, context), overwrite=True,
            slope=self.raster_path(parameters, self.SLOPE, context, feedback),
            roughness=self.raster_path(parameters, self.ROUGHNESS, context, feedback),
            crest_ornament=crest, crest_height_mm=crest_height, **layers, **fields)
        for note in stats.notes:
            feedback.pushInfo(note)
        feedback.pushInfo(f"{stats.faces} faces, {stats.hatches} hatches in {stats.seconds:.1f} s ({stats.crs})")

        uris = load_hatch_layers(output, context, self.OUTPUT)
        return {self.OUTPUT: output, self.SVG: svg or None, self.PDF: pdf or None, "LAYERS": uris,
                "FACES_HATCHED": stats.faces, "HATCHES": stats.hatches}
