"""asbuilt's SegFormer in Python PyTorch: the twin of src/asbuilt/seg/segformer.cc.

Same modules, same parameter and buffer names, same numerics, so weights move
between the two through safetensors files:

    asbuilt model export models/segformer_b0_asbuilt.pt -o tiny.safetensors
    model, meta = load_safetensors_model("tiny.safetensors")      # here
    save_safetensors_model("mine.safetensors", model, meta)       # here
    asbuilt model import mine.safetensors -o mine.pt

The safetensors reader/writer below is the format's whole specification
(8-byte little-endian header length, JSON header, raw little-endian data), so
no extra package is needed. The file's "__metadata__" holds one key,
"asbuilt_meta": the checkpoint metadata JSON (format, config, scale, ...), as
asbuilt's own checkpoints carry it (src/asbuilt/seg/model_io.h).

Used by tools/pytorch/train_gpu.py (GPU training of the shipped model),
tools/pytorch/make_twin_fixture.py (the C++ test fixture) and
bench/seg/segformer_bench.py users who want the same network in Python.
"""

import json
import math
import struct

import torch
import torch.nn as nn
import torch.nn.functional as F

CHECKPOINT_FORMAT = "asbuilt-segformer-v1"
CLASS_NAMES = ["background", "wall", "door", "window"]
# ImageNet statistics in RGB order (mmseg data_preprocessor; model_io.cc).
MEAN_RGB = (123.675, 116.28, 103.53)
STD_RGB = (58.395, 57.12, 57.375)


def config_for(arch, num_classes=4):
    """The published configurations, as seg/segformer_config.cc."""
    c = dict(arch=arch, in_channels=3, embed_dims=[32, 64, 160, 256], num_heads=[1, 2, 5, 8],
             depths=[2, 2, 2, 2], sr_ratios=[8, 4, 2, 1], patch_sizes=[7, 3, 3, 3], strides=[4, 2, 2, 2],
             mlp_ratio=4, decoder_dim=256, num_classes=num_classes, drop_path_rate=0.1, decoder_dropout=0.1)
    if arch == "b0":
        pass
    elif arch == "tiny":
        c["decoder_dim"] = 128
    elif arch == "b1":
        c["embed_dims"] = [64, 128, 320, 512]
    elif arch == "b2":
        c.update(embed_dims=[64, 128, 320, 512], depths=[3, 4, 6, 3], decoder_dim=768)
    else:
        raise ValueError(f"unknown arch {arch!r} (b0, b1, b2, tiny)")
    return c


def _to_map(x, h, w):
    return x.transpose(1, 2).reshape(x.shape[0], x.shape[2], h, w)


def _to_seq(x):
    return x.flatten(2).transpose(1, 2)


def _layer_norm(dim):
    return nn.LayerNorm(dim, eps=1e-6)


class DropPath(nn.Module):
    def __init__(self, p):
        super().__init__()
        self.p = p

    def forward(self, x):
        if not self.training or self.p <= 0:
            return x
        keep = 1.0 - self.p
        mask = torch.empty((x.shape[0],) + (1,) * (x.dim() - 1), dtype=x.dtype, device=x.device).bernoulli_(keep)
        return x * mask / keep


