"""The plugin object QGIS creates: it registers the Processing provider."""
from qgis.core import Qgis, QgsApplication

from . import module
from .provider import RockhatchProvider


class RockhatchPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None

    def initProcessing(self):  # noqa: N802 (QGIS's name)
        """Called by QGIS (and by qgis_process, which never calls initGui)."""
        if self.provider is None:
            self.provider = RockhatchProvider()
            QgsApplication.processingRegistry().addProvider(self.provider)

    def initGui(self):  # noqa: N802
        self.initProcessing()
        ok, message = module.available()
        if not ok and self.iface is not None:
            self.iface.messageBar().pushMessage("Rock hatching", message, Qgis.Warning, 0)

    def unload(self):
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None
