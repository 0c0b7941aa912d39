#!/usr/bin/env bash
# Reproduces models/segformer_b0_asbuilt.pt (see models/MODEL_CARD.md) with
# the asbuilt CLI only: toy-room pre-training, then fine-tuning on views from
# asbuilt's own renderer, then the model card's evaluations.
#
#   scripts/train-shipped-model.sh [BUILD_DIR] [WORK_DIR]
#
# Defaults: BUILD_DIR=build, WORK_DIR=runs/shipped. Resumable: re-running
# skips finished views and continues training from the last checkpoint.
# On a shared/loaded machine OMP_WAIT_POLICY=passive matters (docs/seg.md).
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/shipped}
ASBUILT="$BUILD/asbuilt"
SHARED=${ASBUILT_SHARED_DATA:-../shared/data}
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
mkdir -p "$WORK"

# 1. Data: 4000 toy-room views (seg/toy_rooms.h) + asbuilt renderer views.
"$ASBUILT" experiment toy-rooms -o "$WORK/toy" --count 4000 --seed 1 --width 256 --height 192
"$ASBUILT" dataset synth -o "$WORK/synth_train" --count 800 --seed 4242
"$ASBUILT" dataset synth -o "$WORK/synth_test" --count 200 --seed 777

# 2. Pre-train on toy rooms (the shipped run stopped after epoch 3 of 8 for
#    lack of CPU time; --epochs 3 with the same schedule length reproduces it).
"$ASBUILT" train --images "$WORK/toy" -o "$WORK/pretrain" --arch tiny --epochs 8 --steps-per-epoch 400 \
  --lr 1e-3 --warmup 200 --scale 192x144 --crop 128x128 --val-max 100 --seed 1

# 3. Fine-tune on renderer views.
"$ASBUILT" train --images "$WORK/synth_train" -o "$WORK/finetune" --arch tiny --init "$WORK/pretrain/last.pt" \
  --epochs 2 --steps-per-epoch 200 --lr 3e-4 --scale 192x144 --crop 128x128 --val-max 60 --seed 2

# 4. Evaluations of the model card.
M="$WORK/finetune/best.pt"
"$ASBUILT" eval seg --model "$M" --images "$WORK/synth_test" --json "$WORK/eval_synth_test.json"
for room in p01_rect_1door_2win p02_L_shape; do
  "$ASBUILT" eval seg --model "$M" --images "$SHARED/blender-rooms-public/$room/left" \
    --labels "$SHARED/blender-rooms-public/$room/labels" --json "$WORK/eval_blender_$room.json"
done
"$ASBUILT" eval seg --model "$M" --images "$SHARED/ade20k_sceneparsing_samples/images" \
  --labels "$SHARED/ade20k_sceneparsing_samples/annotations" --label-map ade20k --json "$WORK/eval_ade20k.json"
echo "model: $M"
