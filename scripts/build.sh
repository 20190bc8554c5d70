#!/usr/bin/env bash
# wqmesh: builds the core natively (build/native: library, command line,
# GoogleTest tests), to wasm (build/wasm: wasm/wqmesh.mjs and its binary
# wasm/wqmesh.wasm, then copied beside wasm/index.mjs with the option table
# wasm/options.mjs), the libFuzzer
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

# Stops with a clear error when command $1 is missing.
need() {
  command -v "$1" >/dev/null || { echo "build: error: $1 not found (run scripts/setup.sh)" >&2; exit 1; }
}
# build_folder NAME WHAT CONFIGURE...: configures build/NAME with the command
# CONFIGURE... the first time (WHAT says how, in the log), then builds it.
build_folder() {
  local name=$1 what=$2 start
  shift 2
  if [ ! -f "build/$name/CMakeCache.txt" ]; then
    say "configuring build/$name ($what)"
    "$@"
  fi
  say "building build/$name with $jobs jobs"
  start=$(date +%s)
  cmake --build "build/$name" -j "$jobs"
  say "$name build done in $(( $(date +%s) - start )) s"
}

if want native; then
  need cmake
  build_folder native "Release" cmake -S . -B build/native -DCMAKE_BUILD_TYPE=Release
fi

if want wasm; then
  need emcmake
  # Debian's emcc finds acorn (its JS optimizer) through Node's module path.
  export NODE_PATH=/usr/share/nodejs${NODE_PATH:+:$NODE_PATH}
  build_folder wasm "Release, emcmake" emcmake cmake -S . -B build/wasm -DCMAKE_BUILD_TYPE=Release
  say "wasm module: build/wasm/wasm/wqmesh.mjs ($(stat -c %s build/wasm/wasm/wqmesh.mjs) bytes)" \
      "and wqmesh.wasm ($(stat -c %s build/wasm/wasm/wqmesh.wasm) bytes)"
  # The package's files beside wasm/index.mjs (not committed): the glue, its
  # binary and the option table, so that a checkout serves and imports what the package ships.
  node scripts/package_wasm.mjs build/wasm
fi

if want fuzz; then
  need cmake
  need clang++-14
  build_folder fuzz "clang++-14, WQMESH_FUZZ: libFuzzer + ASan + UBSan, RelWithDebInfo" \
    env CXX=clang++-14 cmake -S . -B build/fuzz -DWQMESH_FUZZ=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo
  say "fuzz targets: build/fuzz/bin/fuzz_{read_off,read_stl,build_plc,mesh}"
fi

if want asan; then
  need cmake
  build_folder asan "g++, WQMESH_SANITIZE: ASan + UBSan, -O1 -g" \
    env CXX=g++ cmake -S . -B build/asan -DWQMESH_SANITIZE=ON -DCMAKE_BUILD_TYPE=RelWithDebInfo \
    -DCMAKE_CXX_FLAGS_RELWITHDEBINFO="-O1 -g -DNDEBUG"
fi
