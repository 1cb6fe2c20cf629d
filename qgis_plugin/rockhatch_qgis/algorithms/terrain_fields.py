"""Processing algorithm "Terrain control fields": slope, roughness and hillshade of a DEM."""
import os

from qgis.core import (QgsProcessingException, QgsProcessingParameterRasterDestination,
                       QgsProcessingParameterRasterLayer)

from .common import RockhatchAlgorithm

NODATA = -9999.0
# (output, Terrain attribute, display name, help)
FIELDS = [
    ("SLOPE", "slope", "Slope (percent)", "Slope in percent (100 x tan of the slope angle), Horn's gradient."),
    ("ROUGHNESS", "roughness", "Roughness (0..1)",
     "Vector ruggedness of the terrain in a 3 x 3 window: 0 smooth, 1 rough."),
    ("HILLSHADE", "hillshade", "Hillshade (0..1)", "Hillshade lit from the north-west: 0 dark, 1 light."),
]


class TerrainFields(RockhatchAlgorithm):
    DEM = "DEM"

    def name(self):
        return "terrainfields"

    def displayName(self):  # noqa: N802
        return "Terrain control fields"

    def tags(self):
        return ["slope", "roughness", "ruggedness", "hillshade", "dem", "terrain", "hatching"]

    def initAlgorithm(self, config=None):  # noqa: N802
        dem = QgsProcessingParameterRasterLayer(self.DEM, "DEM")
        dem.setHelp("Elevation raster (metres) with a CRS; a geographic DEM is reprojected to its UTM zone "
                    "first, as the hatching pipeline does.")
        self.addParameter(dem)
        for key, _, title, help_text in FIELDS:
            param = QgsProcessingParameterRasterDestination(key, title, optional=True)
            param.setHelp(f"{help_text} Float32 GeoTIFF on the DEM's grid, NoData {NODATA:g}.")
            self.addParameter(param)

    def shortHelpString(self):  # noqa: N802
        return ("The terrain fields the rock hatching pipeline computes from a DEM and hatches with: "
                "slope (percent), roughness (0..1, vector ruggedness) and hillshade (0..1, lit from the "
                "north-west). Each output is a Float32 GeoTIFF on the DEM's grid and CRS (UTM when the DEM "
                f"is geographic) with NoData {NODATA:g} where the DEM has NoData. Use them to check a DEM before hatching, or edit them and pass them to Rock "
                "hatching as its slope / roughness rasters.")

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        carto = self.carto()
        dem_path = self.raster_path(parameters, self.DEM, context, feedback)
        outputs = [(key, self.parameterAsOutputLayer(parameters, key, context) or "") for key, _, _, _ in FIELDS]
        # Existing outputs are replaced, but never the DEM, nor one output by another.
        self.call(carto.check_outputs, [(self.DEM, dem_path)], outputs, True)
        feedback.setProgressText("reading the DEM")
        dem, notes = self.call(carto.load_dem, dem_path)
        for note in notes:
            feedback.pushInfo(note)
        if feedback.isCanceled():
            return {}
        feedback.setProgress(20)
        feedback.setProgressText("computing the terrain fields")
        terrain = self.call(carto.compute_terrain, dem)
        feedback.setProgress(60)
        results = {}
        for i, (key, attr, _, _) in enumerate(FIELDS):
            if feedback.isCanceled():
                return results
            path = outputs[i][1]
            if not path:
                continue
            feedback.setProgressText(f"writing {attr} to {path}")
            self.write(carto, getattr(terrain, attr), path)
            results[key] = path
            feedback.setProgress(60 + 40 * (i + 1) / len(FIELDS))
        return results

    def write(self, carto, raster, path):
        """A GeoTIFF as the pipeline writes it (the provider offers no other raster format)."""
        if os.path.splitext(path)[1].lower() not in (".tif", ".tiff"):
            raise QgsProcessingException(f"{path}: the terrain fields are written as GeoTIFF (.tif) only")
        self.call(carto.write_geotiff, raster, path, nodata=NODATA)
