#!/usr/bin/env bash
# Installs the dependencies, builds everything and runs the whole test suite.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install_dependencies.sh
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DSPRING_MOTION_BUILD_PYTHON=ON -DSPRING_MOTION_WARNINGS_AS_ERRORS="${SPRING_MOTION_WARNINGS_AS_ERRORS:-OFF}"
cmake --build build -j"$(nproc)"
ctest --test-dir build -j"$(nproc)" --output-on-failure
