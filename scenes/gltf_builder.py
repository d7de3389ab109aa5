"""Helpers shared by the scene generators under scenes/ (standard library only, deterministic).

- `document`: a whole glTF file's bytes from its nodes, camera, meshes, materials and buffer.
- `BufferBuilder`: one glTF buffer being filled: buffer views (each start 4-byte aligned),
  accessors (POSITION with the min/max the specification requires, written as the shortest
  decimal that reads back as the stored float32), index accessors (16-bit when they fit),
  and the buffer itself, either embedded as a base64 data URI or written beside the .gltf.
- `png_bytes`: a PNG image (8-bit grey, grey+alpha, RGB or RGBA) written with zlib and struct.
- Small vector helpers on tuples and `MeshData`, a triangle list with per-vertex normals and
  texture coordinates, with builders for a UV sphere, a box, a quad and flat-faced solids.

A generator beside this file imports it with:

    sys.dont_write_bytecode = True  # no __pycache__ in scenes/
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
    import gltf_builder
"""

import argparse
import base64
import json
import os
import sys
import math
import struct
import zlib

# glTF enumerations
ARRAY_BUFFER = 34962
ELEMENT_ARRAY_BUFFER = 34963
UNSIGNED_BYTE = 5121
UNSIGNED_SHORT = 5123
UNSIGNED_INT = 5125
FLOAT = 5126
TRIANGLES = 4
NEAREST = 9728
LINEAR = 9729
LINEAR_MIPMAP_LINEAR = 9987
CLAMP_TO_EDGE = 33071
REPEAT = 10497

_COMPONENTS = {"SCALAR": 1, "VEC2": 2, "VEC3": 3, "VEC4": 4}


# --- Numbers -------------------------------------------------------------------------------------


def f32(v):
    """v rounded to the nearest float32."""
    return struct.unpack("<f", struct.pack("<f", v))[0]


def shortest_f32(v):
    """The shortest decimal that reads back as the same float32 (for accessor min/max)."""
    target = f32(v)
    for digits in range(1, 18):
        candidate = float("%.*g" % (digits, target))
        if f32(candidate) == target:
            return candidate + 0.0  # no negative zero
    return target


def clean(v, places=12):
    """v rounded for the JSON text (no float noise such as 0.30000000000000004, no -0.0)."""
    return round(v, places) + 0.0


# --- Vectors (tuples of floats) ------------------------------------------------------------------


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def scale(a, s):
    return tuple(x * s for x in a)


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def length(a):
    return math.sqrt(dot(a, a))


def normalize(a):
    n = length(a)
    return tuple(x / n + 0.0 for x in a)  # + 0.0: no -0.0


def quaternion_between(a, b):
    """The unit quaternion [x, y, z, w] of the shortest rotation taking direction a to b."""
    a, b = normalize(a), normalize(b)
    c = dot(a, b)
    if c < -1.0 + 1e-12:  # opposite: half a turn about any axis perpendicular to a
        axis = cross(a, (1.0, 0.0, 0.0))
        if dot(axis, axis) < 1e-12:
            axis = cross(a, (0.0, 1.0, 0.0))
        return list(normalize(axis)) + [0.0]
    axis = cross(a, b)
    return list(normalize(tuple(axis) + (1.0 + c,)))


def rotate(q, v):
    """v rotated by the unit quaternion q = [x, y, z, w]."""
    u, w = tuple(q[:3]), q[3]
    t = scale(cross(u, v), 2.0)
    return add(add(v, scale(t, w)), cross(u, t))


def look_at_quaternion(eye, target, up=(0.0, 1.0, 0.0)):
    """The rotation [x, y, z, w] of a glTF camera node at eye looking at target (a glTF camera
    looks down its local -Z with +Y up)."""
    back = normalize(sub(eye, target))
    right = normalize(cross(up, back))
    return basis_quaternion(right, cross(back, right), back)


