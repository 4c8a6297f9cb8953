#!/usr/bin/env bash
# Builds the library's tests, the examples, the program and the Python module with Debian's Clang (14 on
# Debian 12), warnings as errors, and without GDAL and PROJ (so the program's build on a machine that lacks them is checked; the GCC
# build of scripts/test.sh covers them). It does not run the tests: CI runs them once, with GCC.

set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-deps.sh --clang --mpi --gdal --python
echo "build-clang.sh: configuring build/clang with $(clang++ --version | head -1)"
CC=clang CXX=clang++ cmake -S . -B build/clang -G Ninja -DCMAKE_BUILD_TYPE=Release \
    -DLIDARFX_BUILD_TESTS=ON -DLIDARFX_BUILD_EXAMPLES=ON -DLIDARFX_BUILD_DOC_PICTURES=ON -DLIDARFX_BUILD_PYTHON=ON \
    -DCMAKE_CXX_FLAGS=-Werror \
    -DCMAKE_DISABLE_FIND_PACKAGE_GDAL=ON -DCMAKE_DISABLE_FIND_PACKAGE_PROJ=ON >/dev/null
cmake --build build/clang
echo "build-clang.sh: every target built with clang++ (without GDAL and PROJ, as on a machine that lacks them), no warning"
