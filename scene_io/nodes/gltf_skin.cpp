#include "scene_io/nodes/gltf_skin.h"

#include <fmt/format.h>
#include <glm/gtc/type_ptr.hpp>

#include "scene_io/base/load_error.h"

namespace tessera {

namespace {

// True when `node` is `ancestor` or below it (the hierarchy has been checked: a forest).
bool is_ancestor_or_self(const tinygltf::Model& model, int ancestor, int node) {
  std::vector<int> stack = {ancestor};
  while (!stack.empty()) {
    const int n = stack.back();
    stack.pop_back();
    if (n == node) return true;
    if (n >= 0 && n < static_cast<int>(model.nodes.size()))
      stack.insert(stack.end(), model.nodes[n].children.begin(), model.nodes[n].children.end());
  }
  return false;
}

}  // namespace

std::string skin_name(const tinygltf::Model& model, std::size_t index) {
  const std::string& name = model.skins[index].name;
  return name.empty() ? fmt::format("skin {}", index) : name;
}

Skin read_skin(const tinygltf::Model& model, std::size_t s, const AccessorReader& reader, const std::string& file) {
  const int nodes = static_cast<int>(model.nodes.size());
  const tinygltf::Skin& src = model.skins[s];
  Skin skin;
  skin.name = skin_name(model, s);
  if (src.joints.empty()) throw SceneLoadError(file, fmt::format("skin {} has no joints", s));
  for (int j : src.joints)
    if (j < 0 || j >= nodes)
      throw SceneLoadError(file, fmt::format("skin {} has joint node {}, but the file has {}", s, j,
                                             count_of(model.nodes.size(), "node")));
  if (src.skeleton >= nodes)
    throw SceneLoadError(file, fmt::format("skin {} has skeleton node {}, but the file has {}", s, src.skeleton,
                                           count_of(model.nodes.size(), "node")));
  if (src.skeleton >= 0)
    for (int j : src.joints)
      if (!is_ancestor_or_self(model, src.skeleton, j))
        throw SceneLoadError(file, fmt::format("skin {} has skeleton node {}, which is not an ancestor of its joint "
                                               "node {}", s, src.skeleton, j));
  skin.joints = src.joints;
  skin.skeleton = src.skeleton;
  skin.inverse_bind.assign(src.joints.size(), glm::mat4(1.0f));
  if (src.inverseBindMatrices >= 0) {
    const std::string what = fmt::format("inverseBindMatrices of skin {}", s);
    if (reader.accessor(src.inverseBindMatrices, what).type != TINYGLTF_TYPE_MAT4)
      throw SceneLoadError(file, fmt::format("accessor {} ({}) is not MAT4", src.inverseBindMatrices, what));
    const std::vector<float> m = reader.floats(src.inverseBindMatrices, 16, what);
    if (m.size() != 16 * src.joints.size())
      throw SceneLoadError(file, fmt::format("accessor {} ({}) has {} matrices for {}", src.inverseBindMatrices,
                                             what, m.size() / 16, count_of(src.joints.size(), "joint")));
    for (std::size_t j = 0; j < src.joints.size(); ++j) skin.inverse_bind[j] = glm::make_mat4(&m[16 * j]);
  }
  return skin;
}

SkinInfluences read_skin_influences(const AccessorReader& reader, const tinygltf::Primitive& prim,
                                    std::size_t vertex_count, std::size_t joint_count, const std::string& what) {
  std::vector<std::vector<float>> joint_sets, weight_sets;
  for (int set = 0;; ++set) {
    const auto joints = prim.attributes.find(fmt::format("JOINTS_{}", set));
    const auto weights = prim.attributes.find(fmt::format("WEIGHTS_{}", set));
    const bool has_joints = joints != prim.attributes.end(), has_weights = weights != prim.attributes.end();
    if (!has_joints && !has_weights) break;
    if (has_joints != has_weights)
      throw SceneLoadError(reader.file, fmt::format("{} has {}_{} without {}_{}", what, has_joints ? "JOINTS" : "WEIGHTS",
                                                    set, has_joints ? "WEIGHTS" : "JOINTS", set));
    joint_sets.push_back(reader.floats(joints->second, 4, fmt::format("JOINTS_{} of {}", set, what)));
    weight_sets.push_back(reader.floats(weights->second, 4, fmt::format("WEIGHTS_{} of {}", set, what)));
    if (joint_sets.back().size() != 4 * vertex_count || weight_sets.back().size() != 4 * vertex_count)
      throw SceneLoadError(reader.file, fmt::format("{} has {} joints and {} weights in set {} for {}", what,
                                                    joint_sets.back().size() / 4, weight_sets.back().size() / 4, set,
                                                    count_of(vertex_count, "vertex", "vertices")));
  }
  SkinInfluences out;
  out.per_vertex = static_cast<int>(4 * joint_sets.size());
  out.joints.resize(out.per_vertex * vertex_count);
  out.weights.resize(out.per_vertex * vertex_count);
  for (std::size_t set = 0; set < joint_sets.size(); ++set)
    for (std::size_t v = 0; v < vertex_count; ++v)
      for (int c = 0; c < 4; ++c) {
        const float joint = joint_sets[set][4 * v + c], weight = weight_sets[set][4 * v + c];
        if (!(weight >= 0.0f) || !std::isfinite(weight))
          throw SceneLoadError(reader.file, fmt::format("WEIGHTS_{} of {} has weight {} at vertex {}", set, what,
                                                        weight, v));
        if (weight > 0.0f && !(joint < static_cast<float>(joint_count)))
          throw SceneLoadError(reader.file, fmt::format("JOINTS_{} of {} has joint {} at vertex {}, but the skin has {}",
                                                        set, what, joint, v, count_of(joint_count, "joint")));
        const std::size_t slot = v * out.per_vertex + 4 * set + c;
        out.joints[slot] = weight > 0.0f ? static_cast<std::uint32_t>(joint) : 0;
        out.weights[slot] = weight;
      }
  return out;
}

std::vector<glm::mat4> joint_matrices(const Skin& skin, const std::vector<glm::mat4>& joint_world) {
  std::vector<glm::mat4> out(skin.joints.size());
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = joint_world[j] * skin.inverse_bind[j];
  return out;
}

void apply_skin(const SkinInfluences& influences, const std::vector<glm::mat4>& joints, TriangleMesh& mesh) {
  const int k = influences.per_vertex;
  for (std::size_t v = 0; v < mesh.positions.size(); ++v) {
    glm::mat4 m(0.0f);
    float total = 0.0f;
    for (int i = 0; i < k; ++i) {
      const float w = influences.weights[v * k + i];
      if (w > 0.0f) m += w * joints[influences.joints[v * k + i]], total += w;
    }
    if (!(total > 0.0f)) continue;
    m /= total;
    mesh.positions[v] = glm::vec3(m * glm::vec4(mesh.positions[v], 1.0f));
    const glm::mat3 linear(m);
    if (!mesh.normals.empty()) {
      const glm::vec3 n = glm::transpose(glm::inverse(linear)) * mesh.normals[v];
      if (glm::length(n) > 0.0f && all_finite(n)) mesh.normals[v] = glm::normalize(n);
    }
    if (!mesh.tangents.empty()) {
      const glm::vec3 t = linear * glm::vec3(mesh.tangents[v]);
      if (glm::length(t) > 0.0f) mesh.tangents[v] = glm::vec4(glm::normalize(t), mesh.tangents[v].w);
    }
  }
}

}  // namespace tessera
