// glTF materials, textures, samplers and decoded images -> plain descriptions.
#include "scene_io/materials/gltf_material.h"

#include <algorithm>

#include <fmt/format.h>

#include "scene_io/decode/gltf_images.h"
#include "scene_io/materials/gltf_material_extensions.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

WrapMode wrap_mode(int gl) {
  switch (gl) {
    case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return WrapMode::ClampToEdge;
    case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return WrapMode::MirroredRepeat;
    default: return WrapMode::Repeat;
  }
}

glm::vec2 vec2_of(const tinygltf::Value& v, glm::vec2 fallback) {
  if (!v.IsArray() || v.ArrayLen() != 2) return fallback;
  return {static_cast<float>(v.Get(0).GetNumberAsDouble()),
          static_cast<float>(v.Get(1).GetNumberAsDouble())};
}

double number_of(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key) || !object.Get(key).IsNumber()) return fallback;
  return object.Get(key).GetNumberAsDouble();
}

TextureRef texture_ref(const tinygltf::Model& model, const std::string& file, const GltfDefects& defects,
                       const GltfImageStore& images, int index,
                       int texcoord, const tinygltf::ExtensionMap& extensions,
                       const std::string& what, std::vector<std::string>& warnings) {
  TextureRef ref;
  if (index < 0) return ref;
  if (index >= static_cast<int>(model.textures.size()))
    throw SceneLoadError(file, fmt::format("{} refers to texture {}, but the file has {}", what,
                                           index, count_of(model.textures.size(), "texture")));
  defects.check_used(fmt::format("texture {}", index), file);
  const int source = texture_image(model, file, index, defects, images);
  if (source < 0) {
    warnings.push_back(fmt::format("texture {} has no image tessera can decode; ignored", index));
    return ref;
  }
  ref.image = source;
  ref.texcoord = texcoord;
  if (const tinygltf::Sampler* s = texture_sampler(model, file, index, defects)) {
    ref.wrap_s = wrap_mode(s->wrapS);
    ref.wrap_t = wrap_mode(s->wrapT);
    if (s->magFilter == TINYGLTF_TEXTURE_FILTER_NEAREST) ref.filter = FilterMode::Nearest;
  }
  if (auto it = extensions.find("KHR_texture_transform"); it != extensions.end()) {
    const tinygltf::Value& t = it->second;
    ref.transform.offset = vec2_of(t.Has("offset") ? t.Get("offset") : tinygltf::Value(), {0, 0});
    ref.transform.scale = vec2_of(t.Has("scale") ? t.Get("scale") : tinygltf::Value(), {1, 1});
    ref.transform.rotation = static_cast<float>(number_of(t, "rotation", 0.0));
    ref.texcoord = static_cast<int>(number_of(t, "texCoord", texcoord));
  }
  if (ref.texcoord < 0 || ref.texcoord > 1) {
    warnings.push_back(fmt::format("{} uses TEXCOORD_{}; tessera reads sets 0 and 1, using 0",
                                   what, ref.texcoord));
    ref.texcoord = 0;
  }
  return ref;
}

