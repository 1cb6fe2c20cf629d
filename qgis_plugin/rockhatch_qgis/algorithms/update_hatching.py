"""Processing algorithm "Update rock hatching": rockhatch update on a hatch GeoPackage."""
from qgis.core import (QgsProcessingException, QgsProcessingOutputNumber, QgsProcessingParameterBoolean,
                       QgsProcessingParameterFile, QgsProcessingParameterString)

from ..edit_loop import unsaved_edits, update_file
from .common import Progress, RockhatchAlgorithm


def parse_ids(text):
    """'12, 14;15' -> [12, 14, 15]."""
    ids = []
    for item in (text or "").replace(";", ",").split(","):
        if item.strip():
            try:
                ids.append(int(item))
            except ValueError:
                raise QgsProcessingException(f"FACES: '{item.strip()}' is not a face id (an integer)") from None
    return ids


class UpdateHatching(RockhatchAlgorithm):
    HATCHES, FACES, RESET = "HATCHES", "FACES", "RESET"

    def name(self):
        return "updatehatching"

    def displayName(self):  # noqa: N802
        return "Update rock hatching"

    def tags(self):
        return ["hatching", "rock", "update", "edit", "fingerprint", "cartography"]

    def initAlgorithm(self, config=None):  # noqa: N802
        self.add(QgsProcessingParameterFile(self.HATCHES, "Hatches (GeoPackage written by Rock hatching)",
                                            extension="gpkg"),
            "The hatch GeoPackage of a run (Rock hatching, or the rockhatch command): it keeps the run's options and "
            "one fingerprint per face. Updated in place, in one transaction.")
        self.add(QgsProcessingParameterString(self.FACES, "Faces to redraw as well (ids)", optional=True),
            "Face ids (face_id of the hatches) redrawn whatever their fingerprint, separated by commas. "
            "Default: only the faces whose inputs changed.")
        self.add(QgsProcessingParameterBoolean(self.RESET, "Redraw every face (drop hand edits)", False),
            "Redraws every face and drops every feature, hand edits included; also accepts a file of another "
            "program version, CRS or style. Default: off.")
        self.addOutput(QgsProcessingOutputNumber("REDRAWN", "Faces redrawn"))
        self.addOutput(QgsProcessingOutputNumber("REMOVED", "Faces removed"))
        self.addOutput(QgsProcessingOutputNumber("WRITTEN", "Features written"))
        self.addOutput(QgsProcessingOutputNumber("DELETED", "Features removed"))

    def shortHelpString(self):  # noqa: N802
        return ("Redraws, in a hatch GeoPackage written by Rock hatching (or the rockhatch command), exactly the "
                "faces whose inputs changed since: their geometry or attributes, the lines and faces within the "
                "style's reach, the DEM and rasters within the relief radius. The run's options are the ones the "
                "file keeps. The features of every other face, hand edits included, stay as they are. By default "
                "only those faces are redrawn; the ids given are redrawn as well, and Redraw every face starts "
                "again from a whole run. It is rockhatch update (docs/edit-loop.md).")

    def processAlgorithm(self, parameters, context, feedback):  # noqa: N802
        self.carto()
        path = self.parameterAsFile(parameters, self.HATCHES, context)
        faces = parse_ids(self.parameterAsString(parameters, self.FACES, context))
        reset = self.parameterAsBool(parameters, self.RESET, context)
        # Layers open in QGIS with unsaved edits of the hatches or of the partition: the update
        # would write under the one and not see the other.
        pending = unsaved_edits(path, context.project())
        if pending:
            raise QgsProcessingException("; ".join(pending))

        def update():
            try:
                return update_file(path, faces, reset=reset, progress=Progress(feedback))
            except ValueError as e:  # a file without fingerprints
                raise QgsProcessingException(str(e)) from e

        r = self.call(update)
        feedback.pushInfo(f"{r.faces} faces, {r.redrawn} redrawn ({r.appeared} new), {r.removed} removed; "
                          f"features: {r.deleted} removed, {r.written} written, {r.kept} unchanged; {r.seconds:.2f} s")
        return {"REDRAWN": r.redrawn, "REMOVED": r.removed, "WRITTEN": r.written, "DELETED": r.deleted}
