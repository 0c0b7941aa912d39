#!/usr/bin/env bash
# Issue 21 (real photos): the next model's data with the realism levers of
# `asbuilt dataset synth --levers` (docs/render.md "Realism levers"), its
# training with tools/pytorch/train_gpu.py (one GPU), and the lever ablation
# on the ZInD benchmark (`asbuilt eval zind`, docs/seg.md "Real photos").
# No ZInD pixel, label or figure goes into training or model selection:
# ZInD is read only by `asbuilt eval zind`, after training, for the tables.
#
#   scripts/train-real-model.sh [BUILD_DIR] [WORK_DIR]
#
# Environment (defaults in brackets):
#   STAGES     which steps to run, any of data,train,eval,ablation [data,train,eval,ablation]
#   ABLATION   loo: one run per lever with all levers on but that one (leave-one-out);
#              add: one run per lever alone; both [loo]. Plus "none" and "all" runs.
#   ABL_ITEMS  items of each ablation data set [1500]; every set has the same seed, so the
#              rooms are the same and only the lever differs (levers draw their own streams)
#   ABL_STEPS  fine-tuning steps per ablation run, from the shipped model [1500]
#   ZIND       the ZInD sample tour [../shared/data/zind_sample_tour]
#   SMOKE=1    tiny counts and a few CPU steps of `asbuilt train` (tiny model) instead of
#              train_gpu.py: checks the recipe end to end where there is no GPU
#   PYTHON     a Python with torch (CUDA) and cv2 [python3]
#
# Photos: the photo_textures and outside_photos levers read Debian's
# collections at run time (gimp-data: /usr/share/gimp/2.0/patterns, 1.4 MB of
# patterns; blender: /usr/share/blender/datafiles/studiolights/world, 1.8 MB of
# CC0 HDR panoramas). Without them those levers fall back to procedural
# textures and the sky, with a warning; install with
# `scripts/install-deps.sh --photos`.
#
# Time on one H100 + 16 cores (estimates from the shipped run, MODEL_CARD.md):
# data 8,700 items ≈ 10 min on 16 cores; training 12,000 steps ≈ 11 min;
# each ablation run ≈ 1,500 items (≈ 2 min) + 1,500 steps (≈ 1.5 min) + ZInD eval.
set -euo pipefail
BUILD=${1:-build}
WORK=${2:-runs/real}
ASBUILT="$BUILD/asbuilt"
PYTHON=${PYTHON:-python3}
HERE=$(cd "$(dirname "$0")/.." && pwd)
STAGES=${STAGES:-data,train,eval,ablation}
ABLATION=${ABLATION:-loo}
ABL_ITEMS=${ABL_ITEMS:-1500}
ABL_STEPS=${ABL_STEPS:-1500}
ZIND=${ZIND:-$HERE/../shared/data/zind_sample_tour}
SMOKE=${SMOKE:-0}
LEVERS=(photo_textures outside_photos next_rooms door_leaves home_palette sunlight kitchens wall_details window_dressing
  phone_camera glass_doors close_views ceiling_like_walls wall_art close_doors)
mkdir -p "$WORK"
has() { [[ ",$STAGES," == *",$1,"* ]]; }

if [ "$SMOKE" = 1 ]; then
  N_A=8 N_B=8 N_PLAIN=4 N_VAL=4 N_TEST=4 ABL_ITEMS=4 SIZE=96x72
else
  N_A=3000 N_B=4000 N_PLAIN=1500 N_VAL=200 N_TEST=200 SIZE=320x240
fi

synth() {  # NAME LEVERS COUNT SEED
  "$ASBUILT" dataset synth -o "$WORK/raw/$1" --levers "$2" --count "$3" --seed "$4" --items-per-scene 4 \
    --size "$SIZE"
}

