#!/usr/bin/env bash
# Installs what is missing, builds everything and runs the whole test suite (CTest with
# GoogleTest, plus the Khronos glTF-Validator on the generated scenes). .ci/run runs this.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${TESSERA_BUILD_DIR:-$root/build}"
"$root/third_party_config/install-deps.sh"
if [[ ! -f "$build/build.ninja" ]]; then
  cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release
fi
cmake --build "$build"
cd "$build"
ctest --output-on-failure -j "$(nproc)" "$@"
