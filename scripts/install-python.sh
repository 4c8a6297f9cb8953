#!/usr/bin/env bash
# Builds the lidarfx Python module (Release) and installs it for Debian's python3, in
# /usr/local/lib/python3.X/dist-packages/lidarfx. Debian 12, as root; installs what it needs with apt-get
# (a compiler, CMake, Python headers, NumPy, pybind11, pytest). Then: /usr/bin/python3 -c "import lidarfx".
# The module is compiled for this machine's CPU (-march=native: AVX2/AVX-512 where present, about 5x faster
# kernels than a generic x86-64 build); LIDARFX_MARCH=x86-64-v3 (or x86-64) builds one to copy to other machines.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --python
python=/usr/bin/python3   # Debian's interpreter, even when a version manager's python3 comes first on PATH
build=build/python-install
echo "install-python.sh: building the module in $build (-march=${LIDARFX_MARCH:-native})"
march="${LIDARFX_MARCH:-native}"
cmake -S python -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DPython3_EXECUTABLE="$python" \
    -DCMAKE_CXX_FLAGS="-march=$march" >/dev/null
cmake --build "$build"
cmake --install "$build" | grep -v "^-- Up-to-date" || true
where=$(cd / && "$python" -c "import lidarfx, os; print(os.path.dirname(lidarfx.__file__))")
echo "install-python.sh: lidarfx installed in $where"
echo "install-python.sh: try  $python -c \"import lidarfx; help(lidarfx.extract_waterbodies)\""
if [ "$(command -v python3)" != "$python" ]; then
    echo "install-python.sh: note: 'python3' on this PATH is $(command -v python3), not Debian's; use $python"
fi
