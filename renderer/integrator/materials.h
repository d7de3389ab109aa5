// Materials with their textures decoded once, evaluated at a surface hit into the plain
// values the BSDF and the integrator need. No virtual calls: one struct for every material.
#pragma once

#include <vector>

#include "renderer/scene/scene.h"
#include "renderer/scene_geometry.h"
#include "renderer/texture.h"

namespace tessera {

// A material evaluated at one point.
struct ShadingPoint {
  vec3 base_color{1.0f};  // linear
  float alpha = 1.0f;
  vec3 emission{0.0f};  // radiance leaving the surface
  float metallic = 0.0f, roughness = 1.0f;
  bool double_sided = false;
};

class MaterialTable {
 public:
  explicit MaterialTable(const SceneDescription& scene);

  ShadingPoint evaluate(const SurfaceHit& hit) const;
  const Material& material(int index) const;

 private:
  vec4 lookup(const TextureRef& ref, const std::vector<TextureImage>& images, const SurfaceHit& hit) const;

  std::vector<Material> materials_;
  Material default_material_;  // the glTF default: white, metallic 1, roughness 1
  std::vector<TextureImage> srgb_, linear_;  // by image index; empty where unused
};

}  // namespace tessera
