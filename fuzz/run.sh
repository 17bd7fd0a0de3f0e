#!/usr/bin/env bash
# fuzz/run.sh [SECONDS] — builds the libFuzzer targets (clang++, AddressSanitizer +
# UndefinedBehaviorSanitizer, LeakSanitizer) in their own directory, outside the CMake build,
# and runs each for SECONDS (default 60; the Matrix Market target for a quarter of it) from
# the committed seed corpus, two targets at a time (each with its own log and exit status). Exits non-zero on any crash, leak, timeout, allocation beyond
# the limit, or sanitizer report; the offending input is left in $OUT/artifacts/.
#   OUT (default build-fuzz/ beside fuzz/) may be set with POLYDEC_FUZZ_BUILD.
set -euo pipefail

SECS=${1:-60}
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
OUT=${POLYDEC_FUZZ_BUILD:-$ROOT/build-fuzz}
CXX=${POLYDEC_FUZZ_CXX:-clang++}
command -v "$CXX" >/dev/null || { echo "fuzz/run.sh: $CXX not found" >&2; exit 2; }

EIGEN=$(pkg-config --cflags-only-I eigen3 2>/dev/null || echo -I/usr/include/eigen3)
# UBSan without object-size and pointer-overflow, as the sanitizer build (CMakeLists.txt says why).
# Line tables only: reports name file and line as with -g, and the build takes 101 s instead of 134
# (docs/robustness.md). Eigen's allocation as polydec's headers require (dec/mesh/eigen_abi.h).
CFLAGS=(-std=c++20 -O1 -gline-tables-only -fno-omit-frame-pointer -fsanitize=address,undefined -fno-sanitize=object-size,pointer-overflow -fno-sanitize-recover=all
        -DEIGEN_MAX_ALIGN_BYTES=16 -DEIGEN_MALLOC_ALREADY_ALIGNED=0 -I"$ROOT" -I"$OUT/include" ${EIGEN//-I/-isystem })
mkdir -p "$OUT/objects" "$OUT/artifacts" "$OUT/include/polydec"

# Eigen/Dense and Eigen/Sparse precompiled, as the main build's precompiled headers (some sources
# rely on them for Eigen/Geometry): one for the library's objects (coverage instrumentation only,
# fuzzer-no-link) and one for the targets (fuzzer), since clang refuses a header precompiled with
# other instrumentation. ~4 s of compile saved per source.
# Written once: clang refuses a precompiled header whose source's mtime changed since.
[[ -f $OUT/eigen.h ]] || printf '#include <Eigen/Dense>\n#include <Eigen/Sparse>\n' >"$OUT/eigen.h"
for kind in fuzzer-no-link fuzzer; do
  pch="$OUT/eigen-$kind.pch"
  if [[ ! -f $pch || ${BASH_SOURCE[0]} -nt $pch ]]; then
    "$CXX" "${CFLAGS[@]}" -fsanitize="$kind" -fpch-instantiate-templates -x c++-header "$OUT/eigen.h" -o "$pch"
    rm -rf "$OUT/objects" && mkdir -p "$OUT/objects"
  fi
done
# The installed include layout <polydec/dec/...> (one root for every layer): links to the source folders.
for part in dec operators apps; do ln -sfn "$ROOT/$part" "$OUT/include/polydec/$part"; done

# The library sources the targets need, compiled with coverage instrumentation; a source is
# rebuilt when it or any library header is newer than its object.
newest_header=$(ls -t $(find "$ROOT"/dec "$ROOT"/operators -name "*.h") | head -1)
stale=()
SOURCES=(dec/io/mesh_io.cpp dec/io/obj.cpp dec/io/off.cpp dec/io/ply.cpp dec/io/matrix_market.cpp dec/mesh/mesh.cpp
         dec/surface/virtual_vertex.cpp dec/surface/refinement.cpp dec/surface/refinement_check.cpp dec/volume/refinement_check.cpp dec/surface/complex.cpp dec/surface/prolongation.cpp
         operators/surface/local_matrices.cpp operators/surface/laplacian.cpp operators/surface/gradient.cpp dec/surface/whitney.cpp
         dec/mesh/volume_mesh.cpp dec/mesh/polyhedron_builder.cpp dec/mesh/volume_cells.cpp dec/io/volume_io.cpp dec/io/ovm.cpp
         dec/io/vtk.cpp dec/io/medit.cpp dec/io/msh.cpp dec/io/meshb.cpp dec/io/virtual_positions.cpp dec/surface/virtual_lift.cpp
         dec/io/vtu.cpp)
for rel in "${SOURCES[@]}"; do
  src=$ROOT/$rel
  obj="$OUT/objects/$(basename "$(dirname "$src")")_$(basename "${src%.cpp}").o"
  if [[ ! -f $obj || $src -nt $obj || $newest_header -nt $obj ]]; then stale+=("$src:$obj"); fi
done
t0=$(date +%s)
if ((${#stale[@]})); then
  printf '%s\n' "${stale[@]}" | xargs -P 2 -I{} bash -c 'src=${1%%:*}; obj=${1#*:}; shift; "$@" -c "$src" -o "$obj"' _ {} "$CXX" "${CFLAGS[@]}" -fsanitize=fuzzer-no-link -include-pch "$OUT/eigen-fuzzer-no-link.pch"
  rm -f "$OUT/libpolydec_fuzz.a"
fi
[[ -f $OUT/libpolydec_fuzz.a ]] || ar rcs "$OUT/libpolydec_fuzz.a" "$OUT"/objects/*.o

TARGETS=(obj off ply assemble mtx ovm vtk medit msh meshb virtual_positions vtu)
# The targets, two compiles at a time (a failed compile fails the script).
stale_targets=()
for t in "${TARGETS[@]}"; do
  bin="$OUT/fuzz_$t"
  src="$ROOT/fuzz/fuzz_$t.cpp"
  if [[ ! -f $bin || $src -nt $bin || $ROOT/fuzz/fuzz_common.h -nt $bin || $ROOT/fuzz/fuzz_volume.h -nt $bin ||
        $OUT/libpolydec_fuzz.a -nt $bin ]]; then stale_targets+=("$t"); fi
done
if ((${#stale_targets[@]})); then
  printf '%s\n' "${stale_targets[@]}" | xargs -P 2 -I{} "$CXX" "${CFLAGS[@]}" -fsanitize=fuzzer -include-pch "$OUT/eigen-fuzzer.pch" \
    "$ROOT/fuzz/fuzz_{}.cpp" "$OUT/libpolydec_fuzz.a" -lfmt -lexpat -lz -llz4 -llzma -o "$OUT/fuzz_{}"
fi
echo "fuzz/run.sh: build took $(( $(date +%s) - t0 )) s"

# One target: its run's exit status goes to $OUT/fuzz_$t.status, its output to $OUT/fuzz_$t.log.
run_target() {
  local t=$1 secs=$SECS max_len=16384
  [[ $t == mtx ]] && secs=$(( SECS / 4 > 5 ? SECS / 4 : 5 ))
  [[ $t == assemble ]] && max_len=4096
  mkdir -p "$OUT/corpus/$t"
  local rc=0
  "$OUT/fuzz_$t" "$OUT/corpus/$t" "$ROOT/fuzz/corpus/$t" -dict="$ROOT/fuzz/dict/$t.dict" \
      -max_total_time="$secs" -max_len="$max_len" -timeout=10 -rss_limit_mb=1024 -malloc_limit_mb=256 \
      -artifact_prefix="$OUT/artifacts/$t-" -print_final_stats=1 >"$OUT/fuzz_$t.log" 2>&1 || rc=$?
  echo "$rc $secs" >"$OUT/fuzz_$t.status"
}

# Two at a time (the machine's two cores).
rm -f "$OUT"/fuzz_*.status
for t in "${TARGETS[@]}"; do
  while (( $(jobs -rp | wc -l) >= 2 )); do wait -n || true; done
  run_target "$t" &
done
wait

status=0
for t in "${TARGETS[@]}"; do
  log="$OUT/fuzz_$t.log"
  read -r rc secs <"$OUT/fuzz_$t.status" || { rc=1; secs='?'; }
  if [[ $rc == 0 ]]; then
    runs=$(grep -m1 -o 'stat::number_of_executed_units: *[0-9]*' "$log" | grep -o '[0-9]*$' || echo '?')
    echo "fuzz_$t: ok, $runs inputs in $secs s"
  else
    status=1
    echo "fuzz_$t: FAILED (exit $rc, log: $log)" >&2
    grep -E 'ERROR|SUMMARY|contract violated|non-finite|Test unit written' "$log" | head -20 >&2 || tail -30 "$log" >&2
  fi
done
exit $status
