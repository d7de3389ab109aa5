// Loads a glTF 2.0 file (.gltf with external or data-URI resources, or .glb) into the
// renderer's plain SceneDescription. Throws SceneLoadError naming the file and the problem.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/scene/scene.h"
#include "scene_io/gltf_animation.h"

namespace tessera {

struct GltfLoadParams {
  std::string scene;  // index or name; empty = the file's default scene, else scene 0
  // KHR_materials_variants: the variant by name (else index) whose mapped materials the
  // primitives get; empty = every primitive's default material. (The {} keeps GltfLoadParams{scene}
  // free of -Wmissing-field-initializers.)
  std::string variant{};
  // Animations: which play ("" or "all": every one, "none", a name or an index), and the time
  // in seconds at which the nodes are posed.
  std::string animation{};
  float time = 0.0f;
};

struct GltfLoadResult {
  SceneDescription scene;
  std::vector<std::string> warnings;  // each once, already prefixed with nothing
  std::vector<std::string> material_variants;  // KHR_materials_variants: the names, by index
  int material_variant = -1;  // the variant applied (GltfLoadParams::variant); -1: none
  std::vector<Animation> animations;  // every animation of the file
  std::vector<int> playing;  // the indices of those applied (GltfLoadParams::animation)
  std::size_t morph_meshes = 0, skins = 0;  // meshes with morph targets; skins (not applied yet)
};

GltfLoadResult load_gltf(const std::string& path, const GltfLoadParams& params = {});

// The same loader over bytes in memory (.glb when they start with "glTF", else JSON).
// External resources are looked up relative to base_dir. Used by the fuzzer and tests.
GltfLoadResult load_gltf_from_memory(const std::vector<std::uint8_t>& bytes,
                                     const std::string& display_name,
                                     const std::string& base_dir,
                                     const GltfLoadParams& params = {});

// Extensions tessera implements; anything else in extensionsRequired is refused.
const std::vector<std::string>& supported_gltf_extensions();
bool is_supported_gltf_extension(const std::string& name);

}  // namespace tessera
