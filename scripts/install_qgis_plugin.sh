#!/usr/bin/env bash
# Installs the QGIS plugin qgis_plugin/rockhatch_qgis (the "Rock hatching" Processing
# provider) into a QGIS 3 profile and enables it, or packs it as a zip for the Plugin Manager.
#
#   scripts/install_qgis_plugin.sh [--profile NAME] [--profiles-path DIR] [--copy]
#                                  [--module-path DIR]
#   scripts/install_qgis_plugin.sh --zip OUT.zip
#
#   --profile NAME        profile to install into (default: default)
#   --profiles-path DIR   folder holding the profiles (default: $QGIS_CUSTOM_CONFIG_PATH/profiles
#                         when that variable is set, else ~/.local/share/QGIS/QGIS3/profiles)
#   --copy                copy the plugin folder instead of symlinking it
#   --module-path DIR     folder of the rockhatch Python module (e.g. build/python), saved in the
#                         profile as the setting rockhatch/python_path; not needed after
#                         scripts/setup.sh, which makes the module importable for /usr/bin/python3,
#                         nor for an installed rockhatch (share/rockhatch/qgis_plugin holds this
#                         script; the prefix's module is used when Python cannot import one)
#   --zip OUT.zip         write a zip installable with Plugins > Manage and Install Plugins >
#                         Install from ZIP, and install nothing
set -euo pipefail
HERE="$(cd "$(dirname "$0")" && pwd)"
NAME=rockhatch_qgis
installed_module=""
if [ -d "$HERE/$NAME" ]; then
  # Installed: PREFIX/share/rockhatch/qgis_plugin/{this script,rockhatch_qgis}.
  PLUGIN="$HERE/$NAME"
  prefix="$(cd "$HERE/../../.." && pwd)"
  for d in "$prefix"/lib/python3/dist-packages "$prefix"/lib/python3.*/dist-packages; do
    [ -f "$d/rockhatch/__init__.py" ] && installed_module="$d" && break
  done
else
  # In the clone: scripts/ beside qgis_plugin/.
  PLUGIN="$(cd "$HERE/.." && pwd)/qgis_plugin/$NAME"
fi

profile=default
profiles=""
copy=0
module_path=""
zip=""
while [ $# -gt 0 ]; do
  case "$1" in
    --profile) profile="$2"; shift 2 ;;
    --profiles-path) profiles="$2"; shift 2 ;;
    --copy) copy=1; shift ;;
    --module-path) module_path="$(cd "$2" && pwd)"; shift 2 ;;
    --zip) zip="$2"; shift 2 ;;
    -h|--help) sed -n '2,19p' "$0" | sed 's/^# \{0,1\}//'; exit 0 ;;
    *) echo "install_qgis_plugin: unknown option '$1' (see --help)" >&2; exit 2 ;;
  esac
done

# An installed plugin uses its prefix's module when Python does not import one already.
if [ -z "$module_path" ] && [ -n "$installed_module" ] && \
   ! /usr/bin/python3 -c "import rockhatch" 2>/dev/null; then
  module_path="$installed_module"
fi

if [ -n "$zip" ]; then
  /usr/bin/python3 - "$PLUGIN" "$zip" <<'EOF'
import os, sys, zipfile
src, out = sys.argv[1], sys.argv[2]
with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
    for folder, dirs, files in os.walk(src):
        dirs[:] = sorted(d for d in dirs if d != "__pycache__")
        for f in sorted(files):
            if not f.endswith(".pyc"):
                path = os.path.join(folder, f)
                z.write(path, os.path.join("rockhatch_qgis", os.path.relpath(path, src)))
EOF
  echo "install_qgis_plugin: wrote $zip (Plugins > Manage and Install Plugins > Install from ZIP)"
  exit 0
fi

if [ -z "$profiles" ]; then
  if [ -n "${QGIS_CUSTOM_CONFIG_PATH:-}" ]; then
    profiles="$QGIS_CUSTOM_CONFIG_PATH/profiles"
  else
    profiles="$HOME/.local/share/QGIS/QGIS3/profiles"
  fi
fi
dir="$profiles/$profile"
plugins="$dir/python/plugins"
mkdir -p "$plugins" "$dir/QGIS"
rm -rf "${plugins:?}/$NAME"
if [ "$copy" -eq 1 ]; then
  cp -r "$PLUGIN" "$plugins/$NAME"
  find "$plugins/$NAME" -name __pycache__ -prune -exec rm -rf {} +
else
  ln -s "$PLUGIN" "$plugins/$NAME"
fi

# Enable it ([PythonPlugins] rockhatch_qgis=true), written by Qt's own QSettings so that the
# rest of the profile's QGIS3.ini is kept as QGIS wrote it.
/usr/bin/python3 - "$dir/QGIS/QGIS3.ini" "$module_path" <<'EOF'
import sys
from PyQt5.QtCore import QSettings
s = QSettings(sys.argv[1], QSettings.IniFormat)
s.setValue("PythonPlugins/rockhatch_qgis", True)
if sys.argv[2]:
    s.setValue("rockhatch/python_path", sys.argv[2])
s.sync()
if s.status() != QSettings.NoError:
    sys.exit(f"install_qgis_plugin: cannot write {sys.argv[1]}")
EOF
echo "install_qgis_plugin: $plugins/$NAME -> $PLUGIN ($([ "$copy" -eq 1 ] && echo copy || echo symlink)), enabled in profile '$profile'"
if ! /usr/bin/python3 -c "import rockhatch" 2>/dev/null && [ -z "$module_path" ]; then
  echo "install_qgis_plugin: warning: /usr/bin/python3 cannot import rockhatch: run scripts/setup.sh or pass --module-path build/python" >&2
fi
