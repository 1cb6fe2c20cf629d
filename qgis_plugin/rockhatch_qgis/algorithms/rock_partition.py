"""Processing algorithm "Rock partition from DEM": rockhatch partition on a QGIS raster."""
from qgis.core import (QgsCategorizedSymbolRenderer, QgsFillSymbol, QgsLineSymbol, QgsProcessing,
                       QgsProcessingContext, QgsProcessingException, QgsProcessingLayerPostProcessorInterface,
                       QgsProcessingOutputNumber, QgsProcessingParameterBoolean,
                       QgsProcessingParameterFeatureSource, QgsProcessingParameterFileDestination,
                       QgsProcessingParameterNumber, QgsProcessingParameterRasterLayer, QgsRendererCategory,
                       QgsSingleSymbolRenderer)

from .common import Progress, RockhatchAlgorithm
from .rock_hatching import OGR_EXTENSIONS

# Border colours of the preview and of the loaded lines layer.
KIND_COLOURS = {"ridge": "200,30,30,255", "valley": "30,60,200,255", "other": "120,120,120,255"}


class PartitionStyler(QgsProcessingLayerPostProcessorInterface):
    """Faces as light outlines, lines coloured by kind (ridge red, valley blue, other grey)."""

    def __init__(self, layer):
        super().__init__()
        self.layer = layer

    def postProcessLayer(self, layer, context, feedback):  # noqa: N802 (QGIS's name)
        if self.layer == "lines":
            categories = []
            for kind, colour in KIND_COLOURS.items():
                symbol = QgsLineSymbol.createSimple({"color": colour, "width": "0.5" if kind != "other" else "0.25",
                                                     "width_unit": "MM"})
                categories.append(QgsRendererCategory(kind, symbol, kind))
            layer.setRenderer(QgsCategorizedSymbolRenderer("kind", categories))
        else:
            symbol = QgsFillSymbol.createSimple({"color": "255,230,200,90", "outline_color": "90,90,90,255",
                                                 "outline_width": "0.15", "outline_width_unit": "MM"})
            layer.setRenderer(QgsSingleSymbolRenderer(symbol))
        layer.triggerRepaint()


_STYLERS = {}


