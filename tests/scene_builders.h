// Analytic test scenes built directly as SceneDescription, with no file in between.
#pragma once

#include "renderer/scene/scene.h"

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

}  // namespace tessera::test
