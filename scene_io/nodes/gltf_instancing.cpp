#include "scene_io/nodes/gltf_instancing.h"

#include <cmath>
#include <optional>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>

#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

constexpr const char* kExtension = "EXT_mesh_gpu_instancing";

struct Attribute {
  std::vector<float> values;  // count * components
  std::size_t count = 0;
};

// Attribute `name` of the extension, `components` floats per instance; nullopt when absent.
std::optional<Attribute> read_attribute(const tinygltf::Value& attributes, const char* name, int components,
                                        int node, const AccessorReader& reader) {
  if (!attributes.Has(name)) return std::nullopt;
  const tinygltf::Value& v = attributes.Get(name);
  if (!v.IsNumber())
    throw SceneLoadError(reader.file, fmt::format("node {} has an {} attribute {} that is not an accessor index",
                                                  node, kExtension, name));
  const std::string what = fmt::format("{} of node {}'s {}", name, node, kExtension);
  Attribute a;
  a.values = reader.floats(v.GetNumberAsInt(), components, what);
  a.count = a.values.size() / components;
  return a;
}

}  // namespace

std::vector<glm::mat4> read_gpu_instances(const tinygltf::Node& node, int index, const AccessorReader& reader) {
  const auto ext = node.extensions.find(kExtension);
  if (ext == node.extensions.end()) return {};
  auto fail = [&](const std::string& problem) { throw SceneLoadError(reader.file, problem); };
  if (!ext->second.Has("attributes") || !ext->second.Get("attributes").IsObject())
    fail(fmt::format("node {} has {} without an attributes object", index, kExtension));
  const tinygltf::Value& attributes = ext->second.Get("attributes");
  const auto t = read_attribute(attributes, "TRANSLATION", 3, index, reader);
  const auto r = read_attribute(attributes, "ROTATION", 4, index, reader);
  const auto s = read_attribute(attributes, "SCALE", 3, index, reader);
  std::optional<std::size_t> count;
  for (const auto* a : {&t, &r, &s}) {
    if (!*a) continue;
    if (count && (*a)->count != *count)
      fail(fmt::format("node {} has {} attributes of different counts ({} and {}); they must be equal", index,
                       kExtension, *count, (*a)->count));
    count = (*a)->count;
  }
  if (!count) fail(fmt::format("node {} has {} without TRANSLATION, ROTATION or SCALE", index, kExtension));
  std::vector<glm::mat4> out;
  out.reserve(*count);
  for (std::size_t i = 0; i < *count; ++i) {
    glm::dmat4 m(1.0);
    if (r) {  // glTF stores x, y, z, w
      const float* q = &r->values[4 * i];
      glm::dquat rotation(q[3], q[0], q[1], q[2]);
      if (!(glm::length(rotation) > 1e-6))
        fail(fmt::format("node {} gives {} instance {} a rotation of length 0", index, kExtension, i));
      m = glm::mat4_cast(glm::normalize(rotation));
    }
    if (s)
      for (int c = 0; c < 3; ++c) m[c] *= static_cast<double>(s->values[3 * i + c]);
    if (t) m[3] = glm::dvec4(t->values[3 * i], t->values[3 * i + 1], t->values[3 * i + 2], 1.0);
    out.emplace_back(m);
  }
  return out;
}

}  // namespace tessera
