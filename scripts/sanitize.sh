#!/usr/bin/env bash
# scripts/sanitize.sh — builds polydec with AddressSanitizer and UndefinedBehaviorSanitizer
# (-DPOLYDEC_SANITIZE=ON) in its own build directory and runs the whole test suite there, the
# `polydec` program included (the CLI tests run the sanitized binary). Fails on any test failure
# and on any sanitizer report. Usage: scripts/sanitize.sh [BUILD_DIR] (default build-sanitize/).
# Extra arguments for the test program go in POLYDEC_TEST_ARGS (e.g. a tag such as "[robust]").
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build-sanitize"}
log="$build/sanitize-tests.log"

cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=RelWithDebInfo -DPOLYDEC_SANITIZE=ON \
  -DPOLYDEC_BUILD_BENCH=OFF >/dev/null
ninja -C "$build" polydec_cli polydec_tests

# Any report stops the process with a non-zero status; leaks are reported at exit.
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:halt_on_error=1:strict_string_checks=1}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1}

status=0
# shellcheck disable=SC2086
"$build/polydec_tests" ${POLYDEC_TEST_ARGS:-} 2>&1 | tee "$log" || status=$?
if grep -Eq "runtime error:|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer" "$log"; then
  echo "sanitize.sh: sanitizer report(s) in $log" >&2
  exit 1
fi
if [ "$status" -ne 0 ]; then
  echo "sanitize.sh: test suite failed under sanitizers (status $status), see $log" >&2
  exit "$status"
fi
echo "sanitize.sh: whole test suite passed under ASan + UBSan with zero reports"
