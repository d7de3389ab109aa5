// The meshes' part of gltf_rules.h.
#include <algorithm>
#include <iterator>
#include <map>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "scene_io/base/gltf_json.h"
#include "scene_io/validation/gltf_rules.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

using Json = nlohmann::json;
using Problem = std::optional<std::string>;

// The number of attributes named PREFIX_n.
std::size_t count_sets(const Json& attributes, const std::string& prefix) {
  std::size_t n = 0;
  for (auto it = attributes.begin(); it != attributes.end(); ++it) n += it.key().rfind(prefix, 0) == 0;
  return n;
}

// A vertex attribute's accessor (of the primitive or a morph target, `what` naming it): bounds
// for POSITION, no UNSIGNED_INT, a byteOffset that is a multiple of 4, `count` elements if given.
Problem check_vertex_accessor(const std::string& what, const std::string& name, long long a, const Json& j,
                              std::optional<long long> count = std::nullopt) {
  const Json& accessor = element(j, "accessors", a);
  if (!accessor.is_object()) return std::nullopt;
  if (name == "POSITION" && !has_min_max(accessor))
    return fmt::format("{} POSITION accessor {} has no min and max (glTF requires both)", what, a);
  if (index_of(accessor, "componentType") == 5125)
    return fmt::format("{} {} accessor {} has componentType UNSIGNED_INT (5125), which glTF allows only for indices",
                       what, shorten(name), a);
  if (const long long offset = index_of(accessor, "byteOffset"); offset > 0 && offset % 4 != 0)
    return fmt::format("{} {} accessor {} has byteOffset {} in its bufferView, not a multiple of 4 (glTF requires one "
                       "for vertex data)",
                       what, shorten(name), a, offset);
  if (count && index_of(accessor, "count") != *count)
    return fmt::format("{} {} accessor {} has {} elements, but the primitive's {} has {}", what, shorten(name), a,
                       index_of(accessor, "count"), shorten(name), *count);
  return std::nullopt;
}

// Accessors sharing a vertex bufferView need its byteStride; an index bufferView holds nothing
// else and has none (the validator's MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE,
// BUFFER_VIEW_TARGET_OVERRIDE, MESH_PRIMITIVE_INDICES_ACCESSOR_WITH_BYTESTRIDE).
Problem check_mesh_views(const Json& prims, std::size_t m, const Json& j) {
  std::map<long long, std::set<long long>> vertex;  // bufferView -> accessors
  std::map<long long, std::size_t> index;  // bufferView -> primitive
  for (std::size_t p = 0; p < prims.size(); ++p) {
    std::vector<const Json*> sets = {member(prims[p], "attributes")};
    if (const Json* targets = member(prims[p], "targets"); targets && targets->is_array())
      for (const Json& t : *targets) sets.push_back(&t);
    for (const Json* set : sets) {
      if (!set || !set->is_object()) continue;
      for (auto it = set->begin(); it != set->end(); ++it) {
        const long long a = index_of(*set, it.key().c_str());
        if (const long long v = index_of(element(j, "accessors", a), "bufferView"); v >= 0) vertex[v].insert(a);
      }
    }
    const long long indices = index_of(prims[p], "indices");
    const long long v = index_of(element(j, "accessors", indices), "bufferView");
    if (v < 0) continue;
    if (member(element(j, "bufferViews", v), "byteStride"))
      return fmt::format("mesh {} primitive {} indices accessor {} is in bufferView {}, which has a byteStride (glTF "
                         "forbids one for indices)",
                         m, p, indices, v);
    index.emplace(v, p);
  }
  for (const auto& [v, accessors] : vertex) {
    if (index.count(v))
      return fmt::format("mesh {} uses bufferView {} for both vertex attributes and indices (primitive {}); glTF "
                         "requires separate views",
                         m, v, index[v]);
    if (accessors.size() > 1 && !member(element(j, "bufferViews", v), "byteStride"))
      return fmt::format("mesh {} reads accessors {} and {} from bufferView {}, which has no byteStride (glTF requires "
                         "one when vertex accessors share a view)",
                         m, *accessors.begin(), *std::next(accessors.begin()), v);
  }
  return std::nullopt;
}

Problem check_primitive(const Json& prim, const std::string& what, const Json& j) {
  const Json* attributes = member(prim, "attributes");
  if (!attributes || !attributes->is_object()) return std::nullopt;  // gltf_diagnose.cpp's
  for (auto it = attributes->begin(); it != attributes->end(); ++it)
    if (Problem p = check_vertex_accessor(what, it.key(), index_of(*attributes, it.key().c_str()), j)) return p;
  const std::size_t joints = count_sets(*attributes, "JOINTS_"), weights = count_sets(*attributes, "WEIGHTS_");
  if (joints != weights)
    return fmt::format("{} has {} JOINTS_n and {} WEIGHTS_n attributes; glTF requires as many of each", what, joints,
                       weights);
  const Json* targets = member(prim, "targets");
  for (std::size_t t = 0; t < morph_target_count(prim); ++t) {
    if (!(*targets)[t].is_object()) continue;
    for (auto it = (*targets)[t].begin(); it != (*targets)[t].end(); ++it) {
      if (!member(*attributes, it.key().c_str()))
        return fmt::format("{} morph target {} has {}, which the primitive's attributes lack", what, t,
                           shorten(it.key()));
      const long long a = index_of((*targets)[t], it.key().c_str());
      if (!element(j, "accessors", a).is_object())
        return fmt::format("{} morph target {} {} refers to accessor {}, but the file has {}", what, t,
                           shorten(it.key()), shorten(it->dump()), count_of(array_size(j, "accessors"), "accessor"));
      const long long base = index_of(element(j, "accessors", index_of(*attributes, it.key().c_str())), "count");
      if (Problem p = check_vertex_accessor(fmt::format("{} morph target {}", what, t), it.key(), a, j, base)) return p;
    }
  }
  return std::nullopt;
}

}  // namespace

std::optional<std::string> check_mesh_rules(const Json& mesh, std::size_t m, const Json& j) {
  const Json* prims = member(mesh, "primitives");
  if (!prims || !prims->is_array() || prims->empty()) return std::nullopt;  // gltf_diagnose.cpp's
  const std::size_t targets = morph_target_count((*prims)[0]);
  for (std::size_t p = 0; p < prims->size(); ++p) {
    if (morph_target_count((*prims)[p]) != targets)
      return fmt::format("mesh {} primitives 0 and {} have {} and {} morph targets; glTF requires the same number", m,
                         p, targets, morph_target_count((*prims)[p]));
    if (Problem problem = check_primitive((*prims)[p], fmt::format("mesh {} primitive {}", m, p), j)) return problem;
  }
  if (Problem problem = check_mesh_views(*prims, m, j)) return problem;
  const Json* weights = member(mesh, "weights");
  if (weights && weights->is_array() && weights->size() != targets)
    return fmt::format("mesh {} has {} but {}", m, count_of(weights->size(), "weight"),
                       count_of(targets, "morph target"));
  return std::nullopt;
}

}  // namespace tessera
