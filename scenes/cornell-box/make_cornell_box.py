#!/usr/bin/env python3
"""Writes cornell-box.gltf and cornell-box.bin: the classic Cornell box as a glTF 2.0 scene.

The geometry and the camera are the measured data published by the Cornell University
Program of Computer Graphics ("Cornell Box Data",
https://www.graphics.cornell.edu/online/box/data.html), converted from millimetres to metres
and into glTF's frame. The reflectance and emission spectra are reduced to linear-RGB values
as in the widely used pbrt/Mitsuba versions of the scene. See README.md beside this file.

Frame conversion. The Cornell data is right-handed with +Y up and the camera at
(278, 273, -800) looking down +Z, so +X points to the camera's left (the red wall is at
x ~ 556, the green one at x = 0). glTF cameras look down -Z with +X to the right, so every
point is rotated 180 degrees about +Y (a proper rotation: handedness and winding are kept),
shifted so that the camera sits on the Y axis, and scaled to metres:

    X = (278 - x) / 1000      Y = y / 1000      Z = -z / 1000

The box then spans X in [-0.278, 0.278], Y in [0, 0.5488], Z in [-0.5592, 0] (the open side
at Z = 0) and the camera is at (0, 0.273, 0.8) with the identity orientation.

Standard library only, deterministic: running it again rewrites both files byte for byte.
Usage: python3 make_cornell_box.py [--out-dir DIR] [--check]
"""

import json
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in scenes/
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltf_builder import BufferBuilder, cross, dot, normalize, sub, generator_arguments, write_or_check  # noqa: E402  (scenes/gltf_builder.py)

GLTF_NAME = "cornell-box.gltf"
BIN_NAME = "cornell-box.bin"
GENERATOR = "tessera scenes/cornell-box/make_cornell_box.py"
DATA_URL = "https://www.graphics.cornell.edu/online/box/data.html"

# --- Measured data, in millimetres, in the Cornell frame (quads as published) -----------------

FLOOR = [(552.8, 0.0, 0.0), (0.0, 0.0, 0.0), (0.0, 0.0, 559.2), (549.6, 0.0, 559.2)]
CEILING = [(556.0, 548.8, 0.0), (556.0, 548.8, 559.2), (0.0, 548.8, 559.2), (0.0, 548.8, 0.0)]
BACK_WALL = [(549.6, 0.0, 559.2), (0.0, 0.0, 559.2), (0.0, 548.8, 559.2), (556.0, 548.8, 559.2)]
RIGHT_WALL = [(0.0, 0.0, 559.2), (0.0, 0.0, 0.0), (0.0, 548.8, 0.0), (0.0, 548.8, 559.2)]  # green
LEFT_WALL = [(552.8, 0.0, 0.0), (549.6, 0.0, 559.2), (556.0, 548.8, 559.2), (556.0, 548.8, 0.0)]  # red

SHORT_BLOCK = [
    [(130.0, 165.0, 65.0), (82.0, 165.0, 225.0), (240.0, 165.0, 272.0), (290.0, 165.0, 114.0)],
    [(290.0, 0.0, 114.0), (290.0, 165.0, 114.0), (240.0, 165.0, 272.0), (240.0, 0.0, 272.0)],
    [(130.0, 0.0, 65.0), (130.0, 165.0, 65.0), (290.0, 165.0, 114.0), (290.0, 0.0, 114.0)],
    [(82.0, 0.0, 225.0), (82.0, 165.0, 225.0), (130.0, 165.0, 65.0), (130.0, 0.0, 65.0)],
    [(240.0, 0.0, 272.0), (240.0, 165.0, 272.0), (82.0, 165.0, 225.0), (82.0, 0.0, 225.0)],
]
TALL_BLOCK = [
    [(423.0, 330.0, 247.0), (265.0, 330.0, 296.0), (314.0, 330.0, 456.0), (472.0, 330.0, 406.0)],
    [(423.0, 0.0, 247.0), (423.0, 330.0, 247.0), (472.0, 330.0, 406.0), (472.0, 0.0, 406.0)],
    [(472.0, 0.0, 406.0), (472.0, 330.0, 406.0), (314.0, 330.0, 456.0), (314.0, 0.0, 456.0)],
    [(314.0, 0.0, 456.0), (314.0, 330.0, 456.0), (265.0, 330.0, 296.0), (265.0, 0.0, 296.0)],
    [(265.0, 0.0, 296.0), (265.0, 330.0, 296.0), (423.0, 330.0, 247.0), (423.0, 0.0, 247.0)],
]