Material convert_material(const tinygltf::Model& model, std::size_t i, const std::string& file,
                          const GltfDefects& defects, const GltfImageStore& images, std::vector<std::string>& warnings) {
  const tinygltf::Material& m = model.materials[i];
  const std::string what = fmt::format("material {}", i);
  auto ref = [&](const tinygltf::TextureInfo& t, const char* slot) {
    return texture_ref(model, file, defects, images, t.index, t.texCoord, t.extensions, what + " " + slot, warnings);
  };
  Material mat;
  mat.name = m.name;
  const auto& pbr = m.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() == 4)
    mat.base_color_factor = {pbr.baseColorFactor[0], pbr.baseColorFactor[1],
                             pbr.baseColorFactor[2], pbr.baseColorFactor[3]};
  mat.base_color_texture = ref(pbr.baseColorTexture, "baseColorTexture");
  mat.metallic_factor = static_cast<float>(pbr.metallicFactor);
  mat.roughness_factor = static_cast<float>(pbr.roughnessFactor);
  mat.metallic_roughness_texture = ref(pbr.metallicRoughnessTexture, "metallicRoughnessTexture");
  mat.normal_texture = texture_ref(model, file, defects, images, m.normalTexture.index, m.normalTexture.texCoord,
                                   m.normalTexture.extensions, what + " normalTexture", warnings);
  mat.normal_scale = static_cast<float>(m.normalTexture.scale);
  if (m.emissiveFactor.size() == 3)
    mat.emissive_factor = {m.emissiveFactor[0], m.emissiveFactor[1], m.emissiveFactor[2]};
  mat.emissive_texture = ref(m.emissiveTexture, "emissiveTexture");
  if (auto it = m.extensions.find("KHR_materials_emissive_strength"); it != m.extensions.end())
    mat.emissive_strength = static_cast<float>(number_of(it->second, "emissiveStrength", 1.0));
  if (!(mat.emissive_strength >= 0.0f))
    throw SceneLoadError(file, what + ": KHR_materials_emissive_strength.emissiveStrength must not be negative");
  // tessera ignores occlusion (a path tracer traces it), but glTF requires the reference to resolve.
  if (m.occlusionTexture.index >= static_cast<int>(model.textures.size()))
    throw SceneLoadError(file, fmt::format("{} occlusionTexture refers to texture {}, but the file has {}", what,
                                           m.occlusionTexture.index, count_of(model.textures.size(), "texture")));
  mat.alpha_mode = m.alphaMode == "MASK"    ? AlphaMode::Mask
                   : m.alphaMode == "BLEND" ? AlphaMode::Blend
                                            : AlphaMode::Opaque;
  mat.alpha_cutoff = static_cast<float>(m.alphaCutoff);
  mat.double_sided = m.doubleSided;
  read_material_extensions(
      m,
      [&](int index, int texcoord, const tinygltf::ExtensionMap& ext, const std::string& slot) {
        return texture_ref(model, file, defects, images, index, texcoord, ext, what + " " + slot, warnings);
      },
      [&](const std::string& problem) { throw SceneLoadError(file, what + ": " + problem); }, mat);
  const bool finite = all_finite((mat.base_color_factor)) &&
                      all_finite((mat.emissive_factor)) &&
                      std::isfinite(mat.emissive_strength) && std::isfinite(mat.metallic_factor) &&
                      std::isfinite(mat.roughness_factor);
  if (!finite) throw SceneLoadError(file, what + " has a non-finite factor");
  return mat;
}

}  // namespace

const tinygltf::Sampler* texture_sampler(const tinygltf::Model& model, const std::string& file, int index,
                                         const GltfDefects& defects) {
  const int sampler = model.textures[index].sampler;
  if (sampler >= static_cast<int>(model.samplers.size()))
    throw SceneLoadError(file, fmt::format("texture {} refers to sampler {}, but the file has {}", index, sampler,
                                           count_of(model.samplers.size(), "sampler")));
  if (sampler < 0) return nullptr;
  defects.check_used(fmt::format("sampler {}", sampler), file);
  return &model.samplers[sampler];
}

std::vector<Material> convert_materials(const tinygltf::Model& model, const std::string& file,
                                        const GltfDefects& defects, const GltfImageStore& images,
                                        const std::vector<bool>& used, std::vector<std::string>& warnings) {
  std::vector<Material> out;
  for (std::size_t i = 0; i < model.materials.size(); ++i)
    out.push_back(defects.read_object(used[i], fmt::format("material {}", i), file, warnings,
                                      [&] { return convert_material(model, i, file, defects, images, warnings); },
                                      Material{}));
  return out;
}

std::vector<int> images_shown(const std::vector<Material>& materials, const std::vector<bool>& used) {
  std::vector<int> out;
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (used[i])
      for (const TextureSlot& slot : texture_slots(materials[i]))
        if (slot.ref->present()) out.push_back(slot.ref->image);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

std::vector<Image> convert_images(const tinygltf::Model& model, const GltfImageStore& images,
                                  const std::vector<int>& shown, const std::string& file) {
  images.decode(model, shown);
  std::vector<Image> out(model.images.size());
  for (std::size_t i = 0; i < model.images.size(); ++i) {
    const tinygltf::Image& src = model.images[i];
    out[i].name = src.name.empty() ? src.uri.substr(0, 64) : src.name;
  }
  for (int i : shown) {  // texture_image has refused KTX2 and undecodable images
    const DecodedImage d = images.decoded(i);
    if (!d.problem.empty()) throw SceneLoadError(file, d.problem);
    Image& img = out[static_cast<std::size_t>(i)];
    const bool valid_shape = d.width > 0 && d.height > 0 && d.channels >= 1 && d.channels <= 4 &&
                             (d.bits == 8 || d.bits == 16 || d.bits == 32);
    const std::size_t expected =
        valid_shape ? static_cast<std::size_t>(d.width) * d.height * d.channels * (d.bits / 8) : 0;
    if (!valid_shape || !d.pixels || d.pixels->size() != expected)
      throw SceneLoadError(file, fmt::format("image {} ('{}') could not be decoded", i, img.name));
    img.width = d.width;
    img.height = d.height;
    img.channels = d.channels;
    img.bits_per_channel = d.bits;
    img.pixels = d.pixels;
  }
  return out;
}

}  // namespace tessera
