"""Finds the rockhatch Python module (the project's bindings) for the algorithms.

Where it looks, first match wins:
  1. the folders of the ROCKHATCH_PYTHONPATH environment variable (os.pathsep-separated);
  2. the folder of the QGIS setting rockhatch/python_path (scripts/install_qgis_plugin.sh
     --module-path writes it into the profile);
  3. the interpreter's own path: scripts/setup.sh writes a rockhatch.pth naming its build.
"""
import importlib
import os
import sys

from qgis.core import Qgis, QgsMessageLog, QgsSettings

SETTING = "rockhatch/python_path"
ENV = "ROCKHATCH_PYTHONPATH"

_carto = None
_error = None


def extra_paths():
    paths = [p for p in os.environ.get(ENV, "").split(os.pathsep) if p]
    setting = QgsSettings().value(SETTING, "", type=str)
    if setting:
        paths.append(setting)
    return paths


def carto():
    """The rockhatch.carto module; ImportError with what to do when it cannot be imported."""
    global _carto, _error
    if _carto is not None:
        return _carto
    for p in reversed(extra_paths()):
        if p not in sys.path:
            sys.path.insert(0, p)
    try:
        _carto = importlib.import_module("rockhatch.carto")
        _error = None
        return _carto
    except ImportError as e:
        _error = (f"the rockhatch Python module cannot be imported ({e}); build it with scripts/setup.sh, "
                  f"or name its folder (build/python) in the {ENV} environment variable or the QGIS setting "
                  f"{SETTING} (scripts/install_qgis_plugin.sh --module-path)")
        QgsMessageLog.logMessage(_error, "Rock hatching", Qgis.Critical)
        raise ImportError(_error) from e


def available():
    """(True, "") when the module imports, else (False, the message)."""
    try:
        carto()
        return True, ""
    except ImportError as e:
        return False, str(e)


def rockhatch_error():
    """The exception class of pipeline errors."""
    return importlib.import_module("rockhatch").RockhatchError
