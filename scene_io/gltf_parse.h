// glTF bytes -> tinygltf::Model. tinygltf reads through file-system and image callbacks of
// tessera's own, and every failure becomes one clear line naming what is at fault.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace tessera {

// Throws SceneLoadError(display_name, problem). External files resolve against base_dir.
tinygltf::Model parse_gltf(const std::vector<std::uint8_t>& bytes, const std::string& display_name,
                           const std::string& base_dir);

}  // namespace tessera
