#!/usr/bin/env bash
# Builds with AddressSanitizer and UndefinedBehaviorSanitizer
# (-DSPRING_MOTION_SANITIZE=ON, in build-sanitize) and runs the default test
# suite under them; given test program names (scripts/test_sanitized.sh
# test_fp_traps test_substepping ...), builds and runs only those.
# Assumes the dependencies are installed (scripts/install_dependencies.sh).
# -O1 keeps the instrumented CGAL code fast enough for CI; -g1 (line tables
# only, enough for the sanitizers' stack traces) compiles a third faster than
# full debug information. The examples are left out (the tests run deform()
# on every mesh type they use), and so is the consumer-package test: it only
# checks that an installed package configures and builds, which the plain
# run of scripts/test.sh already shows.
set -euo pipefail
cd "$(dirname "$0")/.."
cmake -S . -B build-sanitize -DCMAKE_BUILD_TYPE=RelWithDebInfo \
  -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g1" -DSPRING_MOTION_SANITIZE=ON -DSPRING_MOTION_BUILD_EXAMPLES=OFF
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:strict_string_checks=1}"
export UBSAN_OPTIONS="${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}"
if [ "$#" -eq 0 ]; then
  cmake --build build-sanitize -j"$(nproc)"
  ctest --test-dir build-sanitize -j"$(nproc)" --output-on-failure -E '^consumer_package$'
else
  cmake --build build-sanitize -j"$(nproc)" --target "$@"
  # each program's test cases are registered as '<program>:<test case>'
  ctest --test-dir build-sanitize -j"$(nproc)" --output-on-failure -R "^($(IFS='|'; echo "$*")):"
fi
