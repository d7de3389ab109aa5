// EXT_meshopt_compression: each compressed bufferView is decoded (meshoptimizer's vertex,
// triangle and index codecs, then the OCTAHEDRAL, QUATERNION or EXPONENTIAL filter) and its
// bytes replaced by the decoded ones, before any accessor is read.
#pragma once

#include <string>

#include <tiny_gltf.h>

namespace tessera {

// Throws SceneLoadError(file, ...) naming the bufferView and the problem.
void decode_meshopt_views(tinygltf::Model& model, const std::string& file);

}  // namespace tessera
