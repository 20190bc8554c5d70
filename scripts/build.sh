#!/usr/bin/env bash
# wqmesh: builds the core natively (build/native: library, command line,
# GoogleTest tests), to wasm (build/wasm: wasm/wqmesh.mjs), the libFuzzer
# targets of the input path (build/fuzz: clang++-14, libFuzzer + ASan + UBSan)
# and the GoogleTest tests under AddressSanitizer and UndefinedBehaviorSanitizer
# (build/asan: g++, -O1). The build folders are reused, so a second run only
# rebuilds what changed. The folders are built one after the other.
# Usage: scripts/build.sh [native|wasm|fuzz|asan|all]...   (default: all)
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(all)
for t in "${targets[@]}"; do
  case "$t" in
    native|wasm|fuzz|asan|all) ;;
    *) echo "build: error: unknown target '$t' (use native, wasm, fuzz, asan or all)" >&2; exit 2 ;;
  esac
done
# True when target $1 was asked for, by name or by `all`.
want() {
  local t
  for t in "${targets[@]}"; do
    if [ "$t" = "$1" ] || [ "$t" = all ]; then return 0; fi
  done
  return 1
}
jobs="$(nproc 2>/dev/null || echo 2)"
say() { printf 'build: %s\n' "$*"; }

if want native; then
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

if want wasm; then
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

if want fuzz; then
  command -v cmake >/dev/null || { echo "build: error: cmake not found (run scripts/setup.sh)" >&2; exit 1; }
  clangxx=/usr/bin/clang++-14
  [ -x "$clangxx" ] || { echo "build: error: $clangxx not found (run scripts/setup.sh)" >&2; exit 1; }
  if [ ! -f build/fuzz/CMakeCache.txt ]; then
    say "configuring build/fuzz (clang++-14, WQMESH_FUZZ: libFuzzer + ASan + UBSan, RelWithDebInfo)"
    CXX="$clangxx" cmake -S . -B build/fuzz -DWQMESH_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
  fi
  say "building build/fuzz with $jobs jobs"
  start=$(date +%s)
  cmake --build build/fuzz -j "$jobs"
  say "fuzz build done in $(( $(date +%s) - start )) s: build/fuzz/bin/fuzz_{read_off,read_stl,build_plc}"
fi

if want asan; then
  command -v cmake >/dev/null || { echo "build: error: cmake not found (run scripts/setup.sh)" >&2; exit 1; }
  if [ ! -f build/asan/CMakeCache.txt ]; then
    say "configuring build/asan (g++, WQMESH_SANITIZE: ASan + UBSan, -O1 -g)"
    CXX=g++ cmake -S . -B build/asan -DWQMESH_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
      -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG"
  fi
  say "building build/asan with $jobs jobs"
  start=$(date +%s)
  cmake --build build/asan -j "$jobs"
  say "asan build done in $(( $(date +%s) - start )) s"
fi
