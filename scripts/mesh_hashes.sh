#!/usr/bin/env bash
# wqmesh: meshes every model of examples/models and ../shared/models (but
# mpi.off, minutes long, and step.off, refused by design) with one binary of
# the command line and prints a line per model: name, the first 16 hex digits
# of the written .mesh file's sha256 (or - when no mesh was written), tets,
# the exit code and the wall seconds. Two binaries' outputs compared line by
# line tell whether a change leaves the meshes bit for bit the same
# (CONTRIBUTING.md: a helper changed must keep every model's mesh).
# A developer's tool, not a test: it asserts nothing and always exits 0 unless
# its own arguments are wrong.
# Usage: scripts/mesh_hashes.sh BIN OUTDIR [extra wqmesh mesh options...]
#   e.g. scripts/mesh_hashes.sh build/rel/bin/wqmesh /tmp/a --no-improve
#   then: diff /tmp/a/summary.txt /tmp/b/summary.txt
# Environment: WQMESH_MODELS (default ../shared/models beside the checkout).
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ $# -lt 2 ]; then
  echo "mesh_hashes: usage: scripts/mesh_hashes.sh BIN OUTDIR [wqmesh mesh options...]" >&2
  exit 2
fi
bin=$1 out=$2
shift 2
[ -x "$bin" ] || { echo "mesh_hashes: error: $bin is not an executable" >&2; exit 2; }
shared="${WQMESH_MODELS:-$root/../shared/models}"
mkdir -p "$out"
models=("$root"/examples/models/*.off)
if [ -d "$shared" ]; then
  for m in "$shared"/*.off "$shared"/*.stl; do
    case "$(basename "$m")" in mpi.off | step.off) continue ;; esac
    models+=("$m")
  done
else
  echo "mesh_hashes: $shared is missing: only examples/models" >&2
fi
summary="$out/summary.txt"
: >"$summary"
for m in "${models[@]}"; do
  name=$(basename "$m")
  stem=${name%.*}
  rm -f "$out/$stem.mesh" "$out/$stem.json"
  start=$(date +%s.%N)
  set +e
  "$bin" mesh "$m" -o "$out/$stem.mesh" --stats "$out/$stem.json" --quiet "$@" >"$out/$stem.log" 2>&1
  rc=$?
  set -e
  secs=$(awk -v a="$start" -v b="$(date +%s.%N)" 'BEGIN { printf "%.2f", b - a }')
  sha=- tets=-
  if [ -f "$out/$stem.mesh" ]; then
    sha=$(sha256sum "$out/$stem.mesh" | cut -c1-16)
    # The Medit file's Tetrahedra block: the keyword, then the count.
    tets=$(awk '/^Tetrahedra/{getline; print $1; exit}' "$out/$stem.mesh")
  fi
  printf '%-38s %-16s %8s %3s %7s\n' "$name" "$sha" "$tets" "$rc" "$secs" | tee -a "$summary"
done
