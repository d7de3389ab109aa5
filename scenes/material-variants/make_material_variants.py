#!/usr/bin/env python3
"""Writes material-variants.gltf: the smallest scene with KHR_materials_variants.

One mesh of two quads facing the camera, each a primitive of its own:

- "panel" (x in [-1, 1], y in [-0.5, 0.7]), default material "white"; variant "red" maps it
  to material "red", variant "green" to material "green".
- "trim" (x in [-1, 1], y in [-0.9, -0.6]), default material "white"; only variant "green"
  maps it (to "dark green"), so with "red" it keeps its default.

The materials are unlit (KHR_materials_unlit): a pixel on a quad shows exactly its base
colour, whatever the BSDF, which makes the scene a test of which material a primitive gets.
The camera at (0, 0, 3) looks down -Z with yfov 0.8 rad and aspect 1: the image centre sees
the panel, the trim crosses rows 0.74 to 0.86 of the height (from the top).

The buffer is embedded as a base64 data URI, so the .gltf is the whole scene (tests copy
and edit it). Standard library only, deterministic.
Usage: python3 make_material_variants.py [--out-dir DIR] [--check]
"""

import argparse
import json
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in scenes/
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import gltf_builder  # noqa: E402  (scenes/gltf_builder.py: buffer views, accessors, data URI)

GLTF_NAME = "material-variants.gltf"
GENERATOR = "tessera scenes/material-variants/make_material_variants.py"

MATERIALS = [  # name, linear RGB base colour
    ("white", (0.8, 0.8, 0.8)),
    ("red", (0.8, 0.05, 0.05)),
    ("green", (0.05, 0.8, 0.05)),
    ("dark green", (0.02, 0.25, 0.02)),
]
VARIANTS = ["red", "green"]

# name, (x0, y0, x1, y1) at z = 0, {variant name: material name}
QUADS = [
    ("panel", (-1.0, -0.5, 1.0, 0.7), {"red": "red", "green": "green"}),
    ("trim", (-1.0, -0.9, 1.0, -0.6), {"green": "dark green"}),
]


def build():
    material_index = {name: i for i, (name, _) in enumerate(MATERIALS)}
    variant_index = {name: i for i, name in enumerate(VARIANTS)}
    buf = gltf_builder.BufferBuilder()
    primitives = []
    for name, (x0, y0, x1, y1), mapping in QUADS:
        positions = [(x0, y0, 0.0), (x1, y0, 0.0), (x1, y1, 0.0), (x0, y1, 0.0)]
        position = buf.vec3(positions, bounds=True, name=name + " positions")
        normal = buf.vec3([(0.0, 0.0, 1.0)] * 4, name=name + " normals")
        indices = buf.indices([0, 1, 2, 0, 2, 3], name=name + " indices")  # counter-clockwise seen from +Z
        mappings = [{"material": material_index[material], "variants": [variant_index[variant]]}
                    for variant, material in mapping.items()]
        primitives.append({
            "attributes": {"POSITION": position, "NORMAL": normal},
            "indices": indices,
            "material": material_index["white"],
            "mode": 4,
            "extensions": {"KHR_materials_variants": {"mappings": mappings}},
        })

    gltf = {
        "asset": {"version": "2.0", "generator": GENERATOR},
        "extensionsUsed": ["KHR_materials_unlit", "KHR_materials_variants"],
        "extensions": {"KHR_materials_variants": {"variants": [{"name": v} for v in VARIANTS]}},
        "scene": 0,
        "scenes": [{"name": "material variants", "nodes": [0, 1]}],
        "nodes": [
            {"name": "panel and trim", "mesh": 0},
            {"name": "Camera", "camera": 0, "translation": [0.0, 0.0, 3.0]},
        ],
        "cameras": [{"name": "Camera", "type": "perspective",
                     "perspective": {"aspectRatio": 1.0, "yfov": 0.8, "znear": 0.01}}],
        "meshes": [{"name": "panel and trim", "primitives": primitives}],
        "materials": [{
            "name": name,
            "pbrMetallicRoughness": {"baseColorFactor": [*rgb, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0},
            "extensions": {"KHR_materials_unlit": {}},
        } for name, rgb in MATERIALS],
        "buffers": [buf.embedded_buffer()],
        "bufferViews": buf.buffer_views,
        "accessors": buf.accessors,
    }
    return (json.dumps(gltf, indent=1) + "\n").encode("utf-8")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out-dir", default=os.path.dirname(os.path.abspath(__file__)))
    parser.add_argument("--check", action="store_true", help="exit 1 if the file in --out-dir is not what this writes")
    args = parser.parse_args()
    path = os.path.join(args.out_dir, GLTF_NAME)
    text = build()
    if args.check:
        with open(path, "rb") as f:
            if f.read() != text:
                print(f"{path} is stale: run {os.path.basename(__file__)}", file=sys.stderr)
                return 1
        return 0
    with open(path, "wb") as f:
        f.write(text)
    return 0


if __name__ == "__main__":
    sys.exit(main())
