#!/usr/bin/env python3
"""Writes the scenes of the paper's figures (after "Ray Tracing in One Weekend", RTOW) as glTF 2.0.

Outputs, beside this script (see README.md):
  three-balls.gltf/.bin      smooth metal, diffuse, rough metal on RTOW's small-world ground
  refraction.gltf/.bin       solid, hollow and absorbing glass with RTOW's diffuse and fuzzy metal
  grid-of-spheres.gltf/.bin  RTOW's cover scene, read from seed/grid_of_spheres.txt (487 spheres)
  timing-scene.gltf/.bin     a fixed, random-free 11 x 11 grid for timing runs
  adversarial.gltf/.bin      one expensive glass-and-metal cluster in a corner, the rest empty
  sky-gradient.hdr           RTOW's sky, lerp((1,1,1), (0.5,0.7,1), 0.5*(d.y+1)), as an
                             equirectangular Radiance RGBE image in tessera's mapping

Every sphere of a scene is a node (translation + uniform scale) placing a glTF mesh whose
primitive uses the scene's one unit-sphere POSITION/NORMAL/indices accessors (a geodesic
icosphere) with its own material. RTOW's ground spheres (radius 100 or 1000) are their own
UV-sphere mesh whose latitude rings are dense where the camera sees the ground and sparse
elsewhere. Both tessellations are worked out from the cameras at 1200x675 so that no silhouette
or ground point is off by more than MAX_ERROR_PX pixels; `--report` prints that working.

Standard library only, deterministic: running it again rewrites every file byte for byte.
Usage: python3 make_paper_scenes.py [--out-dir DIR] [--check] [--report]
"""

import json
import math
import os
import sys

sys.dont_write_bytecode = True  # no __pycache__ in scenes/
sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), ".."))
from gltf_builder import (  # noqa: E402  (scenes/gltf_builder.py)
    BufferBuilder, add, basis_quaternion, clean, cross, dot, generator_arguments, length, normalize, scale, sub,
    write_or_check)

GENERATOR = "tessera scenes/paper/make_paper_scenes.py"
SEED_FILE = os.path.join("seed", "grid_of_spheres.txt")
HDR_NAME = "sky-gradient.hdr"
HDR_WIDTH, HDR_HEIGHT = 512, 256

# The resolution the tessellation is worked out for (the book's final image) and the largest
# geometric error allowed there, in pixels, for sphere silhouettes and for the ground.
SHIPPED_WIDTH, SHIPPED_HEIGHT = 1200, 675
MAX_ERROR_PX = 0.25
# The ground's rings are planned for this fraction of MAX_ERROR_PX (the plan takes the nearest
# point of a band and the frame corner's stretch; the check then measures every triangle).
GROUND_DESIGN_MARGIN = 0.8

SKY_WHITE = (1.0, 1.0, 1.0)
SKY_BLUE = (0.5, 0.7, 1.0)

def closest_distance_to_origin(a, b, c):
    """Distance from the origin to the closest point of triangle abc (Ericson, RTCD 5.1.5)."""
    p = (0.0, 0.0, 0.0)
    ab, ac, ap = sub(b, a), sub(c, a), sub(p, a)
    d1, d2 = dot(ab, ap), dot(ac, ap)
    if d1 <= 0.0 and d2 <= 0.0:
        return length(a)
    bp = sub(p, b)
    d3, d4 = dot(ab, bp), dot(ac, bp)
    if d3 >= 0.0 and d4 <= d3:
        return length(b)
    vc = d1 * d4 - d3 * d2
    if vc <= 0.0 and d1 >= 0.0 and d3 <= 0.0:
        return length(add(a, scale(ab, d1 / (d1 - d3))))
    cp = sub(p, c)
    d5, d6 = dot(ab, cp), dot(ac, cp)
    if d6 >= 0.0 and d5 <= d6:
        return length(c)
    vb = d5 * d2 - d1 * d6
    if vb <= 0.0 and d2 >= 0.0 and d6 <= 0.0:
        return length(add(a, scale(ac, d2 / (d2 - d6))))
    va = d3 * d6 - d5 * d4
    if va <= 0.0 and (d4 - d3) >= 0.0 and (d5 - d6) >= 0.0:
        return length(add(b, scale(sub(c, b), (d4 - d3) / ((d4 - d3) + (d5 - d6)))))
    denom = 1.0 / (va + vb + vc)
    v, w = vb * denom, vc * denom
    return length(add(a, add(scale(ab, v), scale(ac, w))))


# --- Cameras -----------------------------------------------------------------------------------


class Camera:
    """RTOW's camera: look from eye at target, vup, vertical fov in degrees, 16:9."""

    def __init__(self, name, eye, target, up, vfov_deg, aspect=16.0 / 9.0):
        self.name, self.eye, self.target, self.up = name, eye, target, up
        self.vfov_deg, self.aspect = vfov_deg, aspect
        self.back = normalize(sub(eye, target))  # glTF cameras look down -Z: +Z points back
        self.right = normalize(cross(up, self.back))
        self.true_up = cross(self.back, self.right)
        self.tan_half = math.tan(math.radians(vfov_deg) / 2.0)
        self.f_px = (SHIPPED_HEIGHT / 2.0) / self.tan_half  # focal length in pixels at 1200x675
        tan_corner_sq = self.tan_half ** 2 * (1.0 + self.aspect ** 2)
        self.cos2_corner = 1.0 / (1.0 + tan_corner_sq)  # cos^2 of the angle to a frame corner

    def to_camera(self, p):
        d = sub(p, self.eye)
        return (dot(d, self.right), dot(d, self.true_up), -dot(d, self.back))  # x, y, depth

    def ndc(self, p):
        x, y, z = self.to_camera(p)
        if z <= 1e-9:
            return None
        return (x / (z * self.tan_half * self.aspect), y / (z * self.tan_half))

    def in_frame(self, p, margin=0.0):
        q = self.ndc(p)
        return q is not None and abs(q[0]) <= 1.0 + margin and abs(q[1]) <= 1.0 + margin

    def px_per_unit(self, p):
        """Most pixels that a unit displacement across the ray at p moves p's image by
        (the radial stretch of a pinhole: f / (depth * cos(angle off axis)))."""
        x, y, z = self.to_camera(p)
        return self.f_px * math.sqrt(x * x + y * y + z * z) / (z * z)

    def ray_through(self, ndc_x, ndc_y):
        d = add(add(scale(self.right, ndc_x * self.tan_half * self.aspect), scale(self.true_up, ndc_y * self.tan_half)),
                scale(self.back, -1.0))
        return normalize(d)

    def quaternion(self):
        """Rotation (x, y, z, w) whose matrix has columns right, up, back."""
        return basis_quaternion(self.right, self.true_up, self.back)


