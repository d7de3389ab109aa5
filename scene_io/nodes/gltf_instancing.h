// EXT_mesh_gpu_instancing: a node that places its mesh many times, each placement given by
// per-instance TRANSLATION, ROTATION and SCALE accessors (float, or quantized integers as
// KHR_mesh_quantization allows). Each instance is placed at node world * T * R * S.
#pragma once

#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "scene_io/base/gltf_accessor.h"

namespace tessera {

// The local T * R * S of every instance node `index` declares; empty when the node has no
// EXT_mesh_gpu_instancing. Throws SceneLoadError for attributes of different counts, of the
// wrong type, or a rotation of length 0.
std::vector<glm::mat4> read_gpu_instances(const tinygltf::Node& node, int index, const AccessorReader& reader);

}  // namespace tessera
