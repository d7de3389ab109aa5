#include "scene_io/gltf_prepare.h"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene_io/gltf_defects.h"
#include "scene_io/gltf_extensions.h"
#include "scene_io/load_error.h"

namespace tessera {
namespace {

using Json = nlohmann::json;

const Json* member(const Json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

const Json* extension(const Json& object, const char* name) {
  const Json* ext = member(object, "extensions");
  return ext ? member(*ext, name) : nullptr;
}

void check_required(const Json& j, const std::string& name) {
  const Json* required = member(j, "extensionsRequired");
  if (!required || !required->is_array()) return;
  for (const Json& ext : *required)
    if (ext.is_string() && !is_supported_gltf_extension(ext.get<std::string>()))
      throw SceneLoadError(name, fmt::format("requires extension {}, which tessera does not support",
                                             ext.get<std::string>()));
}

// A fallback buffer without a uri has no bytes; the views that point into it are decoded
// from their compressed form (gltf_meshopt.cpp), so 4 zero bytes stand in for it.
bool fill_fallback_buffers(Json& j) {
  Json* buffers = j.contains("buffers") ? &j["buffers"] : nullptr;
  if (!buffers || !buffers->is_array()) return false;
  bool changed = false;
  for (Json& b : *buffers) {
    const Json* ext = extension(b, "EXT_meshopt_compression");
    const Json* fallback = ext ? member(*ext, "fallback") : nullptr;
    if (!fallback || *fallback != true || member(b, "uri")) continue;
    b["uri"] = "data:application/octet-stream;base64,AAAAAA==";
    b["byteLength"] = 4;
    changed = true;
  }
  return changed;
}

// tinygltf refuses an indices accessor without a bufferView, which a Draco primitive's has.
bool point_draco_indices(Json& j) {
  Json* meshes = j.contains("meshes") ? &j["meshes"] : nullptr;
  Json* accessors = j.contains("accessors") ? &j["accessors"] : nullptr;
  if (!meshes || !meshes->is_array() || !accessors || !accessors->is_array()) return false;
  bool changed = false;
  for (const Json& mesh : *meshes) {
    const Json* prims = member(mesh, "primitives");
    if (!prims || !prims->is_array()) continue;
    for (const Json& prim : *prims) {
      const Json* draco = extension(prim, "KHR_draco_mesh_compression");
      const Json* view = draco ? member(*draco, "bufferView") : nullptr;
      const Json* indices = member(prim, "indices");
      if (!view || !view->is_number_unsigned() || !indices || !indices->is_number_unsigned()) continue;
      const auto a = indices->get<std::uint64_t>();
      if (a >= accessors->size() || !(*accessors)[a].is_object() || (*accessors)[a].contains("bufferView"))
        continue;
      (*accessors)[a]["bufferView"] = *view;
      changed = true;
    }
  }
  return changed;
}

// Why buffer `i` has no data tessera can read, or empty when it has.
std::string dataless_buffer(const Json& b, std::size_t i, const GltfJsonContext& context) {
  if (member(b, "uri")) return "";
  const Json* length = member(b, "byteLength");
  if (!context.binary) return fmt::format("buffer {} has no uri (only a .glb's buffer 0 may omit it)", i);
  if (i > 0) return fmt::format("buffer {} has no uri, but only buffer 0 of a .glb may use the BIN chunk", i);
  if (context.bin_chunk_size == 0)
    return "buffer 0 has no uri, so its data is the BIN chunk, but the file has no BIN chunk";
  if (length && length->is_number_unsigned() && length->get<std::uint64_t>() > context.bin_chunk_size)
    return fmt::format("buffer 0 has byteLength {}, but the BIN chunk holds only {} bytes",
                       length->get<std::uint64_t>(), context.bin_chunk_size);
  return "";
}

// Buffers without data become 4-byte placeholders (gltf_parse.cpp empties them again).
bool replace_dataless_buffers(Json& j, const GltfJsonContext& context, GltfDefects& defects) {
  Json* buffers = j.contains("buffers") ? &j["buffers"] : nullptr;
  if (!buffers || !buffers->is_array()) return false;
  bool changed = false;
  for (std::size_t i = 0; i < buffers->size(); ++i) {
    Json& b = (*buffers)[i];
    if (!b.is_object() || extension(b, "EXT_meshopt_compression")) continue;  // fill_fallback_buffers' case
    const std::string problem = dataless_buffer(b, i, context);
    if (problem.empty()) continue;
    // Without a uri, a buffer is valid glTF (its data may come from an extension) until used.
    const bool invalid = context.binary && i == 0;
    defects.add(fmt::format("buffer {}", i), problem, invalid);
    b["uri"] = "data:application/octet-stream;base64,AAAAAA==";
    b["byteLength"] = 4;
    changed = true;
  }
  return changed;
}

// tinygltf hands an image's bufferView to the image decoder without checking that the view
// lies inside its buffer (a buffer replaced by a placeholder above, or a byteLength too small
// for the view): such an image becomes a defect and its data an undecodable stub, so no
// decoder reads past the buffer.
bool replace_images_past_their_buffers(Json& j, GltfDefects& defects) {
  Json* images = j.contains("images") ? &j["images"] : nullptr;
  const Json* views = member(j, "bufferViews");
  const Json* buffers = member(j, "buffers");
  if (!images || !images->is_array() || !views || !views->is_array() || !buffers || !buffers->is_array()) return false;
  auto number = [](const Json* v) { return v && v->is_number_unsigned() ? v->get<std::uint64_t>() : 0; };
  bool changed = false;
  for (std::size_t i = 0; i < images->size(); ++i) {
    Json& image = (*images)[i];
    const Json* view_index = member(image, "bufferView");
    if (!view_index || !view_index->is_number_unsigned() || view_index->get<std::uint64_t>() >= views->size()) continue;
    const Json& view = (*views)[view_index->get<std::size_t>()];
    const Json* buffer_index = member(view, "buffer");
    if (!buffer_index || !buffer_index->is_number_unsigned() || buffer_index->get<std::uint64_t>() >= buffers->size())
      continue;
    const std::uint64_t end = number(member(view, "byteOffset")) + number(member(view, "byteLength"));
    const std::uint64_t size = number(member((*buffers)[buffer_index->get<std::size_t>()], "byteLength"));
    if (end <= size) continue;
    defects.add(fmt::format("image {}", i), fmt::format("image {}'s bufferView {} ends at byte {}, past the {} bytes of "
                                                        "buffer {}'s data", i, view_index->get<std::uint64_t>(), end,
                                                        size, buffer_index->get<std::uint64_t>()));
    image = Json{{"uri", "data:image/png;base64,AAAA"}};  // three bytes no decoder takes for an image
    changed = true;
  }
  return changed;
}

// Accessors tinygltf would refuse for their type become one float zero. (It reads any
// componentType; AccessorReader refuses a wrong one when the accessor is read.)
bool replace_unknown_accessors(Json& j, GltfDefects& defects) {
  static const char* kTypes[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
  Json* accessors = j.contains("accessors") ? &j["accessors"] : nullptr;
  if (!accessors || !accessors->is_array()) return false;
  bool changed = false;
  for (std::size_t i = 0; i < accessors->size(); ++i) {
    Json& a = (*accessors)[i];
    const Json* type = member(a, "type");
    std::string problem;
    if (type && type->is_string() &&
        std::none_of(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return *type == t; }))
      problem = fmt::format("accessor {} has unknown type '{}'", i, type->get<std::string>().substr(0, 40));
    if (problem.empty()) continue;
    defects.add(fmt::format("accessor {}", i), problem);
    a = Json{{"componentType", 5126}, {"type", "SCALAR"}, {"count", 1}};
    changed = true;
  }
  return changed;
}

// An indices accessor without a bufferView (zeros, bar sparse ones) is valid glTF, but
// tinygltf refuses it: it waits in kIndicesWithoutView.
bool hand_over_viewless_indices(Json& j) {
  Json* meshes = j.contains("meshes") ? &j["meshes"] : nullptr;
  const Json* accessors = member(j, "accessors");
  if (!meshes || !meshes->is_array() || !accessors || !accessors->is_array()) return false;
  bool changed = false;
  for (Json& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (Json& prim : mesh["primitives"]) {
      const Json* indices = member(prim, "indices");
      if (!indices || !indices->is_number_unsigned() || indices->get<std::uint64_t>() >= accessors->size()) continue;
      const Json& a = (*accessors)[indices->get<std::size_t>()];
      if (!a.is_object() || a.contains("bufferView")) continue;
      prim["extensions"][kIndicesWithoutView] = Json{{"accessor", *indices}};
      prim.erase("indices");
      changed = true;
    }
  }
  return changed;
}

// Mistakes tinygltf passes over in silence: a mesh without a primitives array (tinygltf reads
// it as a mesh without primitives), a texture reference of a negative index (read as none).
void flag_silent_mistakes(const Json& j, GltfDefects& defects) {
  if (const Json* meshes = member(j, "meshes"); meshes && meshes->is_array())
    for (std::size_t m = 0; m < meshes->size(); ++m) {
      const Json* prims = member((*meshes)[m], "primitives");
      if (!prims || !prims->is_array() || prims->empty())
        defects.add(fmt::format("mesh {}", m),
                    fmt::format("mesh {} has {}; glTF requires an array of at least one primitive", m,
                                !prims ? "no \"primitives\"" : prims->is_array() ? "an empty \"primitives\" array"
                                                                 : "a \"primitives\" that is not an array"));
    }
  const Json* materials = member(j, "materials");
  if (!materials || !materials->is_array()) return;
  for (std::size_t m = 0; m < materials->size(); ++m) {
    std::vector<std::pair<std::string, const Json*>> stack = {{"", &(*materials)[m]}};
    while (!stack.empty()) {  // every textureInfo, in the core material and its extensions
      const auto [key, object] = stack.back();
      stack.pop_back();
      if (!object->is_object()) continue;
      const Json* index = member(*object, "index");
      if (index && index->is_number_integer() && index->get<std::int64_t>() < 0) {
        defects.add(fmt::format("material {}", m), fmt::format("material {} has {} index {}, which names no texture", m,
                                                               key, index->get<std::int64_t>()));
        break;
      }
      for (auto it = object->begin(); it != object->end(); ++it) stack.emplace_back(it.key(), &*it);
    }
  }
}

}  // namespace

std::optional<std::string> prepare_gltf_json(std::string_view json, const std::string& name,
                                             const GltfJsonContext& context, GltfDefects& defects) {
  Json j = Json::parse(json.begin(), json.end(), nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return std::nullopt;
  check_required(j, name);
  bool changed = false;
  if (json.find("EXT_meshopt_compression") != std::string_view::npos) changed |= fill_fallback_buffers(j);
  if (json.find("KHR_draco_mesh_compression") != std::string_view::npos) changed |= point_draco_indices(j);
  changed |= replace_dataless_buffers(j, context, defects);
  changed |= replace_images_past_their_buffers(j, defects);
  changed |= replace_unknown_accessors(j, defects);
  changed |= hand_over_viewless_indices(j);
  flag_silent_mistakes(j, defects);
  if (!changed) return std::nullopt;
  return j.dump();
}

}  // namespace tessera
