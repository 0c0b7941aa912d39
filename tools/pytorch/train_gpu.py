"""Trains asbuilt's SegFormer on a GPU with PyTorch, then `asbuilt model import` brings it home.

The C++ trainer (`asbuilt train`) is the reference and runs anywhere LibTorch
does; this script exists because the project's CPU budget (2 cores) cannot
train a B0 to convergence, while one GPU does it in minutes. Same network
(asbuilt_segformer.py, checked against the C++ forward pass by
seg/model_file_test.cc), same data format (`asbuilt dataset synth` and
`asbuilt experiment toy-rooms` folders: images/ + labels/), the same
augmentation as seg/seg_data.cc (random resize 0.5–2.0 around the base
scale, crop with mmseg's cat_max_ratio, flip, photometric distortion, blur,
sensor noise), AdamW with linear warm-up and poly decay, cross-entropy with
ignore 255 on logits upsampled to the label size, validation mIoU with the
whole-image inference of seg/segmenter.cc.

    python3 tools/pytorch/train_gpu.py --data D1 D2 --val V --arch b0 \
        --scale 320x240 --crop 256x256 --batch 32 --steps 12000 -o OUT
    asbuilt model import OUT/best.safetensors -o models/mine.pt

Writes OUT/best.safetensors, OUT/last.safetensors (atomically, at each
validation), OUT/log.jsonl (one record per validation) and prints progress.
"""

import argparse
import contextlib
import json
import math
import os
import random
import sys
import time

import cv2
import numpy as np
import torch
import torch.nn.functional as F

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asbuilt_segformer as tw  # noqa: E402

cv2.setNumThreads(1)
IMAGE_EXT = (".png", ".jpg", ".jpeg", ".webp", ".bmp")


def size_arg(text):
    w, h = text.lower().split("x")
    return int(w), int(h)


def list_pairs(folder):
    """(image, label) paths of a dataset folder: images/X.* with labels/X.png."""
    img_dir, lab_dir = os.path.join(folder, "images"), os.path.join(folder, "labels")
    pairs = []
    for name in sorted(os.listdir(img_dir)):
        stem, ext = os.path.splitext(name)
        if ext.lower() in IMAGE_EXT and os.path.exists(os.path.join(lab_dir, stem + ".png")):
            pairs.append((os.path.join(img_dir, name), os.path.join(lab_dir, stem + ".png")))
    if not pairs:
        raise SystemExit(f"{folder}: no images/X + labels/X.png pairs")
    return pairs


def read_pair(pair):
    bgr = cv2.imread(pair[0], cv2.IMREAD_COLOR)
    label = cv2.imread(pair[1], cv2.IMREAD_UNCHANGED)
    if bgr is None or label is None or label.ndim != 2 or bgr.shape[:2] != label.shape:
        raise SystemExit(f"{pair}: unreadable or mismatched pair")
    return bgr, label


def fit_size(w, h, sw, sh):
    s = min(sw / w, sh / h)
    return max(1, int(round(w * s))), max(1, int(round(h * s)))


