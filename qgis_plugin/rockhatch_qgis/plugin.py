"""The plugin object QGIS creates: it registers the Processing provider and, in the QGIS
window, the re-hatching actions (edit_loop.py) in the Plugins menu and a toolbar."""
import time

from qgis.core import Qgis, QgsApplication, QgsVectorLayer, QgsWkbTypes

from . import module
from .edit_loop import EditLoop
from .provider import RockhatchProvider

MENU = "&Rock hatching"


class RockhatchPlugin:
    def __init__(self, iface):
        self.iface = iface
        self.provider = None
        self.loop = None
        self.actions = []
        self.toolbar = None

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
        if self.iface is None:
            return
        from qgis.PyQt.QtGui import QIcon
        from qgis.PyQt.QtWidgets import QAction
        from .icon import ICON
        self.loop = EditLoop(canvas=self.iface.mapCanvas(), report=self.message)  # errors of QGIS's Undo/Redo
        self.toolbar = self.iface.addToolBar("Rock hatching")
        self.toolbar.setObjectName("RockhatchToolbar")
        for text, slot in (("Re-hatch the selected or edited faces", self.rehatch),
                           ("Undo the last re-hatching", self.undo)):
            action = QAction(QIcon(ICON), text, self.iface.mainWindow())
            action.triggered.connect(slot)
            self.iface.addPluginToMenu(MENU, action)
            self.toolbar.addAction(action)
            self.actions.append(action)

    def unload(self):
        for action in self.actions:
            self.iface.removePluginMenu(MENU, action)
        self.actions = []
        if self.toolbar is not None:
            self.toolbar.deleteLater()
            self.toolbar = None
        if self.provider is not None:
            QgsApplication.processingRegistry().removeProvider(self.provider)
            self.provider = None

    def message(self, text, level=Qgis.Info):
        self.iface.messageBar().pushMessage("Rock hatching", text, level, 5 if level == Qgis.Info else 0)

    def rehatch(self):
        """The action: the active layer is the partition's faces."""
        layer = self.iface.activeLayer()
        if not isinstance(layer, QgsVectorLayer) or layer.geometryType() != QgsWkbTypes.PolygonGeometry:
            self.message("select the partition's face layer (polygons) first", Qgis.Warning)
            return
        start = time.perf_counter()
        try:
            reports = self.loop.rehatch(layer)
        except (ValueError, RuntimeError) as e:
            self.message(str(e), Qgis.Critical)
            return
        redrawn = sum(r.redrawn for r in reports.values())
        written = sum(r.written + r.deleted for r in reports.values())
        self.message(f"{redrawn} face(s) re-hatched, {written} feature(s) rewritten in "
                     f"{time.perf_counter() - start:.2f} s")

    def undo(self):
        """The action: the last re-hatching undone, through the partition layer's undo stack when
        its command is the last done there (QGIS's Undo and Redo stay in step), else directly."""
        try:
            if not self.loop.undo():
                self.message("nothing to undo", Qgis.Warning)
        except (ValueError, RuntimeError) as e:
            self.message(str(e), Qgis.Critical)