# --- The unit sphere: a geodesic icosphere -----------------------------------------------------

ICOSAHEDRON_FACES = [
    (0, 11, 5), (0, 5, 1), (0, 1, 7), (0, 7, 10), (0, 10, 11), (1, 5, 9), (5, 11, 4), (11, 10, 2),
    (10, 7, 6), (7, 1, 8), (3, 9, 4), (3, 4, 2), (3, 2, 6), (3, 6, 8), (3, 8, 9), (4, 9, 5),
    (2, 4, 11), (6, 2, 10), (8, 6, 7), (9, 8, 1),
]


def icosahedron_vertices():
    t = (1.0 + math.sqrt(5.0)) / 2.0
    raw = [(-1, t, 0), (1, t, 0), (-1, -t, 0), (1, -t, 0), (0, -1, t), (0, 1, t), (0, -1, -t), (0, 1, -t),
           (t, 0, -1), (t, 0, 1), (-t, 0, -1), (-t, 0, 1)]
    return [normalize(tuple(float(c) for c in v)) for v in raw]


_icosphere_cache = {}


def icosphere(n):
    """Frequency-n geodesic sphere: each icosahedron face cut into n*n triangles, every vertex
    pushed out onto the unit sphere. Returns (positions, triangles, max_deviation): the largest
    distance between the sphere and the mesh (at a face's point closest to the centre)."""
    if n in _icosphere_cache:
        return _icosphere_cache[n]
    base = icosahedron_vertices()
    index_of, positions, triangles = {}, [], []

    def vertex(face, i, j):
        a, b, c = face
        weights = ((a, n - i - j), (b, i), (c, j))
        key = tuple(sorted((v, w) for v, w in weights if w > 0))
        if key not in index_of:
            p = (0.0, 0.0, 0.0)
            for v, w in weights:
                p = add(p, scale(base[v], float(w)))
            index_of[key] = len(positions)
            positions.append(normalize(p))
        return index_of[key]

    for face in ICOSAHEDRON_FACES:
        for i in range(n):
            for j in range(n - i):
                triangles.append((vertex(face, i, j), vertex(face, i + 1, j), vertex(face, i, j + 1)))
                if i + j <= n - 2:
                    triangles.append((vertex(face, i + 1, j), vertex(face, i + 1, j + 1), vertex(face, i, j + 1)))
    deviation = 0.0
    for t in triangles:
        a, b, c = (positions[k] for k in t)
        assert dot(cross(sub(b, a), sub(c, a)), add(add(a, b), c)) > 0.0, "icosphere winding"
        deviation = max(deviation, 1.0 - closest_distance_to_origin(a, b, c))
    _icosphere_cache[n] = (positions, triangles, deviation)
    return _icosphere_cache[n]


def silhouette_px_per_unit(camera, centre, radius):
    """Largest px_per_unit over the sphere's silhouette circle seen from camera, counting only the
    part in the frame; None if the silhouette is out of the frame."""
    to_c = sub(centre, camera.eye)
    d = length(to_c)
    if d <= radius:
        return None
    axis = scale(to_c, 1.0 / d)
    circle_centre = add(camera.eye, scale(to_c, 1.0 - (radius * radius) / (d * d)))
    circle_radius = radius * math.sqrt(d * d - radius * radius) / d
    helper = (1.0, 0.0, 0.0) if abs(axis[0]) < 0.9 else (0.0, 1.0, 0.0)
    u = normalize(cross(axis, helper))
    v = cross(axis, u)
    best = None
    for k in range(256):
        phi = 2.0 * math.pi * k / 256
        p = add(circle_centre, add(scale(u, circle_radius * math.cos(phi)), scale(v, circle_radius * math.sin(phi))))
        if camera.in_frame(p):
            s = camera.px_per_unit(p)
            best = s if best is None else max(best, s)
    return best


# --- RTOW's ground sphere: a UV sphere with latitude rings where the camera sees it ------------


def uv_point(centre, radius, theta, phi):
    """Point at polar angle theta from +Y and azimuth phi; the top is computed without
    cancellation so that the ground near y = top is exact to float precision."""
    s = math.sin(theta)
    top = centre[1] + radius
    y = top - 2.0 * radius * math.sin(theta / 2.0) ** 2
    return (centre[0] + radius * s * math.cos(phi), y, centre[2] + radius * s * math.sin(phi))


def uv_normal(theta, phi):
    s = math.sin(theta)
    return (s * math.cos(phi), math.cos(theta), s * math.sin(phi))


def band_deviation(theta1, theta2, segments):
    """Largest distance between the unit sphere and the triangles of the band [theta1, theta2]
    (every triangle of a band is congruent to one of two)."""
    dphi = 2.0 * math.pi / segments
    o = (0.0, 0.0, 0.0)
    a, b = uv_point(o, 1.0, theta1, 0.0), uv_point(o, 1.0, theta1, dphi)  # on the unit sphere
    c, d = uv_point(o, 1.0, theta2, 0.0), uv_point(o, 1.0, theta2, dphi)
    dev = 0.0
    if theta1 > 0.0:  # (a, b, d) is degenerate at the north pole
        dev = max(dev, 1.0 - closest_distance_to_origin(a, b, d))
    if theta2 < math.pi:  # (a, d, c) is degenerate at the south pole
        dev = max(dev, 1.0 - closest_distance_to_origin(a, d, c))
    return dev


