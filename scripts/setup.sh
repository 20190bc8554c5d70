#!/usr/bin/env bash
# wqmesh: installs what the build and the tests need, and only what is missing
# (idempotent): Debian packages for the native, wasm, fuzz (clang-14 with
# libFuzzer) and sanitizer builds, then the npm packages of package-lock.json.
# Chromium (Debian's package, /usr/bin/chromium) runs the browser tests
# (tests/browser/, through playwright-core); clang-format formats the C++
# (scripts/format.sh).
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

say() { printf 'setup: %s\n' "$*"; }

# What each Debian package provides, tested by a command or a path.
missing=()
need_cmd() { command -v "$1" >/dev/null 2>&1 || missing+=("$2"); }
need_path() { [ -e "$1" ] || missing+=("$2"); }

need_cmd emcc emscripten
need_cmd emcmake emscripten
need_path /usr/share/nodejs/acorn node-acorn
need_path /usr/include/CGAL libcgal-dev
need_path /usr/include/boost libboost-dev
need_path /usr/include/gmpxx.h libgmp-dev
need_path /usr/include/mpfr.h libmpfr-dev
need_cmd cmake cmake
need_cmd make make
need_cmd g++ g++
# The fuzz targets (tests/fuzz): clang-14, and libFuzzer's runtime, which is in
# libclang-rt-14-dev, only a Recommends of clang-14 (any 14.x patch version).
need_cmd clang++-14 clang-14
if ! compgen -G "/usr/lib/llvm-14/lib/clang/*/lib/linux/libclang_rt.fuzzer-$(uname -m).a" >/dev/null; then
  missing+=(libclang-rt-14-dev)
fi
# g++'s AddressSanitizer and UndefinedBehaviorSanitizer runtimes (build/asan);
# normally pulled in by g++ through libgcc-12-dev.
if ! compgen -G "/usr/lib/$(uname -m)-linux-gnu/libasan.so.*" >/dev/null; then missing+=(libasan8); fi
if ! compgen -G "/usr/lib/$(uname -m)-linux-gnu/libubsan.so.*" >/dev/null; then missing+=(libubsan1); fi
if [ ! -e /usr/src/googletest ] && [ ! -e /usr/include/gtest/gtest.h ]; then
  missing+=(libgtest-dev)
fi
need_cmd node nodejs
# GNU time: peak memory in examples/node/benchmark.mjs (the shell keyword is not it).
need_path /usr/bin/time time
need_cmd npm npm
# The browser tests (tests/browser/) drive Debian's Chromium with playwright-core.
need_path /usr/bin/chromium chromium
# The C++ format (.clang-format, scripts/format.sh): Debian's clang-format.
need_cmd clang-format clang-format

# De-duplicate, keeping the order.
if [ ${#missing[@]} -gt 0 ]; then
  mapfile -t missing < <(printf '%s\n' "${missing[@]}" | awk '!seen[$0]++')
fi

if [ ${#missing[@]} -eq 0 ]; then
  say "system packages: all present"
else
  say "missing Debian packages: ${missing[*]}"
  if ! command -v apt-get >/dev/null 2>&1; then
    echo "setup: error: apt-get is not available; install these packages by hand: ${missing[*]}" >&2
    exit 1
  fi
  sudo_cmd=()
  if [ "$(id -u)" -ne 0 ]; then
    if command -v sudo >/dev/null 2>&1; then
      sudo_cmd=(sudo)
    else
      echo "setup: error: not root and sudo is not available; as root run:" >&2
      echo "  apt-get update && apt-get install -y --no-install-recommends ${missing[*]}" >&2
      exit 1
    fi
  fi
  say "running: apt-get update"
  "${sudo_cmd[@]}" apt-get update
  say "running: apt-get install -y --no-install-recommends ${missing[*]}"
  DEBIAN_FRONTEND=noninteractive "${sudo_cmd[@]}" apt-get install -y --no-install-recommends "${missing[@]}"
fi

# npm packages: install from the lock file when node_modules is missing or
# older than package-lock.json.
if [ -f package-lock.json ]; then
  if [ ! -d node_modules ] || [ package-lock.json -nt node_modules ]; then
    say "running: npm ci"
    npm ci --no-audit --no-fund
    # With no dependencies npm ci creates no folder: mark the install done.
    mkdir -p node_modules && touch node_modules
  else
    say "npm packages: up to date"
  fi
else
  echo "setup: error: package-lock.json is missing (run 'npm install' once to create it)" >&2
  exit 1
fi
