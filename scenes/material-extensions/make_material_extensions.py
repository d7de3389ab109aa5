#!/usr/bin/env python3
"""Writes three small test scenes for Khronos material extensions (see README.md beside this file):

  iridescence.gltf           KHR_materials_iridescence: a 6 x 3 grid of spheres (film thickness
                             by column, base material by row) and a rod whose film thickness
                             comes from iridescenceThicknessTexture (100 to 1000 nm along it)
  dispersion.gltf            KHR_materials_dispersion (with _transmission, _volume and _ior):
                             three prisms and three brilliant-cut gems, dispersion 0, 1 and 3,
                             inside a curved backdrop of glowing black and white stripes
  diffuse-transmission.gltf  KHR_materials_diffuse_transmission: thin double-sided sheets
                             (factor 0, 0.5, 1, a coloured one, one from a texture) and a sphere,
                             lit from behind by a spot light

Each extension is listed in extensionsUsed only (a viewer without it still shows the scene).
The buffers, and the small PNG textures in them, are embedded as base64 data URIs, so each
.gltf is the whole scene. Units are metres; +Y is up.

Standard library only (with scenes/gltf_builder.py), deterministic: running it again rewrites
every file byte for byte.
Usage: python3 make_material_extensions.py [--out-dir DIR] [--check]
"""

import json
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in scenes/
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
import gltf_builder as gb  # noqa: E402  (scenes/gltf_builder.py)

GENERATOR = "tessera scenes/material-extensions/make_material_extensions.py"
COPYRIGHT = "tessera project, Apache License 2.0"
ASPECT = 16.0 / 9.0

# The sun of scenes/env/spruit_sunrise_1k.hdr in tessera's (Blender's) equirectangular mapping:
# texel (column 613, row 233) of 1024 x 512, u = 0.599, v = 0.456, so it is 8 degrees above the
# horizon at an azimuth of 36 degrees from +X towards +Z (in front of a camera looking down -Z,
# behind it and to the right). The diffuse-transmission scene is turned to have it behind the sheets.
SUN_AZIMUTH_DEG = 35.7


def rgb(*c):
    return [gb.clean(x) for x in c]


