#!/usr/bin/env bash
# Runs the Khronos glTF-Validator on every glTF file tessera generates (everything under
# scenes/ except the third-party models in scenes/khronos). Fails on any validator error.
# The validator (npm package gltf-validator) is installed into tools/node_modules on first use.
set -euo pipefail
root=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
tools="$root/tools"
if [[ ! -d "$tools/node_modules/gltf-validator" ]]; then
  command -v npm >/dev/null || { echo "validate-generated-scenes: npm is required (apt-get install npm)" >&2; exit 1; }
  npm install --silent --no-audit --no-fund --prefix "$tools" gltf-validator@2.0.0-dev.3.10 >&2
fi
mapfile -t files < <(find "$root/scenes" -path "$root/scenes/khronos" -prune -o \( -name '*.gltf' -o -name '*.glb' \) -print | sort)
if [[ ${#files[@]} -eq 0 ]]; then echo "validate-generated-scenes: no generated scenes found" >&2; exit 1; fi
report=$(NODE_PATH="$tools/node_modules" node "$tools/gltf-validate.js" "${files[@]}")
echo "$report"
if echo "$report" | grep -qE 'errors [1-9]'; then exit 1; fi
echo "${#files[@]} passed, 0 failed"
