#!/usr/bin/env bash
# Installs the Debian packages lidarfx needs (only those missing).
# Usage: install-deps.sh [--peers] [--gdal] [--mpi] [--clang] [--python] [--qgis]
set -euo pipefail
packages=(cmake ninja-build g++ clang-format time python3 libeigen3-dev libboost-dev doctest-dev libbenchmark-dev zlib1g-dev)
for arg in "$@"; do
    case "$arg" in
        --peers) packages+=(python3-numpy python3-scipy python3-opencv) ;;
        --gdal) packages+=(libgdal-dev libproj-dev gdal-bin python3-gdal) ;;  # GeoTIFF, OGR vectors, PROJ; gdalinfo in tests
        --clang) packages+=(clang lld) ;;
        --mpi) packages+=(libopenmpi-dev openmpi-bin) ;;
        --python) packages+=(python3-dev python3-numpy python3-pytest python3-pybind11 pybind11-dev python3-matplotlib python3-gdal) ;;  # module, example
        --qgis) packages+=(qgis python3-qgis python3-gdal) ;;  # the QGIS Processing provider and its headless test
    esac
done
missing=()
for p in "${packages[@]}"; do
    dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
    echo "installing: ${missing[*]}"
    if [ "$(id -u)" -ne 0 ]; then sudo=sudo; else sudo=; fi
    $sudo apt-get update -qq
    DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
