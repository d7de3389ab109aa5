#!/usr/bin/env python3
"""Writes scenes where light reaches what it lights only through thick glass, for path guiding.

Outputs, beside this script (see README.md):
  caustic.gltf          a white floor under a glass ball (radius 0.5 m, index 1.5), above which a
                        small emissive square (0.2 m, facing down) is the only light: the floor
                        under the ball is lit only through the glass (a caustic), which light
                        sampling cannot reach (shadow rays stop at refracting glass)
  candle-in-glass.gltf  a wax candle on a wooden table inside a glass hurricane holder (a thick
                        glass tube), lit by the world through the glass

Everything is in one embedded buffer. Standard library only, deterministic: running it again
rewrites every file byte for byte.
Usage: python3 make_hard_light.py [--out-dir DIR] [--check]
"""

import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in scenes/
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltf_builder import (  # noqa: E402  (scenes/gltf_builder.py)
    document as gltf_document, BufferBuilder, MeshData, axis_angle_quaternion, box, generator_arguments,
    look_at_quaternion, quad, uv_sphere, write_or_check)

GENERATOR = "tessera scenes/hard-light/make_hard_light.py"
COPYRIGHT = "tessera contributors, Apache License 2.0"


def diffuse(name, colour, roughness=1.0):
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(colour) + [1.0],
                                                   "metallicFactor": 0.0, "roughnessFactor": roughness}}


def glass(name, thickness):
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0,
                                                   "roughnessFactor": 0.0},
            "extensions": {"KHR_materials_transmission": {"transmissionFactor": 1.0},
                           "KHR_materials_ior": {"ior": 1.5},
                           "KHR_materials_volume": {"thicknessFactor": thickness}}}


def emitter(name, strength):
    return {"name": name, "emissiveFactor": [1.0, 1.0, 1.0],
            "pbrMetallicRoughness": {"baseColorFactor": [0.0, 0.0, 0.0, 1.0], "metallicFactor": 0.0},
            "extensions": {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}}


def mesh_of(buffers, data, name, material_index):
    attributes, indices = buffers.mesh_data(data, name, uv=False)
    return {"name": name, "primitives": [{"attributes": attributes, "indices": indices, "material": material_index}]}


def document(buffers, meshes, materials, nodes, camera):
    extensions = sorted({e for m in materials for e in m.get("extensions", {})})
    return gltf_document(buffers, meshes, materials, nodes, camera, {"generator": GENERATOR, "copyright": COPYRIGHT},
                         extensions)


