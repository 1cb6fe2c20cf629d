"""The Processing provider "Rock hatching" (id rockhatch)."""
from qgis.core import QgsProcessingProvider

from .algorithms.rock_hatching import RockHatching
from .algorithms.rock_hatching_tiled import RockHatchingTiled
from .algorithms.rock_partition import RockPartition
from .algorithms.terrain_fields import TerrainFields
from .algorithms.update_hatching import UpdateHatching
from .icon import WithIcon


class RockhatchProvider(WithIcon, QgsProcessingProvider):
    def id(self):
        return "rockhatch"

    def name(self):
        return "Rock hatching"

    def longName(self):  # noqa: N802
        return "Rock hatching (rockhatch, Loi 2015 chapter 5)"

    def supportedOutputRasterLayerExtensions(self):  # noqa: N802
        return ["tif"]

    def defaultRasterFileExtension(self):  # noqa: N802
        return "tif"

    def loadAlgorithms(self):  # noqa: N802
        self.addAlgorithm(RockHatching())
        self.addAlgorithm(TerrainFields())
        self.addAlgorithm(RockPartition())
        self.addAlgorithm(RockHatchingTiled())
        self.addAlgorithm(UpdateHatching())
