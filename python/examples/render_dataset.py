#!/usr/bin/env python3
"""Renders a small synthetic dataset: N views of a glTF model around a circle, each with its
beauty, depth, normals, albedo and the object's mask, and the cameras in one JSON file.

    PYTHONPATH=build/python python3 python/examples/render_dataset.py \
        scenes/khronos/DamagedHelmet/glTF-Binary/DamagedHelmet.glb out/ --views 24

Each view is out/view_NNN.exr (layers RGBA, Albedo, N, Z and mask) and out/cameras.json holds
every view's world-to-camera and world-to-NDC matrices (row-vector convention, as OpenEXR's
worldToCamera). The file is read once; every view renders from the same loaded scene.
"""

import argparse
import json
import pathlib
import sys
import time

import numpy as np

import tessera


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("scene", help="a .gltf or .glb file")
    parser.add_argument("out", type=pathlib.Path, help="the directory to write the views to")
    parser.add_argument("--views", type=int, default=16)
    parser.add_argument("--size", type=int, default=256, help="width and height in pixels")
    parser.add_argument("--spp", type=int, default=16)
    parser.add_argument("--elevation", type=float, default=20.0, help="degrees above the ground plane")
    args = parser.parse_args()

    args.out.mkdir(parents=True, exist_ok=True)
    scene = tessera.Scene(args.scene)
    cameras = []
    start = time.monotonic()
    for view in range(args.views):
        azimuth = 360.0 * view / args.views
        # film_transparent: A is each pixel's coverage by the model, and RGB has no background.
        layers = scene.render(width=args.size, height=args.size, spp=args.spp, seed=view,
                              orbit=(azimuth, args.elevation), aovs=["albedo", "normal", "depth"],
                              film_transparent=True)
        layers["mask"] = (layers["RGBA"][..., 3:] > 0.5).astype(np.float32)
        tessera.write_exr(args.out / f"view_{view:03d}.exr", layers)
        cameras.append({"view": view, "azimuth": azimuth, "elevation": args.elevation,
                        "world_to_camera": layers.metadata["worldToCamera"].tolist(),
                        "world_to_ndc": layers.metadata["worldToNDC"].tolist()})
        print(f"\rview {view + 1}/{args.views}", end="", file=sys.stderr, flush=True)
    (args.out / "cameras.json").write_text(json.dumps(cameras, indent=1))
    print(f"\n{args.views} views in {time.monotonic() - start:.1f} s -> {args.out}", file=sys.stderr)


if __name__ == "__main__":
    main()
