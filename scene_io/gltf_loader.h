// Loads a glTF 2.0 file (.gltf with external or data-URI resources, or .glb) into the
// renderer's plain SceneDescription. Throws SceneLoadError naming the file and the problem.
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "renderer/description/scene.h"
#include "scene_io/nodes/gltf_animation.h"
#include "scene_io/base/gltf_defects.h"
#include "scene_io/base/gltf_extensions.h"
#include "scene_io/decode/gltf_image_store.h"
#include "scene_io/nodes/gltf_skin.h"

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
  // Motion blur: the shutter is open from time + shutter_open to time + shutter_close
  // (seconds). With motion_steps > 1, what moves in that time is described at that many evenly
  // spaced times (SceneDescription::motion_steps); with 1 the scene is posed at `time` alone.
  float shutter_open = 0.0f, shutter_close = 0.0f;
  int motion_steps = 1;
};

struct GltfLoadResult {
  SceneDescription scene;
  std::vector<std::string> warnings;  // each once, already prefixed with nothing
  std::vector<std::string> material_variants;  // KHR_materials_variants: the names, by index
  int material_variant = -1;  // the variant applied (GltfLoadParams::variant); -1: none
  std::vector<Animation> animations;  // every animation of the file
  std::vector<int> playing;  // the indices of those applied (GltfLoadParams::animation)
  std::size_t morph_meshes = 0;  // meshes with morph targets
  std::vector<Skin> skins;
};

// A glTF file parsed once (tinygltf's model with its buffers and decoded images), to be
// converted at as many times as a frame sequence needs.
struct GltfDocument {
  std::string path;  // as given: errors name it
  tinygltf::Model model;
  GltfDefects defects;  // objects kept as placeholders: refused if used, else warned about
  // The images, encoded; each decoded when a converted scene first shows it, then shared.
  std::shared_ptr<GltfImageStore> images;
  double read_seconds = 0.0;  // read_gltf: reading and parsing (convert_gltf decodes images)
};

GltfDocument read_gltf(const std::string& path);
// The same over bytes in memory (.glb when they start with "glTF", else JSON). External
// resources are looked up relative to base_dir. Used by the fuzzer and tests.
GltfDocument read_gltf_from_memory(const std::vector<std::uint8_t>& bytes, const std::string& display_name,
                                   const std::string& base_dir);

// The document's scene, posed as `params` ask.
GltfLoadResult convert_gltf(const GltfDocument& document, const GltfLoadParams& params = {});

// read_gltf and convert_gltf together.
GltfLoadResult load_gltf(const std::string& path, const GltfLoadParams& params = {});
GltfLoadResult load_gltf_from_memory(const std::vector<std::uint8_t>& bytes,
                                     const std::string& display_name,
                                     const std::string& base_dir,
                                     const GltfLoadParams& params = {});

}  // namespace tessera
