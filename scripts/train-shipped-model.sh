#!/usr/bin/env bash
# Reproduces models/segformer_b0_asbuilt.pt (models/MODEL_CARD.md): data from
# asbuilt's own generators, three training stages with
# tools/pytorch/train_gpu.py (the Python twin of asbuilt's SegFormer; needs a
# PyTorch with CUDA — one GPU, ~20 min of training in all), then
# `asbuilt model import` and the model card's evaluations with asbuilt.
#
#   scripts/train-shipped-model.sh [BUILD_DIR] [WORK_DIR]
#
# Defaults: BUILD_DIR=build, WORK_DIR=runs/b0. PYTHON (default python3) must
# import torch and cv2. The shipped run moved data to a GPU machine in
# pieces of ≤ 64 MiB, hence the item ranges per stage below and the JPEG
# packing (quality 92); stage inits also travelled as float16 copies, which
# this script skips (a difference far below run-to-run noise).
# Without a GPU the same script runs on the CPU, at about 3 images/s: days.
# The CPU-only route is scripts/train-cpu-model.sh (a smaller, weaker model).
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/b0}
ASBUILT="$BUILD/asbuilt"
PYTHON=${PYTHON:-python3}
HERE=$(cd "$(dirname "$0")/.." && pwd)
TRAIN="$PYTHON $HERE/tools/pytorch/train_gpu.py"
PACK="$PYTHON $HERE/tools/pytorch/pack_dataset.py"
mkdir -p "$WORK"

# 1. Data: renderer views (4 per room), toy rooms, a validation set (model
#    selection) and a held-out test set (never seen in training or selection).
"$ASBUILT" dataset synth -o "$WORK/raw/A" --count 3000 --seed 9001 --items-per-scene 4
"$ASBUILT" dataset synth -o "$WORK/raw/B" --count 4000 --seed 9002 --items-per-scene 4
"$ASBUILT" dataset synth -o "$WORK/raw/val" --count 200 --seed 31337 --items-per-scene 4
"$ASBUILT" dataset synth -o "$WORK/raw/test" --count 200 --seed 777
"$ASBUILT" experiment toy-rooms -o "$WORK/raw/toy" --count 450 --seed 11 --width 320 --height 240

# Item ranges as the shipped run used them: NAME SOURCE FIRST COUNT.
slice() {
  local name=$1 src=$2 first=$3 count=$4 tmp="$WORK/slices/$1"
  [ -d "$WORK/packed/$name" ] && return
  mkdir -p "$tmp/images" "$tmp/labels"
  for f in $(ls "$WORK/raw/$src/images" | sed -n "$((first + 1)),$((first + count))p"); do
    ln -sf "$(realpath "$WORK/raw/$src/images/$f")" "$tmp/images/$f"
    ln -sf "$(realpath "$WORK/raw/$src/labels/$f")" "$tmp/labels/$f"
  done
  $PACK "$tmp" "$WORK/packed/$name"
}
slice A_all A 0 3000
slice toy toy 0 450
slice val val 0 200
slice A_1 A 0 1500
slice B_1 B 0 1460
slice A_2 A 1500 400
slice B_2 B 1460 2540

COMMON=(--val "$WORK/packed/val" --arch b0 --scale 320x240 --crop 256x256 --batch 32 --eval-every 1000)
P="$WORK/packed"
# 2. From scratch (the shipped run's time budget resolved to 5036 steps).
[ -f "$WORK/s1/best.safetensors" ] || $TRAIN "${COMMON[@]}" --data "$P/A_all" "$P/toy" -o "$WORK/s1" \
  --steps 5036 --lr 8e-4 --warmup 1000 --seed 0
# 3. Fine-tune on new rooms.
[ -f "$WORK/s2/best.safetensors" ] || $TRAIN "${COMMON[@]}" --data "$P/A_1" "$P/B_1" -o "$WORK/s2" \
  --init "$WORK/s1/best.safetensors" --steps 8500 --lr 4e-4 --warmup 300 --seed 2
# 4. Fine-tune on more new rooms.
[ -f "$WORK/s3/best.safetensors" ] || $TRAIN "${COMMON[@]}" --data "$P/A_2" "$P/B_2" -o "$WORK/s3" \
  --init "$WORK/s2/best.safetensors" --steps 8000 --lr 2.5e-4 --warmup 300 --seed 3

# 5. Into asbuilt, and the model card's evaluations (asbuilt's own metrics).
M="$WORK/segformer_b0_asbuilt.pt"
"$ASBUILT" model import "$WORK/s3/best.safetensors" -o "$M"
"$(dirname "$0")/eval-model.sh" "$ASBUILT" "$M" "$WORK/raw/test" "$WORK"
