"""What both algorithms share: the rockhatch module, file paths of layers, progress, errors."""
from qgis.core import (QgsProcessingAlgorithm, QgsProcessingException, QgsProcessingParameterDefinition,
                       QgsProcessingUtils, QgsRasterFileWriter, QgsRasterPipe)

from .. import module
from ..icon import WithIcon


class RockhatchAlgorithm(WithIcon, QgsProcessingAlgorithm):
    """Base of the provider's algorithms."""

    def createInstance(self):  # noqa: N802 (QGIS's names)
        return type(self)()

    def group(self):
        return ""

    def groupId(self):  # noqa: N802
        return ""

    def canExecute(self):  # noqa: N802
        return module.available()

    def add(self, param, help_text, advanced=False):
        """Adds a parameter with its help (the dialog and `qgis_process help` show it)."""
        param.setHelp(help_text)
        if advanced:
            param.setFlags(param.flags() | QgsProcessingParameterDefinition.FlagAdvanced)
        self.addParameter(param)

    def carto(self):
        """rockhatch.carto, or a QgsProcessingException saying how to make it importable."""
        try:
            return module.carto()
        except ImportError as e:
            raise QgsProcessingException(str(e)) from e

    def raster_path(self, parameters, name, context, feedback):
        """A GDAL-readable path of a raster parameter ('' when it is not given): the layer's
        own source for GDAL layers, else a GeoTIFF copy in the temporary folder."""
        if parameters.get(name) in (None, ""):
            return ""
        layer = self.parameterAsRasterLayer(parameters, name, context)
        if layer is None:
            raise QgsProcessingException(f"{name}: '{parameters.get(name)}' is not a raster layer QGIS can read")
        if layer.providerType() == "gdal":
            return layer.source()
        path = QgsProcessingUtils.generateTempFilename(f"{name.lower()}.tif")
        feedback.pushInfo(f"{name}: writing the {layer.providerType()} layer to {path}")
        provider = layer.dataProvider()
        pipe = QgsRasterPipe()
        pipe.set(provider.clone())
        writer = QgsRasterFileWriter(path)
        if writer.writeRaster(pipe, provider.xSize(), provider.ySize(), provider.extent(), provider.crs()) != 0:
            raise QgsProcessingException(f"{name}: cannot write the layer to {path}")
        return path

    def call(self, fn, *args, **kwargs):
        """Calls the pipeline; its errors (and a style script's) become QgsProcessingException
        with their one-line message."""
        try:
            return fn(*args, **kwargs)
        except QgsProcessingException:
            raise
        except RuntimeError as e:  # RockhatchError is a RuntimeError with the command's exit code
            raise QgsProcessingException(str(e)) from e
        except Exception as e:  # an error raised by a Python style script
            raise QgsProcessingException(f"{type(e).__name__}: {e}") from e


class Progress:
    """The pipeline's progress(fraction, stage) callback on a QgsProcessingFeedback: percent,
    stage text (once per stage), and False once the user cancelled (the pipeline stops)."""

    def __init__(self, feedback, start=0.0, span=100.0):
        self.feedback, self.start, self.span = feedback, start, span
        self.stage = None

    def __call__(self, fraction, stage):
        if stage != self.stage:
            self.stage = stage
            self.feedback.setProgressText(stage)
        self.feedback.setProgress(self.start + self.span * min(max(fraction, 0.0), 1.0))
        return not self.feedback.isCanceled()
