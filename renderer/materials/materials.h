// Materials with their textures decoded once, evaluated at a surface hit into the plain
// values the BSDF and the integrator need. No virtual calls: one struct for every material.
#pragma once

#include <vector>

#include "renderer/description/scene.h"
#include "renderer/geometry/scene_geometry.h"
#include "renderer/materials/texture.h"

namespace tessera {

// A material evaluated at one point: every parameter of the glTF BSDF, textures applied.
struct ShadingPoint {
  vec3 base_color{1.0f};  // linear
  float alpha = 1.0f;
  vec3 emission{0.0f};  // radiance leaving the surface
  float metallic = 0.0f, roughness = 1.0f;
  bool double_sided = false;
  vec3 normal{0.0f};  // shading normal after the normal map (world); zero = no normal map
  float transmission = 0.0f, ior = 1.5f;
  bool thin_walled = true;
  vec3 absorption{0.0f};  // Beer-Lambert coefficient inside the volume, per scene unit
  float specular = 1.0f;
  vec3 specular_color{1.0f};
  float clearcoat = 0.0f, clearcoat_roughness = 0.0f;
  vec3 clearcoat_normal{0.0f};  // the coat's normal map applied (world); zero = the base's normal
  float diffuse_transmission = 0.0f;  // KHR_materials_diffuse_transmission: share of the diffuse base
  vec3 diffuse_transmission_color{1.0f};
  float anisotropy = 0.0f;  // KHR_materials_anisotropy strength
  vec3 anisotropy_direction{0.0f};  // world, in the tangent plane; zero = isotropic
  float iridescence = 0.0f;  // KHR_materials_iridescence: mix toward the film's Fresnel
  float iridescence_ior = 1.3f, iridescence_thickness = 0.0f;  // the film; thickness in nm
  float dispersion = 0.0f;  // KHR_materials_dispersion: 20 / Abbe number; 0 = none
  vec3 sheen_color{0.0f};
  float sheen_roughness = 0.0f;
  bool unlit = false;
};

class MaterialTable {
 public:
  explicit MaterialTable(const SceneDescription& scene);
  // Not copied: texture_uses_ points into srgb_ and linear_ (a move keeps their buffers).
  MaterialTable(const MaterialTable&) = delete;
  MaterialTable& operator=(const MaterialTable&) = delete;
  MaterialTable(MaterialTable&&) = default;
  MaterialTable& operator=(MaterialTable&&) = default;

  ShadingPoint evaluate(const SurfaceHit& hit) const;
  // Starts loading the texels evaluate(hit) will read, every texture's at once: their cache
  // misses then overlap, where each lookup would otherwise wait for the one before it.
  void prefetch_textures(const SurfaceHit& hit) const;
  bool prefetches_textures() const { return prefetches_; }  // has a texture to prefetch
  // evaluate(hit).emission alone (one texture, not every one): what light sampling needs.
  vec3 emission(const SurfaceHit& hit) const { return emission(material(hit.material), hit); }
  void prefetch_emission(const SurfaceHit& hit) const;  // the texels emission(hit) will read
  const Material& material(int index) const;

  // Opacity for the alpha test: 0 or 1 for MASK (alphaCutoff), the alpha itself for BLEND,
  // 1 for OPAQUE. uv holds TEXCOORD_0 and _1, color COLOR_0 (white when absent).
  float opacity(int material, const vec2 uv[2], const vec4& color) const;
  // opacity() as the geometry's alpha filters call it.
  SurfaceOpacity surface_opacity() const {
    return {[](const void* self, int material, const vec2 uv[2], const vec4& color) {
              return static_cast<const MaterialTable*>(self)->opacity(material, uv, color);
            },
            this};
  }

 private:
  // `shared`, where not null: where every texture of the material is read at this hit
  // (see shared_).
  vec3 emission(const Material& m, const SurfaceHit& hit, const TexelQuad* shared = nullptr) const;
  vec4 lookup(const TextureRef& ref, const std::vector<TextureImage>& images, const SurfaceHit& hit,
              const TexelQuad* shared) const;
  vec3 perturbed_normal(const TextureRef& map, float scale, const SurfaceHit& hit, const TexelQuad* shared) const;
  vec3 anisotropy_direction(const Material& m, const SurfaceHit& hit, float& strength,
                            const TexelQuad* shared = nullptr) const;

  ShadingPoint evaluate(const Material& m, const SurfaceHit& hit, const TexelQuad* shared = nullptr) const;
  void set_base_color(const Material& m, const SurfaceHit& hit, ShadingPoint& sp,
                      const TexelQuad* shared = nullptr) const;  // and alpha

  std::vector<Material> materials_;
  Material default_material_;  // the glTF default: white, metallic 1, roughness 1
  // A material without textures is the same at every hit but for its vertex colour and its
  // anisotropy's tangent: evaluated once, at a white vertex without a tangent (by index;
  // `constant_` false where the material has a texture).
  std::vector<ShadingPoint> constant_point_;
  std::vector<char> constant_;
  // Each material's textures larger than kPrefetchAbove bytes, in the encoding each is read
  // in (by material index): a smaller one stays in the caches, and locating its texels twice
  // only costs (BoxTextured's 256x256 texture prefetched: 4% fewer samples/s).
  static constexpr std::size_t kPrefetchAbove = std::size_t{1} << 20;
  struct TextureUse {
    const TextureImage* image;
    const TextureRef* ref;
  };
  std::vector<std::vector<TextureUse>> texture_uses_;
  // By material: one of its textures where all of them sample alike (same_sampling: the usual
  // material, one UV set and sampler, maps of one size), so a hit finds its texels' places
  // once, not once per map (DamagedHelmet: four maps); image null where they differ or none.
  std::vector<TextureUse> shared_;
  bool prefetches_ = false;
  std::vector<TextureImage> srgb_, linear_;  // by image index; empty where unused
};

}  // namespace tessera