class RockPartition(RockhatchAlgorithm):
    DEM, MASK, MIN_SLOPE, MIN_ROUGHNESS, MIN_AREA, SCALE = (
        "DEM", "MASK", "MIN_SLOPE", "MIN_ROUGHNESS", "MIN_AREA", "SCALE")
    THALWEG_AREA, RIDGE_AREA, SMOOTH, OUTPUT, PREVIEW, NETWORK, FIXED_CONTROLS = (
        "THALWEG_AREA", "RIDGE_AREA", "SMOOTH", "OUTPUT", "PREVIEW", "NETWORK", "FIXED_CONTROLS")

    def name(self):
        return "rockpartition"

    def displayName(self):  # noqa: N802
        return "Rock partition from DEM"

    def tags(self):
        return ["partition", "rock", "ridge", "thalweg", "couloir", "arete", "flow accumulation", "dem"]

    def initAlgorithm(self, config=None):  # noqa: N802
        def number(name, title, default, minimum, help_text, advanced=False, integer=False):
            kind = QgsProcessingParameterNumber.Integer if integer else QgsProcessingParameterNumber.Double
            self.add(QgsProcessingParameterNumber(name, title, kind, default, minValue=minimum), help_text, advanced)

        self.add(QgsProcessingParameterRasterLayer(self.DEM, "DEM"),
            "Elevation raster (metres) with a CRS; a geographic DEM is reprojected to its UTM zone, which "
            "becomes the CRS of the partition.")
        self.add(QgsProcessingParameterFeatureSource(self.MASK, "Rock mask polygons", [QgsProcessing.TypeVectorPolygon],
                                                optional=True),
            "Optional polygons: rock is looked for only inside them (e.g. the rock areas of an existing map). "
            "An OpenStreetMap land-cover layer (a natural field, or GDAL's other_tags) counts only its "
            "natural=bare_rock polygons.")
        number(self.MIN_SLOPE, "Minimum slope (percent)", 70.0, 0.0,
               "Rock where the slope, averaged over about 25 m, reaches this many percent. Default: 70 (35 degrees).")
        number(self.MIN_ROUGHNESS, "Minimum roughness (0..1)", 0.001, 0.0,
               "... and where the vector ruggedness (same average) reaches this value. Default: 0.001.")
        number(self.SCALE, "Map scale 1:", 10000.0, 100.0,
               "Scale denominator of the map the partition is for: it sets the smallest rock area and face. "
               "Default: 10000.")
        number(self.MIN_AREA, "Minimum area (mm2 on paper)", 16.0, 0.0,
               "Rock specks, enclosed gaps and faces smaller than this many square millimetres on paper at the "
               "map scale are dropped, filled or merged. Default: 16 (1600 m2 at 1:10000).")
        number(self.THALWEG_AREA, "Thalweg start area (m2)", 6000.0, 0.0,
               "Contributing area at which a thalweg starts (at least 50 cells). Default: 6000.", advanced=True)
        number(self.RIDGE_AREA, "Ridge start area (m2)", 20000.0, 0.0,
               "Contributing area on the inverted DEM at which a ridge starts (at least 100 cells). "
               "Default: 20000.", advanced=True)
        number(self.SMOOTH, "Smoothing (m)", 10.0, 0.0,
               "Smoothing of the DEM before flow routing, metres (0: none). Default: 10.", advanced=True)
        self.add(QgsProcessingParameterFileDestination(self.OUTPUT, "Partition (GeoPackage)", "GeoPackage (*.gpkg)"),
            "GeoPackage with the layers faces (id, fall_line = azimuth in degrees, shade 0..1, area), lines "
            "(kind = ridge / valley / other), mask and network (every traced ridge and thalweg), ready for "
            "Rock hatching. An existing file is replaced.")
        self.add(QgsProcessingParameterFileDestination(self.PREVIEW, "Preview (PNG)", "PNG files (*.png)", optional=True,
                                                  createByDefault=False),
            "Optional PNG: the hillshade, the faces tinted, ridges red, thalwegs blue.")
        self.add(QgsProcessingParameterBoolean(self.NETWORK, "Load the traced network too", False),
            "Also load the network layer (every traced ridge and thalweg, including those that end inside a "
            "face). Default: no.", advanced=True)
        self.add(QgsProcessingParameterBoolean(self.FIXED_CONTROLS, "Fixed direction and density per face", False),
            "Write each face's mean fall line and shade as orientation and density, the attributes Rock hatching "
            "takes as given: each face is then hatched in one direction with one density (the thesis's "
            "hand-made partitions), and editing them changes the drawing. Default: no (fall_line and shade, "
            "derived: hatching follows the terrain inside each face).", advanced=True)
        self.addOutput(QgsProcessingOutputNumber("FACES_COUNT", "Faces"))

    def shortHelpString(self):  # noqa: N802
        return ("Builds the partition Rock hatching needs from a DEM alone (the rockhatch partition command): "
                "the rock mask (steep and rough terrain, optionally inside mask polygons), ridges and thalwegs "
                "by flow accumulation on the inverted and on the plain DEM, the faces between them with borders "
                "labelled ridge / valley / other, and per face its mean fall line (fall_line, azimuth in "
                "degrees) and shade (1 - mean hillshade), derived attributes that Rock hatching does not take "
                "as given: hatching the partition follows the terrain as with an automatic partition (with "
                "'Fixed direction and density per face' they are written as orientation and density, which it "
                "takes as given). "
                "Thresholds: slope in percent (default 70), "
                "roughness 0..1 (default 0.001), minimum area in mm2 on paper at the map scale (default 16 at "
                "1:10000). The faces and lines are loaded with ridges in red and valleys in blue; check and "
                "edit them before hatching, as a cartographer would.")

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        carto = self.carto()
        dem = self.raster_path(parameters, self.DEM, context, feedback)
        options = {
            "min_slope": self.parameterAsDouble(parameters, self.MIN_SLOPE, context),
            "min_roughness": self.parameterAsDouble(parameters, self.MIN_ROUGHNESS, context),
            "min_area_mm2": self.parameterAsDouble(parameters, self.MIN_AREA, context),
            "scale": self.parameterAsDouble(parameters, self.SCALE, context),
            "thalweg_area": self.parameterAsDouble(parameters, self.THALWEG_AREA, context),
            "ridge_area": self.parameterAsDouble(parameters, self.RIDGE_AREA, context),
            "smooth": self.parameterAsDouble(parameters, self.SMOOTH, context),
        }
        if parameters.get(self.MASK) not in (None, ""):
            path, layer = self.parameterAsCompatibleSourceLayerPathAndLayerName(
                parameters, self.MASK, context, OGR_EXTENSIONS, "gpkg", feedback)
            if layer:
                raise QgsProcessingException(
                    f"MASK: give a file with the mask polygons as its only (or first) layer, not '{layer}' of {path}")
            options["mask"] = path
        output = self.parameterAsFileOutput(parameters, self.OUTPUT, context)
        preview = self.parameterAsFileOutput(parameters, self.PREVIEW, context)
        result = self.call(carto.partition_from_dem, dem, output, progress=Progress(feedback), overwrite=True,
                           png=preview or None,
                           fixed_controls=self.parameterAsBool(parameters, self.FIXED_CONTROLS, context), **options)
        for note in result.notes:
            feedback.pushInfo(note)
        faces = len(result.partition.faces)
        layers = ["faces", "lines"] + (["network"] if self.parameterAsBool(parameters, self.NETWORK, context) else [])
        for name in layers:
            uri = f"{output}|layername={name}"
            details = QgsProcessingContext.LayerDetails(name, context.project(), self.OUTPUT)
            _STYLERS[uri] = PartitionStyler("lines" if name != "faces" else "faces")
            details.setPostProcessor(_STYLERS[uri])
            context.addLayerToLoadOnCompletion(uri, details)
        return {self.OUTPUT: output, self.PREVIEW: preview or None, "FACES_COUNT": faces}
