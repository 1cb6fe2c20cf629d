#!/usr/bin/python3
"""The re-hatching action in a real QGIS map canvas, headless: the sample hatched by the
command, its faces and hatch layers in a project, one face's density changed in the faces'
edit buffer, the plugin's toolbar action triggered (its initGui run on a stand-in for QGIS's
window, with the real canvas), the canvas saved before and after, side by side.

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 qgis_plugin/render_edit_loop.py OUT.png

docs/qgis-edit-loop.png is `render_edit_loop.py docs/qgis-edit-loop.png`.
"""
import os
import pathlib
import shutil
import subprocess
import sys
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")
HERE = pathlib.Path(__file__).resolve().parent
ROOT = HERE.parent
SAMPLE = ROOT / "data" / "sample_montblanc"
BUILD = pathlib.Path(os.environ.get("RH_BUILD_DIR", ROOT / "build"))
sys.path.insert(0, str(HERE))
sys.path.insert(0, str(BUILD / "python"))

from qgis.core import QgsApplication, QgsFillSymbol, QgsProject, QgsRectangle, QgsVectorLayer  # noqa: E402
from qgis.gui import QgsMapCanvas  # noqa: E402
from qgis.PyQt.QtCore import QEventLoop, QSize, QTimer  # noqa: E402
from qgis.PyQt.QtGui import QColor, QFont, QImage, QPainter  # noqa: E402

FACE = 7
STYLE = "bidirectional"


def grab(canvas):
    """The canvas once it has drawn every layer."""
    loop = QEventLoop()
    canvas.mapCanvasRefreshed.connect(loop.quit)
    QTimer.singleShot(20000, loop.quit)
    canvas.refreshAllLayers()
    loop.exec_()
    canvas.mapCanvasRefreshed.disconnect(loop.quit)
    return canvas.grab().toImage()


class Iface:
    """What the plugin asks of QGIS's window (QgisInterface): a main window, a toolbar, the
    Plugins menu, the message bar, the canvas and the active layer."""

    def __init__(self, canvas, layer):
        from qgis.PyQt.QtWidgets import QMainWindow
        self.window, self.canvas, self.layer, self.messages = QMainWindow(), canvas, layer, []

    def mainWindow(self):  # noqa: N802 (QGIS's names)
        return self.window

    def addToolBar(self, name):  # noqa: N802
        return self.window.addToolBar(name)

    def addPluginToMenu(self, menu, action):  # noqa: N802
        pass

    def removePluginMenu(self, menu, action):  # noqa: N802
        pass

    def mapCanvas(self):  # noqa: N802
        return self.canvas

    def activeLayer(self):  # noqa: N802
        return self.layer

    def messageBar(self):  # noqa: N802
        return self

    def pushMessage(self, title, text, level=0, duration=0):  # noqa: N802
        self.messages.append(f"{title}: {text}")


def main():
    out_png = sys.argv[1]
    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], True)
    app.initQgis()
    from rockhatch_qgis.algorithms.rock_hatching import FAMILIES, hatch_renderer
    from rockhatch_qgis.plugin import RockhatchPlugin

    work = pathlib.Path(tempfile.mkdtemp(prefix="rockhatch_edit_loop_"))
    part, out = work / "partition.gpkg", work / "hatches.gpkg"
    shutil.copy(SAMPLE / "partition.gpkg", part)
    # A style that hatches by the faces' density (the default, rock, follows the shade).
    subprocess.run([str(BUILD / "carto" / "rockhatch"), "-q", "--dem", str(SAMPLE / "dem.tif"), "--partition",
                    str(part), "--style", STYLE, "-o", str(out)], check=True)
    project = QgsProject.instance()
    faces = QgsVectorLayer(f"{part}|layername=faces", "faces", "ogr")
    faces.setRenderer(faces.renderer().clone())
    faces.renderer().setSymbol(QgsFillSymbol.createSimple(
        {"color": "0,0,0,0", "outline_color": "200,30,30,255", "outline_width": "0.5"}))
    hatches = []
    for name in FAMILIES:
        layer = QgsVectorLayer(f"{out}|layername={name}", name, "ogr")
        if layer.isValid() and layer.featureCount():
            layer.setRenderer(hatch_renderer(name))
            hatches.append(layer)
    project.addMapLayers([faces] + hatches)

    canvas = QgsMapCanvas()
    canvas.resize(QSize(700, 700))
    canvas.setCanvasColor(QColor("white"))
    canvas.setDestinationCrs(faces.crs())
    canvas.setLayers([faces] + hatches)
    box = faces.getFeature(FACE).geometry().boundingBox()
    box.grow(120)
    canvas.setExtent(QgsRectangle(box))
    canvas.show()
    before = grab(canvas)

    # The face's density raised in the edit buffer (0 light .. 1 dark), the action run.
    faces.startEditing()
    density = faces.getFeature(FACE)["density"]
    faces.changeAttributeValue(FACE, faces.fields().indexOf("density"), 0.9)
    # The toolbar's action, as QGIS would trigger it, through the plugin's own initGui.
    plugin = RockhatchPlugin(Iface(canvas, faces))
    plugin.initGui()
    rehatch = next(a for a in plugin.actions if a.text().startswith("Re-hatch"))
    rehatch.trigger()
    after = grab(canvas)
    assert plugin.loop.last, plugin.iface.messages
    report = next(iter(plugin.loop.last.values()))
    print("message bar:", "; ".join(plugin.iface.messages))

    image = QImage(before.width() * 2 + 10, before.height() + 40, QImage.Format_RGB32)
    image.fill(QColor("white"))
    painter = QPainter(image)
    painter.drawImage(0, 40, before)
    painter.drawImage(before.width() + 10, 40, after)
    painter.setFont(QFont("DejaVu Sans", 13))
    painter.drawText(10, 26, f"before: face {FACE} (the middle triangle), style {STYLE}")
    painter.drawText(before.width() + 20, 26, f"after: density {density:g} -> 0.9, re-hatched ({report.redrawn} faces "
                                              "redrawn)")
    painter.end()
    image.save(out_png)
    print(f"{out_png}: {image.width()} x {image.height()} px; {report.redrawn} faces redrawn "
          f"({sorted(report.redrawn_ids)}), features {report.deleted} removed, {report.written} written, "
          f"{report.kept} unchanged")
    project.removeAllMapLayers()
    shutil.rmtree(work)


if __name__ == "__main__":
    main()
