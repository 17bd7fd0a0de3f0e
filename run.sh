#!/usr/bin/env bash
# run.sh — one-step set-up and run on a fresh Debian 12 machine: installs the Debian packages the
# chosen job needs (if missing), configures and builds in ./build (Release), then
#   run.sh demo   builds only the `polydec` program and runs `polydec demo` on a generated mesh
#                 (output in ./polydec-out)
#   run.sh test   builds everything (library, program, tests, benchmark, Python module, PETSc
#                 backend) and runs the whole test suite through ctest: C++, Python and MPI tests
#                 (python3-meshio too: the Python module's optional meshio conversion is tested)
#   run.sh build  the same build as `test`, without running the tests
# POLYDEC_PYTHON selects the Python interpreter for the module (default /usr/bin/python3, the one
# that has Debian's numpy and scipy); CI=true adds -Werror (POLYDEC_WERROR) to polydec's own code.
set -euo pipefail
cd "$(dirname "$0")"
what=${1:-demo}
case "$what" in demo | test | build) ;; *)
  echo "usage: run.sh [demo|test|build]" >&2
  exit 2
  ;;
esac

# The program and library: what the demo needs.
packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libspectra-dev libfmt-dev
          libcli11-dev nlohmann-json3-dev libstb-dev libsuitesparse-dev libopenblas-dev zlib1g-dev libexpat1-dev
          liblz4-dev liblzma-dev)
if [ "$what" != demo ]; then
  # Tests, the Python module and the PETSc/SLEPc backend with OpenMPI.
  packages+=(catch2 pybind11-dev python3-dev python3-numpy python3-scipy python3-pytest python3-venv
             python3-pip python3-setuptools python3-wheel python3-meshio
             libpetsc-real3.18-dev libslepc-real3.18-dev libopenmpi-dev openmpi-bin)
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "run.sh: installing ${missing[*]} (apt-get, a few minutes on a fresh machine)"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
if [ "$what" = demo ]; then
  options=(-DPOLYDEC_BUILD_TESTS=OFF -DPOLYDEC_BUILD_BENCH=OFF -DPOLYDEC_BUILD_PYTHON=OFF -DPOLYDEC_WITH_PETSC=OFF)
  targets=(polydec_cli)
else
  options=(-DPOLYDEC_BUILD_TESTS=ON -DPOLYDEC_BUILD_BENCH=ON -DPOLYDEC_BUILD_PYTHON=ON -DPOLYDEC_WITH_PETSC=ON
           -DPython_EXECUTABLE="${POLYDEC_PYTHON:-/usr/bin/python3}")
  targets=()
fi
# CI (CI=true) builds with -Werror on polydec's own targets: a new warning fails it.
if [ "${CI:-}" = true ]; then options+=(-DPOLYDEC_WERROR=ON); else options+=(-DPOLYDEC_WERROR=OFF); fi
echo "run.sh: configuring build/ (Release) and building ${targets[*]:-everything} on $jobs cores"
# Shared libraries (symbol table: namespace polydec only), as installed; .ci/run installs this build.
# Unity build (batches of 8 sources): a clean build of everything took 14.6 CPU-minutes here against
# about 25 one file at a time; developers who rebuild often configure their own folder without it.
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release -DBUILD_SHARED_LIBS=ON -DPOLYDEC_UNITY_BUILD=ON "${options[@]}" >/dev/null
ninja -C build -j "$jobs" "${targets[@]}"

case "$what" in
  demo) ./build/polydec demo --out polydec-out ;;
  test) ctest --test-dir build --output-on-failure -j "$jobs" ;;
esac