class GroundSphere:
    """RTOW's huge ground sphere as a UV sphere around +Y, stored in world coordinates."""

    def __init__(self, centre, radius, cameras):
        self.centre, self.radius, self.cameras = centre, radius, cameras
        best = None
        for segments in (64, 96, 128, 160, 192, 256, 320, 384, 512):
            rings = self._rings(segments)
            if rings is None:
                continue
            triangles = 2 * segments * (len(rings) - 2)
            if best is None or triangles < best[0]:
                best = (triangles, segments, rings)
        _, self.segments, self.rings = best
        self._build()

    def _allowed(self, theta1, theta2):
        """Largest deviation (world units) allowed for the band [theta1, theta2], over cameras."""
        allowed = math.inf
        for cam in self.cameras:
            rel = sub(cam.eye, self.centre)
            dist = length(rel)
            theta_e = math.acos(max(-1.0, min(1.0, rel[1] / dist)))
            horizon = math.acos(self.radius / dist) * 1.05 + 1e-9  # the front-facing cap, +5 %
            gap = 0.0 if theta1 <= theta_e <= theta2 else min(abs(theta1 - theta_e), abs(theta2 - theta_e))
            if gap > horizon:
                continue  # the camera sees none of this band: it faces away
            nearest = math.sqrt(max(0.0, dist * dist + self.radius ** 2 - 2.0 * dist * self.radius * math.cos(gap)))
            allowed = min(allowed, GROUND_DESIGN_MARGIN * MAX_ERROR_PX * nearest * cam.cos2_corner / cam.f_px)
        return allowed

    def _rings(self, segments):
        max_step = 2.0 * math.pi / segments
        rings, theta, step = [0.0], 0.0, None
        while theta < math.pi:
            lo, hi = 1e-3 * max_step, min(max_step, 2.0 * step if step else max_step, math.pi - theta)
            if band_deviation(theta, theta + hi, segments) * self.radius > self._allowed(theta, theta + hi):
                if band_deviation(theta, theta + lo, segments) * self.radius > self._allowed(theta, theta + lo):
                    return None  # too few segments: the rings alone cannot keep the error
                for _ in range(40):  # bisection for the largest step that keeps the error
                    mid = 0.5 * (lo + hi)
                    if band_deviation(theta, theta + mid, segments) * self.radius <= self._allowed(theta, theta + mid):
                        lo = mid
                    else:
                        hi = mid
                hi = lo
            step = hi
            if math.pi - (theta + step) < 0.5 * step:
                step = math.pi - theta
            theta = theta + step if theta + step < math.pi else math.pi
            rings.append(theta)
        return rings

    def _build(self):
        c, r, n = self.centre, self.radius, self.segments
        self.positions = [uv_point(c, r, 0.0, 0.0)]
        self.normals = [(0.0, 1.0, 0.0)]
        inner = self.rings[1:-1]
        for theta in inner:
            for k in range(n):
                phi = 2.0 * math.pi * k / n
                self.positions.append(uv_point(c, r, theta, phi))
                self.normals.append(uv_normal(theta, phi))
        self.positions.append((c[0], c[1] - r, c[2]))
        self.normals.append((0.0, -1.0, 0.0))
        south = len(self.positions) - 1
        ring = lambda i, k: 1 + i * n + (k % n)
        tris = []
        for k in range(n):
            tris.append((0, ring(0, k + 1), ring(0, k)))
        for i in range(len(inner) - 1):
            for k in range(n):
                tris.append((ring(i, k), ring(i, k + 1), ring(i + 1, k + 1)))
                tris.append((ring(i, k), ring(i + 1, k + 1), ring(i + 1, k)))
        for k in range(n):
            tris.append((south, ring(len(inner) - 1, k), ring(len(inner) - 1, k + 1)))
        out = []
        for t in tris:  # wind counter-clockwise seen from outside
            a, b, cc = (self.positions[i] for i in t)
            mid = scale(add(add(a, b), cc), 1.0 / 3.0)
            if dot(cross(sub(b, a), sub(cc, a)), sub(mid, c)) < 0.0:
                t = (t[0], t[2], t[1])
            out.append(t)
        self.triangles = out

    def check(self):
        """Largest image error (px) over the front-facing triangles in each camera's frame."""
        worst = {}
        band_dev = {}
        for i in range(len(self.rings) - 1):
            band_dev[i] = band_deviation(self.rings[i], self.rings[i + 1], self.segments) * self.radius
        n = self.segments
        for cam in self.cameras:
            e = 0.0
            for idx, t in enumerate(self.triangles):
                band = 0 if idx < n else (len(self.rings) - 2 if idx >= len(self.triangles) - n else 1 + (idx - n) // (2 * n))
                pts = [self.positions[k] for k in t]
                mid = scale(add(add(pts[0], pts[1]), pts[2]), 1.0 / 3.0)
                if dot(sub(mid, self.centre), sub(cam.eye, mid)) <= 0.0:
                    continue  # faces away: hidden behind the ground's own horizon
                samples = pts + [mid]
                if not any(cam.in_frame(p, 0.05) for p in samples):
                    continue
                px_per_unit = max(cam.px_per_unit(p) for p in samples if cam.to_camera(p)[2] > 1e-6)
                e = max(e, band_dev[band] * px_per_unit)
            worst[cam.name] = e
        return worst


# --- RTOW fuzz -> glTF roughness ---------------------------------------------------------------


def rtow_fuzz_fraction(fuzz, t):
    """Fraction of RTOW's fuzzed reflections (normal incidence: mirror direction (0,0,1) plus
    fuzz * a uniform point of the unit ball) within angle t of the mirror direction: the part of
    the ball of radius fuzz around (0,0,1) inside the cone of half-angle t. Each z-slice is a disk
    of radius^2 fuzz^2 - (z-1)^2 cut by the cone's disk of radius^2 (z tan t)^2: both quadratic in
    z, so Simpson's rule is exact between the (at most two) crossings."""
    tt = math.tan(t) ** 2
    z0, z1 = 1.0 - fuzz, 1.0 + fuzz
    cuts = [z0, z1]
    disc = 1.0 - (1.0 + tt) * (1.0 - fuzz * fuzz)
    if disc > 0.0:
        for sign in (-1.0, 1.0):
            z = (1.0 + sign * math.sqrt(disc)) / (1.0 + tt)
            if z0 < z < z1:
                cuts.append(z)
    cuts.sort()
    g = lambda z: min(fuzz * fuzz - (z - 1.0) ** 2, z * z * tt)
    total = 0.0
    for a, b in zip(cuts, cuts[1:]):
        total += (b - a) / 6.0 * (g(a) + 4.0 * g(0.5 * (a + b)) + g(b))
    return total / (4.0 / 3.0 * fuzz ** 3)


def rtow_fuzz_median_angle(fuzz):
    lo, hi = 0.0, math.pi / 2.0
    for _ in range(80):
        mid = 0.5 * (lo + hi)
        if rtow_fuzz_fraction(fuzz, mid) < 0.5:
            lo = mid
        else:
            hi = mid
    return 0.5 * (lo + hi)


def roughness_from_fuzz(fuzz):
    """glTF roughness whose GGX lobe has the same median angle around the mirror direction as
    RTOW's fuzz, at normal incidence. GGX with alpha = roughness^2 puts half of its
    (D cos)-distributed microfacet normals within atan(alpha) of the normal, so half of the
    reflections lie within 2 atan(alpha) of the mirror direction: alpha = tan(median / 2)."""
    if fuzz <= 0.0:
        return 0.0
    alpha = math.tan(rtow_fuzz_median_angle(min(fuzz, 1.0)) / 2.0)
    return clean(math.sqrt(alpha), 6)


# --- Materials ---------------------------------------------------------------------------------


def diffuse(rgb):
    return ("diffuse", tuple(rgb))


def metal(rgb, fuzz):
    return ("metal", tuple(rgb), fuzz)


def glass(ior=1.5, thickness=2.0, attenuation=None):
    return ("glass", ior, thickness, attenuation)


def material_json(name, key):
    kind = key[0]
    if kind == "diffuse":
        return {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(key[1]) + [1.0],
                                                       "metallicFactor": 0.0, "roughnessFactor": 1.0}}
    if kind == "metal":
        m = {"name": name, "pbrMetallicRoughness": {"baseColorFactor": list(key[1]) + [1.0],
                                                    "metallicFactor": 1.0,
                                                    "roughnessFactor": roughness_from_fuzz(key[2])}}
        m["extras"] = {"rtowFuzz": key[2]}
        return m
    _, ior, thickness, attenuation = key
    volume = {"thicknessFactor": thickness}
    if attenuation:
        volume["attenuationDistance"] = attenuation[1]
        volume["attenuationColor"] = list(attenuation[0])
    return {
        "name": name,
        "pbrMetallicRoughness": {"baseColorFactor": [1.0, 1.0, 1.0, 1.0], "metallicFactor": 0.0, "roughnessFactor": 0.0},
        "extensions": {
            "KHR_materials_transmission": {"transmissionFactor": 1.0},
            "KHR_materials_ior": {"ior": ior},
            "KHR_materials_volume": volume,
        },
    }


