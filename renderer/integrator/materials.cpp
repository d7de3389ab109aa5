#include "renderer/integrator/materials.h"

namespace tessera {

MaterialTable::MaterialTable(const SceneDescription& scene) : materials_(scene.materials) {
  srgb_.resize(scene.images.size());
  linear_.resize(scene.images.size());
  auto need = [&](const TextureRef& ref, std::vector<TextureImage>& cache, ColorEncoding enc) {
    if (ref.present() && cache[ref.image].empty())
      cache[ref.image] = make_texture_image(scene.images[ref.image], enc);
  };
  for (const Material& m : materials_) {
    need(m.base_color_texture, srgb_, ColorEncoding::SRGB);
    need(m.emissive_texture, srgb_, ColorEncoding::SRGB);
    need(m.metallic_roughness_texture, linear_, ColorEncoding::Linear);
    need(m.normal_texture, linear_, ColorEncoding::Linear);
  }
}

const Material& MaterialTable::material(int index) const {
  return index >= 0 ? materials_[index] : default_material_;
}

vec4 MaterialTable::lookup(const TextureRef& ref, const std::vector<TextureImage>& images,
                           const SurfaceHit& hit) const {
  if (!ref.present()) return vec4(1.0f);
  return sample_texture(images[ref.image], ref, hit.uv[ref.texcoord]);
}

ShadingPoint MaterialTable::evaluate(const SurfaceHit& hit) const {
  const Material& m = material(hit.material);
  ShadingPoint sp;
  const vec4 base = m.base_color_factor * lookup(m.base_color_texture, srgb_, hit) * hit.color;
  sp.base_color = glm::clamp(vec3(base), 0.0f, 1.0f);
  sp.alpha = base.a;
  sp.emission = m.emissive_factor * m.emissive_strength * vec3(lookup(m.emissive_texture, srgb_, hit));
  const vec4 mr = lookup(m.metallic_roughness_texture, linear_, hit);
  sp.metallic = glm::clamp(m.metallic_factor * mr.b, 0.0f, 1.0f);
  sp.roughness = glm::clamp(m.roughness_factor * mr.g, 0.0f, 1.0f);
  sp.double_sided = m.double_sided;
  return sp;
}

}  // namespace tessera
