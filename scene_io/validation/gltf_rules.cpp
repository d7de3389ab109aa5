#include "scene_io/validation/gltf_rules.h"

#include <algorithm>
#include <functional>
#include <map>
#include <optional>

#include <fmt/format.h>

#include "scene_io/base/gltf_json.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

using Json = nlohmann::json;
using Problem = std::optional<std::string>;

Problem check_accessor(const Json& a, std::size_t i, const Json&) {
  const long long type = index_of(a, "componentType");
  const Json* normalized = member(a, "normalized");
  if (normalized && *normalized == true && (type == 5125 || type == 5126))
    return fmt::format("accessor {} is normalized, but its componentType {} is not a byte or short type; only those "
                       "can be",
                       i, type);
  return std::nullopt;
}

Problem check_buffer_view(const Json& v, std::size_t i, const Json&) {
  if (member(v, "byteStride") && index_of(v, "target") == 34963)
    return fmt::format("bufferView {} has a byteStride but holds indices (target 34963); only vertex data has one", i);
  return std::nullopt;
}

Problem check_camera(const Json& c, std::size_t i, const Json&) {
  if (member(c, "perspective") && member(c, "orthographic"))
    return fmt::format("camera {} has both a \"perspective\" and an \"orthographic\" object; glTF allows only the "
                       "one its type names",
                       i);
  return std::nullopt;
}

Problem check_node(const Json& node, std::size_t i, const Json& j) {
  const Json* matrix = member(node, "matrix");
  if (matrix && matrix->is_array() && matrix->size() == 16 &&
      std::all_of(matrix->begin(), matrix->end(), [](const Json& v) { return v.is_number(); }) &&
      ((*matrix)[3] != 0 || (*matrix)[7] != 0 || (*matrix)[11] != 0 || (*matrix)[15] != 1))
    return fmt::format("node {} has a matrix whose last row is not 0, 0, 0, 1, so not a translation, rotation and "
                       "scale (glTF requires one)",
                       i);
  const bool mesh = member(node, "mesh") != nullptr;
  if (member(node, "skin") && !mesh) return fmt::format("node {} has a skin but no mesh", i);
  if (member(node, "weights") && !mesh) return fmt::format("node {} has morph weights but no mesh", i);
  const long long skin = index_of(node, "skin");
  if (skin != -1 && !element(j, "skins", skin).is_object())
    return fmt::format("node {} refers to skin {}, but the file has {}", i, shorten(member(node, "skin")->dump()),
                       count_of(array_size(j, "skins"), "skin"));
  return std::nullopt;
}

// Every node's parent (-1: a root); a node claimed by two parents keeps the first.
std::vector<long long> parents_of(const Json& j) {
  std::vector<long long> parent(array_size(j, "nodes"), -1);
  for (std::size_t n = 0; n < parent.size(); ++n) {
    const Json* children = member((*member(j, "nodes"))[n], "children");
    if (!children || !children->is_array()) continue;
    for (const Json& c : *children)
      if (c.is_number_unsigned() && c.get<std::uint64_t>() < parent.size() && parent[c.get<std::size_t>()] == -1)
        parent[c.get<std::size_t>()] = static_cast<long long>(n);
  }
  return parent;
}

Problem check_skin(const Json& skin, std::size_t i, const Json& j) {
  const Json* joints = member(skin, "joints");
  if (!joints || !joints->is_array()) return std::nullopt;  // gltf_diagnose.cpp's
  const std::vector<long long> parent = parents_of(j);
  auto root = [&](long long n) {  // at most one step per node: a cycle ends the climb
    for (std::size_t steps = 0; parent[n] >= 0 && steps < parent.size(); ++steps) n = parent[n];
    return n;
  };
  std::optional<std::pair<long long, long long>> first;  // joint, its root
  for (const Json& joint : *joints) {
    if (!joint.is_number_unsigned() || joint.get<std::uint64_t>() >= parent.size()) continue;
    const long long n = joint.get<long long>(), r = root(n);
    if (!first) first = {n, r};
    if (r != first->second)
      return fmt::format("skin {}'s joints {} and {} have no common root (glTF requires one)", i, first->first, n);
  }
  return std::nullopt;
}

bool has_morph_targets(const Json& node, const Json& j) {
  const Json* prims = member(element(j, "meshes", index_of(node, "mesh")), "primitives");
  return prims && prims->is_array() && !prims->empty() && morph_target_count((*prims)[0]) > 0;
}

Problem check_animation(const Json& animation, std::size_t i, const Json& j) {
  const Json* channels = member(animation, "channels");
  std::map<std::pair<long long, std::string>, std::size_t> targets;
  for (std::size_t c = 0; channels && channels->is_array() && c < channels->size(); ++c) {
    const Json* target = member((*channels)[c], "target");
    const Json* path = target ? member(*target, "path") : nullptr;
    const long long node = target ? index_of(*target, "node") : -1;
    if (node < 0 || !path || !path->is_string()) continue;
    const auto [it, added] = targets.emplace(std::make_pair(node, path->get<std::string>()), c);
    if (!added)
      return fmt::format("animation {} channels {} and {} both animate node {}'s {}", i, it->second, c, node,
                         shorten(path->get<std::string>()));
    if (*path == "weights" && element(j, "nodes", node).is_object() && !has_morph_targets(element(j, "nodes", node), j))
      return fmt::format("animation {} channel {} animates the weights of node {}, which has no mesh with morph "
                         "targets",
                         i, c, node);
  }
  const Json* samplers = member(animation, "samplers");
  for (std::size_t s = 0; samplers && samplers->is_array() && s < samplers->size(); ++s) {
    const long long input = index_of((*samplers)[s], "input");
    const Json& accessor = element(j, "accessors", input);
    if (accessor.is_object() && !has_min_max(accessor))
      return fmt::format("animation {} sampler {} input accessor {} has no min and max (glTF requires both)", i, s,
                         input);
    const Json* interpolation = member((*samplers)[s], "interpolation");
    if (accessor.is_object() && interpolation && *interpolation == "CUBICSPLINE" && index_of(accessor, "count") < 2)
      return fmt::format("animation {} sampler {} is CUBICSPLINE with {}; glTF requires at least 2", i, s,
                         count_of(static_cast<std::size_t>(std::max(index_of(accessor, "count"), 0LL)), "keyframe"));
  }
  return std::nullopt;
}

using Check = std::function<Problem(const Json&, std::size_t, const Json&)>;

void check_all(const Json& j, const char* key, const char* noun, const Check& check, GltfRuleProblems& out) {
  const Json* array = member(j, key);
  for (std::size_t i = 0; array && array->is_array() && i < array->size(); ++i)
    if (Problem p = (*array)[i].is_object() ? check((*array)[i], i, j) : std::nullopt)
      out.objects.push_back({key, i, fmt::format("{} {}", noun, i), std::move(*p)});
}

}  // namespace

GltfRuleProblems find_rule_problems(const Json& j) {
  GltfRuleProblems out;
  check_all(j, "accessors", "accessor", check_accessor, out);
  check_all(j, "bufferViews", "bufferView", check_buffer_view, out);
  check_all(j, "cameras", "camera", check_camera, out);
  check_all(j, "meshes", "mesh", check_mesh_rules, out);
  check_all(j, "nodes", "node", check_node, out);
  check_all(j, "skins", "skin", check_skin, out);
  check_all(j, "animations", "animation", check_animation, out);
  find_file_and_extension_problems(j, out);
  return out;
}

}  // namespace tessera
