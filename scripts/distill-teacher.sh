#!/usr/bin/env bash
# Issue 43 (c): distils the ADE20K-trained teacher (MLCommons DeepLabV3-
# MobileNetV2, read from ../shared/data/ade20k-teachers at run time) into our
# SegFormer-B0. The teacher labels views of real rooms (CC0 360° photos), our
# renderer labels its own rooms exactly, and the shipped B0 is fine-tuned on
# the two mixed half and half (the paper's RS5050), on this machine's CPUs.
#
#   scripts/distill-teacher.sh [BUILD_DIR] [WORK_DIR]
#
# Real rooms (each file's source and licence is written to WORK/real/SOURCES.md):
#   - ../shared/data/cc0-panoramas/*.hdr (Poly Haven, CC0) except the three
#     with hand-made truth in annotated/ (pine_attic, comfy_cafe,
#     colorful_studio): those are held out, to choose on;
#   - hall, lab, workshop, apartment of the npm package @pmndrs/assets
#     (CC0-1.0; its lobby, warehouse and studio are Poly Haven rooms above).
# ZInD is never read here (academic use only: a test set).
#
# Environment (defaults in brackets):
#   STEPS    fine-tuning steps, batch 8, 256x256 crops [300]
#   SYNTH    rendered views [600]
#   THREADS  LibTorch threads [0 = all cores]
#   DATA_ONLY=1  stop after making the data (real views and labels, renders, mix)
#
# Time on 2 cores (2026-12-06): renders 2.6 min, real views and teacher labels
# ≈ 3 min, 300 steps ≈ 20 min.
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/distill}
HERE=$(cd "$(dirname "$0")/.." && pwd)
ASBUILT="$BUILD/asbuilt"
SHARED=${ASBUILT_SHARED_DATA:-$HERE/../shared/data}
TEACHER=$SHARED/ade20k-teachers/deeplabv3_mnv2_ade20k32_uint8.tflite
STEPS=${STEPS:-300}
SYNTH=${SYNTH:-600}
THREADS=${THREADS:-0}
HELD_OUT="pine_attic comfy_cafe colorful_studio"
[ -f "$TEACHER" ] || { echo "distill-teacher: $TEACHER not found (../shared/data/ade20k-teachers)" >&2; exit 1; }
mkdir -p "$WORK/real" "$WORK/panoramas"

# 1. The real rooms' panoramas, with their sources.
sources="$WORK/real/SOURCES.md"
{
  echo "# Real rooms in this dataset: sources and licences"
  echo
  echo "| room | file | source | licence |"
  echo "|---|---|---|---|"
} > "$sources"
for hdr in "$SHARED"/cc0-panoramas/*.hdr; do
  name=$(basename "$hdr" .hdr)
  [[ " $HELD_OUT " == *" $name "* ]] && continue
  ln -sfn "$hdr" "$WORK/panoramas/$name.hdr"
  echo "| $name | ../shared/data/cc0-panoramas/$name.hdr | Poly Haven asset $name (cc0-panoramas/README.md) | CC0 1.0 |" >> "$sources"
done
for name in hall lab workshop apartment; do
  [ -f "$WORK/panoramas/pmndrs_$name.exr" ] || "$HERE/scripts/pmndrs-hdri.sh" "$name" "$WORK/panoramas/pmndrs_$name.exr"
  echo "| pmndrs_$name | package/hdri/$name.exr.js of npm @pmndrs/assets 1.7.0 | pmndrs/assets (npm) | CC0-1.0 |" >> "$sources"
done

# 2. Views (level, and pitched ±25° to show the floor and ceiling edges) and
#    the teacher's labels, mapped onto wall / door / window / background.
export OPENCV_IO_ENABLE_OPENEXR=1
for pano in "$WORK"/panoramas/*.hdr "$WORK"/panoramas/*.exr; do
  name=$(basename "${pano%.*}")
  for pitch in 0 25 -25; do
    dir="$WORK/real/$name/pitch$pitch"
    [ -f "$dir/labels/011.png" ] && continue
    "$ASBUILT" pano views "$pano" -o "$dir" --size 320x240 --fx 160 --pitch "$pitch" --first-yaw 15 > /dev/null
    "$ASBUILT" segment --model "$TEACHER" -o "$dir/labels" --quiet "$dir/images"
  done
done

# 3. Renders with every realism lever, and the mix.
[ -f "$WORK/synth/meta/$(printf '%06d' $((SYNTH - 1))).json" ] ||
  "$ASBUILT" dataset synth -o "$WORK/synth" --levers all --count "$SYNTH" --seed 4301 --items-per-scene 4 \
    --size 320x240
"$ASBUILT" dataset mix --real "$WORK/real" --synthetic "$WORK/synth" --config RS5050 --test-fraction 0.05 \
  --seed 43 -o "$WORK/mix.json"

[ "${DATA_ONLY:-0}" = 1 ] && exit 0  # scripts/finetune-teacher.sh reuses the data above.

# 4. Fine-tune the shipped B0 (resumes after its last finished epoch).
"$ASBUILT" train --manifest "$WORK/mix.json" -o "$WORK/b0" --arch b0 --init "$HERE/models/segformer_b0_asbuilt.pt" \
  --epochs $((STEPS / 50)) --steps-per-epoch 50 --batch 8 --lr 1e-4 --warmup 20 --scale 320x240 --crop 256x256 \
  --val-max 60 --seed 43 --threads "$THREADS"
echo "distill-teacher: model $WORK/b0/best.pt; real views and labels in $WORK/real (SOURCES.md)"