# The light is the published 130 x 105 mm opening in the ceiling (y = 548.8). The ceiling is kept
# whole and the light is a separate quad 0.1 mm below it (as in the Mitsuba version), facing down.
LIGHT_Y = 548.7
LIGHT = [(343.0, LIGHT_Y, 227.0), (343.0, LIGHT_Y, 332.0), (213.0, LIGHT_Y, 332.0), (213.0, LIGHT_Y, 227.0)]

CAMERA_POSITION = (278.0, 273.0, -800.0)  # looking down +z, up +y
FOCAL_LENGTH_MM = 35.0
FILM_SIZE_MM = 25.0  # 25 x 25 mm film: square image

BOX_CENTRE = (278.0, 274.4, 279.6)  # inside the box: wall normals point towards it

# --- Materials: linear-RGB reductions of the measured spectra ---------------------------------

WHITE = (0.725, 0.71, 0.68)  # ~0.73, lower in the blue, as the measured white paint
RED = (0.63, 0.065, 0.05)
GREEN = (0.14, 0.45, 0.091)
LIGHT_REFLECTANCE = (0.78, 0.78, 0.78)  # the light's diffuser reflectance in the Cornell data
LIGHT_RADIANCE = (17.0, 12.0, 4.0)  # W/(m^2 sr), RGB, as in the common pbrt/Mitsuba version


def to_gltf(p):
    """Cornell millimetres (camera looking +z) -> glTF metres (camera looking -z)."""
    x, y, z = p
    return ((CAMERA_POSITION[0] - x) / 1000.0 + 0.0, y / 1000.0 + 0.0, -z / 1000.0 + 0.0)  # no -0.0


def centroid(points):
    n = float(len(points))
    return (sum(p[0] for p in points) / n, sum(p[1] for p in points) / n, sum(p[2] for p in points) / n)


class Mesh:
    """Flat-shaded triangles: each planar quad gets 4 vertices sharing its face normal; a quad
    that is not planar (the measured red wall is ~3 mm off) is split, each triangle with its own
    vertices and normal. Winding is counter-clockwise seen from the side the normal points to."""

    def __init__(self, name):
        self.name = name
        self.positions = []
        self.normals = []
        self.indices = []

    def _oriented(self, tri, facing):
        n = cross(sub(tri[1], tri[0]), sub(tri[2], tri[0]))
        if dot(n, facing) < 0.0:
            tri = [tri[0], tri[2], tri[1]]
            n = (-n[0], -n[1], -n[2])
        return tri, normalize(n)

    def _add(self, points, normal, triangles):
        base = len(self.positions)
        self.positions.extend(points)
        self.normals.extend([normal] * len(points))
        for t in triangles:
            self.indices.extend(base + i for i in t)

    def add_quad(self, quad_mm, facing):
        """facing(centre) -> a vector on the side the face must look to (glTF frame)."""
        quad = [to_gltf(p) for p in quad_mm]
        want = facing(centroid(quad))
        n = cross(sub(quad[1], quad[0]), sub(quad[2], quad[0]))
        offset = dot(normalize(n), sub(quad[3], quad[0]))
        if abs(offset) < 1e-9:
            if dot(n, want) < 0.0:
                quad = [quad[0], quad[3], quad[2], quad[1]]
            _, normal = self._oriented(quad[:3], want)
            self._add(quad, normal, [(0, 1, 2), (0, 2, 3)])
        else:
            for tri in ([quad[0], quad[1], quad[2]], [quad[0], quad[2], quad[3]]):
                tri, normal = self._oriented(tri, want)
                self._add(tri, normal, [(0, 1, 2)])


def towards(point_mm):
    target = to_gltf(point_mm)
    return lambda c: sub(target, c)


def away_from(point_mm):
    source = to_gltf(point_mm)
    return lambda c: sub(c, source)