def basis_quaternion(right, up, back):
    """The rotation [x, y, z, w] whose matrix has the columns right, up, back (an orthonormal,
    right-handed basis), w >= 0, each component rounded by clean()."""
    m = [[right[i], up[i], back[i]] for i in range(3)]
    trace = m[0][0] + m[1][1] + m[2][2]
    if trace > 0.0:
        s = 2.0 * math.sqrt(trace + 1.0)
        q = ((m[2][1] - m[1][2]) / s, (m[0][2] - m[2][0]) / s, (m[1][0] - m[0][1]) / s, 0.25 * s)
    elif m[0][0] > m[1][1] and m[0][0] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[0][0] - m[1][1] - m[2][2])
        q = (0.25 * s, (m[0][1] + m[1][0]) / s, (m[0][2] + m[2][0]) / s, (m[2][1] - m[1][2]) / s)
    elif m[1][1] > m[2][2]:
        s = 2.0 * math.sqrt(1.0 + m[1][1] - m[0][0] - m[2][2])
        q = ((m[0][1] + m[1][0]) / s, 0.25 * s, (m[1][2] + m[2][1]) / s, (m[0][2] - m[2][0]) / s)
    else:
        s = 2.0 * math.sqrt(1.0 + m[2][2] - m[0][0] - m[1][1])
        q = ((m[0][2] + m[2][0]) / s, (m[1][2] + m[2][1]) / s, 0.25 * s, (m[1][0] - m[0][1]) / s)
    if q[3] < 0.0:
        q = tuple(-c for c in q)
    n = math.sqrt(sum(c * c for c in q))
    return [clean(c / n) for c in q]


def axis_angle_quaternion(axis, degrees):
    """The rotation [x, y, z, w] by degrees about axis (right-handed)."""
    a = normalize(axis)
    h = math.radians(degrees) / 2.0
    return [clean(c * math.sin(h)) for c in a] + [clean(math.cos(h))]


# --- Buffers, views and accessors ----------------------------------------------------------------


class BufferBuilder:
    """The binary buffer of a glTF file with its bufferViews and accessors lists. Every method
    that adds an accessor returns its index; `view` returns a buffer view's index."""

    def __init__(self):
        self.blob = bytearray()
        self.buffer_views = []
        self.accessors = []

    def _align(self):
        while len(self.blob) % 4:
            self.blob.append(0)

    def view(self, data, target=None):
        """A buffer view of data, starting at the next multiple of 4 bytes. target: ARRAY_BUFFER
        for vertex attributes, ELEMENT_ARRAY_BUFFER for indices, None for images."""
        self._align()
        view = {"buffer": 0, "byteOffset": len(self.blob), "byteLength": len(data)}
        if target is not None:
            view["target"] = target
        self.buffer_views.append(view)
        self.blob.extend(data)
        return len(self.buffer_views) - 1

    def accessor(self, view, component_type, count, kind, minimum=None, maximum=None, name=None):
        acc = {"bufferView": view, "componentType": component_type, "count": count, "type": kind}
        if minimum is not None:
            acc["min"] = minimum
            acc["max"] = maximum
        if name is not None:
            acc["name"] = name
        self.accessors.append(acc)
        return len(self.accessors) - 1

    def floats(self, values, kind, bounds=False, name=None):
        """A float vertex attribute from a list of tuples (VEC2, VEC3 or VEC4) or numbers
        (SCALAR). bounds: write min and max (required for POSITION)."""
        n = _COMPONENTS[kind]
        rows = [(v,) if n == 1 else tuple(v) for v in values]
        data = b"".join(struct.pack("<%df" % n, *r) for r in rows)
        minimum = maximum = None
        if bounds:
            minimum = [shortest_f32(min(f32(r[i]) for r in rows)) for i in range(n)]
            maximum = [shortest_f32(max(f32(r[i]) for r in rows)) for i in range(n)]
        return self.accessor(self.view(data, ARRAY_BUFFER), FLOAT, len(rows), kind, minimum, maximum, name)

    def vec2(self, values, bounds=False, name=None):
        return self.floats(values, "VEC2", bounds, name)

    def vec3(self, values, bounds=False, name=None):
        return self.floats(values, "VEC3", bounds, name)

    def vec4(self, values, bounds=False, name=None):
        return self.floats(values, "VEC4", bounds, name)

    def indices(self, flat, name=None):
        """A triangle index accessor: unsigned 16-bit when every index is below 65535, else 32."""
        flat = list(flat)
        if max(flat) < 65535:
            data, component_type = struct.pack("<%dH" % len(flat), *flat), UNSIGNED_SHORT
        else:
            data, component_type = struct.pack("<%dI" % len(flat), *flat), UNSIGNED_INT
        return self.accessor(self.view(data, ELEMENT_ARRAY_BUFFER), component_type, len(flat), "SCALAR", name=name)

    def mesh_data(self, mesh, name=None, uv=True):
        """The accessors of a MeshData: (attributes dict, indices accessor). POSITION gets
        min/max; TEXCOORD_0 is written when the mesh has texture coordinates and uv is true
        (the validator reports texture coordinates that no texture uses)."""
        label = (lambda s: "%s %s" % (name, s)) if name else (lambda s: None)
        attributes = {"POSITION": self.vec3(mesh.positions, True, label("positions")),
                      "NORMAL": self.vec3(mesh.normals, False, label("normals"))}
        if mesh.has_uv and uv:
            attributes["TEXCOORD_0"] = self.vec2(mesh.uvs, False, label("texcoords"))
        return attributes, self.indices(mesh.indices, label("indices"))

    def finish(self):
        """The buffer's bytes, padded to a multiple of 4."""
        self._align()
        return bytes(self.blob)

    def embedded_buffer(self):
        """The buffer as a glTF buffer object with the bytes in a base64 data URI."""
        data = self.finish()
        return {"byteLength": len(data), "uri": data_uri(data)}

    def external_buffer(self, uri):
        """The buffer as a glTF buffer object naming a file (write finish() to it)."""
        data = self.finish()
        return {"uri": uri, "byteLength": len(data)}


