#!/usr/bin/env python3
"""The same SegFormer as src/asbuilt/seg/segformer.cc, in Python PyTorch, timed
the same way as bench_seg.

usage: segformer_bench.py ARCH THREADS REPEATS   one-shot: medians as one JSON object
       segformer_bench.py ARCH THREADS serve     bench_seg's peer: reads one command per
           line on stdin (infer | train SIDE | rss | quit), runs it once and answers one
           JSON line ({"s": seconds} or {"peak_rss_mib": …}), so bench_seg can interleave
           C++ and Python measurements (ABBA…) on a loaded machine.
"""
import json
import math
import resource
import sys
import time

import torch
import torch.nn as nn
import torch.nn.functional as F

CONFIGS = {
    "b0": dict(dims=(32, 64, 160, 256), heads=(1, 2, 5, 8), depths=(2, 2, 2, 2), dec=256),
    "tiny": dict(dims=(32, 64, 160, 256), heads=(1, 2, 5, 8), depths=(2, 2, 2, 2), dec=128),
    "b1": dict(dims=(64, 128, 320, 512), heads=(1, 2, 5, 8), depths=(2, 2, 2, 2), dec=256),
    "b2": dict(dims=(64, 128, 320, 512), heads=(1, 2, 5, 8), depths=(3, 4, 6, 3), dec=768),
}


class DropPath(nn.Module):
    def __init__(self, p):
        super().__init__()
        self.p = p

    def forward(self, x):
        if not self.training or self.p <= 0:
            return x
        keep = 1 - self.p
        mask = x.new_empty((x.shape[0],) + (1,) * (x.dim() - 1)).bernoulli_(keep)
        return x * mask / keep


