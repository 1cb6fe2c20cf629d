"""Re-hatching faces in place (rockhatch update from the map): the faces selected in the
partition layer, or changed in its edit buffer, are hatched again into the open hatch
layers drawn from that partition, and the canvas is refreshed; Undo puts back the features
the last re-hatching replaced.

The work is carto.update, the command's own (rockhatch update): the hatch GeoPackage keeps
one fingerprint per face and the options of the run that wrote it (metadata item
RH_RUN_COMMAND), so a face whose inputs changed is redrawn even when it is not selected,
and the features of every other face (hand edits included) stay as they are.
"""
import atexit
import os
import shutil
import tempfile

from osgeo import ogr
from qgis.core import QgsProject, QgsVectorLayer

from . import module

FACES_TABLE = "rockhatch_faces"
COMMAND_KEY = "RH_RUN_COMMAND"


def gpkg_of(layer):
    """The file an OGR vector layer reads, or None."""
    if not isinstance(layer, QgsVectorLayer) or layer.providerType() != "ogr":
        return None
    return layer.source().split("|")[0]


def run_command(gpkg):
    """The arguments of the run that wrote a hatch GeoPackage (without its outputs), or None
    when the file keeps no fingerprints."""
    ds = ogr.Open(gpkg)
    if ds is None or ds.GetLayerByName(FACES_TABLE) is None:
        return None
    command = ds.GetMetadataItem(COMMAND_KEY)
    return command.split("\n") if command else None


def option(args, name, default=None):
    return args[args.index(name) + 1] if name in args else default


def unsaved_edits(path, project=None):
    """What an update of the hatch GeoPackage `path` would not see or would write under:
    the layers of the project with unsaved edits that read this file, or the partition file
    of the run that wrote it. One message per layer."""
    project = project or QgsProject.instance()
    args = run_command(path) or []
    partition = option(args, "--partition")
    watched = {os.path.realpath(path): "hatch layer '{}' has unsaved edits: save or discard them first"}
    if partition and partition != "auto":
        watched[os.path.realpath(partition)] = ("partition layer '{}' has unsaved edits, which the update would not "
                                                "see: save them first (the toolbar's \"Re-hatch the selected or edited faces\" saves them)")
    found = []
    for layer in project.mapLayers().values():
        source = gpkg_of(layer)
        if source and layer.isEditable() and layer.isModified():
            message = watched.get(os.path.realpath(source))
            if message:
                found.append(message.format(layer.name()))
    return found


def update_file(path, faces=(), reset=False, undo="", progress=None):
    """carto.update on a hatch GeoPackage with the options of the run that wrote it: redraws
    the faces whose inputs changed, and `faces` (face ids), or every face with reset."""
    carto = module.carto()
    args = run_command(path)
    if args is None:
        raise ValueError(f"'{path}' keeps no fingerprints (written by a tiled run or an older version): run "
                         "Rock hatching again to write them")
    update = carto.parse_update_command_line(args + ["-q", "-o", path])
    options = update.command.options
    options.overwrite = True
    if update.command.script:
        options.custom_style = carto.load_style(update.command.script)
    return carto.update_options(options, progress, reset=reset, faces=faces, undo=undo)


class EditLoop:
    """The re-hatching of a project's partition layer into its hatch layers, with an undo
    stack (one entry per re-hatching: the files it changed and their undo files)."""

    # Re-hatchings that can be undone, the last ones (each keeps the features it replaced).
    MAX_UNDO = 20

    def __init__(self, project=None, canvas=None):
        self.project = project or QgsProject.instance()
        self.canvas = canvas
        self.undo_stack = []
        self.folder = tempfile.mkdtemp(prefix="rockhatch_undo_")
        atexit.register(shutil.rmtree, self.folder, True)  # the undo files go with the session
        self.count = 0
        self.last = {}  # the last re-hatching's {file: UpdateReport}

    def hatch_files(self, faces):
        """{hatch GeoPackage: [its open layers]} of the files drawn from the partition layer's file."""
        source = gpkg_of(faces)
        if source is None:
            raise ValueError(f"layer '{faces.name()}' is not read from a file OGR reads: it cannot be a partition "
                             "a run read")
        files = {}
        for layer in self.project.mapLayers().values():
            path = gpkg_of(layer)
            if path and layer is not faces:
                files.setdefault(os.path.realpath(path), []).append(layer)
        out = {}
        for path, layers in files.items():
            args = run_command(path)
            partition = option(args or [], "--partition")
            if partition and os.path.exists(partition) and os.path.samefile(partition, source):
                out[path] = layers
        return out

    def faces_asked(self, faces):
        """Feature ids of the faces selected or changed in the edit buffer."""
        ids = set(faces.selectedFeatureIds())
        buffer = faces.editBuffer()
        if buffer is not None:
            ids |= set(buffer.changedGeometries().keys()) | set(buffer.changedAttributeValues().keys())
        return {i for i in ids if i >= 0}

    def rehatch(self, faces, progress=None):
        """Saves the partition layer's edits (the run reads its file), then updates every hatch
        file drawn from it, redrawing the faces asked for and every face whose inputs changed;
        returns {file: UpdateReport}. Raises ValueError (nothing changed) when no open hatch
        layer comes from this partition or a hatch layer has unsaved edits of its own."""
        files = self.hatch_files(faces)
        if not files:
            raise ValueError(f"no open hatch layer was drawn from the partition of layer '{faces.name()}' (a run "
                             "of rockhatch 0.1 or later keeps the fingerprints this needs)")
        for layers in files.values():
            for layer in layers:
                if layer.isEditable() and layer.isModified():
                    raise ValueError(f"hatch layer '{layer.name()}' has unsaved edits: save or discard them first")
        asked = self.faces_asked(faces)
        if faces.isEditable() and faces.isModified() and not faces.commitChanges(False):
            raise ValueError(f"the edits of layer '{faces.name()}' cannot be saved: " + "; ".join(faces.commitErrors()))
        asked = {i for i in asked if faces.getFeature(i).isValid()}
        reports, done = {}, []
        try:
            for path in files:
                id_field = option(run_command(path), "--id-field")
                ids = sorted(int(faces.getFeature(i)[id_field]) if id_field else i for i in asked)
                self.count += 1
                undo = os.path.join(self.folder, f"undo-{self.count}.gpkg")
                reports[path] = update_file(path, ids, undo=undo, progress=progress)
                done.append((path, undo))
        finally:
            self.last = reports
            if done:
                self.undo_stack.append(done)
            while len(self.undo_stack) > self.MAX_UNDO:
                for _, undo in self.undo_stack.pop(0):
                    os.remove(undo)
            self.reload(files)
        return reports

    def undo(self):
        """Puts back what the last re-hatching replaced; False when there is nothing to undo."""
        if not self.undo_stack:
            return False
        carto = module.carto()
        entries = self.undo_stack.pop()
        for path, undo in reversed(entries):
            carto.restore_faces(path, undo)
            os.remove(undo)
        self.reload({path: [layer for layer in self.project.mapLayers().values()
                            if gpkg_of(layer) and os.path.realpath(gpkg_of(layer)) == path]
                     for path, _ in entries})
        return True

    def reload(self, files):
        for layers in files.values():
            for layer in layers:
                layer.reload()
                layer.triggerRepaint()
        if self.canvas is not None:
            self.canvas.refreshAllLayers()
