// glTF 2.0 skins (the specification's 3.7.3): a skinned mesh's vertices follow its joints.
// Each joint's matrix is its node's world transform times its inverse bind matrix, and a
// vertex is the weighted blend of its joints' matrices applied to it, in world space (the
// skinned node's own transform is ignored, as the specification requires).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <tiny_gltf.h>

#include "renderer/description/scene.h"
#include "scene_io/base/gltf_accessor.h"

namespace tessera {

struct Skin {
  std::string name;
  std::vector<int> joints;  // node indices
  std::vector<glm::mat4> inverse_bind;  // one per joint (identity when the file gives none)
  int skeleton = -1;  // the common root of the joints' hierarchy, when the file names it
};

// Skin `index` of the file. Throws SceneLoadError for no joints, joints or a skeleton that are
// not nodes, or inverse bind matrices that are not one MAT4 per joint.
Skin read_skin(const tinygltf::Model& model, std::size_t index, const AccessorReader& reader, const std::string& file);

// "skin 2", or the skin's name.
std::string skin_name(const tinygltf::Model& model, std::size_t index);

// Which joints move a primitive's vertices, and how much: every JOINTS_n/WEIGHTS_n set,
// `per_vertex` = 4 x the number of sets entries per vertex.
struct SkinInfluences {
  int per_vertex = 0;
  std::vector<std::uint32_t> joints;  // index into Skin::joints
  std::vector<float> weights;
};

// Throws SceneLoadError for sets without their pair, counts that differ from the vertex count,
// joint indices beyond the skin's joints, or negative weights.
SkinInfluences read_skin_influences(const AccessorReader& reader, const tinygltf::Primitive& prim,
                                    std::size_t vertex_count, std::size_t joint_count, const std::string& what);

// The skin's joint matrices: joint_world[j] * inverse_bind[j], joint_world[j] being the world
// transform of node skin.joints[j].
std::vector<glm::mat4> joint_matrices(const Skin& skin, const std::vector<glm::mat4>& joint_world);

// Moves the mesh's positions, normals and tangents to where its joints put them (world
// space). Weights are used normalised to sum 1; a vertex with no weight keeps its place.
void apply_skin(const SkinInfluences& influences, const std::vector<glm::mat4>& joints, TriangleMesh& mesh);

}  // namespace tessera