class Document:
    """One glTF file being assembled: materials, meshes, nodes, textures, lights, a camera."""

    def __init__(self, title, description):
        self.title, self.description = title, description
        self.buf = gb.BufferBuilder()
        self.materials, self.meshes, self.nodes, self.roots = [], [], [], []
        self.images, self.textures, self.samplers, self.lights = [], [], [], []
        self.extensions = set()
        self.camera = None
        self.geometry = {}

    def material(self, name, base=(0.8, 0.8, 0.8), metallic=0.0, roughness=0.5, extensions=None, **extra):
        mat = {"name": name, "pbrMetallicRoughness": {
            "baseColorFactor": rgb(*base) + [1.0], "metallicFactor": gb.clean(metallic),
            "roughnessFactor": gb.clean(roughness)}}
        mat.update(extra)
        if extensions:
            mat["extensions"] = extensions
            self.extensions.update(extensions)
        self.materials.append(mat)
        return len(self.materials) - 1

    def add_geometry(self, key, mesh, uv):
        """The accessors of a MeshData, written once and shared by every mesh that uses them
        (TEXCOORD_0 only when uv: the materials that use them have a texture)."""
        if key not in self.geometry:
            self.geometry[key] = self.buf.mesh_data(mesh, uv=uv)
        return self.geometry[key]

    def mesh(self, name, key, material, mesh_data=None, uv=False):
        attributes, indices = self.add_geometry(key, mesh_data, uv)
        self.meshes.append({"name": name, "primitives": [
            {"attributes": dict(attributes), "indices": indices, "material": material, "mode": gb.TRIANGLES}]})
        return len(self.meshes) - 1

    def node(self, name, mesh=None, translation=None, rotation=None, scale=None, children=None, root=True, **extra):
        node = {"name": name}
        if mesh is not None:
            node["mesh"] = mesh
        if children:
            node["children"] = children
        if translation is not None:
            node["translation"] = [gb.clean(c) for c in translation]
        if rotation is not None:
            node["rotation"] = [gb.clean(c) for c in rotation]
        if scale is not None:
            node["scale"] = [gb.clean(c) for c in scale]
        node.update(extra)
        self.nodes.append(node)
        if root:
            self.roots.append(len(self.nodes) - 1)
        return len(self.nodes) - 1

    def sampler(self, mag, min_, wrap_s, wrap_t):
        s = {"magFilter": mag, "minFilter": min_, "wrapS": wrap_s, "wrapT": wrap_t}
        if s not in self.samplers:
            self.samplers.append(s)
        return self.samplers.index(s)

    def texture(self, name, png, sampler):
        view = self.buf.view(png)
        self.images.append({"name": name, "bufferView": view, "mimeType": "image/png"})
        self.textures.append({"name": name, "source": len(self.images) - 1, "sampler": sampler})
        return len(self.textures) - 1

    def light(self, light, name, translation=None, rotation=None, root=True):
        self.lights.append(light)
        self.extensions.add("KHR_lights_punctual")
        return self.node(name, translation=translation, rotation=rotation, root=root,
                         extensions={"KHR_lights_punctual": {"light": len(self.lights) - 1}})

    def look_from(self, eye, target, yfov_deg, root=True):
        self.camera = {"name": "Camera", "type": "perspective", "perspective": {
            "aspectRatio": gb.clean(ASPECT), "yfov": gb.clean(math.radians(yfov_deg)), "znear": 0.05, "zfar": 100.0}}
        return self.node("Camera", translation=eye, rotation=gb.look_at_quaternion(eye, target), camera=0, root=root)

    def build(self, extras):
        gltf = {"asset": {"version": "2.0", "generator": GENERATOR, "copyright": COPYRIGHT,
                          "extras": dict({"title": self.title, "description": self.description}, **extras)},
                "extensionsUsed": sorted(self.extensions)}
        if self.lights:
            gltf["extensions"] = {"KHR_lights_punctual": {"lights": self.lights}}
        gltf.update({"scene": 0, "scenes": [{"name": self.title, "nodes": self.roots}], "nodes": self.nodes,
                     "cameras": [self.camera], "meshes": self.meshes, "materials": self.materials})
        if self.textures:
            gltf.update({"textures": self.textures, "images": self.images, "samplers": self.samplers})
        gltf.update({"accessors": self.buf.accessors, "bufferViews": self.buf.buffer_views,
                     "buffers": [self.buf.embedded_buffer()]})
        return (json.dumps(gltf, indent=1, ensure_ascii=True) + "\n").encode("utf-8")


def floor_quad(size_x, size_z, centre=(0.0, 0.0, 0.0)):
    cx, cy, cz = centre
    return gb.quad((cx - size_x / 2, cy, cz + size_z / 2), (size_x, 0.0, 0.0), (0.0, 0.0, -size_z))


def ramp_png(width, height, channel_values):
    """A horizontal ramp: channel_values(s) -> tuple of bytes for s in [0, 1] left to right."""
    row = bytearray()
    for i in range(width):
        row.extend(channel_values(i / (width - 1)))
    return gb.png_bytes(width, height, [bytes(row)] * height, len(channel_values(0.0)))


# --- 1. KHR_materials_iridescence --------------------------------------------------------------

IRIDESCENCE_THICKNESSES = [200, 300, 400, 500, 600, 800]  # nm, iridescenceThicknessMaximum, by column
IRIDESCENCE_IOR = 1.8  # vivid over a glass base (1.3, the default, shifts it only a few percent)
IRIDESCENCE_ROUGHNESS = 0.15
IRIDESCENCE_ROWS = [  # top to bottom: name, base colour, metallic
    ("dark dielectric", (0.02, 0.02, 0.02), 0.0),
    ("white dielectric", (0.8, 0.8, 0.8), 0.0),
    ("metal", (0.9, 0.9, 0.9), 1.0),
]
IRIDESCENCE_ROD = {"thicknessMinimum": 100, "thicknessMaximum": 1000, "base": (0.02, 0.02, 0.02), "roughness": 0.0}
SPHERE_RADIUS, SPHERE_PITCH = 0.4, 1.0
ROD_RADIUS, ROD_LENGTH = 0.22, 5.8
SOFTBOX_RADIANCE = 1.0
OVERHEAD_RADIANCE = 0.8


