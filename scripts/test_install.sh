#!/usr/bin/env bash
# scripts/test_install.sh — the installed package as a consumer sees it: takes the shared-library
# build of `bash run.sh test` (build/) or, when BUILD_DIR is not a shared build, configures and
# builds one there (default build-install/), installs it into a temporary prefix, checks that the
# installed headers compile on their own and that the shared libraries export nothing outside
# namespace polydec, then configures, builds and runs the three examples/
# out of tree with find_package(polydec 0.3 CONFIG), checks pkg-config, and pip-installs the Python
# module against the installation into a venv and runs the Python tests there
# (scripts/test_pip_install.sh). Exits non-zero on any failure. Usage: scripts/test_install.sh [BUILD_DIR] (default: build/ when it is a shared build,
# else build-install/).
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
build=${1:-"$root/build"}
if ! grep -Eq '^BUILD_SHARED_LIBS:[A-Z]+=ON' "$build/CMakeCache.txt" 2>/dev/null; then
  [ $# -ge 1 ] || build="$root/build-install"
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON \
    -DPOLYDEC_BUILD_TESTS=OFF -DPOLYDEC_BUILD_BENCH=OFF -DPOLYDEC_BUILD_PYTHON=OFF -DPOLYDEC_WITH_PETSC=OFF >/dev/null
fi
prefix=$(mktemp -d /tmp/polydec-prefix.XXXXXX)
work=$(mktemp -d /tmp/polydec-consumer.XXXXXX)
trap 'rm -rf "$prefix" "$work"' EXIT
jobs=$(nproc 2>/dev/null || echo 2)

echo "test_install.sh: shared libraries of $build, installed into $prefix"
ninja -C "$build" -j "$jobs" polydec_operators polydec_apps polydec_cli
cmake --install "$build" --prefix "$prefix" >/dev/null

# (the .pc files name the configured CMAKE_INSTALL_PREFIX: copies with the temporary prefix)
mkdir -p "$work/pkgconfig"
for pc in "$prefix"/lib/pkgconfig/*.pc; do sed "s#^prefix=.*#prefix=$prefix#" "$pc" > "$work/pkgconfig/$(basename "$pc")"; done

# Every installed header compiles by itself (no hidden include-order dependency, no internal header),
# with the flags of polydec.pc.
headers=$(cd "$prefix/include" && find polydec -name '*.h' | sort)
n=$(echo "$headers" | wc -l)
echo "$headers" | xargs -P "$jobs" -I{} sh -c 'printf "#include <%s>\n" "$1" | c++ -std=c++20 -fsyntax-only $2 -x c++ - ||
  { echo "test_install.sh: installed header $1 does not compile on its own" >&2; exit 255; }' _ {} \
  "$(PKG_CONFIG_PATH="$work/pkgconfig" pkg-config --cflags polydec)"
echo "test_install.sh: $n installed headers compile on their own"

# The shared libraries' dynamic symbol table: only namespace polydec (and its type information).
for lib in "$prefix"/lib*/libpolydec_operators.so "$prefix"/lib*/libpolydec_apps.so; do
  foreign=$(nm -D --defined-only "$lib" | awk '{print $3}' | c++filt | grep -v -E '^(polydec::|typeinfo for polydec::|typeinfo name for polydec::|vtable for polydec::|VTT for polydec::|non-virtual thunk to polydec::)' |
            grep -v -E '^POLYDEC_|^_init$|^_fini$' || true)
  if [ -n "$foreign" ]; then
    echo "test_install.sh: $(basename "$lib") exports symbols outside namespace polydec:" >&2
    echo "$foreign" | head -20 >&2
    exit 1
  fi
  echo "test_install.sh: $(basename "$lib"): $(nm -D --defined-only "$lib" | wc -l) exported symbols, all in namespace polydec"
done

# The three examples, each its own CMake project using only find_package(polydec).
export LD_LIBRARY_PATH="$prefix/lib:${LD_LIBRARY_PATH:-}"
# (configured and built side by side; a failed one fails the script at its wait)
pids=()
# geodesics is built for this machine's vector instructions: its distances, allocated in the
# library, are freed in the example (the package fixes Eigen's allocation on both sides).
for ex in hodge_laplacian geodesics eigenpairs; do
  native=""
  [ "$ex" = geodesics ] && native="-DCMAKE_CXX_FLAGS=-march=native"
  (cmake -S "$root/examples/$ex" -B "$work/$ex" -G Ninja -DCMAKE_BUILD_TYPE=Release -DCMAKE_PREFIX_PATH="$prefix" $native >/dev/null &&
     ninja -C "$work/$ex" >/dev/null) &
  pids+=($!)
done
for pid in "${pids[@]}"; do wait "$pid"; done
"$work/hodge_laplacian/hodge_laplacian"
"$prefix/bin/polydec" convert --help >/dev/null
"$work/eigenpairs/eigenpairs" - 9 "$work/eigenpairs.txt"
test "$(wc -l < "$work/eigenpairs.txt")" -eq 9
# Geodesics on a mesh the installed CLI writes (a generated hexagon sphere, from `polydec demo`).
"$prefix/bin/polydec" demo --out "$work/demo" >/dev/null
mesh=$(find "$work/demo" -name '*.ply' | head -1)
"$work/geodesics/geodesics" "$mesh" "$work/distance.ply" 0 7
test -s "$work/distance.ply"

# pkg-config: a consumer of the operators alone compiles and links with polydec-operators.pc.
cat > "$work/pc.cpp" <<'CPP'
#include <polydec/dec/mesh/generators.h>
#include <polydec/operators/surface/laplacian.h>
int main() {
  const polydec::Mesh mesh = polydec::quad_grid(4, 4);
  const polydec::Laplacian L = polydec::assemble_laplacian(mesh, polydec::refine(mesh));
  return (L.S * Eigen::VectorXd::Ones(mesh.n_vertices())).norm() < 1e-12 ? 0 : 1;
}
CPP
pc_flags=$(PKG_CONFIG_PATH="$work/pkgconfig" pkg-config --cflags --libs polydec-operators)
c++ -std=c++20 "$work/pc.cpp" -o "$work/pc" $pc_flags
"$work/pc"
# Built for this machine's vector instructions (-march=native: AVX/AVX-512 where there are), the
# consumer frees a vector the library allocated (L.M_lumped) with Eigen's allocation fixed by the
# .pc file's flags; without them a consumer is refused at compile time (dec/mesh/eigen_abi.h), not
# left to crash.
c++ -std=c++20 -march=native "$work/pc.cpp" -o "$work/pc_native" $pc_flags
"$work/pc_native"
if c++ -std=c++20 -march=native -fsyntax-only "$work/pc.cpp" -I"$prefix/include" $(pkg-config --cflags eigen3) 2>"$work/refused.txt"; then
  echo "test_install.sh: a consumer without -DEIGEN_MAX_ALIGN_BYTES=16 -DEIGEN_MALLOC_ALREADY_ALIGNED=0 compiled" >&2
  exit 1
fi
grep -q 'EIGEN_MALLOC_ALREADY_ALIGNED=0' "$work/refused.txt"
echo "test_install.sh: pkg-config consumer ok, also with -march=native; without the .pc file's Eigen flags refused"

# The Python module as a user installs it: pip into a --system-site-packages venv, built against
# this installation (the module's sources only), then the import and the whole pytest suite.
POLYDEC_PREFIX="$prefix" POLYDEC_CLI="$prefix/bin/polydec" bash "$root/scripts/test_pip_install.sh" "${POLYDEC_PYTHON:-/usr/bin/python3}"
echo "test_install.sh: install, headers, symbol table, 3 examples, pkg-config and the pip-installed Python module ok"