def build_meshes():
    meshes = []

    def single(name, quad, facing):
        m = Mesh(name)
        m.add_quad(quad, facing)
        meshes.append(m)

    inside = towards(BOX_CENTRE)
    single("Floor", FLOOR, inside)
    single("Ceiling", CEILING, inside)
    single("BackWall", BACK_WALL, inside)
    single("LeftWall", LEFT_WALL, inside)
    single("RightWall", RIGHT_WALL, inside)
    for name, faces in (("ShortBlock", SHORT_BLOCK), ("TallBlock", TALL_BLOCK)):
        top = faces[0]
        mid = centroid(top)
        core = (mid[0], mid[1] / 2.0, mid[2])
        m = Mesh(name)
        for quad in faces:
            m.add_quad(quad, away_from(core))
        meshes.append(m)
    single("Light", LIGHT, lambda c: (0.0, -1.0, 0.0))
    return meshes


MATERIAL_OF = {
    "Floor": "White", "Ceiling": "White", "BackWall": "White", "ShortBlock": "White",
    "TallBlock": "White", "LeftWall": "Red", "RightWall": "Green", "Light": "Light",
}


def rounded(values, places=12):
    return [round(v, places) + 0.0 for v in values]


def materials():
    def diffuse(name, rgb):
        return {
            "name": name,
            "pbrMetallicRoughness": {
                "baseColorFactor": rounded(list(rgb) + [1.0]),
                "metallicFactor": 0.0,
                "roughnessFactor": 1.0,
            },
        }

    light = diffuse("Light", LIGHT_REFLECTANCE)
    peak = max(LIGHT_RADIANCE)
    light["emissiveFactor"] = rounded([c / peak for c in LIGHT_RADIANCE])
    light["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": peak}}
    light["doubleSided"] = False  # emits only on the side its normal points to (down)
    return [diffuse("White", WHITE), diffuse("Red", RED), diffuse("Green", GREEN), light]


def build():
    meshes = build_meshes()
    mats = materials()
    material_index = {m["name"]: i for i, m in enumerate(mats)}

    buf = BufferBuilder()
    gltf_meshes, nodes = [], []
    for mesh in meshes:
        position = buf.vec3(mesh.positions, bounds=True)
        normal = buf.vec3(mesh.normals)
        indices = buf.indices(mesh.indices)
        gltf_meshes.append({
            "name": mesh.name,
            "primitives": [{
                "attributes": {"POSITION": position, "NORMAL": normal},
                "indices": indices,
                "material": material_index[MATERIAL_OF[mesh.name]],
                "mode": 4,
            }],
        })
        nodes.append({"name": mesh.name, "mesh": len(gltf_meshes) - 1})

    camera = to_gltf(CAMERA_POSITION)
    yfov = 2.0 * math.atan(FILM_SIZE_MM / 2.0 / FOCAL_LENGTH_MM)
    nodes.append({"name": "Camera", "camera": 0, "translation": rounded(camera)})

    gltf = {
        "asset": {
            "version": "2.0",
            "generator": GENERATOR,
            "copyright": "Geometry, camera, reflectances and light from the Cornell Box data of the Cornell "
                         "University Program of Computer Graphics; glTF conversion by the tessera project",
            "extras": {
                "title": "Cornell box",
                "source": "Cornell Box Data, Cornell University Program of Computer Graphics, " + DATA_URL,
                "units": "metres",
                "frame": "glTF = ((278 - x) / 1000, y / 1000, -z / 1000) for Cornell data (x, y, z) in mm",
                "lightRadianceRGB": rounded(LIGHT_RADIANCE),
                "camera": "35 mm lens, 25 x 25 mm film, at (278, 273, -800) mm looking down +z (Cornell frame)",
            },
        },
        "extensionsUsed": ["KHR_materials_emissive_strength"],
        "scene": 0,
        "scenes": [{"name": "Cornell box", "nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [{
            "name": "Camera",
            "type": "perspective",
            "perspective": {"aspectRatio": 1.0, "yfov": round(yfov, 12), "znear": 0.01},
        }],
        "meshes": gltf_meshes,
        "materials": mats,
        "accessors": buf.accessors,
        "bufferViews": buf.buffer_views,
        "buffers": [buf.external_buffer(BIN_NAME)],
    }
    text = json.dumps(gltf, indent=2, ensure_ascii=True) + "\n"
    return text.encode("utf-8"), buf.finish()


def main():
    args = generator_arguments(__doc__, __file__).parse_args()
    outputs = dict(zip((GLTF_NAME, BIN_NAME), build()))
    return write_or_check(outputs, args.out_dir, args.check, "make_cornell_box")


if __name__ == "__main__":
    sys.exit(main())