def rod_mesh(radius, length, segments=64):
    """A cylinder along X, centred on the origin, with flat end caps. TEXCOORD_0.u runs from 0 at
    -X to 1 at +X along the side (the caps get u = 0 and 1), v around it."""
    m = gb.MeshData()
    x0, x1 = -length / 2.0, length / 2.0
    for i in range(segments + 1):
        a = 2.0 * math.pi * i / segments
        n = (0.0, round(math.cos(a), 15), round(math.sin(a), 15))
        for x, u in ((x0, 0.0), (x1, 1.0)):
            m.vertex((x, radius * n[1], radius * n[2]), n, (u, i / segments))
    for i in range(segments):
        a, b, c, d = 2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3  # a, b at angle i (x0, x1); c, d at i + 1
        m.triangle(a, d, b)
        m.triangle(a, c, d)
    for x, u, sign in ((x0, 0.0, -1.0), (x1, 1.0, 1.0)):
        ring = [(x, radius * math.cos(2.0 * math.pi * i / segments), radius * math.sin(2.0 * math.pi * i / segments))
                for i in range(segments)]
        if sign < 0.0:
            ring.reverse()
        m.flat_polygon(ring, [(u, 0.5)] * segments)
    return m


def iridescence():
    doc = Document("KHR_materials_iridescence spheres",
                   "Columns: film thickness 200, 300, 400, 500, 600, 800 nm (iridescenceThicknessMaximum, no "
                   "texture), film IOR 1.8, roughness 0.15. Rows, top to bottom: dark dielectric, white "
                   "dielectric, metal. Front: a rod whose film thickness runs from 100 nm (left) to 1000 nm "
                   "(right) through iridescenceThicknessTexture.")
    sphere = gb.uv_sphere(1.0, 64, 32)
    row_y = [2.9, 1.9, 0.9]
    for r, (row_name, base, metallic) in enumerate(IRIDESCENCE_ROWS):
        for c, thickness in enumerate(IRIDESCENCE_THICKNESSES):
            name = "%s, film %d nm" % (row_name, thickness)
            mat = doc.material(name, base, metallic, IRIDESCENCE_ROUGHNESS, {"KHR_materials_iridescence": {
                "iridescenceFactor": 1.0, "iridescenceIor": IRIDESCENCE_IOR,
                "iridescenceThicknessMaximum": float(thickness)}})
            x = (c - (len(IRIDESCENCE_THICKNESSES) - 1) / 2.0) * SPHERE_PITCH
            doc.node(name, doc.mesh(name, "sphere", mat, sphere), translation=(x, row_y[r], 0.0),
                     scale=(SPHERE_RADIUS,) * 3)

    # The rod: one texture for both slots, R = 255 (iridescenceTexture: full strength), G = the
    # thickness ramp (iridescenceThicknessTexture: thickness = mix(minimum, maximum, G)), B = 0.
    png = ramp_png(256, 4, lambda s: (255, int(round(255 * s)), 0))
    tex = doc.texture("film thickness ramp (R 1, G 0 to 1)", png,
                      doc.sampler(gb.LINEAR, gb.LINEAR, gb.CLAMP_TO_EDGE, gb.CLAMP_TO_EDGE))
    rod = IRIDESCENCE_ROD
    name = "dark dielectric, film 100 to 1000 nm from texture"
    mat = doc.material(name, rod["base"], 0.0, rod["roughness"], {"KHR_materials_iridescence": {
        "iridescenceFactor": 1.0, "iridescenceTexture": {"index": tex}, "iridescenceIor": IRIDESCENCE_IOR,
        "iridescenceThicknessMinimum": float(rod["thicknessMinimum"]),
        "iridescenceThicknessMaximum": float(rod["thicknessMaximum"]),
        "iridescenceThicknessTexture": {"index": tex}}})
    doc.node("rod, film 100 to 1000 nm", doc.mesh(name, "rod", mat, rod_mesh(ROD_RADIUS, ROD_LENGTH), uv=True),
             translation=(0.0, ROD_RADIUS, 0.9))

    floor = doc.material("floor", (0.18, 0.18, 0.18), 0.0, 0.7)
    doc.node("floor", doc.mesh("floor", "floor", floor, floor_quad(16.0, 12.0)))

    # Two softboxes (emissive panels, out of the frame): one behind and above the camera facing
    # the spheres, which every sphere shows (a near-normal reflection) a little above its middle,
    # and one overhead facing down, which fills the spheres' upper halves (grazing reflections).
    panel = doc.material("softbox", (0.0, 0.0, 0.0), 0.0, 1.0, emissiveFactor=[SOFTBOX_RADIANCE] * 3)
    doc.node("front softbox", doc.mesh("front softbox", "front softbox", panel,
                                       gb.quad((5.0, 1.5, 11.0), (-10.0, 0.0, 0.0), (0.0, 5.0, -1.5))))
    top = doc.material("overhead softbox", (0.0, 0.0, 0.0), 0.0, 1.0, emissiveFactor=[OVERHEAD_RADIANCE] * 3)
    doc.node("overhead softbox", doc.mesh("overhead softbox", "overhead softbox", top,
                                          gb.quad((-5.0, 5.5, -2.0), (10.0, 0.0, 0.0), (0.0, 0.0, 7.0))))
    # No punctual light: a directional key light would be shadowed by the overhead softbox.
    doc.look_from((0.0, 2.0, 9.5), (0.0, 1.6, 0.0), 28.5)
    return doc.build({"layout": "see scenes/material-extensions/README.md"})