class OverlapPatchEmbed(nn.Module):
    def __init__(self, in_ch, dim, patch, stride):
        super().__init__()
        self.proj = nn.Conv2d(in_ch, dim, patch, stride=stride, padding=patch // 2)
        self.norm = _layer_norm(dim)

    def forward(self, x):
        x = self.proj(x)
        h, w = x.shape[2], x.shape[3]
        return self.norm(_to_seq(x)), h, w


class EfficientAttention(nn.Module):
    def __init__(self, dim, heads, sr_ratio):
        super().__init__()
        self.heads, self.sr_ratio = heads, sr_ratio
        self.scale = 1.0 / math.sqrt(dim // heads)
        self.q = nn.Linear(dim, dim)
        self.kv = nn.Linear(dim, 2 * dim)
        self.proj = nn.Linear(dim, dim)
        if sr_ratio > 1:
            self.sr = nn.Conv2d(dim, dim, sr_ratio, stride=sr_ratio)
            self.sr_norm = _layer_norm(dim)

    def forward(self, x, h, w):
        b, n, c = x.shape
        d = c // self.heads
        q = self.q(x).reshape(b, n, self.heads, d).permute(0, 2, 1, 3)
        kv_in = self.sr_norm(_to_seq(self.sr(_to_map(x, h, w)))) if self.sr_ratio > 1 else x
        m = kv_in.shape[1]
        kv = self.kv(kv_in).reshape(b, m, 2, self.heads, d).permute(2, 0, 3, 1, 4)
        if hasattr(F, "scaled_dot_product_attention"):  # PyTorch ≥ 2.0: fused kernels, same maths.
            out = F.scaled_dot_product_attention(q, kv[0], kv[1])
        else:
            out = torch.softmax(q @ kv[0].transpose(-2, -1) * self.scale, dim=-1) @ kv[1]
        return self.proj(out.transpose(1, 2).reshape(b, n, c))


class MixFfn(nn.Module):
    def __init__(self, dim, hidden):
        super().__init__()
        self.fc1 = nn.Conv2d(dim, hidden, 1)
        self.dwconv = nn.Conv2d(hidden, hidden, 3, padding=1, groups=hidden)
        self.fc2 = nn.Conv2d(hidden, dim, 1)

    def forward(self, x, h, w):
        return _to_seq(self.fc2(F.gelu(self.dwconv(self.fc1(_to_map(x, h, w))))))


class MitBlock(nn.Module):
    def __init__(self, dim, heads, mlp_ratio, sr_ratio, drop_path):
        super().__init__()
        self.norm1 = _layer_norm(dim)
        self.attn = EfficientAttention(dim, heads, sr_ratio)
        self.norm2 = _layer_norm(dim)
        self.ffn = MixFfn(dim, dim * mlp_ratio)
        self.drop_path = DropPath(drop_path)

    def forward(self, x, h, w):
        x = x + self.drop_path(self.attn(self.norm1(x), h, w))
        return x + self.drop_path(self.ffn(self.norm2(x), h, w))


class MixTransformer(nn.Module):
    def __init__(self, c):
        super().__init__()
        total = sum(c["depths"])
        k = 0
        in_ch = c["in_channels"]
        self.depths = c["depths"]
        for i in range(4):
            setattr(self, f"patch_embed{i}",
                    OverlapPatchEmbed(in_ch, c["embed_dims"][i], c["patch_sizes"][i], c["strides"][i]))
            for j in range(c["depths"][i]):
                p = c["drop_path_rate"] * k / (total - 1) if total > 1 else 0.0
                setattr(self, f"block{i}_{j}",
                        MitBlock(c["embed_dims"][i], c["num_heads"][i], c["mlp_ratio"], c["sr_ratios"][i], p))
                k += 1
            setattr(self, f"norm{i}", _layer_norm(c["embed_dims"][i]))
            in_ch = c["embed_dims"][i]

    def forward(self, x):
        outs = []
        for i in range(4):
            x, h, w = getattr(self, f"patch_embed{i}")(x)
            for j in range(self.depths[i]):
                x = getattr(self, f"block{i}_{j}")(x, h, w)
            x = _to_map(getattr(self, f"norm{i}")(x), h, w)
            outs.append(x)
        return outs


class SegformerHead(nn.Module):
    def __init__(self, c):
        super().__init__()
        d = c["decoder_dim"]
        for i in range(4):
            setattr(self, f"linear_c{i}", nn.Sequential(nn.Conv2d(c["embed_dims"][i], d, 1, bias=False),
                                                        nn.BatchNorm2d(d), nn.ReLU(inplace=True)))
        self.fuse = nn.Sequential(nn.Conv2d(4 * d, d, 1, bias=False), nn.BatchNorm2d(d), nn.ReLU(inplace=True))
        self.dropout = nn.Dropout(c["decoder_dropout"])
        self.classifier = nn.Conv2d(d, c["num_classes"], 1)

    def forward(self, feats):
        size = feats[0].shape[2:]
        up = []
        for i in (3, 2, 1, 0):  # mmseg order: deepest first.
            y = getattr(self, f"linear_c{i}")(feats[i])
            if i > 0:
                y = F.interpolate(y, size=size, mode="bilinear", align_corners=False)
            up.append(y)
        return self.classifier(self.dropout(self.fuse(torch.cat(up, 1))))


class Segformer(nn.Module):
    """(B, 3, H, W) normalised RGB → (B, classes, ceil(H/4), ceil(W/4)) logits."""

    def __init__(self, config):
        super().__init__()
        self.config = dict(config)
        self.encoder = MixTransformer(config)
        self.decoder = SegformerHead(config)
        self._init_weights()

    def _init_weights(self):
        with torch.no_grad():
            for m in self.modules():
                if isinstance(m, nn.Linear):
                    m.weight.normal_(0.0, 0.02).clamp_(-0.04, 0.04)
                    if m.bias is not None:
                        m.bias.zero_()
                elif isinstance(m, nn.Conv2d):
                    fan_out = m.kernel_size[0] * m.kernel_size[1] * m.out_channels / m.groups
                    m.weight.normal_(0.0, math.sqrt(2.0 / fan_out))
                    if m.bias is not None:
                        m.bias.zero_()
                elif isinstance(m, nn.LayerNorm):
                    m.weight.fill_(1.0)
                    m.bias.zero_()
            self.decoder.classifier.weight.normal_(0.0, 0.01)

    def forward(self, x):
        return self.decoder(self.encoder(x))


def images_to_tensor(rgb_uint8):
    """(B, H, W, 3) uint8 RGB tensor → normalised float (B, 3, H, W)."""
    x = rgb_uint8.permute(0, 3, 1, 2).float()
    mean = torch.tensor(MEAN_RGB, device=x.device).view(1, 3, 1, 1)
    std = torch.tensor(STD_RGB, device=x.device).view(1, 3, 1, 1)
    return (x - mean) / std


# --- safetensors -------------------------------------------------------------

_DTYPES = {torch.float32: "F32", torch.int64: "I64", torch.float16: "F16", torch.bfloat16: "BF16",
           torch.int32: "I32", torch.uint8: "U8"}
_FROM_NAME = {v: k for k, v in _DTYPES.items()}


def write_safetensors(path, tensors, metadata=None):
    """tensors: name → tensor (any device); metadata: str → str. Atomic."""
    header, blobs, offset = {}, [], 0
    for name in sorted(tensors):
        t = tensors[name].detach().to("cpu").contiguous()
        data = t.reshape(-1).view(torch.uint8).numpy().tobytes() if t.numel() else b""
        header[name] = {"dtype": _DTYPES[t.dtype], "shape": list(t.shape), "data_offsets": [offset, offset + len(data)]}
        blobs.append(data)
        offset += len(data)
    if metadata:
        header["__metadata__"] = {str(k): str(v) for k, v in metadata.items()}
    text = json.dumps(header, separators=(",", ":")).encode()
    text += b" " * ((8 - len(text) % 8) % 8)  # Align the data (the format's recommendation).
    tmp = f"{path}.tmp"
    with open(tmp, "wb") as f:
        f.write(struct.pack("<Q", len(text)))
        f.write(text)
        for b in blobs:
            f.write(b)
    import os
    os.replace(tmp, path)


def read_safetensors(path):
    """→ (name → CPU tensor, metadata dict)."""
    with open(path, "rb") as f:
        raw = f.read()
    (n,) = struct.unpack("<Q", raw[:8])
    header = json.loads(raw[8:8 + n])
    meta = header.pop("__metadata__", {})
    base = 8 + n
    out = {}
    for name, h in header.items():
        b, e = h["data_offsets"]
        dtype = _FROM_NAME[h["dtype"]]
        buf = bytearray(raw[base + b:base + e])
        t = torch.frombuffer(buf, dtype=dtype) if buf else torch.empty(0, dtype=dtype)
        out[name] = t.reshape(h["shape"]).clone()
    return out, meta


def save_safetensors_model(path, model, meta):
    """Writes every parameter and buffer under its asbuilt name + the metadata."""
    meta = dict(meta)
    meta.setdefault("format", CHECKPOINT_FORMAT)
    meta["config"] = model.config
    meta.setdefault("class_names", CLASS_NAMES)
    meta["parameters"] = sum(p.numel() for p in model.parameters())
    tensors = {k: v for k, v in model.state_dict().items()}
    write_safetensors(path, tensors, {"asbuilt_meta": json.dumps(meta)})


def load_safetensors_model(path, map_location="cpu"):
    tensors, meta = read_safetensors(path)
    meta = json.loads(meta["asbuilt_meta"])
    model = Segformer(meta["config"])
    model.load_state_dict(tensors, strict=True)
    return model.to(map_location), meta
