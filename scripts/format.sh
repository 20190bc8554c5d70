#!/usr/bin/env bash
# wqmesh: formats the C++ sources with the repository's .clang-format
# (CONTRIBUTING.md, Format): every tracked and untracked-but-not-ignored
# .cpp/.h/.hpp/.cc/.h.in file under core/, wasm/, tests/ and examples/
# (never build/ or node_modules/).
# Usage: scripts/format.sh           formats them in place
#        scripts/format.sh --check   lists the files that differ from the
#                                    format and exits 1 if any does
#        scripts/format.sh [--check] FILE...   only these files
# SPDX-License-Identifier: GPL-3.0-or-later
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

check=0
if [ "${1:-}" = "--check" ]; then
  check=1
  shift
fi
case "${1:-}" in
  -*) echo "format: error: unknown option '$1' (use --check)" >&2; exit 2 ;;
esac

tool=""
for c in clang-format clang-format-14; do
  if command -v "$c" >/dev/null 2>&1; then tool=$c; break; fi
done
[ -n "$tool" ] || { echo "format: error: clang-format not found (run scripts/setup.sh)" >&2; exit 1; }

files=()
if [ $# -gt 0 ]; then
  files=("$@")
else
  mapfile -t files < <(git ls-files --cached --others --exclude-standard -- core wasm tests examples |
    grep -E '\.(cpp|cc|h|hpp)$' | grep -v -E '(^|/)(build|node_modules)/' | sort -u)
fi
[ ${#files[@]} -gt 0 ] || { echo "format: no C++ files found" >&2; exit 0; }

if [ $check -eq 0 ]; then
  "$tool" -i --style=file "${files[@]}"
  echo "format: formatted ${#files[@]} files with $("$tool" --version | head -1)"
  exit 0
fi

bad=()
for f in "${files[@]}"; do
  [ -f "$f" ] || continue
  if ! "$tool" --dry-run -Werror --style=file "$f" >/dev/null 2>&1; then bad+=("$f"); fi
done
if [ ${#bad[@]} -gt 0 ]; then
  printf '%s\n' "${bad[@]}"
  echo "format: ${#bad[@]} of ${#files[@]} files differ from .clang-format (run bash scripts/format.sh)" >&2
  exit 1
fi
echo "format: all ${#files[@]} files follow .clang-format"