class Attention(nn.Module):
    def __init__(self, dim, heads, sr):
        super().__init__()
        self.heads, self.sr_ratio, self.scale = heads, sr, (dim // heads) ** -0.5
        self.q, self.kv, self.proj = nn.Linear(dim, dim), nn.Linear(dim, 2 * dim), nn.Linear(dim, dim)
        if sr > 1:
            self.sr = nn.Conv2d(dim, dim, sr, sr)
            self.sr_norm = nn.LayerNorm(dim, eps=1e-6)

    def forward(self, x, h, w):
        b, n, c = x.shape
        d = c // self.heads
        q = self.q(x).reshape(b, n, self.heads, d).permute(0, 2, 1, 3)
        kv_in = x
        if self.sr_ratio > 1:
            kv_in = self.sr_norm(self.sr(x.transpose(1, 2).reshape(b, c, h, w)).flatten(2).transpose(1, 2))
        m = kv_in.shape[1]
        kv = self.kv(kv_in).reshape(b, m, 2, self.heads, d).permute(2, 0, 3, 1, 4)
        attn = torch.softmax(q @ kv[0].transpose(-2, -1) * self.scale, -1)
        return self.proj((attn @ kv[1]).transpose(1, 2).reshape(b, n, c))


class MixFfn(nn.Module):
    def __init__(self, dim, hidden):
        super().__init__()
        self.fc1 = nn.Conv2d(dim, hidden, 1)
        self.dwconv = nn.Conv2d(hidden, hidden, 3, padding=1, groups=hidden)
        self.fc2 = nn.Conv2d(hidden, dim, 1)

    def forward(self, x, h, w):
        b, n, c = x.shape
        y = self.dwconv(self.fc1(x.transpose(1, 2).reshape(b, c, h, w)))
        return self.fc2(F.gelu(y)).flatten(2).transpose(1, 2)


class Block(nn.Module):
    def __init__(self, dim, heads, sr, dp):
        super().__init__()
        self.norm1, self.norm2 = nn.LayerNorm(dim, eps=1e-6), nn.LayerNorm(dim, eps=1e-6)
        self.attn, self.ffn, self.drop_path = Attention(dim, heads, sr), MixFfn(dim, 4 * dim), DropPath(dp)

    def forward(self, x, h, w):
        x = x + self.drop_path(self.attn(self.norm1(x), h, w))
        return x + self.drop_path(self.ffn(self.norm2(x), h, w))


class Segformer(nn.Module):
    def __init__(self, arch, classes=4, drop_path=0.1):
        super().__init__()
        c = CONFIGS[arch]
        total = sum(c["depths"])
        self.embeds, self.enorms, self.stages = nn.ModuleList(), nn.ModuleList(), nn.ModuleList()
        inc, k = 3, 0
        for i, (dim, heads, depth, sr, ps, st) in enumerate(
                zip(c["dims"], c["heads"], c["depths"], (8, 4, 2, 1), (7, 3, 3, 3), (4, 2, 2, 2))):
            self.embeds.append(nn.ModuleList([nn.Conv2d(inc, dim, ps, st, ps // 2), nn.LayerNorm(dim, eps=1e-6)]))
            blocks = []
            for _ in range(depth):
                blocks.append(Block(dim, heads, sr, drop_path * k / (total - 1)))
                k += 1
            self.stages.append(nn.ModuleList(blocks))
            self.enorms.append(nn.LayerNorm(dim, eps=1e-6))
            inc = dim
        C = c["dec"]
        self.linear_c = nn.ModuleList(
            [nn.Sequential(nn.Conv2d(d, C, 1, bias=False), nn.BatchNorm2d(C), nn.ReLU(True)) for d in c["dims"]])
        self.fuse = nn.Sequential(nn.Conv2d(4 * C, C, 1, bias=False), nn.BatchNorm2d(C), nn.ReLU(True))
        self.dropout = nn.Dropout(0.1)
        self.classifier = nn.Conv2d(C, classes, 1)

    def forward(self, x):
        feats = []
        for (conv, norm), blocks, enorm in zip(self.embeds, self.stages, self.enorms):
            x = conv(x)
            b, c, h, w = x.shape
            x = norm(x.flatten(2).transpose(1, 2))
            for blk in blocks:
                x = blk(x, h, w)
            x = enorm(x).transpose(1, 2).reshape(b, c, h, w)
            feats.append(x)
        size = feats[0].shape[2:]
        up = []
        for i in (3, 2, 1, 0):
            y = self.linear_c[i](feats[i])
            if i > 0:
                y = F.interpolate(y, size=size, mode="bilinear", align_corners=False)
            up.append(y)
        return self.classifier(self.dropout(self.fuse(torch.cat(up, 1))))


def median(fn, repeats):
    t = []
    for _ in range(repeats):
        s = time.perf_counter()
        fn()
        t.append(time.perf_counter() - s)
    t.sort()
    return t[len(t) // 2]


class Workload:
    """The three measured operations, exactly as bench_seg.cc runs them."""

    def __init__(self, arch):
        torch.manual_seed(0)
        self.model = Segformer(arch)
        self.x = torch.randn(1, 3, 480, 640)
        self.opt = None
        self.batches = {}

    def infer(self):
        self.model.eval()
        with torch.no_grad():
            F.interpolate(self.model(self.x), size=(480, 640), mode="bilinear", align_corners=False).argmax(1)

    def train(self, side):
        self.model.train()
        if self.opt is None:
            self.opt = torch.optim.AdamW(self.model.parameters(), lr=1e-4, weight_decay=1e-3)
        if side not in self.batches:
            self.batches[side] = (torch.randn(2, 3, side, side), torch.randint(0, 4, (2, side, side)))
        xb, yb = self.batches[side]
        logits = F.interpolate(self.model(xb), size=(side, side), mode="bilinear", align_corners=False)
        loss = F.cross_entropy(logits, yb, ignore_index=255)
        self.opt.zero_grad()
        loss.backward()
        self.opt.step()


def peak_rss_mib():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024


def serve(work):
    print(json.dumps({"ready": True, "parameters": sum(p.numel() for p in work.model.parameters()),
                      "torch": torch.__version__, "threads": torch.get_num_threads()}), flush=True)
    for line in sys.stdin:
        cmd = line.split()
        if not cmd or cmd[0] == "quit":
            break
        if cmd[0] == "rss":
            print(json.dumps({"peak_rss_mib": peak_rss_mib()}), flush=True)
            continue
        faults = resource.getrusage(resource.RUSAGE_SELF).ru_minflt
        start = time.perf_counter()
        if cmd[0] == "infer":
            work.infer()
        elif cmd[0] == "train":
            work.train(int(cmd[1]))
        else:
            print(json.dumps({"error": f"unknown command {cmd[0]}"}), flush=True)
            continue
        seconds = time.perf_counter() - start
        print(json.dumps({"s": seconds, "minflt": resource.getrusage(resource.RUSAGE_SELF).ru_minflt - faults}),
              flush=True)


def main():
    arch, threads = sys.argv[1], int(sys.argv[2])
    torch.set_num_threads(threads)
    work = Workload(arch)
    if sys.argv[3] == "serve":
        serve(work)
        return
    repeats = int(sys.argv[3])
    params = sum(p.numel() for p in work.model.parameters())
    out = {"arch": arch, "threads": threads, "parameters": params, "torch": torch.__version__}
    work.infer()
    out["infer_640x480_s"] = median(work.infer, repeats)
    for side in (256, 512):
        work.train(side)
        out[f"train_{side}_images_per_s"] = 2 / median(lambda: work.train(side), repeats)
    out["peak_rss_mib"] = peak_rss_mib()
    print(json.dumps(out))


if __name__ == "__main__":
    main()
