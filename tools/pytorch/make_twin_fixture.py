"""Writes the fixture that proves the Python twin and the C++ SegFormer agree.

    /usr/bin/python3 tools/pytorch/make_twin_fixture.py src/asbuilt/seg/testdata

twin_model.safetensors: a small random SegFormer (dims 8/16/24/32, every
    block kind: spatial reduction 8/4/2/1, batch norm with non-trivial running
    statistics) with asbuilt metadata;
twin_io.safetensors: an input (1, 3, 37, 45) — odd sizes exercise the
    convolutions' padding — and the twin's eval-mode logits for it.
seg/model_file_test.cc imports the model with ImportModel, runs the C++
forward pass and compares the logits.
"""

import os
import sys

import torch

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import asbuilt_segformer as tw  # noqa: E402


def main(out_dir):
    torch.manual_seed(7)
    config = tw.config_for("b0")
    config.update(arch="twin-test", embed_dims=[8, 16, 24, 32], num_heads=[1, 2, 3, 4], depths=[1, 2, 1, 1],
                  decoder_dim=16)
    model = tw.Segformer(config)
    with torch.no_grad():
        for name, buf in model.named_buffers():
            if name.endswith("running_mean"):
                buf.normal_(0.0, 0.2)
            elif name.endswith("running_var"):
                buf.uniform_(0.5, 1.5)
            elif name.endswith("num_batches_tracked"):
                buf.fill_(3)
        for p in model.parameters():  # Make biases and norms non-trivial too.
            p.add_(0.05 * torch.randn_like(p))
    model.eval()
    x = torch.randn(1, 3, 37, 45)
    with torch.no_grad():
        logits = model(x)
    meta = {"format": tw.CHECKPOINT_FORMAT, "scale": [45, 37], "crop": [32, 32], "epoch": 1,
            "trainer": "tools/pytorch/make_twin_fixture.py"}
    os.makedirs(out_dir, exist_ok=True)
    tw.save_safetensors_model(os.path.join(out_dir, "twin_model.safetensors"), model, meta)
    tw.write_safetensors(os.path.join(out_dir, "twin_io.safetensors"), {"input": x, "logits": logits})
    print("logits", tuple(logits.shape), "written to", out_dir)


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "src/asbuilt/seg/testdata")
