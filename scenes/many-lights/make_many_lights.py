#!/usr/bin/env python3
"""Writes scenes lit by many lights as glTF 2.0, for many-light sampling (the light tree).

Outputs, beside this script (see README.md):
  street-of-lamps.gltf   a street 240 m long between two rows of houses, lit at night by 1,024
                         KHR_lights_punctual lights: 512 street lamps (spot lights pointing
                         down) in two rows and 512 small point lights in the houses' windows
  lamp-grid.gltf         a white floor under a 32 x 32 grid of point lights 1 m up, 0.5 m apart:
                         the closed-form irradiance sum of the tests and docs
  emissive-hall.gltf     a hall 120 m long lit only by its ceiling: 5,120 small emissive panels
                         (10,240 emissive triangles) in a 40 x 128 grid 8 m up, over a floor with
                         two rows of pillars, tables and benches (the emissive triangles' light tree)

Everything is in one embedded buffer. The street's houses are boxes, each its own node placing
one shared box mesh; the hall's panels, pillars and furniture are each one mesh in world space. Standard library only, deterministic: running it again rewrites every file
byte for byte.
Usage: python3 make_many_lights.py [--out-dir DIR] [--check]
"""

import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in scenes/
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltf_builder import (  # noqa: E402  (scenes/gltf_builder.py)
    document as gltf_document, BufferBuilder, MeshData, axis_angle_quaternion, box, generator_arguments,
    look_at_quaternion, quad, write_or_check)

GENERATOR = "tessera scenes/many-lights/make_many_lights.py"
COPYRIGHT = "tessera contributors, Apache License 2.0"

STREET_LENGTH = 240.0
LAMPS_PER_SIDE = 256
HOUSES_PER_SIDE = 32


def material(name, colour, roughness=0.8):
    return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(colour) + [1.0],
                                                   "metallicFactor": 0.0, "roughnessFactor": roughness}}


def document(buffers, meshes, materials, nodes, lights, camera, extensions_used=("KHR_lights_punctual",)):
    return gltf_document(buffers, meshes, materials, nodes, camera, {"generator": GENERATOR, "copyright": COPYRIGHT},
                         extensions_used, {"KHR_lights_punctual": {"lights": lights}} if lights else None)


def mesh_of(buffers, data, name, material_index):
    attributes, indices = buffers.mesh_data(data, name, uv=False)
    return {"name": name, "primitives": [{"attributes": attributes, "indices": indices, "material": material_index}]}


def street_of_lamps():
    b = BufferBuilder()
    materials = [material("asphalt", (0.25, 0.25, 0.25)), material("plaster", (0.7, 0.65, 0.55))]
    half = STREET_LENGTH / 2
    meshes = [mesh_of(b, quad((-30.0, 0.0, half), (60.0, 0.0, 0.0), (0.0, 0.0, -STREET_LENGTH)), "street", 0),
              mesh_of(b, box((1.0, 1.0, 1.0), (0.0, 0.5, 0.0)), "house", 1)]
    nodes = [{"name": "street", "mesh": 0}]
    # Houses: 6 m wide, 5.5 m deep, 6 to 12 m tall, their fronts 8 m from the street's axis.
    for side in (-1, 1):
        for i in range(HOUSES_PER_SIDE):
            z = half - (i + 0.5) * STREET_LENGTH / HOUSES_PER_SIDE
            height = 6.0 + 6.0 * (((i * 7 + (3 if side > 0 else 0)) % 5) / 4.0)
            nodes.append({"name": "house %s %d" % ("left" if side < 0 else "right", i), "mesh": 1,
                          "translation": [side * 10.75, 0.0, z], "scale": [5.5, height, 6.0]})
    lights = []
    down = axis_angle_quaternion((1.0, 0.0, 0.0), -90.0)  # -Z turned to -Y
    # Street lamps: warm spots 5 m up, 3.5 m from the axis, pointing down.
    for side in (-1, 1):
        for i in range(LAMPS_PER_SIDE):
            z = half - (i + 0.5) * STREET_LENGTH / LAMPS_PER_SIDE
            lights.append({"type": "spot", "color": [1.0, 0.78, 0.52], "intensity": 20.0,
                           "spot": {"innerConeAngle": 0.6, "outerConeAngle": 1.1}})
            nodes.append({"name": "lamp %d" % len(lights), "translation": [side * 3.5, 5.0, z], "rotation": down,
                          "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})
    # Windows: dim cool points in front of the houses' fronts, two floors, four per house.
    for side in (-1, 1):
        for i in range(HOUSES_PER_SIDE):
            z0 = half - i * STREET_LENGTH / HOUSES_PER_SIDE
            for floor in (2.0, 4.5):
                for k in range(4):
                    z = z0 - (k + 0.5) * STREET_LENGTH / HOUSES_PER_SIDE / 4
                    lights.append({"type": "point", "color": [0.75, 0.85, 1.0], "intensity": 1.5})
                    nodes.append({"name": "window %d" % len(lights), "translation": [side * 7.4, floor, z],
                                  "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})
    eye, target = (1.5, 3.0, half - 2.0), (-1.0, 2.0, half - 40.0)
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_at_quaternion(eye, target)})
    camera = {"type": "perspective", "perspective": {"yfov": 0.8, "aspectRatio": 16 / 9, "znear": 0.05}}
    return document(b, meshes, materials, nodes, lights, camera)


def lamp_grid():
    b = BufferBuilder()
    materials = [material("white", (1.0, 1.0, 1.0), 1.0)]
    meshes = [mesh_of(b, quad((-20.0, 0.0, 20.0), (40.0, 0.0, 0.0), (0.0, 0.0, -40.0)), "floor", 0)]
    nodes = [{"name": "floor", "mesh": 0}]
    lights = []
    for row in range(32):
        for col in range(32):
            lights.append({"type": "point", "color": [1.0, 1.0, 1.0], "intensity": 0.05})
            nodes.append({"name": "light %d,%d" % (row, col), "translation": [(col - 15.5) * 0.5, 1.0, (row - 15.5) * 0.5],
                          "extensions": {"KHR_lights_punctual": {"light": len(lights) - 1}}})
    eye, target = (0.0, 9.0, 14.0), (0.0, 0.0, 0.0)
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_at_quaternion(eye, target)})
    camera = {"type": "perspective", "perspective": {"yfov": 0.7, "aspectRatio": 16 / 9, "znear": 0.05}}
    return document(b, meshes, materials, nodes, lights, camera)