# --- glTF writer -------------------------------------------------------------------------------


class SceneWriter:
    def __init__(self, stem, title, camera, sphere_frequency):
        self.stem, self.title, self.camera = stem, title, camera
        self.buf = BufferBuilder()
        self.meshes, self.nodes, self.materials = [], [], []
        self.material_index, self.mesh_index = {}, {}
        self.extensions = set()
        positions, triangles, self.sphere_deviation = icosphere(sphere_frequency)
        self.sphere_frequency = sphere_frequency
        self.sphere_triangles = len(triangles)
        self.unit_position = self._vec3(positions, True)
        self.unit_normal = self._vec3(positions, False)
        self.unit_indices = self._indices(triangles)
        self.inward = None
        self.unique_triangles = self.sphere_triangles
        self.extras = {}

    def _vec3(self, values, bounds):
        return self.buf.vec3(values, bounds)

    def _indices(self, triangles):
        return self.buf.indices(i for t in triangles for i in t)

    def material(self, name, key):
        if key not in self.material_index:
            mat = material_json(name, key)
            self.extensions.update(mat.get("extensions", {}).keys())
            self.materials.append(mat)
            self.material_index[key] = len(self.materials) - 1
        return self.material_index[key]

    def _mesh(self, name, attributes, indices, material):
        key = (attributes["POSITION"], attributes["NORMAL"], indices, material)
        if key not in self.mesh_index:
            self.meshes.append({"name": name, "primitives": [{"attributes": attributes, "indices": indices,
                                                              "material": material, "mode": 4}]})
            self.mesh_index[key] = len(self.meshes) - 1
        return self.mesh_index[key]

    def sphere(self, node_name, centre, radius, material_name, key, inward=False):
        """A node placing the unit sphere (its normals and winding turned inward if asked)."""
        mat = self.material(material_name, key)
        if inward:
            if self.inward is None:
                positions, triangles, _ = icosphere(self.sphere_frequency)
                self.inward = (self._vec3([scale(p, -1.0) for p in positions], False),
                               self._indices([(t[0], t[2], t[1]) for t in triangles]))
            attributes = {"POSITION": self.unit_position, "NORMAL": self.inward[0]}
            indices = self.inward[1]
            mesh_name = "Sphere, inward (%s)" % self.materials[mat]["name"]
        else:
            attributes = {"POSITION": self.unit_position, "NORMAL": self.unit_normal}
            indices = self.unit_indices
            mesh_name = "Sphere (%s)" % self.materials[mat]["name"]
        mesh = self._mesh(mesh_name, attributes, indices, mat)
        self.nodes.append({"name": node_name, "mesh": mesh, "translation": [c + 0.0 for c in centre],
                           "scale": [radius + 0.0] * 3})

    def ground(self, ground, material_name, key):
        mat = self.material(material_name, key)
        position = self._vec3(ground.positions, True)
        normal = self._vec3(ground.normals, False)
        indices = self._indices(ground.triangles)
        self.unique_triangles += len(ground.triangles)
        mesh = self._mesh("Ground (%s)" % material_name, {"POSITION": position, "NORMAL": normal}, indices, mat)
        self.nodes.append({"name": "Ground", "mesh": mesh})

    def build(self, description):
        cam = self.camera
        self.nodes.append({"name": cam.name, "camera": 0, "translation": [clean(c) for c in cam.eye],
                           "rotation": cam.quaternion()})
        bin_name = self.stem + ".bin"
        gltf = {
            "asset": {
                "version": "2.0",
                "generator": GENERATOR,
                "copyright": "Scene after Ray Tracing in One Weekend (Peter Shirley, Trevor David Black, "
                             "Steve Hollasch); glTF conversion by the tessera project",
                "extras": dict({"title": self.title, "description": description,
                                "background": "RTOW sky: lerp((1,1,1), (0.5,0.7,1.0), 0.5*(d.y+1)); "
                                              "scenes/paper/sky-gradient.hdr",
                                "units": "RTOW scene units", "sphereMesh": "frequency-%d geodesic icosphere, %d "
                                "triangles, largest distance from the sphere %.3g radii" % (
                                    self.sphere_frequency, self.sphere_triangles, self.sphere_deviation)},
                               **self.extras),
            },
            "scene": 0,
            "scenes": [{"name": self.title, "nodes": list(range(len(self.nodes)))}],
            "nodes": self.nodes,
            "cameras": [{"name": cam.name, "type": "perspective",
                         "perspective": {"aspectRatio": clean(cam.aspect), "yfov": clean(math.radians(cam.vfov_deg)),
                                         "znear": 0.001}}],
            "meshes": self.meshes,
            "materials": self.materials,
            "accessors": self.buf.accessors,
            "bufferViews": self.buf.buffer_views,
            "buffers": [self.buf.external_buffer(bin_name)],
        }
        if self.extensions:
            gltf["extensionsUsed"] = sorted(self.extensions)
            gltf = {k: gltf[k] for k in ["asset", "extensionsUsed"] + [k for k in gltf if k not in ("asset", "extensionsUsed")]}
        text = json.dumps(gltf, indent=1, ensure_ascii=True) + "\n"
        return {self.stem + ".gltf": text.encode("utf-8"), bin_name: self.buf.finish()}