# --- 2. KHR_materials_dispersion -------------------------------------------------------------------

GLASS_IOR = 1.7
DISPERSIONS = [0.0, 1.0, 3.0]  # left to right; Abbe number 20 / dispersion (infinite, 20, 6.7)
PRISM_SIDE, PRISM_HEIGHT = 0.55, 1.2
PRISM_YAW_DEG = 60.0  # an edge towards the camera: a view ray enters a front face and leaves by the back one
GEM_DIAMETER = 0.7
PAIR_X = [-1.55, 0.0, 1.55]  # a prism (left) and a gem (right) per dispersion value
PRISM_OFFSET_X, GEM_OFFSET_X = -0.33, 0.4
BACKDROP_RADIUS, BACKDROP_HEIGHT, STRIPE_PAIRS = 4.0, 3.2, 24
BACKDROP_RADIANCE = 1.0
BACKDROP_ARC_DEG = 180.0


def brilliant(diameter):
    """A simplified round brilliant, 57 flat facets: an octagonal table, 8 star and 16 upper
    girdle facets on the crown, a 16-sided girdle and 16 pavilion facets down to a point (the
    culet). Proportions of diameter D: table 0.57 D, crown 0.16 D, girdle 0.03 D, pavilion 0.43 D.
    Centred on the girdle's middle, table up."""
    r = diameter / 2.0
    table_r, crown_h, girdle_h, pavilion_d = 0.57 * r, 0.16 * diameter, 0.03 * diameter, 0.43 * diameter
    gy = girdle_h / 2.0

    def ring(radius, y, count, offset=0.0):
        return [(radius * math.cos(2 * math.pi * (k + offset) / count), y,
                 -radius * math.sin(2 * math.pi * (k + offset) / count)) for k in range(count)]

    table = ring(table_r, gy + crown_h, 8)
    top = ring(r, gy, 16)
    bottom = ring(r, -gy, 16)
    culet = (0.0, -gy - pavilion_d, 0.0)
    faces = [table]
    for k in range(8):
        t0, t1 = table[k], table[(k + 1) % 8]
        g0, g1, g2 = top[2 * k], top[2 * k + 1], top[(2 * k + 2) % 16]
        faces += [[t0, g1, t1], [t0, g0, g1], [t1, g1, g2]]
    for j in range(16):
        faces.append([top[j], bottom[j], bottom[(j + 1) % 16], top[(j + 1) % 16]])
        faces.append([bottom[j], culet, bottom[(j + 1) % 16]])
    return convex_solid(faces)


def convex_solid(faces):
    """Flat-shaded MeshData of a convex solid's faces (each a planar polygon, either winding):
    every face is turned to face away from the solid's centre."""
    points = [p for f in faces for p in f]
    centre = gb.scale(tuple(map(sum, zip(*points))), 1.0 / len(points))
    m = gb.MeshData()
    for f in faces:
        n = gb.cross(gb.sub(f[1], f[0]), gb.sub(f[2], f[0]))
        mid = gb.scale(tuple(map(sum, zip(*f))), 1.0 / len(f))
        m.flat_polygon(f if gb.dot(n, gb.sub(mid, centre)) > 0.0 else list(reversed(f)))
    return m


