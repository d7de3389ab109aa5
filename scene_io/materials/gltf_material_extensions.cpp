#include "scene_io/materials/gltf_material_extensions.h"

#include <cmath>

namespace tessera {
namespace {

const tinygltf::Value* extension(const tinygltf::Material& m, const char* name) {
  auto it = m.extensions.find(name);
  return it == m.extensions.end() ? nullptr : &it->second;
}

float number(const tinygltf::Value& object, const char* key, float fallback) {
  if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsNumber()) return fallback;
  return static_cast<float>(object.Get(key).GetNumberAsDouble());
}

glm::vec3 color(const tinygltf::Value& object, const char* key, glm::vec3 fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& v = object.Get(key);
  if (!v.IsArray() || v.ArrayLen() != 3) return fallback;
  return {v.Get(0).GetNumberAsDouble(), v.Get(1).GetNumberAsDouble(), v.Get(2).GetNumberAsDouble()};
}

// A textureInfo object inside an extension.
TextureRef texture(const tinygltf::Value& object, const char* key, const TextureResolver& resolve) {
  if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsObject()) return {};
  const tinygltf::Value& info = object.Get(key);
  if (!info.Has("index") || !info.Get("index").IsNumber()) return {};
  tinygltf::ExtensionMap extensions;
  if (info.Has("extensions") && info.Get("extensions").IsObject())
    for (const std::string& name : info.Get("extensions").Keys()) extensions[name] = info.Get("extensions").Get(name);
  const int texcoord = info.Has("texCoord") && info.Get("texCoord").IsNumber() ? info.Get("texCoord").GetNumberAsInt() : 0;
  return resolve(info.Get("index").GetNumberAsInt(), texcoord, extensions, key);
}

// The `scale` of a normalTextureInfo inside an extension.
float texture_scale(const tinygltf::Value& object, const char* key) {
  if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsObject()) return 1.0f;
  return number(object.Get(key), "scale", 1.0f);
}

}  // namespace

