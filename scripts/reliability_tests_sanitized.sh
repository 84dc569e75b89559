#!/usr/bin/env bash
# Builds and runs the reliability tests (issue 7) under AddressSanitizer and
# UndefinedBehaviorSanitizer without building the whole library: only the
# sources these tests use are compiled (-O1 -g), into build-asan/manual/.
# The full sanitized suite is -DSPRING_MOTION_SANITIZE=ON (scripts/test_sanitized.sh).
#
#   scripts/reliability_tests_sanitized.sh
set -euo pipefail
cd "$(dirname "$0")/.."
out=build-asan/manual
mkdir -p "$out"
flags=(-std=c++17 -O1 -g -fsanitize=address,undefined -fno-omit-frame-pointer -fno-sanitize-recover=undefined
       -fopenmp -Iinclude -I/usr/include/eigen3 "-DSPRING_MOTION_TEST_DATA_DIR=\"$PWD/tests/data\"")
# REUSE=1 keeps existing objects (faster; stale if headers changed since)
obj() { [ "${REUSE:-0}" = 1 ] && [ -f "$out/$2.o" ] || g++ "${flags[@]}" -c "$1" -o "$out/$2.o"; }
objs=()
for s in tests/catch_main.cpp src/naca0012_mesh_2.cpp src/report_json.cpp src/io/Token_reader.cpp src/io/Raw_mesh.cpp \
         src/io/read_medit.cpp src/io/read_gmsh.cpp src/io/read_mesh.cpp src/io/write_mesh.cpp; do
  name="$(basename "${s%.cpp}")"
  obj "$s" "$name"
  objs+=("$out/$name.o")
done
status=0
for t in test_api_misuse test_fp_traps test_substepping test_determinism test_fuzz_regressions; do
  obj "tests/$t.cpp" "$t"
  g++ "${flags[@]}" "$out/$t.o" "${objs[@]}" -o "$out/$t" -lgmp -lmpfr
  echo "== $t"
  "$out/$t" | tail -n 2 || status=1
done
exit $status
