#!/usr/bin/env bash
# Builds the libFuzzer targets (clang++-14, ASan + UBSan) and runs each for
# SECONDS (default 600), one after the other, from its seed corpus.
#
#   fuzz/run.sh [SECONDS] [TARGET...]        TARGET: read_medit read_gmsh read_gmsh_binary read_su2 deform
#
# Build dir: $FUZZ_BUILD_DIR (default build-fuzz beside fuzz/). New corpus
# entries go to $FUZZ_BUILD_DIR/corpus/<target> (the seeds in fuzz/corpus
# are only read); crashes to $FUZZ_BUILD_DIR/artifacts/<target>/; each run's
# log, whose last lines give executions and coverage, to
# $FUZZ_BUILD_DIR/logs/<target>.log. Exit status 1 if any target found a crash.
set -uo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
seconds="${1:-600}"
shift || true
targets=("$@")
[ ${#targets[@]} -gt 0 ] || targets=(read_medit read_gmsh read_gmsh_binary read_su2 deform)
build="${FUZZ_BUILD_DIR:-$here/../build-fuzz}"
# The library's own dependencies, then clang 14 with libFuzzer (Debian packages).
bash "$here/../scripts/install_dependencies.sh" || exit 2
if ! compgen -G "/usr/lib/llvm-14/lib/clang/*/lib/linux/libclang_rt.fuzzer-x86_64.a" >/dev/null || ! command -v clang++-14 >/dev/null; then
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -q --no-install-recommends clang-14 libclang-rt-14-dev || exit 2
fi
if [ ! -f "$build/CMakeCache.txt" ]; then
  CXX="${CXX:-clang++-14}" cmake -S "$here" -B "$build" -DCMAKE_BUILD_TYPE=RelWithDebInfo || exit 2
fi
cmake --build "$build" -j"${JOBS:-1}" --target $(printf 'fuzz_%s ' "${targets[@]}") || exit 2
status=0
for t in "${targets[@]}"; do
  mkdir -p "$build/corpus/$t" "$build/artifacts/$t" "$build/logs"
  echo "== fuzz_$t for ${seconds} s"
  # -rss_limit_mb: a reader that believes a huge count in a hostile file and
  # allocates for it is a finding, not a machine-wide out-of-memory.
  "$build/fuzz_$t" "$build/corpus/$t" "$here/corpus/$t" -max_total_time="$seconds" -rss_limit_mb=2048 \
    -timeout=20 -print_final_stats=1 -artifact_prefix="$build/artifacts/$t/" > "$build/logs/$t.log" 2>&1
  rc=$?
  grep -E "^(stat::number_of_executed_units|stat::peak_rss_mb|Done)|cov: " "$build/logs/$t.log" | tail -4
  if [ $rc -ne 0 ]; then
    echo "fuzz_$t: finding, see $build/logs/$t.log and $build/artifacts/$t/"
    status=1
  fi
done
exit $status