def data_uri(data, mime="application/octet-stream"):
    return "data:%s;base64,%s" % (mime, base64.b64encode(bytes(data)).decode("ascii"))


# --- PNG -----------------------------------------------------------------------------------------


def png_bytes(width, height, rows, channels):
    """An 8-bit PNG. rows: height rows, each a bytes-like of width * channels values (1 grey,
    2 grey + alpha, 3 RGB, 4 RGBA), top row first. No filtering and no compression (stored
    deflate blocks): the bytes do not depend on the zlib library's version. For small images."""
    colour_type = {1: 0, 2: 4, 3: 2, 4: 6}[channels]
    raw = bytearray()
    for row in rows:
        assert len(row) == width * channels
        raw.append(0)  # filter type None
        raw.extend(row)
    assert len(raw) == height * (1 + width * channels)

    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    header = struct.pack(">IIBBBBB", width, height, 8, colour_type, 0, 0, 0)
    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib_stored(bytes(raw)))
            + chunk(b"IEND", b""))


def zlib_stored(data):
    """A zlib stream holding data in stored (uncompressed) deflate blocks of at most 65535 bytes."""
    out = bytearray(b"\x78\x01")
    blocks = [data[i:i + 65535] for i in range(0, len(data), 65535)] or [b""]
    for k, block in enumerate(blocks):
        out.append(1 if k == len(blocks) - 1 else 0)
        out.extend(struct.pack("<HH", len(block), len(block) ^ 0xFFFF))
        out.extend(block)
    out.extend(struct.pack(">I", zlib.adler32(data) & 0xFFFFFFFF))
    return bytes(out)


# --- Meshes --------------------------------------------------------------------------------------


