#!/usr/bin/env bash
# Installs the lidarfx QGIS Processing provider: apt-get installs QGIS and what the build needs, builds and
# installs the lidarfx program (/usr/local/bin/lidarfx) and the lidarfx Python module (install-python.sh),
# copies the plugin into the default QGIS profile of the user running it and enables it (desktop and
# qgis_process). Debian 12, as root; run again to update. Then:
#   QT_QPA_PLATFORM=offscreen qgis_process.bin list | grep lidarfx
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --gdal --qgis
bash scripts/install-python.sh   # the module behind sky view factor and cast shadows
build=build/qgis-plugin
echo "install-qgis-plugin.sh: building the lidarfx program in $build (-march=${LIDARFX_MARCH:-native})"
cmake -S . -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DLIDARFX_BUILD_TESTS=OFF -DLIDARFX_BUILD_EXAMPLES=ON \
    -DCMAKE_CXX_FLAGS="-march=${LIDARFX_MARCH:-native}" >/dev/null
cmake --build "$build" --target lidarfx_cli
# The program only: `cmake --install` would also put the library's headers and CMake package in /usr/local,
# which a QGIS user does not need and a later build could pick up instead of its own checkout.
install -D -m 755 "$build/lidarfx" /usr/local/bin/lidarfx
command -v lidarfx >/dev/null || { echo "install-qgis-plugin.sh: lidarfx is not on PATH after install" >&2; exit 1; }
profile="${QGIS_CUSTOM_CONFIG_PATH:-$HOME/.local/share/QGIS/QGIS3}/profiles/default"
plugins="$profile/python/plugins"
mkdir -p "$plugins"
rm -rf "$plugins/lidarfx_processing.new"
cp -r qgis/lidarfx_processing "$plugins/lidarfx_processing.new"
find "$plugins/lidarfx_processing.new" -name __pycache__ -prune -exec rm -rf {} +
rm -rf "$plugins/lidarfx_processing"                     # only the plugin's own folder is replaced
mv "$plugins/lidarfx_processing.new" "$plugins/lidarfx_processing"
# Enabled for the desktop (QGIS3.ini [PythonPlugins]) and for qgis_process (its own list).
# (qgis_process exits 1 with "already enabled" on a second run: that is success here.)
enabled=$(QT_QPA_PLATFORM=offscreen qgis_process.bin plugins enable lidarfx_processing 2>&1) || {
    grep -q "already enabled" <<<"$enabled" || { echo "$enabled" >&2; exit 1; }; }
ini="$profile/QGIS/QGIS3.ini"
mkdir -p "$(dirname "$ini")"
# QSettings reads and writes the file exactly as QGIS does, changing only this one key.
/usr/bin/python3 - "$ini" <<'PY'
import sys
from qgis.PyQt.QtCore import QSettings
settings = QSettings(sys.argv[1], QSettings.IniFormat)
settings.setValue("PythonPlugins/lidarfx_processing", True)
settings.sync()
PY
echo "install-qgis-plugin.sh: the lidarfx provider is installed in $plugins/lidarfx_processing and enabled:"
QT_QPA_PLATFORM=offscreen qgis_process.bin list 2>/dev/null | grep "lidarfx:" || {
    echo "install-qgis-plugin.sh: qgis_process does not list the lidarfx algorithms" >&2; exit 1; }
