#include "scene_io/gltf_prepare.h"

#include <fmt/format.h>
#include <nlohmann/json.hpp>

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

}  // namespace

std::optional<std::string> prepare_gltf_json(std::string_view json, const std::string& name) {
  Json j = Json::parse(json.begin(), json.end(), nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return std::nullopt;
  check_required(j, name);
  const bool compressed = json.find("EXT_meshopt_compression") != std::string_view::npos ||
                          json.find("KHR_draco_mesh_compression") != std::string_view::npos;
  if (!compressed) return std::nullopt;
  const bool fallback = fill_fallback_buffers(j);
  const bool draco = point_draco_indices(j);
  if (!fallback && !draco) return std::nullopt;
  return j.dump();
}

}  // namespace tessera
