"""Re-hatching faces in place (rockhatch update from the map): the faces selected in the
partition layer, or changed in its edit buffer, are hatched again into the open hatch
layers drawn from that partition, and the canvas is refreshed; Undo puts back the features
the last re-hatching replaced. While the partition layer is being edited, each re-hatching is
also a command on its undo stack, so QGIS's own Undo (Ctrl+Z) and Redo work on it.

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
from qgis.core import Qgis, QgsMessageLog, QgsProject, QgsVectorLayer
from qgis.PyQt import sip
from qgis.PyQt.QtWidgets import QUndoCommand

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
        if source and has_edits(layer):
            message = watched.get(os.path.realpath(source))
            if message:
                found.append(message.format(layer.name()))
    return found


def has_edits(layer):
    """Whether a layer has unsaved edits: QGIS's isModified() less the re-hatchings on its undo
    stack (a RehatchCommand counts as a change for QGIS, but what it did is in the files)."""
    if not layer.isEditable() or not layer.isModified():
        return False
    stack = layer.undoStack()
    return stack.index() > len(ours(layer))


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


class RehatchCommand(QUndoCommand):
    """One re-hatching on the partition layer's undo stack: QGIS's Undo (Ctrl+Z) and Redo.
    It keeps nothing of its own: its Rehatching (files, faces, undo files) belongs to the
    EditLoop, so Qt may delete the command (a save clears the stack) and the toolbar's Undo
    still has what it needs. undo() and redo() make the re-hatching undone or done and do
    nothing when it is so already: the redo() QUndoStack.push calls at once finds it done."""

    def __init__(self, loop, rehatching):
        super().__init__(rehatching.text)
        self.loop = loop
        self.rehatching = rehatching

    def undo(self):
        self.loop.from_qt(self, undo=True)

    def redo(self):
        self.loop.from_qt(self, undo=False)


def ours(layer):
    """The RehatchCommands of a layer's undo stack, done (below its index), in stack order."""
    stack = layer.undoStack()
    return [c for c in map(stack.command, range(stack.index())) if isinstance(c, RehatchCommand)]


class Rehatching:
    """One re-hatching: the faces asked for in each file (what redo asks for again) and, while
    it is done, the files it changed with their undo files."""

    def __init__(self, layer_id, faces):
        self.layer_id = layer_id
        self.faces = faces  # [(hatch file, face ids)]
        self.files = []  # [(hatch file, undo file)] while done
        self.dropped = False  # older than the last MAX_UNDO: its undo files are gone
        self.text = "Re-hatch"  # the command's text, the faces redrawn once known


