#!/usr/bin/env bash
# wqmesh: runs the libFuzzer targets of tests/fuzz (built in build/fuzz by
# `scripts/build.sh fuzz`) for SECONDS each, one after the other, and prints
# their executions per second and total executions. Exits non-zero if any
# target finds a crash, a sanitizer report, an exception other than
# wqmesh::InputError, a broken contract or an input slower than 10 s; the
# input is kept in build/fuzz/artifacts/ (replay it with the target's binary).
#
# Corpus: every target starts from tests/fuzz/corpus/ (inputs kept in the repo,
# such as past findings, replayed on every run) and from seeds written into
# build/fuzz/seeds/: the OFF models of examples/models and STL files made from
# them (tests/fuzz/make_seeds.mjs), OFF for read_off, STL for read_stl, both
# for build_plc. New inputs go to build/fuzz/corpus/TARGET, kept between runs.
# Logs: build/fuzz/logs/TARGET.log.
#
# fuzz_mesh runs the mesher itself on small star-shaped polyhedra decoded
# from the bytes (tests/fuzz/fuzz_mesh.cpp); it needs no seeds nor dictionary
# (its corpus: build/fuzz/corpus/mesh and tests/fuzz/corpus/mesh).
#
# Usage: scripts/fuzz.sh [SECONDS] [TARGET...]
#   SECONDS  run time of each target (default 20)
#   TARGET   read_off, read_stl, build_plc, mesh (default: all four)
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

seconds="${1:-20}"
[ $# -gt 0 ] && shift
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(read_off read_stl build_plc mesh)
case "$seconds" in
  ''|*[!0-9]*) echo "fuzz: error: SECONDS must be a whole number, not '$seconds'" >&2; exit 2 ;;
esac
for t in "${targets[@]}"; do
  case "$t" in
    read_off|read_stl|build_plc|mesh) ;;
    *) echo "fuzz: error: unknown target '$t' (use read_off, read_stl, build_plc or mesh)" >&2; exit 2 ;;
  esac
  [ -x "build/fuzz/bin/fuzz_$t" ] || { echo "fuzz: error: build/fuzz/bin/fuzz_$t is missing (run scripts/build.sh fuzz)" >&2; exit 1; }
done
say() { printf 'fuzz: %s\n' "$*"; }

# Seeds, written anew on every run from the project's own models.
rm -rf build/fuzz/seeds
mkdir -p build/fuzz/seeds/off build/fuzz/seeds/stl build/fuzz/artifacts build/fuzz/logs
cp examples/models/*.off build/fuzz/seeds/off/
node tests/fuzz/make_seeds.mjs build/fuzz/seeds/stl >/dev/null

export UBSAN_OPTIONS="print_stacktrace=1:halt_on_error=1${UBSAN_OPTIONS:+:$UBSAN_OPTIONS}"
status=0
for t in "${targets[@]}"; do
  case "$t" in
    read_off) seeds=(build/fuzz/seeds/off) ;;
    read_stl) seeds=(build/fuzz/seeds/stl) ;;
    build_plc) seeds=(build/fuzz/seeds/off build/fuzz/seeds/stl) ;;
    mesh) seeds=() ;;
  esac
  mkdir -p "build/fuzz/corpus/$t"
  log="build/fuzz/logs/$t.log"
  if [ "$t" = mesh ]; then
    # Bytes decoded into a polyhedron: no dictionary; its own kept corpus.
    kept=()
    [ -d tests/fuzz/corpus/mesh ] && kept=(tests/fuzz/corpus/mesh)
    # Inputs of every length at once (a polyhedron of 66 vertices reads 202 bytes).
    cmd=(build/fuzz/bin/fuzz_$t -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048
         -max_len=256 -len_control=0
         -print_final_stats=1 -artifact_prefix="build/fuzz/artifacts/$t-" "build/fuzz/corpus/$t" "${kept[@]}")
  else
    cmd=(build/fuzz/bin/fuzz_$t -max_total_time="$seconds" -timeout=10 -rss_limit_mb=2048
         -print_final_stats=1 -dict=tests/fuzz/off_stl.dict -artifact_prefix="build/fuzz/artifacts/$t-"
         "build/fuzz/corpus/$t" tests/fuzz/corpus "${seeds[@]}")
  fi
  say "${cmd[*]}"
  rc=0
  "${cmd[@]}" >"$log" 2>&1 || rc=$?
  runs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
  rate=$(sed -n 's/^stat::average_exec_per_sec: *//p' "$log" | tail -1)
  cov=$(grep -o 'cov: [0-9]* ft: [0-9]* corp: [0-9]*' "$log" | tail -1 || true)
  if [ "$rc" -eq 0 ]; then
    say "$t: ${runs:-?} executions in $seconds s, ${rate:-?} exec/s, ${cov:-no coverage line}"
  else
    status=1
    echo "fuzz: $t FAILED (exit $rc) after ${runs:-?} executions; the end of $log:" >&2
    tail -n 60 "$log" >&2
    artifact=$(sed -n "s/.*Test unit written to //p" "$log" | tail -1)
    [ -n "$artifact" ] && echo "fuzz: replay with: build/fuzz/bin/fuzz_$t $artifact" >&2
  fi
done
exit "$status"
