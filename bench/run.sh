#!/usr/bin/env bash
# Runs every benchmark program and joins their sections into bench/RESULTS.md.
#   bench/run.sh [BUILD_DIR] [NAME…]     (names: render, stereo, plan, …)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true
export ASBUILT_NO_PROGRESS=1
mkdir -p bench/results
programs=()
if (($# > 0)); then
  for n in "$@"; do programs+=("$build/bench/bench_$n"); done
else
  programs=("$build"/bench/bench_*)
fi
for p in "${programs[@]}"; do
  [[ -x "$p" ]] || { echo "bench: $p not built" >&2; continue; }
  name=$(basename "$p"); name=${name#bench_}
  echo "== bench $name" >&2
  "$p" "bench/results/$name.md" || echo "bench: $name failed (exit $?)" >&2
done
{
  echo "# Benchmark results"
  echo
  echo "Written by \`make bench\` (bench/run.sh). Machine: $(nproc) cores, $(free -g | awk '/Mem:/{print $2}') GiB;"
  echo "$(uname -srm). Figures are medians; ratios are against a reference measured in the same run."
  echo
  for f in bench/results/*.md; do
    [[ -f "$f" ]] || continue
    cat "$f"
    echo
  done
} > bench/RESULTS.md.tmp
mv bench/RESULTS.md.tmp bench/RESULTS.md
echo "bench: wrote bench/RESULTS.md" >&2
