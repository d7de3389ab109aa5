# shellcheck shell=bash
# The start every docs/make-*.sh script shares; each sources it first. Strict mode, the
# tessera program ($TESSERA, default build/tessera) as $bin and as the function `tessera`,
# the repository root as the working directory, and two helpers.
set -euo pipefail
script=$(basename -- "$0")
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
bin=${TESSERA:-$root/build/tessera}
if [[ ! -x "$bin" ]]; then
  echo "$script: $bin is not there; build it first (./tessera --version), or set TESSERA=path/to/tessera" >&2
  exit 1
fi
bin=$(realpath -- "$bin")
cd "$root"
tessera() { "$bin" "$@"; }

need_oiiotool() {
  command -v oiiotool >/dev/null || { echo "$script: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 1; }
}

run() {  # prints the command as the docs show it, runs it, prints its time
  echo "\$ $*" >&2
  local t0=$SECONDS
  "$@"
  echo "  ($((SECONDS - t0)) s)" >&2
}
