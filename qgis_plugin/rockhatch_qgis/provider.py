"""The Processing provider "Rock hatching" (id rockhatch)."""
import os

from qgis.core import QgsProcessingProvider
from qgis.PyQt.QtGui import QIcon

from .algorithms.rock_hatching import RockHatching
from .algorithms.terrain_fields import TerrainFields

ICON = os.path.join(os.path.dirname(__file__), "icon.svg")


class RockhatchProvider(QgsProcessingProvider):
    def id(self):
        return "rockhatch"

    def name(self):
        return "Rock hatching"

    def longName(self):  # noqa: N802
        return "Rock hatching (rockhatch, Loi 2015 chapter 5)"

    def icon(self):
        return QIcon(ICON)

    def svgIconPath(self):  # noqa: N802
        return ICON

    def supportedOutputRasterLayerExtensions(self):  # noqa: N802
        return ["tif"]

    def defaultRasterFileExtension(self):  # noqa: N802
        return "tif"

    def loadAlgorithms(self):  # noqa: N802
        self.addAlgorithm(RockHatching())
        self.addAlgorithm(TerrainFields())
