#!/usr/bin/env bash
# The tests that need a real Slurm cluster (`make test-cluster`, and ctest
# cluster/slurm when root and Slurm are there), run against the one-node
# cluster on localhost that scripts/slurm/local-cluster.sh has brought up.
#
#   tests/cluster/run.sh [BUILD_DIR]   BUILD_DIR: where `asbuilt` was built (default build)
#
# 1. the cluster's own self-test (sbatch, array, dependency, srun, scancel);
# 2. `asbuilt cluster synth`, 4 shards through sbatch, then the merge job:
#    the manifest equals one process's, byte for byte; `cluster status`;
# 3. the same with one task's asbuilt killed -9 mid-run and the rest
#    cancelled (scancel): no item left partial, the status names them, and
#    `cluster synth --resume` finishes to the same manifest;
# 4. a damaged file is caught by `dataset verify`;
# 5. `asbuilt cluster eval`, 3 shards and the merge: metrics.json equals one
#    process's `eval seg --json`, byte for byte;
# 6. `asbuilt cluster train --tasks 2`: two ranks under srun give the single
#    process's epoch losses within 1e-4, and the same weights on both ranks;
#    one rank killed -9 after the first checkpoint stops the job, and
#    `cluster train --resume` finishes the run from it.
set -euo pipefail
cd "$(dirname "$0")/../.."
BUILD=$(cd "${1:-build}" && pwd)
ASBUILT=$BUILD/asbuilt
# shellcheck source=/dev/null
. "${ASBUILT_SLURM_DIR:-/tmp/asbuilt-slurm}/env.sh"

T=$(mktemp -d /tmp/asbuilt-cluster-test.XXXXXX)
trap 'rm -rf "$T"' EXIT
ITEMS=(--count 24 --seed 5 --size 160x120 --spp 2 --items-per-scene 3)
fail() { echo "tests/cluster: FAIL: $*" >&2; exit 1; }
ok() { echo "ok    $*"; }

# Waits (at most $2 s) until job $1 has left the queue.
wait_job() {
  local t=0
  while [[ -n $(squeue -h -j "$1" 2>/dev/null) ]]; do
    ((t++ < $2 * 5)) || fail "job $1 still queued after $2 s"
    sleep 0.2
  done
}
# The merge job id `cluster synth` printed.
merge_job() { sed -n 's/.*merge job \([0-9]*\).*/\1/p' <<<"$1" | tail -1; }

bash scripts/slurm/local-cluster.sh selftest

"$ASBUILT" dataset synth -o "$T/ref" "${ITEMS[@]}" >/dev/null 2>&1
"$ASBUILT" dataset merge "$T/ref" >/dev/null

# 2. Four shards and the merge, through sbatch.
out=$("$ASBUILT" cluster synth -o "$T/ds" --shards 4 "${ITEMS[@]}")
wait_job "$(merge_job "$out")" 300
cmp -s "$T/ref/synth_manifest.json" "$T/ds/synth_manifest.json" ||
  fail "4-shard manifest differs from one process's: $(cat "$T"/ds/cluster/logs/merge-*.out)"
status=$("$ASBUILT" cluster status "$T/ds")
grep -q "items complete: 24 of 24" <<<"$status" && grep -q "^merged:" <<<"$status" || fail "status: $status"
ok "cluster synth: 4 shards + merge = one process's manifest; status: all done, merged"

# 3. Kill one task's asbuilt with SIGKILL as soon as it has finished an item, cancel the rest.
out=$("$ASBUILT" cluster synth -o "$T/killed" --shards 4 "${ITEMS[@]}")
array=$(sed -n 's/.*as job \([0-9]*\).*/\1/p' <<<"$out")
for _ in $(seq 600); do
  compgen -G "$T/killed/meta/*.json" >/dev/null && break
  sleep 0.05
done
pkill -9 -f "dataset synth -o $T/killed --shard 0/4" || true
scancel "$array"
wait_job "$array" 60
wait_job "$(merge_job "$out")" 60
[[ ! -e $T/killed/synth_manifest.json ]] || fail "the merge ran over missing items"
for meta in "$T"/killed/meta/*.json; do
  i=$(basename "$meta" .json)
  for f in images labels idmaps depth; do [[ -e $T/killed/$f/$i.png ]] || fail "item $i is partial: no $f"; done
done
for f in "$T"/killed/{images,labels,idmaps,depth}/*.png; do
  [[ -e $T/killed/meta/$(basename "$f" .png).json ]] || fail "partial item: $f without its meta file"
done
status=$("$ASBUILT" cluster status "$T/killed")
grep -Eq "killed \(exit 137\)|cancelled" <<<"$status" || fail "status names no killed or cancelled shard: $status"
grep -q -- "--resume" <<<"$status" || fail "status does not say how to finish: $status"
ok "a task killed -9 and the rest cancelled: no partial item; status: $(grep -Ec 'killed|cancelled' <<<"$status") shards stopped"
sed 's/^/      /' <<<"$status"
out=$("$ASBUILT" cluster synth -o "$T/killed" --resume)
wait_job "$(merge_job "$out")" 300
cmp -s "$T/ref/synth_manifest.json" "$T/killed/synth_manifest.json" ||
  fail "resumed manifest differs: $(cat "$T"/killed/cluster/logs/merge-*.out)"
ok "cluster synth --resume: $(sed -n 's/.*submitted \([0-9]*\) task.*/\1/p' <<<"$out") shard(s) again, the same manifest"

