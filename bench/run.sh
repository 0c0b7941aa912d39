#!/usr/bin/env bash
# Runs every benchmark program and joins their sections into bench/RESULTS.md.
#   bench/run.sh [BUILD_DIR] [NAME…]     (names: render, stereo, plan, …)
#   bench/run.sh --join                  only join the existing sections
set -euo pipefail
cd "$(dirname "$0")/.."
join_only=0
if [[ "${1:-}" == "--join" ]]; then join_only=1; shift; fi
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
((join_only)) && programs=()
for p in "${programs[@]}"; do
  [[ -x "$p" ]] || { echo "bench: $p not built" >&2; continue; }
  name=$(basename "$p"); name=${name#bench_}
  echo "== bench $name" >&2
  "$p" "bench/results/$name.md" || echo "bench: $name failed (exit $?)" >&2
done
{
  echo "# Benchmark results"
  echo
  echo "Written by \`make bench\` (bench/run.sh), one section per benchmark program (bench/results/)."
  echo "Figures are medians; ratios are against a reference measured in the same run. Each section"
  echo "says the machine and load it was measured under: the first sections were measured on the"
  echo "2-core development machine while it was heavily loaded (load average ~20), so absolute times"
  echo "are pessimistic and the same-run ratios are the figures to compare."
  echo
  for f in bench/results/*.md; do
    [[ -f "$f" ]] || continue
    cat "$f"
    echo
  done
} > bench/RESULTS.md.tmp
mv bench/RESULTS.md.tmp bench/RESULTS.md
echo "bench: wrote bench/RESULTS.md" >&2
