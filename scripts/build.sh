#!/usr/bin/env bash
# wqmesh: builds the core natively (build/native: library, command line,
# GoogleTest tests) and to wasm (build/wasm: wasm/wqmesh.mjs). The build folders
# are reused, so a second run only rebuilds what changed.
# Usage: scripts/build.sh [native|wasm|all]   (default: all)
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

what="${1:-all}"
case "$what" in
  native|wasm|all) ;;
  *) echo "build: error: unknown target '$what' (use native, wasm or all)" >&2; exit 2 ;;
esac
jobs="$(nproc 2>/dev/null || echo 2)"
say() { printf 'build: %s\n' "$*"; }

if [ "$what" = native ] || [ "$what" = all ]; then
  command -v cmake >/dev/null || { echo "build: error: cmake not found (run scripts/setup.sh)" >&2; exit 1; }
  if [ ! -f build/native/CMakeCache.txt ]; then
    say "configuring build/native (Release)"
    cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release
  fi
  say "building build/native with $jobs jobs"
  start=$(date +%s)
  cmake --build build/native -j "$jobs"
  say "native build done in $(( $(date +%s) - start )) s"
fi

if [ "$what" = wasm ] || [ "$what" = all ]; then
  command -v emcmake >/dev/null || { echo "build: error: emcmake not found (run scripts/setup.sh)" >&2; exit 1; }
  # Debian's emcc finds acorn (its JS optimizer) through Node's module path.
  export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
  if [ ! -f build/wasm/CMakeCache.txt ]; then
    say "configuring build/wasm (Release, emcmake)"
    emcmake cmake -S . -B build/wasm -DCMAKE_BUILD_TYPE=Release
  fi
  say "building build/wasm with $jobs jobs"
  start=$(date +%s)
  cmake --build build/wasm -j "$jobs"
  say "wasm build done in $(( $(date +%s) - start )) s: build/wasm/wasm/wqmesh.mjs ($(stat -c %s build/wasm/wasm/wqmesh.mjs) bytes)"
fi