def resting_on_facet(mesh, towards):
    """The rotation that lays mesh on the facet whose normal is closest to the direction towards,
    and the height that puts that facet on y = 0: (quaternion, lift)."""
    best = max(range(len(mesh.normals)), key=lambda i: gb.dot(mesh.normals[i], towards))
    q = gb.quaternion_between(mesh.normals[best], (0.0, -1.0, 0.0))
    lift = -min(gb.rotate(q, p)[1] for p in mesh.positions)
    return q, lift


def backdrop_mesh(radius, height, degrees, segments, u_repeat):
    """An open vertical part of a cylinder about +Y facing inwards, degrees of arc centred on -Z.
    TEXCOORD_0.u runs from 0 at the left end (seen from inside, looking down -Z) to u_repeat at
    the right end (a REPEAT sampler tiles the texture), v from 1 at the bottom to 0 at the top."""
    m = gb.MeshData()
    start = math.radians(90.0 + degrees / 2.0)  # angle from +X towards -Z of the left end (-X side)
    for i in range(segments + 1):
        a = start - math.radians(degrees) * i / segments
        p = (radius * math.cos(a), 0.0, -radius * math.sin(a))
        n = (round(-math.cos(a), 15), 0.0, round(math.sin(a), 15))
        u = u_repeat * i / segments
        m.vertex(p, n, (u, 1.0))
        m.vertex((p[0], height, p[2]), n, (u, 0.0))
    for i in range(segments):
        a, b, c, d = 2 * i, 2 * i + 1, 2 * i + 2, 2 * i + 3
        m.triangle(a, c, d)
        m.triangle(a, d, b)
    return m


def disk(radius, segments):
    ring = [(radius * math.cos(2 * math.pi * k / segments), 0.0, -radius * math.sin(2 * math.pi * k / segments))
            for k in range(segments)]
    m = gb.MeshData()
    m.flat_polygon(ring)
    return m


