#!/usr/bin/env bash
# The reliability tests (docs/reliability.md) alone under AddressSanitizer and
# UndefinedBehaviorSanitizer, in the sanitized build of scripts/test_sanitized.sh
# (which, without arguments, runs the whole suite so).
#
#   scripts/reliability_tests_sanitized.sh
set -euo pipefail
exec "$(dirname "$0")/test_sanitized.sh" test_api_misuse test_fp_traps test_fp_traps_source_order test_substepping test_determinism \
  test_fuzz_regressions