HALL_LENGTH, HALL_WIDTH, HALL_HEIGHT = 120.0, 30.0, 8.0
PANELS_ACROSS, PANELS_ALONG = 40, 128


def emissive_material(name, colour, strength):
    m = material(name, (0.0, 0.0, 0.0))
    m["emissiveFactor"] = list(colour)
    m["extensions"] = {"KHR_materials_emissive_strength": {"emissiveStrength": strength}}
    return m


def emissive_hall():
    """A hall 120 m long and 30 m wide lit only by small ceiling panels facing down (one-sided
    emitters: the light tree's cones matter), warm ones with every eighth row cool, over a grey
    floor between two walls; two rows of pillars, and tables and benches between them."""
    b = BufferBuilder()
    materials = [material("floor", (0.45, 0.43, 0.4), 0.6), material("wall", (0.6, 0.6, 0.62)),
                 material("stone", (0.7, 0.68, 0.62), 0.5), material("wood", (0.5, 0.32, 0.18), 0.45),
                 emissive_material("warm panel", (1.0, 0.86, 0.68), 4.0),
                 emissive_material("cool panel", (0.7, 0.85, 1.0), 4.0)]
    half_l, half_w = HALL_LENGTH / 2, HALL_WIDTH / 2
    floor = quad((-half_w, 0.0, half_l), (HALL_WIDTH, 0.0, 0.0), (0.0, 0.0, -HALL_LENGTH))
    walls = quad((-half_w, 0.0, -half_l), (0.0, 0.0, HALL_LENGTH), (0.0, HALL_HEIGHT + 1.0, 0.0))
    walls.extend(quad((half_w, 0.0, half_l), (0.0, 0.0, -HALL_LENGTH), (0.0, HALL_HEIGHT + 1.0, 0.0)))
    pillars = MeshData()
    for side in (-1, 1):
        for i in range(16):
            pillars.extend(box((0.8, HALL_HEIGHT, 0.8), (side * 8.0, HALL_HEIGHT / 2, half_l - 4.0 - i * 7.5)))
    furniture = MeshData()
    for i in range(14):
        z = half_l - 7.75 - i * 7.5
        for x in (-3.0, 3.0):
            furniture.extend(box((1.6, 0.06, 3.2), (x, 0.75, z)))  # table top
            for lx in (-0.7, 0.7):
                for lz in (-1.5, 1.5):
                    furniture.extend(box((0.06, 0.72, 0.06), (x + lx, 0.36, z + lz)))
            for bx in (-1.2, 1.2):  # benches
                furniture.extend(box((0.35, 0.45, 3.0), (x + bx, 0.225, z)))
    warm, cool = MeshData(), MeshData()
    step_x, step_z = HALL_WIDTH / PANELS_ACROSS, HALL_LENGTH / PANELS_ALONG
    for row in range(PANELS_ALONG):
        for col in range(PANELS_ACROSS):
            x, z = -half_w + (col + 0.5) * step_x, half_l - (row + 0.5) * step_z
            # 0.4 x 0.6 m, facing down: cross(+X, +Z) = -Y.
            panel = quad((x - 0.2, HALL_HEIGHT, z - 0.3), (0.4, 0.0, 0.0), (0.0, 0.0, 0.6))
            (cool if row % 8 == 7 else warm).extend(panel)
    meshes = [mesh_of(b, floor, "floor", 0), mesh_of(b, walls, "walls", 1), mesh_of(b, pillars, "pillars", 2),
              mesh_of(b, furniture, "furniture", 3), mesh_of(b, warm, "warm panels", 4),
              mesh_of(b, cool, "cool panels", 5)]
    nodes = [{"name": mesh["name"], "mesh": i} for i, mesh in enumerate(meshes)]
    eye, target = (2.0, 1.7, half_l - 1.0), (-1.0, 2.2, half_l - 40.0)
    nodes.append({"name": "camera", "camera": 0, "translation": list(eye), "rotation": look_at_quaternion(eye, target)})
    camera = {"type": "perspective", "perspective": {"yfov": 0.9, "aspectRatio": 16 / 9, "znear": 0.05}}
    return document(b, meshes, materials, nodes, [], camera, extensions_used=("KHR_materials_emissive_strength",))


def main():
    args = generator_arguments(__doc__, __file__).parse_args()
    outputs = {"street-of-lamps.gltf": street_of_lamps(), "lamp-grid.gltf": lamp_grid(),
               "emissive-hall.gltf": emissive_hall()}
    return write_or_check(outputs, args.out_dir, args.check, GENERATOR)


if __name__ == "__main__":
    sys.exit(main())