def add_stray_light(bgr, label, rng):
    """seg/seg_data.cc AddStrayLight: patches of sun or lamp light, and, half
    the time, dimmed windows, so that brightness alone does not say window."""
    h, w = label.shape
    gain = np.zeros((h, w), np.float32)
    for _ in range(1 + int(rng.random() * 3)):
        mask = np.zeros((h, w), np.uint8)
        cx, cy = rng.uniform(0, w), rng.uniform(0, h)
        extent = min(w, h)
        a, b, angle = rng.uniform(0.08, 0.35) * extent, rng.uniform(0.05, 0.25) * extent, rng.uniform(0, 180)
        if rng.random() < 0.6:
            skew, t = rng.uniform(-0.8, 0.8), np.deg2rad(angle)
            ax = np.array([a * np.cos(t), a * np.sin(t)])
            ay = np.array([b * (-np.sin(t) + skew * np.cos(t)), b * (np.cos(t) + skew * np.sin(t))])
            c = np.array([cx, cy])
            quad = np.array([c - ax - ay, c + ax - ay, c + ax + ay, c - ax + ay]).round().astype(np.int32)
            cv2.fillConvexPoly(mask, quad, 255, cv2.LINE_AA)
        else:
            cv2.ellipse(mask, (int(cx), int(cy)), (int(a), int(b)), angle, 0, 360, 255, cv2.FILLED, cv2.LINE_AA)
        soft = cv2.GaussianBlur(mask.astype(np.float32) / 255, (0, 0), rng.uniform(0.5, 0.5 * b))
        gain += soft * rng.uniform(0.5, 3.0)
    warmth = rng.uniform(0, 0.25)
    tint = np.array([1 - warmth, 1, 1 + 0.5 * warmth], np.float32)  # BGR.
    img = np.clip(bgr.astype(np.float32) * (1 + gain[..., None] * tint), 0, 255).astype(np.uint8)
    if rng.random() < 0.5:
        window = label == 3
        if window.any():
            grey = cv2.cvtColor(cv2.cvtColor(img, cv2.COLOR_BGR2GRAY), cv2.COLOR_GRAY2BGR).astype(np.float32)
            keep, scale = rng.uniform(0.2, 1.0), rng.uniform(0.35, 0.9)
            dim = img.astype(np.float32) * keep * scale + grey * (1 - keep) * scale
            img[window] = np.clip(dim[window], 0, 255).astype(np.uint8)
    return img


def augment(bgr, label, a, rng):
    """seg/seg_data.cc AugmentPair, in NumPy/OpenCV."""
    fw, fh = fit_size(bgr.shape[1], bgr.shape[0], *a.scale)
    ratio = rng.uniform(0.5, 2.0)
    size = (max(1, int(fw * ratio)), max(1, int(fh * ratio)))
    bgr = cv2.resize(bgr, size, interpolation=cv2.INTER_LINEAR)
    # INTER_NEAREST_EXACT: INTER_NEAREST moves label edges half a pixel right
    # and down of the image's (seg/segmenter.h, label_offset_px).
    label = cv2.resize(label, size, interpolation=cv2.INTER_NEAREST_EXACT)
    cw, ch = a.crop
    pw, ph = max(0, cw - size[0]), max(0, ch - size[1])
    if pw or ph:
        bgr = cv2.copyMakeBorder(bgr, 0, ph, 0, pw, cv2.BORDER_CONSTANT, value=(0, 0, 0))
        label = cv2.copyMakeBorder(label, 0, ph, 0, pw, cv2.BORDER_CONSTANT, value=255)
    for _ in range(10):
        x = rng.randrange(0, bgr.shape[1] - cw + 1)
        y = rng.randrange(0, bgr.shape[0] - ch + 1)
        hist = np.bincount(label[y:y + ch, x:x + cw].ravel(), minlength=256)[:255]
        if (hist > 0).sum() > 1 and hist.max() < 0.75 * hist.sum():
            break
    bgr = bgr[y:y + ch, x:x + cw]
    label = label[y:y + ch, x:x + cw]
    if rng.random() < 0.5:
        bgr, label = bgr[:, ::-1], label[:, ::-1]
    if a.stray_light > 0 and rng.random() < a.stray_light:
        bgr = add_stray_light(np.ascontiguousarray(bgr), np.ascontiguousarray(label), rng)
    f = bgr.astype(np.float32)
    if rng.random() < 0.5:
        f += rng.uniform(-32, 32)
    contrast_first = rng.random() < 0.5
    if contrast_first and rng.random() < 0.5:
        f *= rng.uniform(0.5, 1.5)
    img = np.clip(f, 0, 255).astype(np.uint8)
    if rng.random() < 0.5 or rng.random() < 0.5:
        hsv = cv2.cvtColor(img, cv2.COLOR_BGR2HSV)
        if rng.random() < 0.5:
            hsv[..., 1] = np.clip(hsv[..., 1].astype(np.float32) * rng.uniform(0.5, 1.5), 0, 255).astype(np.uint8)
        if rng.random() < 0.5:
            dh = int(rng.uniform(-9, 9))
            hsv[..., 0] = ((hsv[..., 0].astype(np.int16) + dh + 180) % 180).astype(np.uint8)
        img = cv2.cvtColor(hsv, cv2.COLOR_HSV2BGR)
    if not contrast_first and rng.random() < 0.5:
        img = np.clip(img.astype(np.float32) * rng.uniform(0.5, 1.5), 0, 255).astype(np.uint8)
    if rng.random() < 0.3:
        img = cv2.GaussianBlur(img, (0, 0), rng.uniform(0.3, 1.5))
    if rng.random() < 0.3:
        noise = np.random.default_rng(rng.getrandbits(32)).normal(0, rng.uniform(2, 10), img.shape)
        img = np.clip(img.astype(np.float32) + noise, 0, 255).astype(np.uint8)
    return np.ascontiguousarray(img[..., ::-1]), np.ascontiguousarray(label)  # RGB.