# --- Tessellation planning ---------------------------------------------------------------------


def plan_sphere_frequency(camera, spheres):
    """Smallest icosphere frequency whose silhouettes are within MAX_ERROR_PX at 1200x675.
    spheres: (centre, radius). Returns (frequency, largest silhouette px per radius)."""
    worst = 0.0
    for centre, radius in spheres:
        s = silhouette_px_per_unit(camera, centre, radius)
        if s is not None:
            worst = max(worst, s * radius)
    for n in range(1, 65):
        if icosphere(n)[2] * worst <= MAX_ERROR_PX:
            return n, worst
    raise RuntimeError("no icosphere frequency is fine enough")


REPORT = []


def frame_extent(camera, spheres):
    """NDC box (x0, y0, x1, y1) of the spheres' silhouettes, frame = [-1, 1]^2."""
    box = [math.inf, math.inf, -math.inf, -math.inf]
    for centre, radius in spheres:
        to_c = sub(centre, camera.eye)
        d = length(to_c)
        axis = scale(to_c, 1.0 / d)
        cc = add(camera.eye, scale(to_c, 1.0 - (radius * radius) / (d * d)))
        cr = radius * math.sqrt(d * d - radius * radius) / d
        helper = (1.0, 0.0, 0.0) if abs(axis[0]) < 0.9 else (0.0, 1.0, 0.0)
        u = normalize(cross(axis, helper))
        v = cross(axis, u)
        for k in range(64):
            phi = 2.0 * math.pi * k / 64
            q = camera.ndc(add(cc, add(scale(u, cr * math.cos(phi)), scale(v, cr * math.sin(phi)))))
            if q:
                box = [min(box[0], q[0]), min(box[1], q[1]), max(box[2], q[0]), max(box[3], q[1])]
    return box


def make_scene(stem, title, camera, spheres, ground_spec, description, extras=None, min_frequency=1):
    """spheres: (node name, centre, radius, material name, material key, inward)."""
    n, worst_px = plan_sphere_frequency(camera, [(s[1], s[2]) for s in spheres])
    n = max(n, min_frequency)
    w = SceneWriter(stem, title, camera, n)
    ground = GroundSphere(ground_spec[0], ground_spec[1], [camera])
    w.ground(ground, ground_spec[2], ground_spec[3])
    for node_name, centre, radius, mat_name, key, inward in spheres:
        w.sphere(node_name, centre, radius, mat_name, key, inward)
    ground_err = ground.check()[camera.name]
    w.extras = dict(extras or {})
    w.extras["groundMesh"] = ("UV sphere, radius %g, %d segments x %d bands, %d triangles; largest image error "
                              "at 1200x675 %.3f px" % (ground.radius, ground.segments, len(ground.rings) - 1,
                                                       len(ground.triangles), ground_err))
    REPORT.append({
        "frame": frame_extent(camera, [(s[1], s[2]) for s in spheres]),
        "scene": stem, "spheres": len(spheres), "largest_silhouette_radius_px": worst_px, "frequency": n,
        "sphere_triangles": w.sphere_triangles, "sphere_deviation": w.sphere_deviation,
        "silhouette_error_px": w.sphere_deviation * worst_px, "ground_segments": ground.segments,
        "ground_bands": len(ground.rings) - 1, "ground_triangles": len(ground.triangles),
        "ground_error_px": ground_err, "materials": len(w.materials), "meshes": len(w.meshes),
    })
    return w.build(description)


# --- The scenes --------------------------------------------------------------------------------

# RTOW (4th ed.) chapters 10-11: the small world. Ground sphere radius 100 at (0, -100.5, -1),
# camera at the origin looking down -Z, vertical fov 90 degrees, 16:9.
SMALL_GROUND = ((0.0, -100.5, -1.0), 100.0, "Ground yellow", diffuse((0.8, 0.8, 0.0)))
BOOK_CAMERA = Camera("RTOW camera", (0.0, 0.0, 0.0), (0.0, 0.0, -1.0), (0.0, 1.0, 0.0), 90.0)


