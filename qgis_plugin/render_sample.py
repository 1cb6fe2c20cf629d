#!/usr/bin/python3
"""Renders the sample hatched by the QGIS plugin with QGIS's own renderer, headless: the
Terrain control fields hillshade under the hatch layers as the plugin loads and styles them.

    QT_QPA_PLATFORM=offscreen /usr/bin/python3 qgis_plugin/render_sample.py OUT.png [--style NAME]
        [--scale 10000] [--dpi 150] [--gray]

docs/qgis-rockhatch.png is `render_sample.py docs/qgis-rockhatch.png --gray`.
"""
import argparse
import os
import pathlib
import sys
import tempfile

os.environ.setdefault("QT_QPA_PLATFORM", "offscreen")
os.environ.setdefault("GDAL_PAM_ENABLED", "NO")  # no dem.tif.aux.xml in data/
HERE = pathlib.Path(__file__).resolve().parent
SAMPLE = HERE.parent / "data" / "sample_montblanc"
sys.path.insert(0, str(HERE))
sys.path.append("/usr/share/qgis/python/plugins")

from qgis.core import (QgsApplication, QgsContrastEnhancement, QgsMapRendererSequentialJob,  # noqa: E402
                       QgsMapSettings, QgsProject, QgsRasterLayer, QgsSingleBandGrayRenderer)
from qgis.PyQt.QtCore import QSize  # noqa: E402
from qgis.PyQt.QtGui import QColor, QImage  # noqa: E402


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("output")
    ap.add_argument("--style", default="bidirectional")
    ap.add_argument("--scale", type=float, default=10000)
    ap.add_argument("--dpi", type=int, default=150)
    ap.add_argument("--gray", action="store_true", help="8-bit gray PNG (smaller)")
    args = ap.parse_args()

    QgsApplication.setPrefixPath("/usr", True)
    app = QgsApplication([], False)
    app.initQgis()
    import processing
    from processing.core.Processing import Processing
    Processing.initialize()
    from rockhatch_qgis.provider import RockhatchProvider
    provider = RockhatchProvider()  # the registry does not keep the Python object alive
    QgsApplication.processingRegistry().addProvider(provider)

    work = tempfile.mkdtemp(prefix="rockhatch_render_")
    project = QgsProject.instance()
    processing.run("rockhatch:terrainfields", {"DEM": str(SAMPLE / "dem.tif"), "HILLSHADE": f"{work}/hs.tif"})
    processing.runAndLoadResults("rockhatch:rockhatching", {
        "DEM": str(SAMPLE / "dem.tif"), "FACES": f"{SAMPLE / 'partition.gpkg'}|layername=faces",
        "STYLE": args.style, "SCALE": args.scale, "OUTPUT": f"{work}/hatches.gpkg"})
    hatches = list(project.mapLayers().values())

    shade = QgsRasterLayer(f"{work}/hs.tif", "hillshade")
    renderer = QgsSingleBandGrayRenderer(shade.dataProvider(), 1)
    stretch = QgsContrastEnhancement(shade.dataProvider().dataType(1))
    stretch.setContrastEnhancementAlgorithm(QgsContrastEnhancement.StretchToMinimumMaximum)
    stretch.setMinimumValue(0)
    stretch.setMaximumValue(1)
    renderer.setContrastEnhancement(stretch)
    renderer.setOpacity(0.35)
    shade.setRenderer(renderer)

    settings = QgsMapSettings()
    settings.setLayers(hatches + [shade])
    settings.setDestinationCrs(shade.crs())
    settings.setBackgroundColor(QColor("white"))
    extent = shade.extent()
    pixels = round(extent.width() / args.scale * 1000 / 25.4 * args.dpi)
    settings.setOutputSize(QSize(pixels, round(pixels * extent.height() / extent.width())))
    settings.setOutputDpi(args.dpi)
    settings.setExtent(extent)
    job = QgsMapRendererSequentialJob(settings)
    job.start()
    job.waitForFinished()
    image = job.renderedImage()
    if args.gray:
        image = image.convertToFormat(QImage.Format_Grayscale8)
    image.save(args.output)
    print(f"{args.output}: {image.width()} x {image.height()} px, 1:{settings.scale():.0f}, "
          f"{', '.join(f'{lay.name()} {lay.featureCount()}' for lay in hatches)}")


if __name__ == "__main__":
    main()