class Stream(torch.utils.data.IterableDataset):
    """Endless augmented crops; each worker has its own seeded generator."""

    def __init__(self, samples, args):
        self.samples, self.args = samples, args

    def __iter__(self):
        info = torch.utils.data.get_worker_info()
        rng = random.Random(self.args.seed * 1000 + (info.id if info else 0))
        while True:
            bgr, label = self.samples[rng.randrange(len(self.samples))]
            img, lab = augment(bgr, label, self.args, rng)
            yield torch.from_numpy(img), torch.from_numpy(lab.astype(np.int64))


def mixed_precision(device):
    """bf16 autocast on a GPU (weights stay float32); nothing on the CPU."""
    return torch.autocast("cuda", dtype=torch.bfloat16) if device.type == "cuda" else contextlib.nullcontext()


def confusion(pred, label, n=4):
    m = label != 255
    return torch.bincount(label[m] * n + pred[m], minlength=n * n).reshape(n, n)


def metrics_of(conf):
    conf = conf.double()
    tp = conf.diag()
    gt, pr = conf.sum(1), conf.sum(0)
    iou = tp / (gt + pr - tp)
    prec, rec = tp / pr, tp / gt
    fs = 2 * prec * rec / (prec + rec)
    present = gt > 0  # mmseg: classes absent from the labels are NaN and left out of the means.

    def mean(v):
        v = v[present]
        v = v[~torch.isnan(v)]
        return float(v.mean()) if len(v) else float("nan")

    return {"mIoU": mean(iou), "mFscore": mean(fs), "mPrecision": mean(prec), "mRecall": mean(rec),
            "aAcc": float(tp.sum() / conf.sum()), "IoU": [float(x) for x in iou]}