def three_balls():
    spheres = [
        ("Left: smooth metal", (-1.0, 0.0, -1.0), 0.5, "Metal silver fuzz 0", metal((0.8, 0.8, 0.8), 0.0), False),
        ("Centre: diffuse", (0.0, 0.0, -1.2), 0.5, "Diffuse blue", diffuse((0.1, 0.2, 0.5)), False),
        ("Right: rough metal", (1.0, 0.0, -1.0), 0.5, "Metal gold fuzz 1", metal((0.8, 0.6, 0.2), 1.0), False),
    ]
    return make_scene("three-balls", "Three balls: smooth metal, diffuse, rough metal", BOOK_CAMERA, spheres,
                      SMALL_GROUND, "RTOW 4th ed. section 10.6 (fuzzed metal) with the left sphere's fuzz 0: "
                      "smooth metal, diffuse, rough metal (fuzz 1). Also the bounce figure (--max-bounces 1 and 5).")


REFRACTION_CAMERA = Camera("Refraction camera", (0.0, 0.9, 3.4), (0.0, 0.0, -1.1), (0.0, 1.0, 0.0), 40.0)
ABSORBING = ((0.3, 0.8, 0.6), 1.0)  # attenuationColor, attenuationDistance (world units)


def refraction():
    # The middle three are RTOW 4th ed. section 11.5 exactly (hollow glass, blue diffuse, fuzzy
    # gold), with the hollow sphere modelled as in the 3rd edition: an outer sphere and a
    # negative-radius inner one, here an inner sphere whose normals and winding face inward.
    clear = glass(1.5, 2.0)
    spheres = [
        ("Solid glass", (-2.1, 0.0, -1.2), 0.5, "Glass ior 1.5", clear, False),
        ("Hollow glass, outside", (-1.0, 0.0, -1.0), 0.5, "Glass ior 1.5, hollow shell (outside)",
         glass(1.5, 0.2), False),
        ("Hollow glass, inside (inward normals)", (-1.0, 0.0, -1.0), 0.4, "Glass ior 1.5, hollow shell (inside)",
         glass(1.5, 0.25), True),
        ("Diffuse", (0.0, 0.0, -1.2), 0.5, "Diffuse blue", diffuse((0.1, 0.2, 0.5)), False),
        ("Rough metal", (1.0, 0.0, -1.0), 0.5, "Metal gold fuzz 1", metal((0.8, 0.6, 0.2), 1.0), False),
        ("Absorbing glass", (2.1, 0.0, -1.2), 0.5, "Glass ior 1.5, absorbing (green)",
         glass(1.5, 2.0, ABSORBING), False),
    ]
    return make_scene("refraction", "Refraction: solid, hollow and absorbing glass", REFRACTION_CAMERA, spheres,
                      SMALL_GROUND, "RTOW 4th ed. section 11.5 (hollow glass, diffuse, fuzzy metal) flanked by a "
                      "solid glass sphere and an absorbing (KHR_materials_volume) glass sphere.")


GRID_CAMERA = Camera("RTOW cover camera", (13.0, 2.0, 3.0), (0.0, 0.0, 0.0), (0.0, 1.0, 0.0), 20.0)
BIG_GROUND_CENTRE, BIG_GROUND_RADIUS = (0.0, -1000.0, 0.0), 1000.0


def read_seed(path):
    spheres = []
    with open(path, "r", encoding="ascii") as f:
        for line_no, line in enumerate(f, 1):
            words = line.split()
            if not words or words[0].startswith("#"):
                continue
            if words[0] != "sphere" or not words[4].startswith("r="):
                raise ValueError("%s:%d: not a sphere line" % (path, line_no))
            centre = tuple(float(w) for w in words[1:4])
            radius = float(words[4][2:])
            kind = words[5]
            if kind == "lambertian":
                key = diffuse(tuple(float(w) for w in words[6:9]))
            elif kind == "metal":
                if not words[9].startswith("fuzz="):
                    raise ValueError("%s:%d: metal without fuzz=" % (path, line_no))
                key = metal(tuple(float(w) for w in words[6:9]), float(words[9][5:]))
            elif kind == "dielectric":
                if words[6] != "ir=1.5":
                    raise ValueError("%s:%d: only ir=1.5 is expected" % (path, line_no))
                key = glass(1.5, 2.0)
            else:
                raise ValueError("%s:%d: unknown material %s" % (path, line_no, kind))
            spheres.append((centre, radius, kind, key))
    return spheres


def grid_of_spheres(seed_path):
    seed = read_seed(seed_path)
    if len(seed) != 487:
        raise ValueError("%s: expected 487 spheres, found %d" % (seed_path, len(seed)))
    ground = seed[0]
    if ground[0] != BIG_GROUND_CENTRE or ground[1] != BIG_GROUND_RADIUS or ground[2] != "lambertian":
        raise ValueError("%s: the first sphere is not RTOW's ground" % seed_path)
    spheres = []
    for i, (centre, radius, kind, key) in enumerate(seed[1:], 2):
        if kind == "dielectric":
            name = "Glass ior 1.5"
        elif kind == "metal":
            name = "Metal %03d" % i
        else:
            name = "Diffuse %03d" % i
        spheres.append(("Sphere %03d (%s)" % (i, kind), centre, radius, name, key, False))
    aperture = 2.0 * 10.0 * math.tan(math.radians(0.3))
    return make_scene("grid-of-spheres", "Grid of spheres (RTOW cover)", GRID_CAMERA, spheres,
                      (BIG_GROUND_CENTRE, BIG_GROUND_RADIUS, "Ground grey", ground[3]),
                      "RTOW's final scene, sphere for sphere from seed/grid_of_spheres.txt (node 'Sphere NNN' is "
                      "line NNN of its sphere list, the ground being 1).",
                      {"thinLens": {"aperture": clean(aperture, 9), "focusDistance": 10.0,
                                    "note": "glTF has no lens: render with --aperture %.7f --focus-distance 10"
                                            % aperture}})