class MeshData:
    """Triangles with per-vertex normals and (optionally) texture coordinates. Winding is
    counter-clockwise seen from the side the normals point to."""

    def __init__(self):
        self.positions, self.normals, self.uvs, self.indices = [], [], [], []
        self.has_uv = False

    def vertex(self, position, normal, uv=None):
        self.positions.append(tuple(float(c) + 0.0 for c in position))
        self.normals.append(tuple(float(c) + 0.0 for c in normal))
        self.uvs.append(tuple(uv) if uv is not None else (0.0, 0.0))
        self.has_uv = self.has_uv or uv is not None
        return len(self.positions) - 1

    def triangle(self, a, b, c):
        self.indices.extend((a, b, c))

    def flat_polygon(self, points, uvs=None):
        """A planar convex polygon (counter-clockwise seen from its front) as a fan of triangles
        with vertices of its own sharing the face normal: flat shading."""
        n = normalize(cross(sub(points[1], points[0]), sub(points[2], points[0])))
        first = None
        for i, p in enumerate(points):
            k = self.vertex(p, n, uvs[i] if uvs else None)
            first = k if first is None else first
        for i in range(1, len(points) - 1):
            self.triangle(first, first + i, first + i + 1)

    def transformed(self, offset=(0.0, 0.0, 0.0), q=None):
        """A copy rotated by the quaternion q (if given) and then moved by offset."""
        out = MeshData()
        for p, n, uv in zip(self.positions, self.normals, self.uvs):
            if q is not None:
                p, n = rotate(q, p), rotate(q, n)
            out.vertex(add(p, offset), n, uv if self.has_uv else None)
        out.indices = list(self.indices)
        return out

    def extend(self, other):
        base = len(self.positions)
        for p, n, uv in zip(other.positions, other.normals, other.uvs):
            self.vertex(p, n, uv if other.has_uv else None)
        self.indices.extend(base + i for i in other.indices)
        return self


def uv_sphere(radius=1.0, segments=48, rings=24, centre=(0.0, 0.0, 0.0)):
    """A UV sphere about +Y with smooth normals and TEXCOORD_0: u runs once around, from +X
    (u = 0) through -Z (0.25), -X (0.5) and +Z (0.75); v from 0 at the top to 1 at the bottom."""
    m = MeshData()
    for j in range(rings + 1):
        theta = math.pi * j / rings
        for i in range(segments + 1):
            phi = 2.0 * math.pi * i / segments
            n = (math.sin(theta) * math.cos(phi), math.cos(theta), -math.sin(theta) * math.sin(phi))
            n = tuple(round(c, 15) for c in n)
            m.vertex(add(centre, scale(n, radius)), n, (i / segments, j / rings))
    row = segments + 1
    for j in range(rings):
        for i in range(segments):
            a, b = j * row + i, j * row + i + 1
            c, d = a + row, b + row
            if j > 0:
                m.triangle(a, c, b)
            if j < rings - 1:
                m.triangle(b, c, d)
    return m


def quad(corner, edge_u, edge_v, uv_scale=(1.0, 1.0)):
    """A parallelogram corner + s * edge_u + t * edge_v (s, t in [0, 1]), facing
    cross(edge_u, edge_v). TEXCOORD_0 = (s * uv_scale[0], (1 - t) * uv_scale[1]): the image's
    top row is at the far end of edge_v."""
    m = MeshData()
    su, sv = uv_scale
    points = [corner, add(corner, edge_u), add(add(corner, edge_u), edge_v), add(corner, edge_v)]
    m.flat_polygon(points, [(0.0, sv), (su, sv), (su, 0.0), (0.0, 0.0)])
    return m


