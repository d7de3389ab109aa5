// When tinygltf refuses a file its message rarely says which buffer, view, image or camera
// is at fault (and sometimes spans several lines). This looks at the JSON again, in the
// order tinygltf reads it, and names the first problem it finds.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <nlohmann/json.hpp>

namespace tessera {

struct GltfDiagnoseInput {
  std::string_view json;  // the glTF JSON text
  bool binary = false;  // from a .glb
  std::size_t bin_chunk_size = 0;  // .glb BIN chunk bytes
  std::string base_dir;  // where external files are looked up
};

// The arrays of objects a glTF file holds, and what one of their objects is called.
struct GltfObjectArray {
  const char* key;
  const char* noun;
};
inline constexpr GltfObjectArray kGltfArrays[] = {
    {"buffers", "buffer"},     {"bufferViews", "bufferView"}, {"accessors", "accessor"}, {"meshes", "mesh"},
    {"nodes", "node"},         {"scenes", "scene"},           {"materials", "material"}, {"images", "image"},
    {"textures", "texture"},   {"samplers", "sampler"},       {"cameras", "camera"},     {"skins", "skin"},
    {"animations", "animation"}};

// One line without the file name, or nullopt when nothing specific is found.
std::optional<std::string> diagnose_gltf_json(const GltfDiagnoseInput& in);

// A problem confined to one object, which tinygltf would refuse the whole file for or read
// as something else in silence (a texture reference without an index as none).
struct GltfObjectProblem {
  std::string array;  // where the object is: "buffers", "meshes", ..., "lights" (KHR_lights_punctual)
  std::size_t index = 0;
  std::string object;  // "buffer 1"
  std::string text;  // "buffer 1 has no valid byteLength"
};

// Every object of `j` with such a problem, array by array. A buffer without a uri
// is left to gltf_prepare.cpp (whether that is a problem depends on the container). External
// files resolve against base_dir.
std::vector<GltfObjectProblem> find_object_problems(const nlohmann::json& j, const std::string& base_dir);

// tinygltf's (possibly multi-line) error text as one line, for when the diagnosis finds nothing.
std::string reword_tinygltf_error(const std::string& err, std::string_view json);

// True for a uri with a scheme (http://, https://, file://...): not a local relative path.
bool is_remote_uri(const std::string& uri);

// The path of an external resource: base_dir joined with the percent-decoded uri.
std::string resolve_gltf_uri(const std::string& base_dir, const std::string& uri);

// Why `path` cannot be read, or empty when it can.
std::string unreadable_reason(const std::string& path);

}  // namespace tessera