TIMING_DIFFUSE = [(0.7, 0.3, 0.3), (0.3, 0.6, 0.3), (0.2, 0.3, 0.7), (0.7, 0.6, 0.2)]
TIMING_METAL = [((0.8, 0.8, 0.8), 0.0), ((0.8, 0.6, 0.2), 0.1), ((0.6, 0.7, 0.8), 0.3)]


def timing_scene():
    spheres = []
    for i in range(11):
        for j in range(11):
            x, z = -10.0 + 2.0 * i, -10.0 + 2.0 * j
            if z == 0.0 and x in (-4.0, 0.0, 4.0):
                continue  # where the three big spheres stand
            kind = (i + j) % 3
            if kind == 0:
                rgb = TIMING_DIFFUSE[(i + 2 * j) % len(TIMING_DIFFUSE)]
                name, key = "Diffuse %d" % ((i + 2 * j) % len(TIMING_DIFFUSE)), diffuse(rgb)
            elif kind == 1:
                rgb, fuzz = TIMING_METAL[(2 * i + j) % len(TIMING_METAL)]
                name, key = "Metal %d" % ((2 * i + j) % len(TIMING_METAL)), metal(rgb, fuzz)
            else:
                name, key = "Glass ior 1.5", glass(1.5, 2.0)
            spheres.append(("Sphere %d,%d" % (i, j), (x, 0.2, z), 0.2, name, key, False))
    spheres.append(("Big glass", (0.0, 1.0, 0.0), 1.0, "Glass ior 1.5", glass(1.5, 2.0), False))
    spheres.append(("Big diffuse", (-4.0, 1.0, 0.0), 1.0, "Diffuse brown", diffuse((0.4, 0.2, 0.1)), False))
    spheres.append(("Big metal", (4.0, 1.0, 0.0), 1.0, "Metal fuzz 0", metal((0.7, 0.6, 0.5), 0.0), False))
    return make_scene("timing-scene", "Timing scene (fixed grid)", GRID_CAMERA, spheres,
                      (BIG_GROUND_CENTRE, BIG_GROUND_RADIUS, "Ground grey", diffuse((0.5, 0.5, 0.5))),
                      "RTOW's cover without its randomness: 118 small spheres on an 11 x 11 grid (2 units apart, "
                      "the 3 under the big spheres left out), diffuse/metal/glass in turn, the three big spheres, "
                      "the ground, the cover's camera.")


ADVERSARIAL_CAMERA = Camera("Adversarial camera", (0.0, 1.5, 8.0), (0.0, 0.6, 0.0), (0.0, 1.0, 0.0), 30.0)
CLUSTER_RADIUS, CLUSTER_SPHERE = 0.5, 0.04
CLUSTER_NDC = (-0.70, -0.52)  # where the cluster's centre lands in the frame (lower left)
# Deliberately finer than its 15 px spheres need (frequency 5): the cluster is meant to be expensive.
ADVERSARIAL_FREQUENCY = 16


def adversarial():
    cam = ADVERSARIAL_CAMERA
    # Face-centred cubic packing (2 % gaps) of small spheres inside a ball.
    step = 2.0 * CLUSTER_SPHERE * 1.02 / math.sqrt(2.0)
    limit = int(CLUSTER_RADIUS / step) + 2
    offsets = []
    for i in range(-limit, limit + 1):
        for j in range(-limit, limit + 1):
            for k in range(-limit, limit + 1):
                if (i + j + k) % 2:
                    continue
                p = (i * step, j * step, k * step)
                if length(p) <= CLUSTER_RADIUS - CLUSTER_SPHERE:
                    offsets.append(((i, j, k), p))
    lowest = min(p[1] for _, p in offsets) - CLUSTER_SPHERE
    # Put the cluster's centre on the camera ray through CLUSTER_NDC at the height that sets its
    # lowest sphere on the ground sphere (found by a few fixed-point steps).
    ray = cam.ray_through(*CLUSTER_NDC)
    height = -lowest
    for _ in range(8):
        t = (height - cam.eye[1]) / ray[1]
        centre = add(cam.eye, scale(ray, t))
        r2 = centre[0] ** 2 + centre[2] ** 2
        ground_y = BIG_GROUND_CENTRE[1] + math.sqrt(BIG_GROUND_RADIUS ** 2 - r2)
        height = ground_y - lowest
    centre = (clean(centre[0], 6), clean(height, 6), clean(centre[2], 6))
    kinds = [("Glass ior 1.5", glass(1.5, 2.0)), ("Metal mirror", metal((0.9, 0.9, 0.9), 0.0)),
             ("Metal gold fuzz 0.1", metal((0.8, 0.6, 0.2), 0.1))]
    spheres = []
    for (i, j, k), p in offsets:
        name, key = kinds[(i - j + 2 * k) % 3]
        spheres.append(("Cluster %d,%d,%d" % (i, j, k), tuple(clean(c, 9) for c in add(centre, p)),
                        CLUSTER_SPHERE, name, key, False))
    return make_scene("adversarial", "Adversarial: one expensive cluster in a corner", cam, spheres,
                      (BIG_GROUND_CENTRE, BIG_GROUND_RADIUS, "Ground grey", diffuse((0.5, 0.5, 0.5))),
                      "%d small glass and metal spheres packed into a ball of radius %g in the lower left of the "
                      "frame; the rest is the ground and the sky." % (len(spheres), CLUSTER_RADIUS),
                      {"clusterCentre": list(centre)}, min_frequency=ADVERSARIAL_FREQUENCY)


# --- RTOW's sky as an equirectangular Radiance HDR ---------------------------------------------


def rgbe(rgb):
    """Radiance RGBE, rounded to nearest (tessera reads it through OpenImageIO: m * 2^(e-136))."""
    top = max(rgb)
    if top < 1e-32:
        return bytes((0, 0, 0, 0))
    _, e = math.frexp(top)
    while True:
        factor = math.ldexp(1.0, 8 - e)
        m = [int(math.floor(c * factor + 0.5)) for c in rgb]
        if max(m) <= 255:
            return bytes((m[0], m[1], m[2], e + 128))
        e += 1


