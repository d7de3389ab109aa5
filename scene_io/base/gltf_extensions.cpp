#include "scene_io/base/gltf_extensions.h"

#include <algorithm>
#include <map>

namespace tessera {

const std::vector<std::string>& supported_gltf_extensions() {
  static const std::vector<std::string> names = {
      "EXT_mesh_gpu_instancing",
      "EXT_meshopt_compression",
      "EXT_texture_webp",
      "KHR_draco_mesh_compression",
      "KHR_lights_punctual",
      "KHR_materials_anisotropy",
      "KHR_materials_clearcoat",
      "KHR_materials_diffuse_transmission",
      "KHR_materials_dispersion",
      "KHR_materials_emissive_strength",
      "KHR_materials_ior",
      "KHR_materials_iridescence",
      "KHR_materials_sheen",
      "KHR_materials_specular",
      "KHR_materials_transmission",
      "KHR_materials_unlit",
      "KHR_materials_variants",
      "KHR_materials_volume",
      "KHR_mesh_quantization",
      "KHR_texture_basisu",  // as a fallback: see gltf_extension_status
      "KHR_texture_transform"};
  return names;
}

bool is_supported_gltf_extension(const std::string& name) {
  const auto& s = supported_gltf_extensions();
  return std::find(s.begin(), s.end(), name) != s.end();
}

ExtensionStatus gltf_extension_status(const std::string& name) {
  if (name == "KHR_texture_basisu")
    return {ExtensionSupport::Fallback,
            "no Basis Universal decoder in Debian, so each texture's PNG/JPEG/WebP source is used "
            "(a texture without one is refused)"};
  if (is_supported_gltf_extension(name)) return {ExtensionSupport::Supported, ""};
  // Why some common ones are ignored; any other is simply not implemented.
  static const std::map<std::string, std::string> reasons = {
      {"KHR_materials_pbrSpecularGlossiness", "archived extension; the metallic-roughness material is used"},
      {"KHR_animation_pointer", "not implemented; only node and morph-weight animations play"},
      {"KHR_xmp_json_ld", "metadata only"}};
  auto it = reasons.find(name);
  return {ExtensionSupport::Ignored, it != reasons.end() ? it->second : "tessera does not implement it"};
}

std::string describe_extension_status(const std::string& name) {
  const ExtensionStatus s = gltf_extension_status(name);
  switch (s.support) {
    case ExtensionSupport::Supported: return "supported";
    case ExtensionSupport::Fallback: return "used as a fallback: " + s.why;
    default: return "ignored: " + s.why;
  }
}

}  // namespace tessera
