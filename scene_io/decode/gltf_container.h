// The outer layer of a glTF file: JSON text, or a binary glTF (.glb) container holding a
// JSON chunk and an optional BIN chunk. Checked here, before tinygltf sees the bytes,
// so that a truncated or foreign file gets a message saying exactly what is wrong.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace tessera {

struct GltfContainer {
  bool binary = false;
  std::string_view json;  // the glTF JSON: the whole file, or the .glb's JSON chunk
  std::size_t bin_chunk_size = 0;  // .glb only; 0 when it has no BIN chunk
  std::size_t trailing_bytes = 0;  // .glb only: bytes after the length its header gives
};

// Throws SceneLoadError(display_name, ...) for an empty file, a file that is neither glTF
// JSON nor binary glTF, and a .glb whose header or chunks are inconsistent.
GltfContainer check_gltf_container(const std::vector<std::uint8_t>& bytes,
                                   const std::string& display_name);

// The same .glb (checked by check_gltf_container) with its JSON chunk replaced by `json`.
std::vector<std::uint8_t> replace_glb_json(const std::vector<std::uint8_t>& glb, std::string_view json);

}  // namespace tessera
