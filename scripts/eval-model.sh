#!/usr/bin/env bash
# The model card's evaluations of one segmenter checkpoint (models/MODEL_CARD.md):
# held-out renderer views, blender-rooms-public, and the two real indoor photos.
#
#   scripts/eval-model.sh ASBUILT MODEL SYNTH_TEST_DIR WORK_DIR
#
# Writes WORK_DIR/eval_{synth_test,blender,ade20k_indoor,nyuv2}.json.
set -euo pipefail
ASBUILT=$1 M=$2 TEST=$3 WORK=$4
SHARED=${ASBUILT_SHARED_DATA:-../shared/data}
"$ASBUILT" eval seg --model "$M" --images "$TEST" --json "$WORK/eval_synth_test.json"
"$ASBUILT" eval seg --model "$M" --images "$SHARED/blender-rooms-public" --json "$WORK/eval_blender.json"
mkdir -p "$WORK/ade_indoor/images" "$WORK/ade_indoor/labels" "$WORK/nyu/images" "$WORK/nyu/labels"
ADE="$SHARED/ade20k_sceneparsing_samples"
cp "$ADE/images/ADE_val_00001519.png" "$WORK/ade_indoor/images/"
cp "$ADE/annotations/ADE_val_00001519.png" "$WORK/ade_indoor/labels/"
cp "$SHARED/nyuv2_sample/image.png" "$WORK/nyu/images/frame.png"
cp "$SHARED/nyuv2_sample/semantic40_ids.png" "$WORK/nyu/labels/frame.png"
"$ASBUILT" eval seg --model "$M" --images "$WORK/ade_indoor/images" --labels "$WORK/ade_indoor/labels" \
  --label-map ade20k --json "$WORK/eval_ade20k_indoor.json"
"$ASBUILT" eval seg --model "$M" --images "$WORK/nyu/images" --labels "$WORK/nyu/labels" \
  --label-map nyu40 --json "$WORK/eval_nyuv2.json"
echo "model: $M"
