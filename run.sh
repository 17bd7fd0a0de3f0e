#!/usr/bin/env bash
# run.sh — one-step set-up and run on a fresh Debian 12 machine: installs the Debian packages
# polydec needs (if missing), configures and builds in ./build (Release), then
#   run.sh demo   runs `polydec demo` on a generated mesh, output in ./polydec-out
#   run.sh test   runs the whole test suite (ctest)
#   run.sh build  only builds
set -euo pipefail
cd "$(dirname "$0")"
what=${1:-demo}

packages=(build-essential cmake ninja-build pkg-config libeigen3-dev libspectra-dev libfmt-dev catch2
          libcli11-dev nlohmann-json3-dev libstb-dev libsuitesparse-dev libopenblas-dev)
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "run.sh: installing ${missing[*]}"
  sudo=""
  [ "$(id -u)" -ne 0 ] && sudo="sudo"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq "${missing[@]}" >/dev/null
fi

jobs=$(nproc 2>/dev/null || echo 2)
cmake -S . -B build -G Ninja -DCMAKE_BUILD_TYPE=Release >/dev/null
ninja -C build -j "$jobs"

case "$what" in
  demo)
    ./build/polydec demo --out polydec-out
    ;;
  test)
    ctest --test-dir build --output-on-failure -j "$jobs"
    ;;
  build) ;;
  *)
    echo "usage: run.sh [demo|test|build]" >&2
    exit 2
    ;;
esac