def box(size, centre=(0.0, 0.0, 0.0)):
    """An axis-aligned box, flat-shaded, each face its own 4 vertices and UVs over the face."""
    hx, hy, hz = (s / 2.0 for s in size)
    cx, cy, cz = centre
    m = MeshData()
    faces = [  # corner, edge_u, edge_v (counter-clockwise seen from outside)
        ((cx + hx, cy - hy, cz + hz), (0.0, 0.0, -2 * hz), (0.0, 2 * hy, 0.0)),   # +X
        ((cx - hx, cy - hy, cz - hz), (0.0, 0.0, 2 * hz), (0.0, 2 * hy, 0.0)),    # -X
        ((cx - hx, cy + hy, cz + hz), (2 * hx, 0.0, 0.0), (0.0, 0.0, -2 * hz)),   # +Y
        ((cx - hx, cy - hy, cz - hz), (2 * hx, 0.0, 0.0), (0.0, 0.0, 2 * hz)),    # -Y
        ((cx - hx, cy - hy, cz + hz), (2 * hx, 0.0, 0.0), (0.0, 2 * hy, 0.0)),    # +Z
        ((cx + hx, cy - hy, cz - hz), (-2 * hx, 0.0, 0.0), (0.0, 2 * hy, 0.0)),   # -Z
    ]
    for corner, eu, ev in faces:
        m.extend(quad(corner, eu, ev))
    return m


def prism(profile, height, base_y=0.0):
    """A straight prism standing on y = base_y: profile is a convex polygon of (x, z) points
    (either orientation); flat-shaded (every face its own vertices)."""
    m = MeshData()
    area2 = sum(profile[i][0] * profile[(i + 1) % len(profile)][1] - profile[(i + 1) % len(profile)][0] * profile[i][1]
                for i in range(len(profile)))
    if area2 > 0.0:  # counter-clockwise in (x, z): the top would face -Y
        profile = list(reversed(profile))
    bottom = [(x, base_y, z) for x, z in profile]
    top = [(x, base_y + height, z) for x, z in profile]
    m.flat_polygon(top)
    m.flat_polygon(list(reversed(bottom)))
    k = len(profile)
    for i in range(k):
        j = (i + 1) % k
        m.flat_polygon([bottom[i], bottom[j], top[j], top[i]])
    return m


def document(buffers, meshes, materials, nodes, camera, asset, extensions_used=(), extensions=None):
    """One glTF file's bytes: the nodes (all in scene 0), one camera, the meshes and materials,
    one embedded buffer; `asset` is {"generator": ..., "copyright": ...}; `extensions` (the
    document's own, e.g. KHR_lights_punctual's lights) only when given."""
    gltf = {"asset": dict({"version": "2.0"}, **asset), "extensionsUsed": list(extensions_used)}
    if extensions:
        gltf["extensions"] = extensions
    gltf.update({
        "scene": 0,
        "scenes": [{"nodes": list(range(len(nodes)))}],
        "nodes": nodes,
        "cameras": [camera],
        "meshes": meshes,
        "materials": materials,
        "buffers": [buffers.embedded_buffer()],
        "bufferViews": buffers.buffer_views,
        "accessors": buffers.accessors,
    })
    return (json.dumps(gltf, indent=1, ensure_ascii=True) + "\n").encode("utf-8")


def write_or_check(outputs, out_dir, check, program):
    """Writes each {file name: bytes} into out_dir, or with check writes nothing and returns 1
    when a file there differs from what would be written (naming it), else 0."""
    if check:
        stale = [os.path.join(out_dir, name) for name, data in sorted(outputs.items())
                 if not os.path.exists(os.path.join(out_dir, name))
                 or open(os.path.join(out_dir, name), "rb").read() != data]
        for path in stale:
            print("%s: %s is not what the generator writes" % (program, path), file=sys.stderr)
        return 1 if stale else 0
    os.makedirs(out_dir, exist_ok=True)
    for name, data in sorted(outputs.items()):
        with open(os.path.join(out_dir, name), "wb") as f:
            f.write(data)
        print("wrote %s (%d bytes)" % (os.path.join(out_dir, name), len(data)))
    return 0


def generator_arguments(doc, script):
    """The generators' command line: --out-dir (default: beside `script`) and --check. Returns
    the parser, to which a generator may add its own options before parse_args()."""
    parser = argparse.ArgumentParser(description=doc.splitlines()[0])
    parser.add_argument("--out-dir", default=os.path.dirname(os.path.abspath(script)),
                        help="where to write the files [default: beside this script]")
    parser.add_argument("--check", action="store_true",
                        help="write nothing; exit 1 if the files in --out-dir differ from what would be written")
    return parser