# 4. A damaged file.
printf 'x' | dd of="$T/ds/images/000007.png" bs=1 seek=100 conv=notrunc status=none
if "$ASBUILT" dataset verify "$T/ds" >"$T/verify.txt" 2>&1; then fail "verify passed a damaged file"; fi
grep -q "images/000007.png: changed since the merge" "$T/verify.txt" || fail "verify: $(cat "$T/verify.txt")"
ok "dataset verify names a damaged file"

# 5. A sharded evaluation (skipped by a build without LibTorch).
if "$ASBUILT" eval seg --model default --images "$T/ref" --json "$T/eval-whole.json" >"$T/eval.txt" 2>&1; then
  out=$("$ASBUILT" cluster eval default "$T/ref" -o "$T/eval" --shards 3)
  wait_job "$(merge_job "$out")" 300
  cmp -s "$T/eval-whole.json" "$T/eval/metrics.json" ||
    fail "cluster eval metrics differ from one process's: $(cat "$T"/eval/cluster/logs/eval-merge-*.out)"
  "$ASBUILT" cluster status "$T/eval" | grep -q "shards done: 3 of 3" || fail "eval status: $("$ASBUILT" cluster status "$T/eval")"
  ok "cluster eval: 3 shards + merge = one process's metrics.json"
else
  grep -q "no LibTorch" "$T/eval.txt" || fail "eval seg: $(cat "$T/eval.txt")"
  echo "skip  cluster eval: this build has no LibTorch"
fi

# 6. Data-parallel training (skipped by a build without LibTorch).
if ! grep -q "no LibTorch" "$T/eval.txt"; then
  "$ASBUILT" experiment toy-rooms -o "$T/toy" --count 10 --width 48 --height 32 --seed 5 >/dev/null 2>&1
  train=(--images "$T/toy" --arch tiny --batch 2 --scale 48x32 --crop 48x32 --lr 1e-5 --val-fraction 0.2 --seed 3
    --threads 1)
  "$ASBUILT" train -o "$T/single" "${train[@]}" --epochs 2 --steps-per-epoch 4 >/dev/null 2>&1
  out=$("$ASBUILT" cluster train -o "$T/two" --tasks 2 "${train[@]}" --epochs 2 --steps-per-epoch 4 --dist-timeout 60)
  job=$(sed -n 's/.*submitted job \([0-9]*\).*/\1/p' <<<"$out")
  wait_job "$job" 300
  grep -q "weights identical on the 2 ranks" "$T"/two/cluster/logs/train-*.out ||
    fail "cluster train: $(cat "$T"/two/cluster/logs/train-*.out)"
  python3 - "$T/single/log.csv" "$T/two/log.csv" <<'PY' || fail "cluster train: losses differ from one process's"
import csv, sys
a, b = ([float(r["train_loss"]) for r in csv.DictReader(open(p))] for p in sys.argv[1:])
assert len(a) == len(b) == 2 and all(abs(x - y) <= 1e-4 for x, y in zip(a, b)), (a, b)
PY
  ok "cluster train: 2 ranks under srun = one process's losses (1e-4), identical weights on both ranks"

  out=$("$ASBUILT" cluster train -o "$T/killed-train" --tasks 2 "${train[@]}" --epochs 3 --steps-per-epoch 80 \
    --dist-timeout 60)
  job=$(sed -n 's/.*submitted job \([0-9]*\).*/\1/p' <<<"$out")
  for _ in $(seq 1200); do [[ -e $T/killed-train/last.pt ]] && break; sleep 0.05; done
  [[ -e $T/killed-train/last.pt ]] || fail "cluster train wrote no checkpoint: $(cat "$T"/killed-train/cluster/logs/*)"
  kill -9 "$(pgrep -f "^$ASBUILT train -o $T/killed-train" | tail -1)" 2>/dev/null || true
  wait_job "$job" 120
  epochs=$("$ASBUILT" cluster status "$T/killed-train" | sed -n 's/^epochs done: \([0-9]*\).*/\1/p')
  ((epochs < 3)) || fail "the kill came after the run had finished"
  out=$("$ASBUILT" cluster train -o "$T/killed-train" --resume)
  wait_job "$(sed -n 's/.*submitted job \([0-9]*\).*/\1/p' <<<"$out")" 300
  status=$("$ASBUILT" cluster status "$T/killed-train")
  grep -q "^epochs done: 3" <<<"$status" || fail "resumed cluster train: $status $(tail -5 "$T"/killed-train/cluster/logs/*)"
  ok "cluster train: a rank killed -9 after epoch $epochs of 3; --resume finished the run from its checkpoint"
fi

echo "tests/cluster: passed"
