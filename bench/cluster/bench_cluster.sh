#!/usr/bin/env bash
# bench_cluster OUT.md — what the Slurm path costs and gives (issue 41), on the
# one-node cluster of scripts/slurm/local-cluster.sh (brought up if needed and
# down after; needs root and `scripts/install-deps.sh --cluster`):
#   - a bare `asbuilt dataset synth` + `dataset merge` (the reference);
#   - `asbuilt cluster synth --shards 1` and `--shards 2` (sbatch, array job,
#     merge job), to the merged manifest;
# each ROUNDS times (median), the same items; samples per hour and the ratio
# to the reference; then core-hours per 1000 labelled pairs at the paper's
# 640x480, from a bare run.
set -euo pipefail
out=${1:?usage: bench_cluster OUT.md}
asbuilt="@PROJECT_BINARY_DIR@/asbuilt"  # Set by CMake (bench/cluster/CMakeLists.txt).
src="@PROJECT_SOURCE_DIR@"
: "${ROUNDS:=3}" "${ITEMS:=32}"
items=(--count "$ITEMS" --seed 7 --size 320x240)
cluster="bash $src/scripts/slurm/local-cluster.sh"
if [[ $(id -u) -ne 0 ]] || ! command -v slurmctld >/dev/null; then
  echo "bench_cluster: needs root and Slurm (scripts/install-deps.sh --cluster)" >&2
  exit 1
fi
was_up=0
$cluster status >/dev/null 2>&1 && was_up=1
$cluster up >/dev/null
# shellcheck source=/dev/null
. "${ASBUILT_SLURM_DIR:-/tmp/asbuilt-slurm}/env.sh"
T=$(mktemp -d /tmp/asbuilt-bench-cluster.XXXXXX)
cleanup() { rm -rf "$T"; ((was_up)) || $cluster down >/dev/null; }
trap cleanup EXIT

now() { date +%s.%N; }
calc() { awk "BEGIN {print $*}"; }
wait_job() { while [[ -n $(squeue -h -j "$1" 2>/dev/null) ]]; do sleep 0.1; done; }
median() { sort -g | awk '{a[NR] = $1} END {print (NR % 2) ? a[(NR + 1) / 2] : (a[NR / 2] + a[NR / 2 + 1]) / 2}'; }

bare() {
  local d=$T/bare-$1 t0
  t0=$(now)
  "$asbuilt" dataset synth -o "$d" "${items[@]}" >/dev/null 2>&1
  "$asbuilt" dataset merge "$d" >/dev/null 2>&1
  calc "$(now) - $t0"
}
slurm() {  # shards round
  local d=$T/slurm-$1-$2 t0 o
  t0=$(now)
  o=$("$asbuilt" cluster synth -o "$d" --shards "$1" "${items[@]}")
  wait_job "$(sed -n 's/.*merge job \([0-9]*\).*/\1/p' <<<"$o")"
  [[ -f $d/synth_manifest.json ]] || { echo "bench_cluster: no manifest in $d" >&2; exit 1; }
  cmp -s "$d/synth_manifest.json" "$T/bare-1/synth_manifest.json" || { echo "bench_cluster: manifests differ" >&2; exit 1; }
  calc "$(now) - $t0"
}

declare -A times
for r in $(seq "$ROUNDS"); do
  times[bare]+="$(bare "$r") "
  times[s1]+="$(slurm 1 "$r") "
  times[s2]+="$(slurm 2 "$r") "
  echo "bench_cluster: round $r of $ROUNDS" >&2
done
med() { tr ' ' '\n' <<<"${times[$1]}" | grep . | median; }
ref=$(med bare)
row() {  # label key
  local m
  m=$(med "$2")
  printf '| %s | %.1f | %.0f | %.3f |\n' "$1" "$m" "$(calc "$ITEMS * 3600 / $m")" "$(calc "$m / $ref")"
}

# Core-hours per 1000 labelled pairs at 640x480 (a bare run; every core busy).
t0=$(now)
"$asbuilt" dataset synth -o "$T/paper" --count 8 --seed 7 --size 640x480 >/dev/null 2>&1
paper=$(calc "$(now) - $t0")
cores=$(nproc)
core_hours=$(calc "$paper * $cores / 8 * 1000 / 3600")

{
  echo "## Slurm: sharded dataset synthesis (bench_cluster)"
  echo
  echo "$(date -u +%Y-%m-%d), $(nproc) cores ($(uname -n)), one-node Slurm $(sinfo --version | awk '{print $2}') on localhost"
  echo "(scripts/slurm/local-cluster.sh). $ITEMS items at 320x240, seed 7; median of $ROUNDS rounds; every"
  echo "run ends with the merged manifest (all three give the same bytes, checked). Load average at the"
  echo "start: $(cut -d' ' -f1-3 /proc/loadavg)."
  echo
  echo "| path | wall s | samples / hour | ratio to bare |"
  echo "|---|---|---|---|"
  row "bare \`dataset synth\` + \`dataset merge\`" bare
  row "\`cluster synth --shards 1\` (sbatch, array, merge job)" s1
  row "\`cluster synth --shards 2\`" s2
  echo
  printf 'Overhead of the Slurm path over a bare run: %+.1f %% (target <= 5 %%).\n' \
    "$(calc "($(med s1) / $ref - 1) * 100")"
  echo
  printf 'At 640x480 (the paper'"'"'s size), a bare run makes 8 labelled pairs in %.1f s on %d cores: %.2f\n' "$paper" "$cores" "$core_hours"
  printf 'core-hours per 1000 pairs; 100 000 pairs are %.0f core-hours, %.1f h of wall time on a 32-node\n' \
    "$(calc "$core_hours * 100")" "$(calc "$core_hours * 100 / (32 * 32)")"
  echo "cluster of 32-core nodes (one shard per core, no overhead counted)."
} >"$out"
cat "$out"