def camera_node(eye, target, yfov):
    node = {"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_at_quaternion(eye, target)}
    return node, {"type": "perspective", "perspective": {"yfov": yfov, "aspectRatio": 16 / 9, "znear": 0.05}}


def caustic():
    b = BufferBuilder()
    materials = [diffuse("floor", (0.8, 0.8, 0.8)), glass("glass", 1.0), emitter("light", 400.0)]
    down = axis_angle_quaternion((1.0, 0.0, 0.0), 180.0)  # the square's front turned to face -Y
    meshes = [mesh_of(b, quad((-3.0, 0.0, 3.0), (6.0, 0.0, 0.0), (0.0, 0.0, -6.0)), "floor", 0),
              mesh_of(b, uv_sphere(0.5, 64, 32, (0.0, 0.0, 0.0)), "ball", 1),
              mesh_of(b, quad((-0.1, 0.0, 0.1), (0.2, 0.0, 0.0), (0.0, 0.0, -0.2)), "light", 2)]
    nodes = [{"name": "floor", "mesh": 0}, {"name": "ball", "mesh": 1, "translation": [0.0, 1.0, 0.0]},
             {"name": "light", "mesh": 2, "translation": [0.0, 2.2, 0.0], "rotation": down}]
    node, camera = camera_node((0.0, 2.6, 4.2), (0.0, 0.5, 0.0), 0.7)
    nodes.append(node)
    return document(b, meshes, materials, nodes, camera)


def tube(inner, outer, height, segments=96):
    """A thick glass tube standing on y = 0, open at the top, with a closed bottom: one closed
    surface (outer wall, rim, inner wall, inner and outer bottom faces)."""
    m = MeshData()
    bottom = 0.02  # the glass base's thickness
    ring = [(math.cos(2 * math.pi * i / segments), math.sin(2 * math.pi * i / segments)) for i in range(segments)]
    for i in range(segments):
        (c0, s0), (c1, s1) = ring[i], ring[(i + 1) % segments]
        # Outer wall (normals out), inner wall (normals in, towards the axis).
        m.flat_polygon([(outer * c0, 0.0, outer * s0), (outer * c0, height, outer * s0),
                        (outer * c1, height, outer * s1), (outer * c1, 0.0, outer * s1)])
        m.flat_polygon([(inner * c0, bottom, inner * s0), (inner * c1, bottom, inner * s1),
                        (inner * c1, height, inner * s1), (inner * c0, height, inner * s0)])
        # The rim (up), the inside floor (up) and the underside (down).
        m.flat_polygon([(inner * c0, height, inner * s0), (inner * c1, height, inner * s1),
                        (outer * c1, height, outer * s1), (outer * c0, height, outer * s0)])
        m.flat_polygon([(0.0, bottom, 0.0), (inner * c0, bottom, inner * s0), (inner * c1, bottom, inner * s1)][::-1])
        m.flat_polygon([(0.0, 0.0, 0.0), (outer * c0, 0.0, outer * s0), (outer * c1, 0.0, outer * s1)])
    return m


def cylinder(radius, height, segments=64):
    m = MeshData()
    ring = [(math.cos(2 * math.pi * i / segments), math.sin(2 * math.pi * i / segments)) for i in range(segments)]
    for i in range(segments):
        (c0, s0), (c1, s1) = ring[i], ring[(i + 1) % segments]
        m.flat_polygon([(radius * c0, 0.0, radius * s0), (radius * c0, height, radius * s0),
                        (radius * c1, height, radius * s1), (radius * c1, 0.0, radius * s1)])
        m.flat_polygon([(0.0, height, 0.0), (radius * c0, height, radius * s0), (radius * c1, height, radius * s1)][::-1])
    return m


def candle_in_glass():
    b = BufferBuilder()
    materials = [diffuse("table", (0.45, 0.3, 0.18), 0.6), glass("glass", 0.01), diffuse("wax", (0.9, 0.85, 0.7))]
    meshes = [mesh_of(b, box((2.0, 0.05, 1.2), (0.0, -0.025, 0.0)), "table", 0),
              mesh_of(b, tube(0.09, 0.1, 0.36), "hurricane", 1),
              mesh_of(b, cylinder(0.04, 0.16), "candle", 2)]
    # The holder stands 1 mm above the table: with its underside on the table top, the two faces
    # would coincide, and a ray inside the glass would meet either (the table, or the glass's
    # underside reflecting it back by total internal reflection), pixel by pixel.
    gap = 0.001
    nodes = [{"name": "table", "mesh": 0}, {"name": "hurricane", "mesh": 1, "translation": [0.0, gap, 0.0]},
             {"name": "candle", "mesh": 2, "translation": [0.0, 0.02 + gap, 0.0]}]
    node, camera = camera_node((0.0, 0.35, 0.75), (0.0, 0.14, 0.0), 0.6)
    nodes.append(node)
    return document(b, meshes, materials, nodes, camera)


def main():
    args = generator_arguments(__doc__, __file__).parse_args()
    outputs = {"caustic.gltf": caustic(), "candle-in-glass.gltf": candle_in_glass()}
    return write_or_check(outputs, args.out_dir, args.check, GENERATOR)


if __name__ == "__main__":
    sys.exit(main())
