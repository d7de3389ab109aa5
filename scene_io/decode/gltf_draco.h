// KHR_draco_mesh_compression: each compressed primitive's Draco stream is decoded, and its
// indices and mapped attributes become plain bufferViews in the component types their
// accessors declare (normalized integers included), before any accessor is read.
#pragma once

#include <string>

#include <tiny_gltf.h>

namespace tessera {

// Throws SceneLoadError(file, ...) naming the mesh, the primitive and the problem.
void decode_draco_primitives(tinygltf::Model& model, const std::string& file);

}  // namespace tessera
