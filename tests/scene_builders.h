// Analytic test scenes built directly as SceneDescription, with no file in between.
#pragma once

#include "renderer/description/scene.h"

namespace tessera::test {

// A quad centred at `center` spanning +-u and +-v; its front face looks along cross(u, v).
TriangleMesh make_quad(glm::vec3 center, glm::vec3 u, glm::vec3 v, int material);

// A geodesic sphere (subdivided icosahedron); `inward` turns its front faces and normals
// towards the centre. Flat (no NORMAL) unless `smooth`: with interpolated normals some
// cosine-weighted directions fall below the true faces, and the closed forms no longer hold.
TriangleMesh make_sphere(glm::vec3 center, float radius, int subdivisions, int material, bool inward = false,
                         bool smooth = false);

int add_material(SceneDescription& scene, const Material& material);
// Adds the mesh as its own glTF-like mesh placed once (or at each transform given).
int add_mesh(SceneDescription& scene, TriangleMesh mesh, const std::vector<glm::mat4>& placements = {glm::mat4(1.0f)});

Material diffuse(glm::vec3 albedo);  // Lambertian: a glTF dielectric with specular 0
Material emitter(glm::vec3 radiance);  // black diffuse that emits `radiance`

// A perspective camera at `eye` looking at `target` with +Y up.
Camera look_at(glm::vec3 eye, glm::vec3 target, float yfov_degrees);

// A diffuse floor and sphere (albedo 0.7) under a small square emitter of radiance 5: soft
// shadows and indirect light, noisy everywhere but where rays see only the background.
SceneDescription lit_floor_and_sphere();

// A diffuse floor of `albedo` under a square emitter of radiance `le` (half side a, height
// h, facing down): the radiance of the point below the emitter's centre, albedo/pi * Le * pi
// * 4 F(a/h, a/h), with F the corner form factor of a parallel rectangle (Howell's
// catalogue, C-11): F(X, Y) = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2)
// atan(X/sqrt(1+Y^2))].
double floor_under_square_emitter(double a, double h, double le, double albedo);

}  // namespace tessera::test