def rle_channel(data):
    """New-style Radiance run-length encoding of one channel of one scanline."""
    out, i, n = bytearray(), 0, len(data)
    while i < n:
        run = 1
        while i + run < n and run < 127 and data[i + run] == data[i]:
            run += 1
        if run >= 3:
            out += bytes((128 + run, data[i]))
            i += run
            continue
        start = i  # literal bytes up to the next run of 3 or more (at most 128)
        while i < n and i - start < 128:
            if i + 2 < n and data[i] == data[i + 1] == data[i + 2]:
                break
            i += 1
        out += bytes((i - start,)) + bytes(data[start:i])
    return out


def sky_direction_y(row):
    """d.y at the centre of image row `row` in tessera's mapping, v = 0.5 - asin(d.y)/pi."""
    v = (row + 0.5) / HDR_HEIGHT
    return math.sin((0.5 - v) * math.pi)


def sky_rgb(dy):
    a = 0.5 * (dy + 1.0)
    return tuple((1.0 - a) * w + a * b for w, b in zip(SKY_WHITE, SKY_BLUE))


def sky_hdr():
    header = ("#?RADIANCE\n# RTOW sky: lerp((1,1,1), (0.5,0.7,1.0), a), a = 0.5*(d.y+1); equirectangular, row 0 "
              "looks up (v = 0.5 - asin(d.y)/pi); written by %s\nFORMAT=32-bit_rle_rgbe\n\n-Y %d +X %d\n"
              % (GENERATOR, HDR_HEIGHT, HDR_WIDTH)).encode("ascii")
    out = bytearray(header)
    for row in range(HDR_HEIGHT):
        pixel = rgbe(sky_rgb(sky_direction_y(row)))  # the sky does not depend on u
        out += bytes((2, 2, HDR_WIDTH >> 8, HDR_WIDTH & 255))
        for ch in range(4):
            out += rle_channel(bytes((pixel[ch],)) * HDR_WIDTH)
    return bytes(out)


def sky_error():
    """Largest |decoded texel - RTOW sky| over the rows and largest error of the bilinear
    interpolation between rows (in v, while the sky is linear in d.y), both in radiance."""
    quant = 0.0
    for row in range(HDR_HEIGHT):
        want = sky_rgb(sky_direction_y(row))
        px = rgbe(want)
        got = [m * math.ldexp(1.0, px[3] - 136) for m in px[:3]]
        quant = max(quant, max(abs(g - w) for g, w in zip(got, want)))
    interp = 0.0
    for row in range(HDR_HEIGHT - 1):
        y0, y1 = sky_direction_y(row), sky_direction_y(row + 1)
        v0, v1 = (row + 0.5) / HDR_HEIGHT, (row + 1.5) / HDR_HEIGHT
        for k in range(1, 8):
            v = v0 + (v1 - v0) * k / 8.0
            dy = math.sin((0.5 - v) * math.pi)
            lerp = sky_rgb(y0 + (y1 - y0) * k / 8.0)
            interp = max(interp, max(abs(a - b) for a, b in zip(lerp, sky_rgb(dy))))
    return quant, interp


# --- Main --------------------------------------------------------------------------------------


def build_all(here):
    outputs = {}
    outputs.update(three_balls())
    outputs.update(refraction())
    outputs.update(grid_of_spheres(os.path.join(here, SEED_FILE)))
    outputs.update(timing_scene())
    outputs.update(adversarial())
    outputs[HDR_NAME] = sky_hdr()
    return outputs


def print_report():
    print("Tessellation at %dx%d, largest error allowed %.2f px" % (SHIPPED_WIDTH, SHIPPED_HEIGHT, MAX_ERROR_PX))
    print("%-16s %7s %12s %4s %6s %10s %9s %14s %8s %9s %5s %6s" % (
        "scene", "spheres", "silh. r (px)", "freq", "tris", "dev (r)", "err (px)", "ground NxB", "tris",
        "err (px)", "mats", "meshes"))
    for r in REPORT:
        print("%-16s %7d %12.1f %4d %6d %10.3g %9.3f %14s %8d %9.3f %5d %6d" % (
            r["scene"], r["spheres"], r["largest_silhouette_radius_px"], r["frequency"], r["sphere_triangles"],
            r["sphere_deviation"], r["silhouette_error_px"], "%dx%d" % (r["ground_segments"], r["ground_bands"]),
            r["ground_triangles"], r["ground_error_px"], r["materials"], r["meshes"]))
    print("\nSpheres' extent in the frame of the scenes framed here (NDC, the frame is -1..1; y up)")
    for r in REPORT:
        if r["scene"] in ("grid-of-spheres", "timing-scene"):
            continue  # the book's camera; spheres run out of the frame on every side
        print("  %-16s x %+.3f .. %+.3f   y %+.3f .. %+.3f" % (r["scene"], r["frame"][0], r["frame"][2], r["frame"][1], r["frame"][3]))
    print("\nRTOW fuzz -> glTF roughness (median-angle match at normal incidence)")
    for fz in (0.0, 0.05, 0.1, 0.2, 0.3, 0.4, 0.5, 0.75, 1.0):
        med = math.degrees(rtow_fuzz_median_angle(fz)) if fz > 0 else 0.0
        print("  fuzz %.2f  median angle %6.2f deg  roughness %.4f" % (fz, med, roughness_from_fuzz(fz)))
    quant, interp = sky_error()
    print("\nsky-gradient.hdr %dx%d: largest texel error %.5f, largest interpolation error %.2g" % (
        HDR_WIDTH, HDR_HEIGHT, quant, interp))
    print("grid thin lens: --aperture %.7f --focus-distance 10" % (2.0 * 10.0 * math.tan(math.radians(0.3))))


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    parser = generator_arguments(__doc__, __file__)
    parser.add_argument("--report", action="store_true", help="also print how the tessellation was worked out")
    args = parser.parse_args()
    outputs = build_all(here)
    if args.report:
        print_report()
    return write_or_check(outputs, args.out_dir, args.check, "make_paper_scenes")


if __name__ == "__main__":
    sys.exit(main())
