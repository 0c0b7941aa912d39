#!/usr/bin/env bash
# Issue 38: the learning loop on real photos, leave-one-room-out. The three
# CC0 360° photos with hand-made truth (../shared/data/cc0-panoramas/
# annotated: Poly Haven, CC0) are surveyed with the default model, corrected
# as a surveyor would through the review page's HTTP API
# (scripts/review-from-truth.py replays the hand-made layout and saves), and
# `asbuilt learn` fine-tunes the default model on two of them plus renders,
# judging on the third; each room is left out in turn.
#
#   scripts/learn-cc0-loo.sh [BUILD_DIR] [WORK_DIR]
#
# Environment: MODEL to improve [default], SYNTH (a `dataset synth` folder to
# mix in; made here with every realism lever when absent), EPOCHS of 50
# steps [4], THREADS [0 = all cores].
# Time on 2 cores (2026-12-06), EPOCHS=2: surveys and reviews ≈ 1 min, each
# learn run ≈ 2 min. ZInD is never read here.
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/learn-cc0}
HERE=$(cd "$(dirname "$0")/.." && pwd)
ASBUILT="$BUILD/asbuilt"
SHARED=${ASBUILT_SHARED_DATA:-$HERE/../shared/data}
EPOCHS=${EPOCHS:-4}
MODEL=${MODEL:-default}
THREADS=${THREADS:-0}
ROOMS="comfy_cafe colorful_studio pine_attic"
mkdir -p "$WORK/reviews"

for room in $ROOMS; do
  out="$WORK/reviews/$room"
  [ -d "$out/review/training/labels" ] && continue
  "$ASBUILT" survey "$SHARED/cc0-panoramas/annotated/$room/capture.json" -o "$out" --quiet
  python3 "$HERE/scripts/review-from-truth.py" "$out" "$SHARED/cc0-panoramas/annotated/$room/truth.json" \
    --asbuilt "$ASBUILT"
done

if [ -z "${SYNTH:-}" ]; then
  SYNTH=$WORK/synth
  [ -f "$SYNTH/meta/000599.json" ] ||
    "$ASBUILT" dataset synth -o "$SYNTH" --levers all --count 600 --seed 4301 --items-per-scene 4 --size 320x240
fi

for room in $ROOMS; do
  "$ASBUILT" learn "$WORK/reviews" --model "$MODEL" --hold-out "$WORK/reviews/$room" --synthetic "$SYNTH" --config RS5050 \
    --epochs "$EPOCHS" --threads "$THREADS" -o "$WORK/loo_${MODEL}_$room" | tail -1
done
echo "learn-cc0-loo: reports in $WORK/loo_${MODEL}_*/report.md"
