#!/usr/bin/env bash
# Issue 21 (real photos) where there is no GPU: fine-tunes the shipped B0 on
# asbuilt's realism-levered renders mixed half and half with plain ones
# (`dataset synth --levers`, docs/render.md "Realism levers"), with and
# without the stray-light augmentation (`asbuilt train --stray-light`), on
# this machine's CPU cores, and once more with the close_doors lever's views
# added to the levered renders; then scores each run on the renderer's held-out
# views, on blender-rooms-public and on the ZInD benchmark (docs/seg.md
# "Real photos"). Checkpoints are chosen by synthetic validation mIoU alone:
# ZInD is read only by `asbuilt eval zind`, after training (academic use
# only: a test set, never training data).
#
#   scripts/train-cpu-finetune.sh [BUILD_DIR] [WORK_DIR]
#
# Environment (defaults in brackets):
#   RUNS     which runs, a list of stray-light shares on the levered data, and
#            doorsS for share S on the data with close_doors views [0.5,0,doors0.5]
#   EPOCHS   epochs of 50 steps, batch 8, 256x256 crops [6]
#   THREADS  LibTorch threads per run; the runs go side by side [1]
#   ZIND     the ZInD sample tour [../shared/data/zind_sample_tour]
#
# Time on 2 cores (2026-12-04): data ≈ 15 min (+8–20 for close_doors, with other work), each
# 300-step run ≈ 28 min with two side by side, each ZInD evaluation ≈ 2–3 min.
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/cpu-finetune}
ASBUILT="$BUILD/asbuilt"
HERE=$(cd "$(dirname "$0")/.." && pwd)
RUNS=${RUNS:-0.5,0,doors0.5}
EPOCHS=${EPOCHS:-6}
THREADS=${THREADS:-1}
ZIND=${ZIND:-$HERE/../shared/data/zind_sample_tour}
SHARED=${ASBUILT_SHARED_DATA:-$HERE/../shared/data}
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
mkdir -p "$WORK/data"

# 1. Data: the same rooms for every run (resumable: finished items are kept).
synth() {  # NAME LEVERS COUNT SEED
  "$ASBUILT" dataset synth -o "$WORK/data/$1" --levers "$2" --count "$3" --seed "$4" --items-per-scene 4 \
    --size 320x240
}
synth plain none 900 9104
synth levered all,-close_doors 1200 9201
# The same rooms and items but for the close_doors views (the lever draws its
# own stream): 20 % of the items become close-up door views.
mkdir -p "$WORK/data3"
ln -sfn ../data/plain "$WORK/data3/plain"
"$ASBUILT" dataset synth -o "$WORK/data3/levered" --levers all --count 1200 --seed 9201 --items-per-scene 4 \
  --size 320x240
[ -d "$WORK/synth_test" ] || "$ASBUILT" dataset synth -o "$WORK/synth_test" --count 200 --seed 777

# 2. The runs, side by side (each re-run resumes after its last finished epoch).
IFS=, read -r -a shares <<< "$RUNS"
name() { [[ $1 == doors* ]] && echo "$1" || echo "stray$1"; }
for r in "${shares[@]}"; do
  data="$WORK/data" s=$r
  [[ $r == doors* ]] && data="$WORK/data3" s=${r#doors}
  "$ASBUILT" train --images "$data" -o "$WORK/$(name "$r")" --arch b0 --init "$HERE/models/segformer_b0_asbuilt.pt" \
    --epochs "$EPOCHS" --steps-per-epoch 50 --batch 8 --lr 1e-4 --warmup 20 --scale 320x240 --crop 256x256 \
    --val-fraction 0.05 --val-max 40 --seed 21 --stray-light "$s" --threads "$THREADS" --quiet \
    > "$WORK/$(name "$r").log" 2>&1 &
done
wait

# 3. Scores: renderer views held out, Blender's rooms, and the real home.
for r in "${shares[@]}"; do
  out="$WORK/$(name "$r")" M="$WORK/$(name "$r")/best.pt"
  "$ASBUILT" eval seg --model "$M" --images "$WORK/synth_test" --json "$out/eval_synth_test.json"
  "$ASBUILT" eval seg --model "$M" --images "$SHARED/blender-rooms-public" --json "$out/eval_blender.json"
  [ -d "$ZIND" ] && "$ASBUILT" eval zind --model "$M" --zind "$ZIND" -o "$out/zind"
done
echo "runs in $WORK: stray*/ doors*/ best.pt, eval_*.json, zind/metrics.md"