class EditLoop:
    """The re-hatching of a project's partition layers into their hatch layers, with an undo
    list (the last MAX_UNDO re-hatchings done, the toolbar's Undo) and, while the partition
    layer is being edited, one RehatchCommand per re-hatching on its undo stack (QGIS's Undo).
    `report(text, level)` shows what goes wrong inside Qt's calls (QgsMessageLog by default)."""

    # Re-hatchings that can be undone, the last ones (each keeps the features it replaced).
    MAX_UNDO = 20

    def __init__(self, project=None, canvas=None, report=None):
        self.project = project or QgsProject.instance()
        self.canvas = canvas
        self.report = report or (lambda text, level: QgsMessageLog.logMessage(text, "Rock hatching", level))
        self.undo_stack = []  # Rehatchings done, the last one last
        self.commands = []  # the RehatchCommands pushed (Python keeps them: else Qt calls the base class's)
        self.watched = set()  # ids of the layers whose rollBack is watched
        self.rolling_back = set()  # ids of the layers rolling back
        self.folder = tempfile.mkdtemp(prefix="rockhatch_undo_")
        atexit.register(shutil.rmtree, self.folder, True)  # the undo files go when Python exits
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
        layer comes from this partition or a hatch layer has unsaved edits of its own. When the
        layer is being edited, pushes a RehatchCommand on its undo stack (after the re-hatchings
        of its stack that the save cleared, pushed again)."""
        files = self.hatch_files(faces)
        if not files:
            raise ValueError(f"no open hatch layer was drawn from the partition of layer '{faces.name()}' (a run "
                             "of rockhatch 0.1 or later keeps the fingerprints this needs)")
        self.refuse_edited(files)
        asked = self.faces_asked(faces)
        cleared = []
        if has_edits(faces):
            cleared = [c.rehatching for c in ours(faces)]  # the save clears the undo stack
            if not faces.commitChanges(False):
                raise ValueError(f"the edits of layer '{faces.name()}' cannot be saved: "
                                 + "; ".join(faces.commitErrors()))
        asked = {i for i in asked if faces.getFeature(i).isValid()}
        wanted = []
        for path in files:
            id_field = option(run_command(path), "--id-field")
            wanted.append((path, sorted(int(faces.getFeature(i)[id_field]) if id_field else i for i in asked)))
        rehatching = Rehatching(faces.id(), wanted)
        try:
            self.last = {}
            self.apply(rehatching, self.last, progress)
        finally:
            redrawn = set().union(*(r.redrawn_ids for r in self.last.values()))
            rehatching.text = f"Re-hatch {len(redrawn)} face(s)"
            if faces.isEditable():
                self.push(faces, [r for r in cleared if r.files] + ([rehatching] if rehatching.files else []))
        return self.last

    def apply(self, rehatching, reports, progress=None):
        """Runs a re-hatching's updates, each writing a new undo file, into `reports` ({file:
        UpdateReport}); the files that ran are done and undoable even when a later one fails."""
        try:
            for path, ids in rehatching.faces:
                self.count += 1
                undo = os.path.join(self.folder, f"undo-{self.count}.gpkg")
                reports[path] = update_file(path, ids, undo=undo, progress=progress)
                rehatching.files.append((path, undo))
        finally:
            if rehatching.files:
                self.undo_stack.append(rehatching)
            while len(self.undo_stack) > self.MAX_UNDO:
                old = self.undo_stack.pop(0)
                for _, undo in old.files:
                    os.remove(undo)
                old.files, old.dropped = [], True
            self.reload(path for path, _ in rehatching.faces)

    def push(self, faces, rehatchings):
        """One RehatchCommand per re-hatching on the layer's undo stack (their first redo() does
        nothing: they are done)."""
        self.commands = [c for c in self.commands if not sip.isdeleted(c)]
        if faces.id() not in self.watched:
            self.watched.add(faces.id())
            layer_id = faces.id()
            faces.beforeRollBack.connect(lambda: self.rolling_back.add(layer_id))
            faces.afterRollBack.connect(lambda: self.rolling_back.discard(layer_id))
        for rehatching in rehatchings:
            command = RehatchCommand(self, rehatching)
            self.commands.append(command)
            faces.undoStack().push(command)

    def undo(self):
        """The toolbar's Undo: puts back what the last re-hatching replaced, through the layer's
        undo stack when its command is the stack's last done (QGIS's Undo then moves with it);
        False when there is nothing to undo."""
        if not self.undo_stack:
            return False
        rehatching = self.undo_stack[-1]
        layer = self.project.mapLayer(rehatching.layer_id)
        stack = layer.undoStack() if isinstance(layer, QgsVectorLayer) and layer.isEditable() else None
        top = stack.command(stack.index() - 1) if stack is not None and stack.index() > 0 else None
        if isinstance(top, RehatchCommand) and top.rehatching is rehatching:
            stack.undo()  # errors go to self.report
        else:
            self.undo_rehatching(rehatching)
        return True

    def undo_rehatching(self, rehatching):
        """Restores the features the re-hatching replaced, file by file (its last file first)."""
        later = {path for r in self.undo_stack[self.undo_stack.index(rehatching) + 1:] for path, _ in r.files}
        busy = later & {path for path, _ in rehatching.files}
        if busy:
            raise ValueError(f"a later re-hatching changed '{busy.pop()}': undo it first")
        carto = module.carto()
        try:
            while rehatching.files:
                path, undo = rehatching.files[-1]
                carto.restore_faces(path, undo)
                os.remove(undo)
                rehatching.files.pop()
        finally:
            if not rehatching.files:
                self.undo_stack.remove(rehatching)
            self.reload(path for path, _ in rehatching.faces)

    def from_qt(self, command, undo):
        """A RehatchCommand's undo() or redo(), called by Qt: nothing may escape into it."""
        rehatching = command.rehatching
        try:
            if not undo:
                if not rehatching.files and not rehatching.dropped:
                    self.refuse_edited(path for path, _ in rehatching.faces)
                    self.apply(rehatching, {})
            elif rehatching.layer_id in self.rolling_back:
                pass  # the layer's edits discarded: the re-hatching is in the files, it stays
            elif rehatching.dropped or not rehatching.files:
                command.setObsolete(True)  # the stack deletes it
                if rehatching.dropped:
                    self.report(f"'{rehatching.text}' is older than the last {self.MAX_UNDO} re-hatchings: it cannot "
                                "be undone", Qgis.Warning)
            else:
                self.undo_rehatching(rehatching)
        except Exception as e:  # noqa: BLE001 (an exception must not reach Qt)
            self.report(f"{'Undo' if undo else 'Redo'} '{rehatching.text}' failed: {e}", Qgis.Critical)

    def layers_of(self, paths):
        """The project's layers that read these hatch files."""
        paths = set(paths)
        return [layer for layer in self.project.mapLayers().values()
                if gpkg_of(layer) and os.path.realpath(gpkg_of(layer)) in paths]

    def refuse_edited(self, paths):
        """ValueError when a layer reading one of these hatch files has unsaved edits (an update
        would write under them)."""
        for layer in self.layers_of(paths):
            if has_edits(layer):
                raise ValueError(f"hatch layer '{layer.name()}' has unsaved edits: save or discard them first")

    def reload(self, paths):
        """Reloads the layers that read these hatch files and repaints them."""
        for layer in self.layers_of(paths):
            layer.reload()
            layer.triggerRepaint()
        if self.canvas is not None:
            self.canvas.refreshAllLayers()
