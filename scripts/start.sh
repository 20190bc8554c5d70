#!/usr/bin/env bash
# wqmesh: sets up, builds (the command line, the wasm module and the web page
# in build/web), then meshes the built-in default model
# (examples/models/spike.off: a cube with a tall pyramid, edge-edge angles of
# 14 degrees at its apex) with the command line, writes the mesh and its
# statistics under build/start/, prints a summary, and serves the page on
# 127.0.0.1 (scripts/serve.mjs; port $WQMESH_PORT, default 8080, or a free
# one when that is taken) and prints its address; Ctrl-C stops it.
# `--no-serve` exits after the work instead (for scripts and CI).
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

serve=1
for arg in "$@"; do
  case "$arg" in
    --no-serve) serve=0 ;;
    *) echo "start: unknown option '$arg' (known: --no-serve)" >&2; exit 2 ;;
  esac
done

bash scripts/setup.sh
# The command line and the wasm module; the fuzz and sanitizer builds are for
# the tests (scripts/test.sh).
bash scripts/build.sh native wasm
node web/build.mjs

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

if [ "$serve" -eq 1 ]; then
  port="${WQMESH_PORT:-8080}"
  if node -e 'const s = require("net").createServer().once("error", () => process.exit(1)).listen(+process.argv[1], "127.0.0.1", () => s.close())' "$port"; then :; else
    echo "start: port $port is taken, using a free one"
    port=0
  fi
  echo "start: the page (build/web) is served below; open the address in a browser (Ctrl-C stops it)"
  echo "start: e.g. add ?example=spike.off to the address to mesh the default model in the page"
  exec node scripts/serve.mjs --root build/web --port "$port" --quiet
fi
