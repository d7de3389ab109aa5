// The glTF JSON as tinygltf must see it. Before tinygltf reads any accessor or buffer:
// - extensionsRequired is checked, so an unsupported required extension is the one named;
// - compressed files are made acceptable to tinygltf, which knows neither Draco nor meshopt:
//   an EXT_meshopt_compression fallback buffer (no data: all its views are compressed) gets a
//   4-byte placeholder, and a Draco primitive's indices accessor (no bufferView: its data is
//   in the Draco stream) points at the Draco bufferView until gltf_draco.cpp replaces it;
// - objects that tinygltf would refuse although the file may not use them (docs/reliability.md)
//   become placeholders, their problem recorded in GltfDefects: a buffer without data (no uri
//   in a .gltf, or other than buffer 0 in a .glb, or larger than the BIN chunk), and every
//   object gltf_diagnose.h's find_object_problems names (an accessor of an unknown type, a
//   skin without joints, a camera without its numbers, ...); and an indices accessor without a
//   bufferView (allowed: its indices are zeros, bar sparse ones) is handed over as
//   kIndicesWithoutView.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace tessera {

struct GltfDefects;
struct DeclaredMediaTypes;

// The primitive extension an indices accessor without a bufferView is moved to, as
// {"accessor": index}, which tinygltf refuses as `indices`; gltf_parse.cpp moves it back.
inline constexpr const char* kIndicesWithoutView = "TESSERA_indices_without_bufferView";

// What the JSON sits in: a .glb's BIN chunk size matters to buffer 0; external files resolve
// against base_dir.
struct GltfJsonContext {
  bool binary = false;
  std::size_t bin_chunk_size = 0;
  std::string base_dir{};
};

// Throws SceneLoadError(display_name, ...) for an unsupported required extension. Returns
// the rewritten JSON, or nullopt when tinygltf can read `json` as it is (or it is not JSON,
// which tinygltf then reports). `image_types` gets the media types the images declare, as the
// file gives them (gltf_images.h).
std::optional<std::string> prepare_gltf_json(std::string_view json, const std::string& display_name,
                                             const GltfJsonContext& context, GltfDefects& defects,
                                             std::vector<DeclaredMediaTypes>& image_types);

}  // namespace tessera
