// The glTF JSON as tinygltf must see it. Before tinygltf reads any accessor or buffer:
// - extensionsRequired is checked, so an unsupported required extension is the one named;
// - compressed files are made acceptable to tinygltf, which knows neither Draco nor meshopt:
//   an EXT_meshopt_compression fallback buffer (no data: all its views are compressed) gets a
//   4-byte placeholder, and a Draco primitive's indices accessor (no bufferView: its data is
//   in the Draco stream) points at the Draco bufferView until gltf_draco.cpp replaces it.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <string_view>

namespace tessera {

// Throws SceneLoadError(display_name, ...) for an unsupported required extension. Returns
// the rewritten JSON, or nullopt when tinygltf can read `json` as it is (or it is not JSON,
// which tinygltf then reports).
std::optional<std::string> prepare_gltf_json(std::string_view json, const std::string& display_name);

}  // namespace tessera
