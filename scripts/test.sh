#!/usr/bin/env bash
# wqmesh: sets up, builds, then runs every test: the C++ format check, the native GoogleTest tests
# (ctest), the Node tests (wasm module vs command line), the browser tests
# (the package and the web page in headless Chromium), the GoogleTest tests
# again under AddressSanitizer and UndefinedBehaviorSanitizer (build/asan,
# the project's own small models: the tests that read ../shared/models are
# left out) and each libFuzzer target of the input path for 20 s
# (scripts/fuzz.sh). Exits non-zero if any of them fails; every suite runs even
# when an earlier one fails.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
bash scripts/build.sh

status=0
# The C++ format (.clang-format, CONTRIBUTING.md): a file that differs fails
# the run; `bash scripts/format.sh` formats them.
echo "test: scripts/format.sh --check"
bash scripts/format.sh --check || status=1
echo "test: ctest --test-dir build/native --output-on-failure -j2"
ctest --test-dir build/native --output-on-failure -j2 || status=1
echo "test: node --test tests/node/"
node --test tests/node/ || status=1
# The page (build/web, from web/ and the wasm module just built) and the
# browser tests on Debian's headless Chromium: the package in a page, and the
# page itself (tests/browser/page*.test.mjs).
echo "test: node web/build.mjs && node --test tests/browser/"
if node web/build.mjs; then
  node --test tests/browser/ || status=1
else
  status=1
fi

# Sanitizers: any report aborts its test (-fno-sanitize-recover, halt_on_error).
# build/asan's tests see no ../shared/models (tests/native/CMakeLists.txt), so
# the tests of those larger models skip; every other test runs, on the
# project's own small models.
echo "test: ctest --test-dir build/asan --output-on-failure -j2  (ASan + UBSan, small models)"
ASAN_OPTIONS="detect_leaks=1:check_initialization_order=1:detect_stack_use_after_return=1${ASAN_OPTIONS:+:$ASAN_OPTIONS}" \
UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}" \
  ctest --test-dir build/asan --output-on-failure -j2 || status=1

echo "test: scripts/fuzz.sh 20  (libFuzzer, 20 s per target)"
bash scripts/fuzz.sh 20 || status=1

if [ "$status" -ne 0 ]; then
  echo "test: FAILED" >&2
else
  echo "test: all passed"
fi
exit "$status"
