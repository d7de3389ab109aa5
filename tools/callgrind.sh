#!/usr/bin/env bash
# Counts the instructions of one tessera command under Valgrind's callgrind and prints the
# total and the top functions by inclusive cost. Instruction counts do not depend on the
# machine's load, so they compare builds on a shared machine where timings cannot.
#   tools/callgrind.sh OUT.callgrind -- render scenes/cornell-box/cornell-box.gltf \
#       --width 64 --spp 4 --threads 1 -q -o /tmp/x.exr
# Needs: apt-get install valgrind; a built build/tessera (or TESSERA=path).
#
# Valgrind 3.19 (Debian 12) stops with SIGILL on RDTSCP when the CPU does not advertise it
# (as on this project's virtual machines): libhwy, which OpenImageIO loads through libjxl,
# calls hwy::platform::TimerResolution() from a static initialiser, and that uses RDTSCP. A
# one-function library preloaded in its place avoids it; nothing tessera does depends on it.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tessera="${TESSERA:-$root/build/tessera}"
[[ $# -ge 3 && "$2" == "--" ]] || { echo "usage: $0 OUT.callgrind -- TESSERA-ARGS..." >&2; exit 2; }
out=$1
shift 2
stub_dir=$(mktemp -d)
trap 'rm -rf "$stub_dir"' EXIT
cat >"$stub_dir/hwy_stub.cpp" <<'EOF'
#include <cstdint>
namespace hwy { namespace platform { std::uint64_t TimerResolution() { return 1; } } }
EOF
g++ -O2 -shared -fPIC -o "$stub_dir/hwy_stub.so" "$stub_dir/hwy_stub.cpp"
# The generic program (docs/usage.md#instruction-sets), unless TESSERA_ISA says otherwise:
# callgrind does not follow tessera's hand-over to tessera-x86-64-v3 (an exec), and the
# counts stay comparable with those recorded before that program existed.
TESSERA_ISA="${TESSERA_ISA:-x86-64}" LD_PRELOAD="$stub_dir/hwy_stub.so" valgrind --tool=callgrind --callgrind-out-file="$out" "$tessera" "$@" 2>&1 |
  grep -E "I\s+refs" >&2
callgrind_annotate --inclusive=yes "$out" 2>/dev/null | grep -v '^\s*$' | sed -n '/file:function/,$p' | sed -n '2,41p' |
  cut -c1-160
