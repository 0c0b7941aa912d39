#!/usr/bin/env bash
# The CPU route: reproduces the first shipped model, segformer_tiny_asbuilt.pt
# (3.45M params, mIoU 0.64 on blender-rooms-public; models/MODEL_CARD.md,
# "CPU route"; the file is in git history before the B0 model replaced it), with
# the asbuilt CLI only: toy-room pre-training, then two fine-tuning stages on
# views from asbuilt's own renderer (`dataset synth`), then the model card's
# evaluations. The shipped run was cut short by the CPU budget of its
# session; --stop-after and the item cut below replay exactly those cuts
# (same schedules, same data).
#
#   scripts/train-cpu-model.sh [BUILD_DIR] [WORK_DIR]
#
# Defaults: BUILD_DIR=build, WORK_DIR=runs/shipped. Resumable: re-running
# skips finished views and continues training from the last checkpoint.
# On a shared/loaded machine OMP_WAIT_POLICY=passive matters (docs/seg.md).
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/cpu-model}
ASBUILT="$BUILD/asbuilt"
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}
mkdir -p "$WORK"

# 1. Data. Toy rooms (seg/toy_rooms.h) for pre-training; renderer views for
#    fine-tuning (the first 434 items of an 800-item run were used) and a
#    held-out renderer test set with another seed.
"$ASBUILT" experiment toy-rooms -o "$WORK/toy" --count 4000 --seed 1 --width 256 --height 192
"$ASBUILT" dataset synth -o "$WORK/synth/a" --count 800 --seed 4242
for d in images labels idmaps depth meta; do
  find "$WORK/synth/a/$d" -name '000[4-7][0-9][0-9].*' | awk -F/ '{n=$NF; sub(/\..*/,"",n); if (n+0 >= 434) print}' | xargs -r rm -f
done
"$ASBUILT" dataset synth -o "$WORK/synth/b" --count 400 --seed 5151
"$ASBUILT" dataset synth -o "$WORK/synth_test" --count 200 --seed 777

COMMON=(--arch tiny --scale 192x144 --crop 128x128)
# 2. Pre-train on toy rooms: an 8-epoch schedule, stopped after epoch 2.
"$ASBUILT" train --images "$WORK/toy" -o "$WORK/pretrain" "${COMMON[@]}" --epochs 8 --steps-per-epoch 400 \
  --lr 1e-3 --warmup 200 --val-max 100 --seed 1 --stop-after 2
# 3. Fine-tune on the first renderer set: a 6-epoch schedule, stopped after epoch 3.
"$ASBUILT" train --images "$WORK/synth/a" -o "$WORK/ft1" "${COMMON[@]}" --init "$WORK/pretrain/last.pt" \
  --epochs 6 --steps-per-epoch 200 --lr 6e-4 --warmup 50 --val-max 40 --seed 2 --stop-after 3
# 4. Fine-tune on both renderer sets to the end of a 9-epoch schedule.
"$ASBUILT" train --images "$WORK/synth" -o "$WORK/ft2" "${COMMON[@]}" --init "$WORK/ft1/last.pt" \
  --epochs 9 --steps-per-epoch 200 --lr 4e-4 --warmup 20 --val-max 50 --seed 3

# 5. The model card's evaluations.
M="$WORK/ft2/best.pt"
"$(dirname "$0")/eval-model.sh" "$ASBUILT" "$M" "$WORK/synth_test" "$WORK"
