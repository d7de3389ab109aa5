#include "renderer/materials/materials.h"

#include <array>

#include <tbb/parallel_for.h>

namespace tessera {

namespace {

bool textured(const Material& m) {
  for (const TextureSlot& slot : texture_slots(m))
    if (slot.ref->present()) return true;
  return false;
}

}  // namespace

MaterialTable::MaterialTable(const SceneDescription& scene) : materials_(scene.materials) {
  srgb_.resize(scene.images.size());
  linear_.resize(scene.images.size());
  std::vector<std::uint8_t> need_srgb(scene.images.size()), need_linear(scene.images.size());
  // An image without pixels is one no used material shows (scene_io decodes only those): a
  // material the scene does not use may still name it.
  for (const Material& m : materials_)
    for (const TextureSlot& slot : texture_slots(m))
      if (slot.ref->present() && scene.images[slot.ref->image].pixels)
        (slot.srgb ? need_srgb : need_linear)[slot.ref->image] = 1;
  // Each image in each encoding it is read in, all at once (make_texture_image splits rows too).
  tbb::parallel_for(std::size_t{0}, 2 * scene.images.size(), [&](std::size_t k) {
    const std::size_t i = k / 2;
    if (k % 2 == 0 && need_srgb[i]) srgb_[i] = make_texture_image(scene.images[i], ColorEncoding::SRGB);
    if (k % 2 == 1 && need_linear[i]) linear_[i] = make_texture_image(scene.images[i], ColorEncoding::Linear);
  });
  SurfaceHit plain;  // white, no tangent: what the constant points are evaluated at
  plain.p = vec3(0.0f);
  plain.ng = plain.ns = vec3(0.0f, 0.0f, 1.0f);
  for (const Material& m : materials_) {
    constant_.push_back(!textured(m));
    constant_point_.push_back(constant_.back() ? evaluate(m, plain) : ShadingPoint{});
    texture_uses_.emplace_back();
    shared_.emplace_back();
    bool alike = true;
    for (const TextureSlot& slot : texture_slots(m)) {
      if (!slot.ref->present()) continue;
      const TextureImage& image = (slot.srgb ? srgb_ : linear_)[slot.ref->image];
      if (image.stored_bytes() > kPrefetchAbove) texture_uses_.back().push_back({&image, slot.ref});
      TextureUse& first = shared_.back();
      if (!first.image) first = {&image, slot.ref};
      alike = alike && same_sampling(*first.image, *first.ref, image, *slot.ref);
    }
    if (!alike) shared_.back() = {};
    prefetches_ = prefetches_ || !texture_uses_.back().empty();
  }
}

const Material& MaterialTable::material(int index) const {
  return index >= 0 ? materials_[index] : default_material_;
}

float MaterialTable::opacity(int index, const vec2 uv[2], const vec4& color) const {
  const Material& m = material(index);
  if (m.alpha_mode == AlphaMode::Opaque) return 1.0f;
  float alpha = m.base_color_factor.a * color.a;
  if (m.base_color_texture.present())
    alpha *= sample_texture(srgb_[m.base_color_texture.image], m.base_color_texture, uv[m.base_color_texture.texcoord]).a;
  if (m.alpha_mode == AlphaMode::Mask) return alpha >= m.alpha_cutoff ? 1.0f : 0.0f;
  return glm::clamp(alpha, 0.0f, 1.0f);
}

vec4 MaterialTable::lookup(const TextureRef& ref, const std::vector<TextureImage>& images, const SurfaceHit& hit,
                           const TexelQuad* shared) const {
  if (!ref.present()) return vec4(1.0f);
  const TextureImage& image = images[ref.image];
  return shared ? read_texels(image, ref.filter, *shared) : sample_texture(image, ref, hit.uv[ref.texcoord]);
}

// The tangent-space normal map applied to the interpolated frame (glTF: RGB in [0,1] maps
// to [-1,1], scaled in x and y by normalTexture.scale; +Y up in UV space, so the bitangent
// is cross(normal, tangent) * tangent.w).
namespace {

// The hit's tangent frame (tangent, bitangent) orthogonal to its shading normal; false when
// the mesh gives none (no TANGENT and no UVs).
bool tangent_frame(const SurfaceHit& hit, vec3& tangent, vec3& bitangent) {
  const vec3 t_raw = vec3(hit.tangent);
  const vec3 t = t_raw - hit.ns * glm::dot(hit.ns, t_raw);
  const float len = glm::length(t);
  if (!(len > 1e-8f)) return false;
  tangent = t / len;
  bitangent = glm::cross(hit.ns, tangent) * (hit.tangent.w < 0.0f ? -1.0f : 1.0f);
  return true;
}

}  // namespace

vec3 MaterialTable::perturbed_normal(const TextureRef& map, float scale, const SurfaceHit& hit,
                                     const TexelQuad* shared) const {
  vec3 tangent, bitangent;
  if (!tangent_frame(hit, tangent, bitangent)) return vec3(0.0f);
  vec3 n = vec3(lookup(map, linear_, hit, shared)) * 2.0f - 1.0f;
  n.x *= scale;
  n.y *= scale;
  const vec3 world = n.x * tangent + n.y * bitangent + n.z * hit.ns;
  const float wl = glm::length(world);
  return wl > 0.0f && std::isfinite(wl) ? world / wl : vec3(0.0f);
}

// KHR_materials_anisotropy: the direction (texture RG, else the tangent) rotated by
// anisotropyRotation counter-clockwise in tangent space, and the strength x texture B.
vec3 MaterialTable::anisotropy_direction(const Material& m, const SurfaceHit& hit, float& strength,
                                         const TexelQuad* shared) const {
  vec3 tangent, bitangent;
  strength = 0.0f;
  if (!(m.anisotropy_strength > 0.0f) || !tangent_frame(hit, tangent, bitangent)) return vec3(0.0f);
  vec2 d(1.0f, 0.0f);
  strength = m.anisotropy_strength;
  if (m.anisotropy_texture.present()) {
    const vec4 texel = lookup(m.anisotropy_texture, linear_, hit, shared);
    d = vec2(texel) * 2.0f - 1.0f;
    strength *= texel.b;
  }
  const float c = std::cos(m.anisotropy_rotation), s = std::sin(m.anisotropy_rotation);
  const vec3 world = (c * d.x - s * d.y) * tangent + (s * d.x + c * d.y) * bitangent;
  const float len = glm::length(world);
  if (!(len > 1e-8f)) strength = 0.0f;
  return strength > 0.0f ? world / len : vec3(0.0f);
}

vec3 MaterialTable::emission(const Material& m, const SurfaceHit& hit, const TexelQuad* shared) const {
  return m.emissive_factor * m.emissive_strength * vec3(lookup(m.emissive_texture, srgb_, hit, shared));
}

ShadingPoint MaterialTable::evaluate(const SurfaceHit& hit) const {
  if (hit.material < 0) return evaluate(default_material_, hit);
  if (!constant_[hit.material]) {
    const TextureUse& shared = shared_[hit.material];
    if (!shared.image) return evaluate(materials_[hit.material], hit);
    const TexelQuad at = locate_texels(*shared.image, *shared.ref, hit.uv[shared.ref->texcoord]);
    return evaluate(materials_[hit.material], hit, &at);
  }
  // The same values as evaluate(m, hit) gives: what differs from the white, tangentless hit.
  const Material& m = materials_[hit.material];
  ShadingPoint sp = constant_point_[hit.material];
  if (hit.color != vec4(1.0f)) set_base_color(m, hit, sp);
  if (!m.unlit && m.anisotropy_strength > 0.0f) sp.anisotropy_direction = anisotropy_direction(m, hit, sp.anisotropy);
  return sp;
}

void MaterialTable::prefetch_textures(const SurfaceHit& hit) const {
  if (hit.material < 0) return;
  const TextureUse& shared = shared_[hit.material];
  if (shared.image) {
    const TexelQuad at = locate_texels(*shared.image, *shared.ref, hit.uv[shared.ref->texcoord]);
    for (const TextureUse& use : texture_uses_[hit.material]) prefetch_texels(*use.image, at);
    return;
  }
  for (const TextureUse& use : texture_uses_[hit.material])
    prefetch_texels(*use.image, locate_texels(*use.image, *use.ref, hit.uv[use.ref->texcoord]));
}

void MaterialTable::prefetch_emission(const SurfaceHit& hit) const {
  const TextureRef& ref = material(hit.material).emissive_texture;
  if (ref.present()) prefetch_texels(srgb_[ref.image], locate_texels(srgb_[ref.image], ref, hit.uv[ref.texcoord]));
}

void MaterialTable::set_base_color(const Material& m, const SurfaceHit& hit, ShadingPoint& sp,
                                   const TexelQuad* shared) const {
  const vec4 base = m.base_color_factor * lookup(m.base_color_texture, srgb_, hit, shared) * hit.color;
  sp.base_color = glm::clamp(vec3(base), 0.0f, 1.0f);
  sp.alpha = glm::clamp(base.a, 0.0f, 1.0f);
}

ShadingPoint MaterialTable::evaluate(const Material& m, const SurfaceHit& hit, const TexelQuad* shared) const {
  auto lookup = [&](const TextureRef& ref, const std::vector<TextureImage>& images) {
    return this->lookup(ref, images, hit, shared);
  };
  ShadingPoint sp;
  set_base_color(m, hit, sp, shared);
  sp.emission = emission(m, hit, shared);
  sp.double_sided = m.double_sided;
  sp.unlit = m.unlit;
  if (m.unlit) return sp;
  const vec4 mr = lookup(m.metallic_roughness_texture, linear_);
  sp.metallic = glm::clamp(m.metallic_factor * mr.b, 0.0f, 1.0f);
  sp.roughness = glm::clamp(m.roughness_factor * mr.g, 0.0f, 1.0f);
  if (m.normal_texture.present() && hit.tangent != vec4(0.0f))
    sp.normal = perturbed_normal(m.normal_texture, m.normal_scale, hit, shared);
  sp.transmission = glm::clamp(m.transmission_factor * lookup(m.transmission_texture, linear_).r, 0.0f, 1.0f);
  sp.ior = m.ior;
  const float thickness = m.thickness_factor * lookup(m.thickness_texture, linear_).g;
  sp.thin_walled = !(thickness > 0.0f);
  if (!sp.thin_walled && std::isfinite(m.attenuation_distance) && m.attenuation_distance > 0.0f)
    sp.absorption = -glm::log(glm::max(m.attenuation_color, vec3(1e-6f))) / m.attenuation_distance;
  sp.specular = glm::clamp(m.specular_factor * lookup(m.specular_texture, linear_).a, 0.0f, 1.0f);
  sp.specular_color = m.specular_color_factor * vec3(lookup(m.specular_color_texture, srgb_));
  sp.clearcoat = glm::clamp(m.clearcoat_factor * lookup(m.clearcoat_texture, linear_).r, 0.0f, 1.0f);
  sp.clearcoat_roughness =
      glm::clamp(m.clearcoat_roughness_factor * lookup(m.clearcoat_roughness_texture, linear_).g, 0.0f, 1.0f);
  if (sp.clearcoat > 0.0f && m.clearcoat_normal_texture.present() && hit.tangent != vec4(0.0f))
    sp.clearcoat_normal = perturbed_normal(m.clearcoat_normal_texture, m.clearcoat_normal_scale, hit, shared);
  sp.anisotropy_direction = anisotropy_direction(m, hit, sp.anisotropy, shared);
  sp.diffuse_transmission = glm::clamp(
      m.diffuse_transmission_factor * lookup(m.diffuse_transmission_texture, linear_).a, 0.0f, 1.0f);
  sp.diffuse_transmission_color = glm::clamp(
      m.diffuse_transmission_color_factor * vec3(lookup(m.diffuse_transmission_color_texture, srgb_)), 0.0f, 1.0f);
  sp.iridescence = glm::clamp(m.iridescence_factor * lookup(m.iridescence_texture, linear_).r, 0.0f, 1.0f);
  if (sp.iridescence > 0.0f) {
    sp.iridescence_ior = m.iridescence_ior;
    sp.iridescence_thickness =
        m.iridescence_thickness_texture.present()
            ? glm::mix(m.iridescence_thickness_min, m.iridescence_thickness_max,
                       lookup(m.iridescence_thickness_texture, linear_).g)
            : m.iridescence_thickness_max;
  }
  sp.dispersion = sp.thin_walled ? 0.0f : m.dispersion;  // a property of the volume
  sp.sheen_color = glm::clamp(m.sheen_color_factor * vec3(lookup(m.sheen_color_texture, srgb_)), 0.0f, 1.0f);
  sp.sheen_roughness = glm::clamp(m.sheen_roughness_factor * lookup(m.sheen_roughness_texture, linear_).a, 0.0f, 1.0f);
  return sp;
}

}  // namespace tessera
