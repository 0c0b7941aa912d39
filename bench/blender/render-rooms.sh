#!/usr/bin/env bash
# The Blender bench's rooms (issue 37): 24 scenes of the kinds real rooms come
# in, each rendered by Blender Cycles as a 360° panorama with an exact label
# pass, written as a panorama capture with its truth plan:
#
#   OUT/NN_KIND/scene.json  capture.json  pano.png  labels.exr  truth.json
#
#
# and labels_noskirting.exr, the label pass of the same room without its
# skirting boards (the control of bench_blender's bias experiment). Odd NN are
# the calibration half, even NN the held-out half (bench_blender reads the
# split from the name). A room already rendered is kept, so a second run only
# surveys.
#
#   bench/blender/render-rooms.sh ASBUILT OUT [SAMPLES]
set -euo pipefail

asbuilt=${1:?usage: render-rooms.sh ASBUILT OUT [SAMPLES]}
out=${2:?usage: render-rooms.sh ASBUILT OUT [SAMPLES]}
samples=${3:-64}
width=1024
command -v blender > /dev/null || { echo "render-rooms.sh: blender is not installed" >&2; exit 2; }
mkdir -p "$out"

# NN KIND: how the scene is made. random SEED OPTIONS… or text DESCRIPTION.
rooms=(
  "01_room random 3701 --rig-spot survey"
  "02_room random 3702 --rig-spot survey"
  "03_room random 3703 --rig-spot survey"
  "04_room random 3704 --rig-spot survey"
  "05_room random 3705 --rig-spot survey"
  "06_room random 3706 --rig-spot survey"
  "07_room random 3707 --rig-spot survey"
  "08_room random 3708 --rig-spot survey"
  "09_L_rotated random 3709 --rig-spot survey --l-shape-probability 1 --rotated-probability 1"
  "10_L_rotated random 3710 --rig-spot survey --l-shape-probability 1 --rotated-probability 1"
  "11_rotated random 3711 --rig-spot survey --l-shape-probability 0 --rotated-probability 1"
  "12_rotated random 3712 --rig-spot survey --l-shape-probability 0 --rotated-probability 1"
  "13_hall random 3713 --rig-spot survey --min-side 10 --max-side 16 --min-height-m 3.2 --max-height-m 4.5"
  "14_hall random 3714 --rig-spot survey --min-side 10 --max-side 16 --min-height-m 3.2 --max-height-m 4.5"
  "15_small random 3715 --rig-spot survey --min-side 1.8 --max-side 3"
  "16_small random 3716 --rig-spot survey --min-side 1.8 --max-side 3"
  "17_near_wall random 3717 --rig-spot random"
  "18_near_wall random 3718 --rig-spot random"
  "19_near_wall random 3719 --rig-spot random --l-shape-probability 1"
  "20_near_wall random 3720 --rig-spot random --l-shape-probability 1"
  "21_corridor text a corridor 1.5 m wide and 7 m long with a door and a window"
  "22_corridor text a hallway 1.8 by 6 m with a door, a window with a sill at 1.2 m"
  "23_windows text a room 5 by 4 m with a door, a window with a sill at 0.4 m and a window with a sill at 1.5 m"
  "24_windows text a living room 6 by 4.5 m with two doors, a window with a sill at 0.9 m, a window with a sill at 0.5 m"
)

# The label pass of DIR/scene.json with every room's skirting taken out.
labels_without_skirting() {
  local dir=$1
  python3 -c '
import json, sys
d = sys.argv[1]
scene = json.load(open(d + "/scene.json"))
for room in scene["rooms"]:
    room["skirting"] = False
json.dump(scene, open(d + "/noskirting.json", "w"))
' "$dir"
  "$asbuilt" scene export-blender "$dir/noskirting.json" -o "$dir/noskirting.py" --panorama "$width" \
    --labels-pass > /dev/null
  blender -b --factory-startup -P "$dir/noskirting.py" -o "$dir/noskirting/" -f 1 >> "$dir/blender.log" 2>&1
  mv "$dir/noskirting/index/index_0001.exr" "$dir/labels_noskirting.exr.tmp"
  rm -rf "$dir/noskirting" "$dir/noskirting.py" "$dir/noskirting.json"
  mv "$dir/labels_noskirting.exr.tmp" "$dir/labels_noskirting.exr"
}

n=0
for spec in "${rooms[@]}"; do
  read -r name how rest <<< "$spec"
  n=$((n + 1))
  dir="$out/$name"
  if [ -f "$dir/capture.json" ]; then
    [ -f "$dir/labels_noskirting.exr" ] || labels_without_skirting "$dir"
    continue
  fi
  tmp="$out/.$name.tmp"
  rm -rf "$tmp" && mkdir -p "$tmp"
  if [ "$how" = random ]; then
    read -r seed options <<< "$rest"
    # shellcheck disable=SC2086  # options are words
    "$asbuilt" scene random --seed "$seed" $options -o "$tmp/random" > /dev/null
    mv "$tmp"/random/scene_*.json "$tmp/scene.json"
    rm -rf "$tmp/random"
  else
    "$asbuilt" scene text "$rest" -o "$tmp/scene.json" > /dev/null
  fi
  "$asbuilt" scene truth "$tmp/scene.json" -o "$tmp/truth.json" > /dev/null
  "$asbuilt" scene export-blender "$tmp/scene.json" -o "$tmp/pano.py" --panorama "$width" --samples "$samples" > /dev/null
  "$asbuilt" scene export-blender "$tmp/scene.json" -o "$tmp/labels.py" --panorama "$width" --labels-pass > /dev/null
  echo "render-rooms.sh: $n/${#rooms[@]} $name" >&2
  blender -b --factory-startup -P "$tmp/pano.py" -o "$tmp/photo/" -f 1 > "$tmp/blender.log" 2>&1
  blender -b --factory-startup -P "$tmp/labels.py" -o "$tmp/label_pass/" -f 1 >> "$tmp/blender.log" 2>&1
  mv "$tmp/photo/0001.png" "$tmp/pano.png"
  mv "$tmp/label_pass/index/index_0001.exr" "$tmp/labels.exr"
  rm -rf "$tmp/photo" "$tmp/label_pass" "$tmp/pano.py" "$tmp/labels.py"
  # The camera stands where the scene's rig turns.
  python3 - "$tmp" << 'EOF'
import json, sys
d = sys.argv[1]
scene = json.load(open(d + "/scene.json"))
turn = scene.get("turn") or {}
position = turn.get("position_m") or scene["viewpoints"][0]["position_m"]
json.dump({"version": 1, "kind": "panorama", "panorama": "pano.png", "position_m": position},
          open(d + "/capture.json", "w"), indent=1)
EOF
  labels_without_skirting "$tmp"
  rm -rf "$dir" && mv "$tmp" "$dir"
done
echo "render-rooms.sh: ${#rooms[@]} rooms in $out" >&2