@torch.no_grad()
def evaluate(model, samples, args, device):
    """Whole-image inference as seg/segmenter.cc: fit to the scale, upsample logits to the image."""
    model.eval()
    conf = torch.zeros(4, 4, dtype=torch.int64, device=device)
    for bgr, label in samples:
        w, h = fit_size(bgr.shape[1], bgr.shape[0], *args.scale)
        img = cv2.resize(bgr, (w, h), interpolation=cv2.INTER_LINEAR)[..., ::-1].copy()
        x = tw.images_to_tensor(torch.from_numpy(img)[None].to(device))
        with mixed_precision(device):
            logits = model(x)
        logits = F.interpolate(logits.float(), size=label.shape, mode="bilinear", align_corners=False)
        conf += confusion(logits.argmax(1)[0].reshape(-1), torch.from_numpy(label.astype(np.int64)).to(device).reshape(-1))
    model.train()
    return metrics_of(conf.cpu())


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--data", nargs="+", required=True, help="training folders (images/ + labels/)")
    p.add_argument("--val", nargs="+", required=True, help="validation folders (never trained on)")
    p.add_argument("-o", "--out", required=True)
    p.add_argument("--arch", default="b0")
    p.add_argument("--scale", type=size_arg, default=(320, 240))
    p.add_argument("--crop", type=size_arg, default=(256, 256))
    p.add_argument("--batch", type=int, default=32)
    p.add_argument("--stray-light", type=float, default=0.0,
                   help="share of crops given light patches and dimmed windows (asbuilt train --stray-light)")
    p.add_argument("--steps", type=int, default=10000)
    p.add_argument("--lr", type=float, default=1e-3)
    p.add_argument("--weight-decay", type=float, default=1e-2)
    p.add_argument("--warmup", type=int, default=500)
    p.add_argument("--eval-every", type=int, default=1000)
    p.add_argument("--workers", type=int, default=max(1, (os.cpu_count() or 2) - 2))
    p.add_argument("--init", default="", help="safetensors to start from (asbuilt model export, or a run here)")
    p.add_argument("--budget-min", type=float, default=0,
                   help="fit the schedule to this many minutes of training: after 200 steps, --steps is set from "
                        "the measured rate (the resolved value is printed and stored in the metadata)")
    p.add_argument("--time-limit-min", type=float, default=0, help="stop cleanly after this long (0 = none)")
    p.add_argument("--seed", type=int, default=0)
    args = p.parse_args()

    torch.manual_seed(args.seed)
    random.seed(args.seed)
    device = torch.device("cuda" if torch.cuda.is_available() else "cpu")
    os.makedirs(args.out, exist_ok=True)
    t0 = time.time()
    train_pairs = [q for d in args.data for q in list_pairs(d)]
    val_pairs = [q for d in args.val for q in list_pairs(d)]
    from multiprocessing import Pool
    with Pool(max(1, args.workers)) as pool:
        train = pool.map(read_pair, train_pairs, chunksize=64)
        val = pool.map(read_pair, val_pairs, chunksize=64)
    print(f"data: {len(train)} train, {len(val)} val pairs read in {time.time() - t0:.1f} s", flush=True)

    if args.init:
        model, init_meta = tw.load_safetensors_model(args.init)
        config = model.config
        print(f"init: {args.init} ({init_meta.get('trainer', '?')})", flush=True)
    else:
        config = tw.config_for(args.arch)
        model = tw.Segformer(config)
    model = model.to(device).to(memory_format=torch.channels_last)
    params = sum(q.numel() for q in model.parameters())
    gpu = torch.cuda.get_device_name(0) if device.type == "cuda" else "cpu"
    print(f"model: {config['arch']} {params / 1e6:.2f}M params on {gpu}, torch {torch.__version__}", flush=True)

    decay = [q for n, q in model.named_parameters() if q.ndim > 1]
    no_decay = [q for n, q in model.named_parameters() if q.ndim <= 1]  # Norms and biases (mmseg custom_keys).
    opt = torch.optim.AdamW([{"params": decay, "weight_decay": args.weight_decay},
                             {"params": no_decay, "weight_decay": 0.0}], lr=args.lr, betas=(0.9, 0.999))

    def lr_at(step):
        if step < args.warmup:
            return args.lr * (step + 1) / args.warmup
        return args.lr * (1 - (step - args.warmup) / max(1, args.steps - args.warmup)) ** 1.0

    loader = torch.utils.data.DataLoader(Stream(train, args), batch_size=args.batch, num_workers=args.workers,
                                         pin_memory=True, persistent_workers=True, prefetch_factor=4)
    mean = torch.tensor(tw.MEAN_RGB, device=device).view(1, 3, 1, 1)
    std = torch.tensor(tw.STD_RGB, device=device).view(1, 3, 1, 1)
    history, best, best_step = [], -1.0, 0
    run_loss, run_n, step = 0.0, 0, 0
    t_train = time.time()
    model.train()

    def save(name, record_meta):
        meta = {"format": tw.CHECKPOINT_FORMAT, "scale": list(args.scale), "crop": list(args.crop),
                "label_resize": "nearest_exact",
                "epoch": int(round(step * args.batch / len(train))), "step": step,
                "history": history, "best_miou": best, "best_epoch": int(round(best_step * args.batch / len(train))),
                "best_step": best_step,
                "options": {k: (list(v) if isinstance(v, tuple) else v) for k, v in vars(args).items()},
                "trainer": f"tools/pytorch/train_gpu.py, PyTorch {torch.__version__}, {gpu}"}
        meta.update(record_meta)
        tw.save_safetensors_model(os.path.join(args.out, name), model, meta)

    def validate():
        nonlocal best, best_step, run_loss, run_n
        m = evaluate(model, val, args, device)
        rec = {"epoch": int(round(step * args.batch / len(train))), "step": step, "lr": lr_at(step),
               "train_loss": run_loss / max(1, run_n), "val_mIoU": m["mIoU"], "val_mFscore": m["mFscore"],
               "val_mPrecision": m["mPrecision"], "val_mRecall": m["mRecall"], "val_aAcc": m["aAcc"],
               "wall_s": time.time() - t_train}
        history.append(rec)
        with open(os.path.join(args.out, "log.jsonl"), "a") as f:
            f.write(json.dumps(dict(rec, val_IoU=m["IoU"])) + "\n")
        run_loss, run_n = 0.0, 0
        if m["mIoU"] > best:
            best, best_step = m["mIoU"], step
            save("best.safetensors", {})
        save("last.safetensors", {})
        print(f"step {step}/{args.steps}: loss {rec['train_loss']:.4f} val mIoU {m['mIoU']:.4f} "
              f"IoU {' '.join(f'{x:.3f}' for x in m['IoU'])} best {best:.4f}@{best_step} "
              f"({time.time() - t_train:.0f} s)", flush=True)

    for img, lab in loader:
        for g in opt.param_groups:
            g["lr"] = lr_at(step)
        x = img.to(device, non_blocking=True).permute(0, 3, 1, 2).float()
        x = ((x - mean) / std).contiguous(memory_format=torch.channels_last)
        y = lab.to(device, non_blocking=True)
        with mixed_precision(device):
            logits = model(x)
        logits = F.interpolate(logits.float(), size=y.shape[1:], mode="bilinear", align_corners=False)
        loss = F.cross_entropy(logits, y, ignore_index=255)
        opt.zero_grad(set_to_none=True)
        loss.backward()
        opt.step()
        run_loss += float(loss.detach()) if step % 20 == 0 else 0.0  # Sampled: a sync per step costs.
        run_n += 1 if step % 20 == 0 else 0
        step += 1
        if args.budget_min > 0 and step == 200:
            per_step = (time.time() - t_train) / step
            args.steps = max(step + 1, int((60 * args.budget_min - 200 * per_step) / per_step * 0.97) + step)
            args.budget_min = 0
            print(f"  budget: {per_step * 1000:.1f} ms/step → --steps {args.steps}", flush=True)
        if step % 200 == 0:
            el = time.time() - t_train
            print(f"  step {step}: loss {float(loss.detach()):.4f}, {step * args.batch / el:.0f} img/s, "
                  f"ETA {el / step * (args.steps - step):.0f} s", flush=True)
        out_of_time = args.time_limit_min > 0 and time.time() - t0 > 60 * args.time_limit_min
        if step % args.eval_every == 0 or step >= args.steps or out_of_time:
            validate()
        if step >= args.steps or out_of_time:
            break
    print(f"done: {step} steps in {time.time() - t_train:.0f} s, best val mIoU {best:.4f} at step {best_step}",
          flush=True)


if __name__ == "__main__":
    main()
