#!/usr/bin/env bash
# bench_cluster OUT.md — what the Slurm path costs and gives (issue 41), on the
# one-node cluster of scripts/slurm/local-cluster.sh (brought up if needed and
# down after; needs root and `scripts/install-deps.sh --cluster`):
#   - a bare `asbuilt dataset synth` + `dataset merge` (the reference);
#   - `asbuilt cluster synth --shards 1` and `--shards 2` (sbatch, array job,
#     merge job), to the merged manifest;
# each ROUNDS times (median), the same ITEMS items at the paper's 640x480;
# samples per hour, the ratio to the reference, the Slurm path's fixed cost in
# seconds, and core-hours per 1000 labelled pairs.
set -euo pipefail
out=${1:?usage: bench_cluster OUT.md}
asbuilt="@PROJECT_BINARY_DIR@/asbuilt"  # Set by CMake (bench/cluster/CMakeLists.txt).
src="@PROJECT_SOURCE_DIR@"
: "${ROUNDS:=3}" "${ITEMS:=48}"
items=(--count "$ITEMS" --seed 7 --size 640x480)
tiny=(--count 2 --seed 7 --size 640x480)  # Two items: what the Slurm path costs beyond the work.
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

bare() {  # round [tiny]
  local d=$T/bare-$1${2:-} t0 opts=("${items[@]}")
  [[ -n ${2:-} ]] && opts=("${tiny[@]}")
  t0=$(now)
  "$asbuilt" dataset synth -o "$d" "${opts[@]}" >/dev/null 2>&1
  "$asbuilt" dataset merge "$d" >/dev/null 2>&1
  calc "$(now) - $t0"
}
slurm() {  # shards round [tiny]
  local d=$T/slurm-$1-$2${3:-} t0 o opts=("${items[@]}")
  [[ -n ${3:-} ]] && opts=("${tiny[@]}")
  t0=$(now)
  o=$("$asbuilt" cluster synth -o "$d" --shards "$1" "${opts[@]}")
  wait_job "$(sed -n 's/.*merge job \([0-9]*\).*/\1/p' <<<"$o")"
  [[ -f $d/synth_manifest.json ]] || { echo "bench_cluster: no manifest in $d" >&2; exit 1; }
  cmp -s "$d/synth_manifest.json" "$T/bare-1${3:-}/synth_manifest.json" || { echo "bench_cluster: manifests differ" >&2; exit 1; }
  calc "$(now) - $t0"
}

declare -A times
for r in $(seq "$ROUNDS"); do
  times[bare]+="$(bare "$r") "
  times[s1]+="$(slurm 1 "$r") "
  times[s2]+="$(slurm 2 "$r") "
  times[bare_tiny]+="$(bare "$r" tiny) "
  times[s1_tiny]+="$(slurm 1 "$r" tiny) "
  echo "bench_cluster: round $r of $ROUNDS" >&2
done
med() { tr ' ' '\n' <<<"${times[$1]}" | grep . | median; }
ref=$(med bare)
row() {  # label key
  local m
  m=$(med "$2")
  printf '| %s | %.1f | %.0f | %.3f | %s |\n' "$1" "$m" "$(calc "$ITEMS * 3600 / $m")" "$(calc "$m / $ref")" \
    "$(awk '{for (i = 1; i <= NF; ++i) printf "%s%.1f", (i > 1 ? ", " : ""), $i}' <<<"${times[$2]}")"
}

cores=$(nproc)
fixed=$(calc "$(med s1_tiny) - $(med bare_tiny)")
core_hours=$(calc "$ref * $cores / $ITEMS * 1000 / 3600")

{
  echo "## Slurm: sharded dataset synthesis (bench_cluster)"
  echo
  echo "$(date -u +%Y-%m-%d), $(nproc) cores ($(uname -n)), one-node Slurm $(sinfo --version | awk '{print $2}') on localhost"
  echo "(scripts/slurm/local-cluster.sh). $ITEMS items at 640x480, seed 7; median of $ROUNDS rounds; every"
  echo "run ends with the merged manifest (all three give the same bytes, checked). Load average at the"
  echo "start: $(cut -d' ' -f1-3 /proc/loadavg)."
  echo
  echo "| path | wall s | samples / hour | ratio to bare | each round, s |"
  echo "|---|---|---|---|---|"
  row "bare \`dataset synth\` + \`dataset merge\`" bare
  row "\`cluster synth --shards 1\` (sbatch, array, merge job)" s1
  row "\`cluster synth --shards 2\`" s2
  echo
  printf 'Slurm path against a bare run: %+.1f %% with one task, %+.1f %% with two (target <= 5 %%). Its\n' \
    "$(calc "($(med s1) / $ref - 1) * 100")" "$(calc "($(med s2) / $ref - 1) * 100")"
  printf 'cost beyond the work, measured on 2 items (%.1f s bare, %.1f s through Slurm), is %.1f s: two sbatch\n' \
    "$(med bare_tiny)" "$(med s1_tiny)" "$fixed"
  echo "calls, the scheduler starting the array task and then the merge job after it. It does not grow"
  printf 'with the work: under 5 %% of any run longer than %.0f s.\n' "$(calc "$fixed * 20")"
  echo "On 2 cores two tasks can only match one: each task already renders on both cores."
  echo
  printf 'A bare run makes %d labelled 640x480 pairs in %.1f s on %d cores: %.2f core-hours per 1000\n' \
    "$ITEMS" "$ref" "$cores" "$core_hours"
  printf 'pairs; 100 000 pairs are %.0f core-hours: %.0f min on a 32-node cluster of 32-core nodes (one\n' \
    "$(calc "$core_hours * 100")" "$(calc "$core_hours * 100 / (32 * 32) * 60")"
  echo "shard per node, the fixed cost above added once)."
} >"$out"
cat "$out"