# Fine-tunes from INIT on DATA… → OUT/best (safetensors or .pt), then an asbuilt model.
train() {  # OUT INIT STEPS LR DATA...
  local out=$1 init=$2 steps=$3 lr=$4
  shift 4
  if [ "$SMOKE" = 1 ]; then
    # A few CPU steps of the C++ trainer on a tiny model (no GPU here); the
    # data folders are merged with symlinks (asbuilt train takes one folder).
    local merged="$out/data"
    mkdir -p "$merged/images" "$merged/labels"
    for d in "$@"; do
      for f in "$d"/images/*.png; do
        ln -sf "$(realpath "$f")" "$merged/images/$(basename "$d")_$(basename "$f")"
        ln -sf "$(realpath "${f/images/labels}")" "$merged/labels/$(basename "$d")_$(basename "$f")"
      done
    done
    "$ASBUILT" train --images "$merged" -o "$out" --arch tiny --epochs 1 --steps-per-epoch "$steps" --batch 2 \
      --scale 96x72 --crop 64x64 --val-max 2 --threads 2 --seed 1
    cp "$out/last.pt" "$out/model.pt"
  else
    [ -f "$out/best.safetensors" ] || $PYTHON "$HERE/tools/pytorch/train_gpu.py" --data "$@" \
      --val "$WORK/raw/val" --arch b0 --scale 320x240 --crop 256x256 --batch 32 --eval-every 500 \
      --init "$init" --steps "$steps" --lr "$lr" --warmup 200 --seed 0 -o "$out"
    "$ASBUILT" model import "$out/best.safetensors" -o "$out/model.pt"
  fi
}

zind_eval() {  # MODEL OUT
  if [ ! -d "$ZIND" ]; then echo "no ZInD tour at $ZIND: skipping the benchmark" >&2; return; fi
  local extra=()
  [ "$SMOKE" = 1 ] && extra=(--max-panoramas 1 --views 2)
  "$ASBUILT" eval zind --model "$1" --zind "$ZIND" -o "$2" --no-sheets "${extra[@]}"
}

# 0. The shipped model as the starting point (exported for train_gpu.py).
INIT="$WORK/shipped.safetensors"
[ -f "$INIT" ] || "$ASBUILT" model export "$HERE/models/segformer_b0_asbuilt.pt" -o "$INIT"

# 1. Data: two levered training sets, a plain set (keeps the renderer's
#    look in the mix), a levered validation set for model selection, and the
#    model card's plain held-out test set.
if has data; then
  synth A all "$N_A" 9101
  synth B all "$N_B" 9102
  synth plain none "$N_PLAIN" 9103
  synth val all "$N_VAL" 31338
  synth test none "$N_TEST" 777
fi

# 2. The next model: fine-tuned from the shipped one on all three sets.
if has train; then
  if [ "$SMOKE" = 1 ]; then STEPS=3; else STEPS=12000; fi
  train "$WORK/next" "$INIT" "$STEPS" 4e-4 "$WORK/raw/A" "$WORK/raw/B" "$WORK/raw/plain"
fi

# 3. Its evaluations: the model card's (renderer, Blender rooms) and ZInD.
if has eval; then
  "$HERE/scripts/eval-model.sh" "$ASBUILT" "$WORK/next/model.pt" "$WORK/raw/test" "$WORK/next" || true
  zind_eval "$WORK/next/model.pt" "$WORK/next/zind"
fi

# 4. Ablation: the same rooms (seed 9301) with each lever set, one short
#    fine-tuning run each from the shipped model, scored on ZInD.
if has ablation; then
  CONFIGS=(none all)
  for l in "${LEVERS[@]}"; do
    case "$ABLATION" in
      loo) CONFIGS+=("all,-$l") ;;
      add) CONFIGS+=("$l") ;;
      both) CONFIGS+=("all,-$l" "$l") ;;
    esac
  done
  if [ "$SMOKE" = 1 ]; then CONFIGS=(none all "all,-${LEVERS[0]}"); ABL_STEPS=2; fi
  for c in "${CONFIGS[@]}"; do
    name=abl_${c//,/_}
    synth "$name" "$c" "$ABL_ITEMS" 9301
    train "$WORK/$name" "$INIT" "$ABL_STEPS" 2e-4 "$WORK/raw/$name"
    zind_eval "$WORK/$name/model.pt" "$WORK/$name/zind"
  done
  # The table: ZInD whole-view mIoU and per-class IoU per configuration.
  $PYTHON - "$WORK" "${CONFIGS[@]}" <<'EOF'
import json, os, sys
work, configs = sys.argv[1], sys.argv[2:]
rows = ["| levers | mIoU | wall IoU | door IoU | window IoU | window precision | door recall | upper mIoU |",
        "|---|---|---|---|---|---|---|---|"]
for c in configs:
    path = os.path.join(work, "abl_" + c.replace(",", "_"), "zind", "metrics.json")
    if not os.path.exists(path):
        rows.append(f"| {c} | (no ZInD result) | | | | | | |")
        continue
    m = json.load(open(path))
    w, cls = m["whole"], m["whole"]["classes"]
    f = lambda v: "n/a" if v is None else f"{v:.3f}"
    rows.append(f"| {c} | {f(w['mIoU'])} | {f(cls[1]['IoU'])} | {f(cls[2]['IoU'])} | {f(cls[3]['IoU'])} | "
                f"{f(cls[3].get('Precision'))} | {f(cls[2].get('Recall'))} | {f(m['upper']['mIoU'])} |")
text = ("ZInD benchmark (asbuilt eval zind; ZInD: academic use only, research measurement, never training "
        "data). Each row: the shipped model fine-tuned on the same synthetic rooms with these levers.\n\n"
        + "\n".join(rows) + "\n")
open(os.path.join(work, "ablation.md"), "w").write(text)
print(text)
EOF
fi
