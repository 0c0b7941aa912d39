#!/usr/bin/env bash
# Checks that every C++ file of the library, tests, benches and fuzzers is
# formatted by .clang-format (ctest style/clang_format). `make format`
# formats them. Exit 77 (skip) without clang-format.
#   scripts/check_format.sh [SOURCE_DIR]
set -euo pipefail
cd "${1:-$(dirname "$0")/..}"
command -v clang-format >/dev/null 2>&1 || { echo "clang-format not installed"; exit 77; }
mapfile -t files < <(find src bench fuzz -name '*.cc' -o -name '*.h' 2>/dev/null | sort)
if ! clang-format --dry-run --Werror "${files[@]}" 2>/tmp/asbuilt_format.$$; then
  grep -o '^[^:]*:[0-9]*' /tmp/asbuilt_format.$$ | sort -u | head -20
  echo "check_format: these files are not formatted: run 'make format'" >&2
  rm -f /tmp/asbuilt_format.$$
  exit 1
fi
rm -f /tmp/asbuilt_format.$$
echo "check_format: ${#files[@]} files formatted"
