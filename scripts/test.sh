#!/usr/bin/env bash
# wqmesh: sets up, builds, then runs every test: the native GoogleTest tests
# (ctest) and the Node tests (wasm module vs command line). Exits non-zero if
# any of them fails; both suites run even when the first one fails.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/setup.sh
bash scripts/build.sh

status=0
echo "test: ctest --test-dir build/native --output-on-failure -j2"
ctest --test-dir build/native --output-on-failure -j2 || status=1
echo "test: node --test tests/node/"
node --test tests/node/ || status=1

if [ "$status" -ne 0 ]; then
  echo "test: FAILED" >&2
else
  echo "test: all passed"
fi
exit "$status"
