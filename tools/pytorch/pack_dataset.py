"""Packs dataset folders small for a trip to a GPU machine: images as JPEG (quality 92), labels as PNG.

    python3 tools/pytorch/pack_dataset.py SRC DST [--max N]

SRC holds images/ + labels/ (asbuilt dataset synth, experiment toy-rooms);
DST gets images/X.jpg + labels/X.png. 320×240 views take ≈ 11 KB per pair.
"""
import argparse
import os
import shutil

import cv2


def main():
    p = argparse.ArgumentParser()
    p.add_argument("src")
    p.add_argument("dst")
    p.add_argument("--max", type=int, default=0)
    p.add_argument("--quality", type=int, default=92)
    a = p.parse_args()
    os.makedirs(os.path.join(a.dst, "images"), exist_ok=True)
    os.makedirs(os.path.join(a.dst, "labels"), exist_ok=True)
    names = sorted(n for n in os.listdir(os.path.join(a.src, "images")) if n.endswith(".png"))
    if a.max:
        names = names[:a.max]
    n = 0
    for name in names:
        stem = name[:-4]
        label = os.path.join(a.src, "labels", stem + ".png")
        if not os.path.exists(label):
            continue
        im = cv2.imread(os.path.join(a.src, "images", name), cv2.IMREAD_COLOR)
        cv2.imwrite(os.path.join(a.dst, "images", stem + ".jpg"), im, [cv2.IMWRITE_JPEG_QUALITY, a.quality])
        shutil.copyfile(label, os.path.join(a.dst, "labels", stem + ".png"))
        n += 1
    print(f"{a.src} → {a.dst}: {n} pairs")


if __name__ == "__main__":
    main()
