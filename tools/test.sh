#!/usr/bin/env bash
# Installs what is missing, builds everything and runs the whole test suite. .ci/run runs this.
#  1. build/ (Release): CTest with GoogleTest, the Khronos glTF-Validator on the generated
#     scenes, and fuzz.gltf_loader: the libFuzzer target (built with clang in build-fuzz/)
#     for TESSERA_FUZZ_SECONDS (60).
#  2. build-asan/: the whole suite again under AddressSanitizer + UndefinedBehaviorSanitizer.
#  3. build-tsan/: the scheduler, determinism, resume and call-watch tests under ThreadSanitizer
#     (tests/CMakeLists.txt says which: the build builds no others).
# Arguments go to the first CTest run (e.g. -R Resume). TESSERA_SANITIZERS=0 skips 2 and 3
# (a quicker local run). docs/reliability.md has the timings.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
build="${TESSERA_BUILD_DIR:-$root/build}"
jobs=$(nproc)
"$root/third_party_config/install-deps.sh"

# Configures (once) and builds one directory: configure_and_build DIR [TARGET] -- CMAKE_ARGS...
configure_and_build() {
  local dir=$1 target=$2
  shift 3
  [[ -f "$dir/build.ninja" ]] || cmake -S "$root" -B "$dir" -G Ninja "$@"
  cmake --build "$dir" ${target:+--target "$target"}
}

# -O1 with line tables (-g1): sanitizer reports with file and line, at a tolerable speed; full
# debug information made the sanitizer builds a fifth slower.
sanitizer_flags=(-DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g1")

configure_and_build "$build" "" -- -DCMAKE_BUILD_TYPE=Release
if command -v clang++ >/dev/null 2>&1; then
  configure_and_build "$build-fuzz" tessera_fuzz_gltf -- -DCMAKE_CXX_COMPILER=clang++ "${sanitizer_flags[@]}" \
    "-DTESSERA_SANITIZE=address;undefined" -DTESSERA_FUZZ=ON -DTESSERA_BUILD_TESTS=OFF
else
  echo "tessera: clang++ not found: the fuzz test will be skipped" >&2
fi
(cd "$build" && ctest --output-on-failure -j "$jobs" "$@")

[[ "${TESSERA_SANITIZERS:-1}" == 0 ]] && exit 0
# The validator and the fuzzer check files, not tessera's code: not run again.
configure_and_build "$build-asan" "" -- "${sanitizer_flags[@]}" "-DTESSERA_SANITIZE=address;undefined"
# tools/lsan.supp: fontconfig's process-long caches (the charts' font), not tessera's.
(cd "$build-asan" && LSAN_OPTIONS="suppressions=$root/tools/lsan.supp ${LSAN_OPTIONS:-}" \
  ctest --output-on-failure -j "$jobs" -E '^(gltf_validator|fuzz)\.')

# clang: it builds this twice as fast as g++. TBB's own synchronisation is not instrumented;
# tools/tsan.supp says what that hides and why nothing of tessera's is lost.
configure_and_build "$build-tsan" tessera_tests -- -DCMAKE_CXX_COMPILER=clang++ "${sanitizer_flags[@]}" \
  -DTESSERA_SANITIZE=thread
(cd "$build-tsan" && TSAN_OPTIONS="suppressions=$root/tools/tsan.supp halt_on_error=1 ${TSAN_OPTIONS:-}" \
  ctest --output-on-failure -j "$jobs" -L gtest)
