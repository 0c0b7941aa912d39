#!/usr/bin/env bash
# The ratio experiment of docs/seg.md ("A modest run on this machine"), with
# the data that exists here:
#   R  (stand-in, NOT real photos): blender-rooms-public room p01 (12 Blender
#      Cycles renders, another renderer than ours); test: room p02 (12 frames
#      of a different room, so no view of the test room is ever trained on)
#   S  240 views of asbuilt's own renderer (`dataset synth`, seed 4242)
#   extra test: the only two real indoor photos with annotations here (ADE20K
#      ADE_val_00001519, the NYUv2 README frame), imported to our 4 classes
#
#   scripts/ratio-experiment.sh [BUILD_DIR] [WORK_DIR]
#
# Defaults: BUILD_DIR=build, WORK_DIR=runs/ratios. Resumable: re-running
# skips rendered views and finished trainings.
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/ratios}
ASBUILT="$BUILD/asbuilt"
SHARED=${ASBUILT_SHARED_DATA:-../shared/data}
export OMP_WAIT_POLICY=${OMP_WAIT_POLICY:-passive}  # docs/seg.md: matters on a loaded machine.
mkdir -p "$WORK"

# 1. Synthetic views.
"$ASBUILT" dataset synth -o "$WORK/synth" --count 240 --seed 4242

# 2. The real photos, labels imported to background / wall / door / window.
R="$WORK/real_photos"
mkdir -p "$R/ade_indoor/images" "$R/nyu/images" "$WORK/annotations/ade" "$WORK/annotations/nyu"
cp "$SHARED/ade20k_sceneparsing_samples/images/ADE_val_00001519.png" "$R/ade_indoor/images/"
cp "$SHARED/ade20k_sceneparsing_samples/annotations/ADE_val_00001519.png" "$WORK/annotations/ade/"
cp "$SHARED/nyuv2_sample/image.png" "$R/nyu/images/nyu_office.png"
cp "$SHARED/nyuv2_sample/semantic40_ids.png" "$WORK/annotations/nyu/nyu_office.png"
"$ASBUILT" labels import --format ade20k "$WORK/annotations/ade" -o "$R/ade_indoor/labels"
"$ASBUILT" labels import --format nyuv2 "$WORK/annotations/nyu" -o "$R/nyu/labels"

# 3. The experiment: four configs, same test room, same schedule.
B="$SHARED/blender-rooms-public"
"$ASBUILT" experiment ratios --real "$B/p01_rect_1door_2win" --real-test "$B/p02_L_shape" \
  --synthetic "$WORK/synth" --extra-test "$R" --configs R100,S100,RS5050,RS8020 -o "$WORK/out" \
  --arch tiny --scale 192x144 --crop 128x128 --epochs 8 --steps-per-epoch 150 --batch 2 \
  --lr 1e-3 --warmup 100 --val-max 24 --seed 1
