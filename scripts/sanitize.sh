#!/usr/bin/env bash
# scripts/sanitize.sh — builds polydec with AddressSanitizer and UndefinedBehaviorSanitizer
# (-DPOLYDEC_SANITIZE=ON) in its own build directory and runs the test suite there (all but
# `polydec paper --quick`, see below), the `polydec` program included (the CLI tests run the
# sanitized binary). Fails on any test failure
# and on any sanitizer report. Usage: scripts/sanitize.sh [BUILD_DIR] (default build-sanitize/).
# Extra arguments for the test program go in POLYDEC_TEST_ARGS (e.g. a tag such as "[robust]");
# POLYDEC_JOBS limits the parallel compile jobs. POLYDEC_TEST_OBJECTS_FROM=BUILD (what .ci/run sets
# to the README's build/): the test program links BUILD's test objects, brought up to date there
# first, instead of compiling the test sources again (they are not instrumented either way).
set -euo pipefail

root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build-sanitize"}
log="$build/sanitize-tests.log"

# -O1 with line tables only (-g1): stack traces name file and line, and the build takes about
# half the time of -O2 -g (Eigen-heavy sources dominate the compile). POLYDEC_SANITIZE_DEBUG=-g0
# (what .ci/run sets) drops the line tables: ~5% less compiler time, reports name functions only.
# The unity build (batches of 8 files, CMakeLists.txt) compiles the Eigen templates once per batch;
# POLYDEC_UNITY=OFF turns it off.
objects=""
if [ -n "${POLYDEC_TEST_OBJECTS_FROM:-}" ]; then
  objects=$(cd "$POLYDEC_TEST_OBJECTS_FROM" && pwd)
  ninja -C "$objects" ${POLYDEC_JOBS:+-j"$POLYDEC_JOBS"} polydec_tests
  for list in polydec_tests_objects.txt polydec_plain_reference_objects.txt; do
    test -s "$objects/$list" || { echo "sanitize.sh: $objects/$list is missing or empty" >&2; exit 1; }
  done
fi
cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=None -DCMAKE_CXX_FLAGS="-O1 ${POLYDEC_SANITIZE_DEBUG:--g1}" \
  -DPOLYDEC_SANITIZE=ON -DPOLYDEC_TEST_OBJECTS_FROM="$objects" \
  -DPOLYDEC_BUILD_BENCH=OFF -DPOLYDEC_UNITY_BUILD=${POLYDEC_UNITY:-ON} >/dev/null
# Every program a ctest test runs: the test program, the `polydec` program and README.md's programs.
ninja -C "$build" ${POLYDEC_JOBS:+-j"$POLYDEC_JOBS"} polydec_cli polydec_tests polydec_readme

# Any report stops the process with a non-zero status; leaks are reported at exit. Reports also go
# to files under $reports (log_path), so that those of the `polydec` processes the CLI tests start,
# whose stderr the tests capture, are not lost.
reports="$build/sanitizer-reports"
rm -rf "$reports" && mkdir -p "$reports"
export ASAN_OPTIONS=${ASAN_OPTIONS:-detect_leaks=1:abort_on_error=1:halt_on_error=1:strict_string_checks=1:log_path=$reports/asan}
export UBSAN_OPTIONS=${UBSAN_OPTIONS:-print_stacktrace=1:halt_on_error=1:log_path=$reports/ubsan}

# The whole suite through ctest, one process per test case, as many at a time as there are cores;
# with POLYDEC_TEST_ARGS, the test program directly with those arguments.
status=0
if [ -n "${POLYDEC_TEST_ARGS:-}" ]; then
  # shellcheck disable=SC2086
  "$build/polydec_tests" $POLYDEC_TEST_ARGS 2>&1 | tee "$log" || status=$?
else
  # The layer checks (label layers) compile headers with the system compiler and run no polydec code:
  # the main build's run has them. `polydec paper --quick` (the whole evaluation, ~90 CPU-s here, the
  # suite's largest test) runs in the main build's suite only: the library code it drives is
  # sanitized by the other tests, and its own driver by tests/apps/paper's unit tests. So do the four
  # largest volume tests (55, 36, 25 and 23 CPU-s sanitized): smaller tests of the same code run
  # here (volume form spectra: `polydec spectrum --form 1|2|3 on a volume mesh`, the hexahedral ball;
  # the volume mesh complex's assembly: its other eight cases; volume heat geodesics: symmetry,
  # several sources, the CLI) (docs/robustness.md, CI time). And five convergence and spectrum
  # tests on larger meshes (7-12 s each sanitized) whose code the smaller cases beside them run:
  # the volume diamond's Franke convergence (its symmetry, scaling and squashed-cube cases), the
  # HEX SPHERE's clusters (the REGULAR SPHERE's), the unit spheres' form spectra (the mesh
  # complex's b1 count, the 2-form and the assembled 1-form eigenpairs), the mesh complex's solves
  # (its gradient, torus and bad-size case).
  skip="^polydec paper --quick|^volume form spectra on a solid torus|^volume form spectra on a jittered cube"
  skip+="|^volume mesh complex: the assembly into slots equals a triplet assembly"
  skip+="|^volume heat geodesics in a box converge"
  skip+="|^diamond \\(volume\\): 3D Franke Poisson converges"
  skip+="|^spectrum: eigenvalues cluster at l\\(l\\+1\\) with multiplicity 2l\\+1 on the HEX SPHERE"
  skip+="|^unit hexagon sphere: 1-form spectrum approaches|^unit sphere: 1- and 2-form spectra of both complexes"
  skip+="|^mesh complex: ordinary solves, harmonic dimension"
  ctest --test-dir "$build" --output-on-failure -LE layers -E "$skip" \
    -j "${POLYDEC_JOBS:-$(nproc)}" 2>&1 | tee "$log" || status=$?
fi
if [ -n "$(ls -A "$reports")" ] || grep -Eq "runtime error:|AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer" "$log"; then
  echo "sanitize.sh: sanitizer report(s):" >&2
  cat "$reports"/* >&2 || true
  exit 1
fi
if [ "$status" -ne 0 ]; then
  echo "sanitize.sh: test suite failed under sanitizers (status $status), see $log" >&2
  exit "$status"
fi
echo "sanitize.sh: test suite passed under ASan + UBSan with zero reports"
