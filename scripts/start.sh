#!/usr/bin/env bash
# wqmesh: sets up, builds, then meshes the built-in default model
# (examples/models/spike.off: a cube with a tall pyramid, edge-edge angles of
# 14 degrees at its apex) with the command line, writes the mesh and its
# statistics under build/start/ and prints a summary.
# There is no page to serve yet (the web issue brings it), so the script
# always exits after the work; `--no-serve` is accepted for the day it serves.
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

for arg in "$@"; do
  case "$arg" in
    --no-serve) ;;
    *) echo "start: unknown option '$arg' (known: --no-serve)" >&2; exit 2 ;;
  esac
done

bash scripts/setup.sh
# The command line and the wasm module; the fuzz and sanitizer builds are for
# the tests (scripts/test.sh).
bash scripts/build.sh native wasm

model=examples/models/spike.off
mkdir -p build/start
echo "start: build/native/bin/wqmesh check $model"
build/native/bin/wqmesh check "$model" --compact > build/start/check.json
echo "start: build/native/bin/wqmesh mesh $model -o build/start/spike.vtu --stats build/start/spike.json"
build/native/bin/wqmesh mesh "$model" -o build/start/spike.vtu --stats build/start/spike.json
node -e '
const s = JSON.parse(require("fs").readFileSync("build/start/spike.json", "utf8"));
const keys = ["input_points", "sharp_elements", "points_inserted", "vertices", "tets", "min_dihedral_deg",
              "slivers_before_pump", "slivers", "skinny", "near_small_angle", "violations", "volume_input",
              "volume_mesh", "time_s"];
for (const k of keys) console.log(`start: ${k.padEnd(20)} ${s[k]}`);
console.log("start: mesh in build/start/spike.vtu (open it in ParaView), statistics in build/start/spike.json");
'