void read_material_extensions(const tinygltf::Material& src, const TextureResolver& resolve,
                              const std::function<void(const std::string&)>& fail, Material& mat) {
  if (const tinygltf::Value* e = extension(src, "KHR_materials_transmission")) {
    mat.transmission_factor = number(*e, "transmissionFactor", 0.0f);
    mat.transmission_texture = texture(*e, "transmissionTexture", resolve);
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_ior")) {
    mat.ior = number(*e, "ior", 1.5f);
    if (mat.ior == 0.0f) mat.ior = 1e4f;  // the specification's 0: reflect everything (f0 = 1)
    if (!(mat.ior >= 1.0f) || !std::isfinite(mat.ior)) fail("KHR_materials_ior.ior must be 0 or at least 1");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_volume")) {
    mat.thickness_factor = number(*e, "thicknessFactor", 0.0f);
    mat.thickness_texture = texture(*e, "thicknessTexture", resolve);
    mat.attenuation_distance = number(*e, "attenuationDistance", std::numeric_limits<float>::infinity());
    mat.attenuation_color = color(*e, "attenuationColor", glm::vec3(1.0f));
    if (!(mat.attenuation_distance > 0.0f)) fail("KHR_materials_volume.attenuationDistance must be positive");
    if (!(mat.thickness_factor >= 0.0f)) fail("KHR_materials_volume.thicknessFactor must not be negative");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_specular")) {
    mat.specular_factor = number(*e, "specularFactor", 1.0f);
    mat.specular_texture = texture(*e, "specularTexture", resolve);
    mat.specular_color_factor = color(*e, "specularColorFactor", glm::vec3(1.0f));
    mat.specular_color_texture = texture(*e, "specularColorTexture", resolve);
    if (!(mat.specular_factor >= 0.0f && mat.specular_factor <= 1.0f))
      fail("KHR_materials_specular.specularFactor must be between 0 and 1");
    if (!(glm::all(glm::greaterThanEqual(mat.specular_color_factor, glm::vec3(0.0f)))))
      fail("KHR_materials_specular.specularColorFactor must not be negative");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_clearcoat")) {
    mat.clearcoat_factor = number(*e, "clearcoatFactor", 0.0f);
    mat.clearcoat_texture = texture(*e, "clearcoatTexture", resolve);
    mat.clearcoat_roughness_factor = number(*e, "clearcoatRoughnessFactor", 0.0f);
    mat.clearcoat_roughness_texture = texture(*e, "clearcoatRoughnessTexture", resolve);
    mat.clearcoat_normal_texture = texture(*e, "clearcoatNormalTexture", resolve);
    mat.clearcoat_normal_scale = texture_scale(*e, "clearcoatNormalTexture");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_diffuse_transmission")) {
    mat.diffuse_transmission_factor = number(*e, "diffuseTransmissionFactor", 0.0f);
    mat.diffuse_transmission_texture = texture(*e, "diffuseTransmissionTexture", resolve);
    mat.diffuse_transmission_color_factor = color(*e, "diffuseTransmissionColorFactor", glm::vec3(1.0f));
    mat.diffuse_transmission_color_texture = texture(*e, "diffuseTransmissionColorTexture", resolve);
    if (!(mat.diffuse_transmission_factor >= 0.0f && mat.diffuse_transmission_factor <= 1.0f))
      fail("KHR_materials_diffuse_transmission.diffuseTransmissionFactor must be in [0, 1]");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_anisotropy")) {
    mat.anisotropy_strength = number(*e, "anisotropyStrength", 0.0f);
    mat.anisotropy_rotation = number(*e, "anisotropyRotation", 0.0f);
    mat.anisotropy_texture = texture(*e, "anisotropyTexture", resolve);
    if (!(mat.anisotropy_strength >= 0.0f && mat.anisotropy_strength <= 1.0f))
      fail("KHR_materials_anisotropy.anisotropyStrength must be in [0, 1]");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_iridescence")) {
    mat.iridescence_factor = number(*e, "iridescenceFactor", 0.0f);
    mat.iridescence_texture = texture(*e, "iridescenceTexture", resolve);
    mat.iridescence_ior = number(*e, "iridescenceIor", 1.3f);
    mat.iridescence_thickness_min = number(*e, "iridescenceThicknessMinimum", 100.0f);
    mat.iridescence_thickness_max = number(*e, "iridescenceThicknessMaximum", 400.0f);
    mat.iridescence_thickness_texture = texture(*e, "iridescenceThicknessTexture", resolve);
    if (!(mat.iridescence_factor >= 0.0f && mat.iridescence_factor <= 1.0f))
      fail("KHR_materials_iridescence.iridescenceFactor must be in [0, 1]");
    if (!(mat.iridescence_ior >= 1.0f)) fail("KHR_materials_iridescence.iridescenceIor must be at least 1");
    if (!(mat.iridescence_thickness_min >= 0.0f && mat.iridescence_thickness_max >= 0.0f))
      fail("KHR_materials_iridescence thicknesses must not be negative");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_dispersion")) {
    mat.dispersion = number(*e, "dispersion", 0.0f);
    if (!(mat.dispersion >= 0.0f)) fail("KHR_materials_dispersion.dispersion must not be negative");
  }
  if (const tinygltf::Value* e = extension(src, "KHR_materials_sheen")) {
    mat.sheen_color_factor = color(*e, "sheenColorFactor", glm::vec3(0.0f));
    mat.sheen_color_texture = texture(*e, "sheenColorTexture", resolve);
    mat.sheen_roughness_factor = number(*e, "sheenRoughnessFactor", 0.0f);
    mat.sheen_roughness_texture = texture(*e, "sheenRoughnessTexture", resolve);
  }
  if (extension(src, "KHR_materials_unlit")) mat.unlit = true;
  const bool finite = std::isfinite(mat.transmission_factor) && std::isfinite(mat.thickness_factor) &&
                      std::isfinite(mat.specular_factor) && all_finite(mat.specular_color_factor) &&
                      all_finite(mat.attenuation_color) && std::isfinite(mat.clearcoat_factor) &&
                      std::isfinite(mat.clearcoat_roughness_factor) && all_finite(mat.sheen_color_factor) &&
                      std::isfinite(mat.sheen_roughness_factor) && std::isfinite(mat.clearcoat_normal_scale) &&
                      std::isfinite(mat.anisotropy_rotation) && all_finite(mat.diffuse_transmission_color_factor) &&
                      std::isfinite(mat.iridescence_ior) && std::isfinite(mat.iridescence_thickness_min) &&
                      std::isfinite(mat.iridescence_thickness_max) && std::isfinite(mat.dispersion);
  if (!finite) fail("has a non-finite extension factor");
}

}  // namespace tessera
