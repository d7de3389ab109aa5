#!/usr/bin/env python3
"""docs/images/python-dataset.png's contact sheet: views of python/examples/render_dataset.py's
output, one row per view, columns beauty, albedo, normals, depth and mask, display-encoded
(sRGB for colours, 0.5 + 0.5 N for normals, near dark to far light for depth) and written as
an EXR that oiiotool turns into the PNG (docs/make-images.sh).

    python3 docs/python-dataset-sheet.py DATASET_DIR SHEET.exr VIEW [VIEW ...]
"""

import sys

import numpy as np

import tessera


def srgb(linear):
    c = np.clip(linear, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * np.power(c, 1 / 2.4) - 0.055)


def row(layers):
    mask = layers["mask"][..., :1]
    z = layers["Z"][..., :1]
    hit = np.isfinite(z)
    near, far = np.min(z[hit]), np.max(z[hit])
    depth = np.where(hit, 0.15 + 0.85 * (z - near) / max(far - near, 1e-6), 1.0)
    return [srgb(layers["RGBA"][..., :3]), srgb(layers["Albedo"]), (0.5 + 0.5 * layers["N"]) * mask + (1 - mask),
            np.repeat(depth, 3, axis=2), np.repeat(mask, 3, axis=2)]


def main():
    directory, out, views = sys.argv[1], sys.argv[2], sys.argv[3:]
    rows = [np.concatenate(row(tessera.read_exr(f"{directory}/view_{int(v):03d}.exr")), axis=1) for v in views]
    sheet = np.concatenate(rows, axis=0).astype(np.float32)
    tessera.write_exr(out, {"RGB": sheet})


if __name__ == "__main__":
    main()
