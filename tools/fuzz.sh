#!/usr/bin/env bash
# Runs the libFuzzer target over scene loading for a bounded time.
#   tools/fuzz.sh FUZZER [SECONDS]      (default 60; CTest's fuzz.gltf_loader runs it so)
# Seeds: tests/data, tests/data/malformed, tests/data/fuzz-regressions and the shipped scenes
# under 64 KiB. The growing corpus is kept in build-fuzz/corpus between runs. A crash, a
# sanitizer report, a leak or a hang (> 10 s on one input) fails the run and leaves the input
# as build-fuzz/artifacts/crash-* (or leak-*, timeout-*): fix it, then copy the file into
# tests/data/fuzz-regressions/ so fuzz_regression_test keeps it fixed. Exit 77 (CTest: skipped)
# when the fuzzer was not built because clang is missing.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
fuzzer=${1:?usage: tools/fuzz.sh FUZZER [SECONDS]}
seconds=${2:-60}
if [[ ! -x "$fuzzer" ]]; then
  echo "fuzz: $fuzzer was not built (no clang++?): skipped" >&2
  exit 77
fi
work=$(cd "$(dirname "$fuzzer")/.." && pwd)
mkdir -p "$work/corpus" "$work/artifacts" "$work/seeds"
find "$root/scenes" -type f \( -name '*.gltf' -o -name '*.glb' \) -size -64k -exec cp {} "$work/seeds/" \;
export TESSERA_FUZZ_BASE_DIR="$root/tests/data"
# ASan's leak checker needs ptrace-like rights some sandboxes lack; a leak is still found
# by the ASan test suite's own runs.
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}"
exec "$fuzzer" -max_total_time="$seconds" -max_len=65536 -timeout=10 -rss_limit_mb=2048 \
  -print_final_stats=1 -artifact_prefix="$work/artifacts/" \
  "$work/corpus" "$root/tests/data" "$root/tests/data/malformed" "$root/tests/data/conformance" "$root/tests/data/fuzz-regressions" "$work/seeds"