def dispersion():
    doc = Document("KHR_materials_dispersion prisms and gems",
                   "Left to right: dispersion 0, 1, 3 (Abbe number infinite, 20, 6.7); clear glass, IOR 1.7, "
                   "roughness 0. Back row: upright triangular prisms; front row: brilliant-cut gems resting on "
                   "a pavilion facet. Behind them a curved backdrop of glowing black and white stripes.")
    prism = gb.prism([(0.0, -PRISM_SIDE / math.sqrt(3.0)),
                      (PRISM_SIDE / 2.0, PRISM_SIDE / (2.0 * math.sqrt(3.0))),
                      (-PRISM_SIDE / 2.0, PRISM_SIDE / (2.0 * math.sqrt(3.0)))], PRISM_HEIGHT)
    gem = brilliant(GEM_DIAMETER)
    gem_q, gem_lift = resting_on_facet(gem, gb.normalize((0.0, -1.0, 1.0)))
    for x, d in zip(PAIR_X, DISPERSIONS):
        name = "glass, dispersion %g" % d
        ext = {"KHR_materials_transmission": {"transmissionFactor": 1.0},
               "KHR_materials_volume": {"thicknessFactor": PRISM_SIDE},
               "KHR_materials_ior": {"ior": GLASS_IOR},
               "KHR_materials_dispersion": {"dispersion": d}}  # 0 written out: the reference
        mat = doc.material(name, (1.0, 1.0, 1.0), 0.0, 0.0, ext)
        doc.node("prism, dispersion %g" % d, doc.mesh("prism (%s)" % name, "prism", mat, prism),
                 translation=(x + PRISM_OFFSET_X, 0.0, 0.0), rotation=gb.axis_angle_quaternion((0.0, 1.0, 0.0), PRISM_YAW_DEG))
        doc.node("gem, dispersion %g" % d, doc.mesh("gem (%s)" % name, "gem", mat, gem),
                 translation=(x + GEM_OFFSET_X, gem_lift, 0.15), rotation=gem_q)

    # The backdrop: vertical black and white stripes, emissive (a light box), black base colour
    # so the pattern is the same whatever else lights it.
    # The texture is 8 pairs of 16-texel stripes, tiled STRIPE_PAIRS / 8 times along the arc.
    stripe_px = 16
    row = bytes([0] * stripe_px + [255] * stripe_px) * 8
    png = gb.png_bytes(len(row), 4, [row] * 4, 1)
    tex = doc.texture("stripes (8 black and white pairs)", png,
                      doc.sampler(gb.LINEAR, gb.LINEAR_MIPMAP_LINEAR, gb.REPEAT, gb.REPEAT))
    backdrop = doc.material("striped light box", (0.0, 0.0, 0.0), 0.0, 1.0,
                            emissiveFactor=[BACKDROP_RADIANCE] * 3, emissiveTexture={"index": tex})
    doc.node("backdrop", doc.mesh("backdrop", "backdrop", backdrop, backdrop_mesh(
        BACKDROP_RADIUS, BACKDROP_HEIGHT, BACKDROP_ARC_DEG, 96, STRIPE_PAIRS / 8.0), uv=True))
    floor = doc.material("floor", (0.35, 0.35, 0.35), 0.0, 0.8)
    doc.node("floor", doc.mesh("floor", "floor", floor, disk(BACKDROP_RADIUS, 96)))
    doc.light({"name": "key", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": 2.0},
              "key light", rotation=gb.quaternion_between((0.0, 0.0, -1.0), gb.normalize((-0.6, -0.8, -0.5))))
    doc.look_from((0.0, 1.3, 6.5), (0.0, 0.72, 0.0), 24.0)
    return doc.build({"layout": "see scenes/material-extensions/README.md"})


# --- 3. KHR_materials_diffuse_transmission --------------------------------------------------------

SHEET_W, SHEET_H, SHEET_GAP, SHEET_BOTTOM = 0.7, 1.3, 0.22, 0.15
SHEET_BASE = (0.8, 0.8, 0.8)
ORANGE = (1.0, 0.45, 0.1)
SHEETS = [  # name, diffuseTransmissionFactor, colour factor, texture?
    ("t 0", 0.0, None, False),
    ("t 0.5", 0.5, None, False),
    ("t 1", 1.0, None, False),
    ("t 1, orange", 1.0, ORANGE, False),
    ("t 0 to 1 from texture", 1.0, None, True),
]
SPOT_DISTANCE, SPOT_HEIGHT, SPOT_CANDELA = 10.0, 4.0, 330.0
SUN_OFF_AXIS_DEG = 40.0
FILL_LUX = 0.25


def check_diffuse_transmission(ext):
    """The checks of the extension's JSON schema (glTF-Validator 2.0.0-dev.3.10 does not know
    KHR_materials_diffuse_transmission, so it cannot make them)."""
    allowed = {"diffuseTransmissionFactor", "diffuseTransmissionTexture", "diffuseTransmissionColorFactor",
               "diffuseTransmissionColorTexture", "extensions", "extras"}
    assert set(ext) <= allowed, ext
    assert 0.0 <= ext.get("diffuseTransmissionFactor", 0.0) <= 1.0
    colour = ext.get("diffuseTransmissionColorFactor", [1.0, 1.0, 1.0])
    assert len(colour) == 3 and all(0.0 <= c <= 1.0 for c in colour)
    for key in ("diffuseTransmissionTexture", "diffuseTransmissionColorTexture"):
        if key in ext:
            assert isinstance(ext[key]["index"], int) and ext[key]["index"] >= 0
    return ext


def diffuse_transmission():
    doc = Document("KHR_materials_diffuse_transmission sheets",
                   "Thin double-sided sheets, base colour 0.8, roughness 0.6, left to right: "
                   "diffuseTransmissionFactor 0, 0.5, 1, 1 with an orange diffuseTransmissionColorFactor, and 1 x "
                   "a texture whose alpha ramps 0 (bottom) to 1 (top); right: a sphere (factor 1, orange). Lit "
                   "from behind by a spot light, a weak fill from the front.")
    group = []
    count = len(SHEETS) + 1
    pitch = SHEET_W + SHEET_GAP
    xs = [(i - (count - 1) / 2.0) * pitch for i in range(count)]
    ramp = None
    for x, (name, t, colour, textured) in zip(xs, SHEETS):
        ext = {"diffuseTransmissionFactor": gb.clean(t)}
        if colour is not None:
            ext["diffuseTransmissionColorFactor"] = rgb(*colour)
        if textured:
            if ramp is None:
                # A vertical ramp in alpha (RGB white): rows top to bottom go from 255 to 0.
                rows = [bytes([255, 255, 255, int(round(255 * (1.0 - k / 63.0)))] * 4) for k in range(64)]
                ramp = doc.texture("alpha ramp 0 (bottom) to 1 (top)", gb.png_bytes(4, 64, rows, 4),
                                   doc.sampler(gb.LINEAR, gb.LINEAR, gb.CLAMP_TO_EDGE, gb.CLAMP_TO_EDGE))
            ext["diffuseTransmissionTexture"] = {"index": ramp}
        mat = doc.material("sheet, " + name, SHEET_BASE, 0.0, 0.6,
                           {"KHR_materials_diffuse_transmission": check_diffuse_transmission(ext)},
                           doubleSided=True)
        sheet = gb.quad((-SHEET_W / 2.0, 0.0, 0.0), (SHEET_W, 0.0, 0.0), (0.0, SHEET_H, 0.0))
        key = "sheet with uv" if textured else "sheet"
        group.append(doc.node("sheet, " + name, doc.mesh("sheet, " + name, key, mat, sheet, uv=textured),
                              translation=(x, SHEET_BOTTOM, 0.0), root=False))
    sphere_mat = doc.material("sphere, t 1, orange", SHEET_BASE, 0.0, 0.6, {
        "KHR_materials_diffuse_transmission": check_diffuse_transmission({
            "diffuseTransmissionFactor": 1.0, "diffuseTransmissionColorFactor": rgb(*ORANGE)})})
    radius = SHEET_W / 2.0
    group.append(doc.node("sphere, t 1, orange", doc.mesh("sphere, t 1, orange", "sphere", sphere_mat,
                                                          gb.uv_sphere(1.0, 64, 32)),
                          translation=(xs[-1], radius, 0.0), scale=(radius,) * 3, root=False))
    floor = doc.material("floor", (0.15, 0.15, 0.15), 0.0, 0.9)
    group.append(doc.node("floor", doc.mesh("floor", "floor", floor, floor_quad(20.0, 20.0)), root=False))

    # Back light: a spot far behind the sheets (local -Z), aimed at their middle; its inner cone
    # covers every sheet. Fill: a weak directional light from the camera's side.
    spot_pos = (0.0, SPOT_HEIGHT, -SPOT_DISTANCE)
    aim = gb.normalize(gb.sub((0.0, SHEET_BOTTOM + SHEET_H / 2.0, 0.0), spot_pos))
    group.append(doc.light({"name": "back light", "type": "spot", "color": [1.0, 1.0, 1.0],
                            "intensity": SPOT_CANDELA, "spot": {"innerConeAngle": math.radians(22.0),
                                                                "outerConeAngle": math.radians(30.0)}},
                           "back light (spot)", translation=spot_pos,
                           rotation=gb.quaternion_between((0.0, 0.0, -1.0), aim), root=False))
    group.append(doc.light({"name": "fill", "type": "directional", "color": [1.0, 1.0, 1.0], "intensity": FILL_LUX},
                           "fill light", rotation=gb.quaternion_between((0.0, 0.0, -1.0),
                                                                       gb.normalize((0.3, -0.5, -1.0))), root=False))
    group.append(doc.look_from((0.0, 1.6, 6.0), (0.0, 0.7, 0.0), 30.0, root=False))
    # Everything above is built looking down -Z; the group is turned about +Y so that the sunrise
    # environment's sun is behind the sheets, SUN_OFF_AXIS_DEG to the left of straight behind
    # (straight behind, the sun and its bright sky would be in the frame).
    doc.node("scene (turned towards the environment's sun)", children=group,
             rotation=gb.axis_angle_quaternion((0.0, 1.0, 0.0), -(90.0 + SUN_AZIMUTH_DEG) + SUN_OFF_AXIS_DEG))
    return doc.build({"layout": "see scenes/material-extensions/README.md"})


OUTPUTS = {
    "iridescence.gltf": iridescence,
    "dispersion.gltf": dispersion,
    "diffuse-transmission.gltf": diffuse_transmission,
}


def main():
    args = gb.generator_arguments(__doc__, __file__).parse_args()
    outputs = {name: make() for name, make in OUTPUTS.items()}
    return gb.write_or_check(outputs, args.out_dir, args.check, "make_material_extensions")


if __name__ == "__main__":
    sys.exit(main())
