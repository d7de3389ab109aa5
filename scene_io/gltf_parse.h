// glTF bytes -> tinygltf::Model. tinygltf reads through file-system and image callbacks of
// tessera's own, and every failure becomes one clear line naming what is at fault.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene_io/base/gltf_defects.h"
#include "scene_io/decode/gltf_image_store.h"

namespace tessera {

// Throws SceneLoadError(display_name, problem) for what makes the whole file unreadable; a
// problem confined to one object (a buffer, accessor or image) goes to `defects` instead, the
// object kept as an empty placeholder. The images' encoded bytes go to `images`, to be decoded
// when a scene shows them. External files resolve against base_dir.
tinygltf::Model parse_gltf(const std::vector<std::uint8_t>& bytes, const std::string& display_name,
                           const std::string& base_dir, GltfDefects& defects, GltfImageStore& images);

}  // namespace tessera
