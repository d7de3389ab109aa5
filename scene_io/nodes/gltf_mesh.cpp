// glTF mesh primitives -> TriangleMesh: attributes, index validation, strips and fans.
#include "scene_io/nodes/gltf_mesh.h"

#include <fmt/format.h>

#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

template <typename Vec, int N>
MeshArray<Vec> to_vectors(const std::vector<float>& flat) {
  MeshArray<Vec> out(flat.size() / N);
  for (std::size_t i = 0; i < out.size(); ++i)
    for (int c = 0; c < N; ++c) out[i][c] = flat[i * N + c];
  return out;
}

// Triangle list from the primitive's (possibly implicit) indices and topology mode.
MeshArray<std::uint32_t> triangulate(const std::vector<std::uint32_t>& idx, int mode, const std::string& what,
                                     std::vector<std::string>& warnings) {
  MeshArray<std::uint32_t> tris;
  if (mode == TINYGLTF_MODE_TRIANGLES) {
    const std::size_t usable = idx.size() - idx.size() % 3;
    if (usable != idx.size())
      warnings.push_back(fmt::format("{}: {} indices is not a multiple of 3; the last {} ignored",
                                     what, idx.size(), idx.size() - usable));
    tris.assign(idx.begin(), idx.begin() + usable);
  } else if (mode == TINYGLTF_MODE_TRIANGLE_STRIP) {
    // Specification: triangle i = {v_i, v_{i+(1+i%2)}, v_{i+(2-i%2)}}, keeping the winding.
    for (std::size_t i = 0; i + 2 < idx.size(); ++i) {
      tris.push_back(idx[i]);
      tris.push_back(idx[i + 1 + i % 2]);
      tris.push_back(idx[i + 2 - i % 2]);
    }
  } else {  // TRIANGLE_FAN: triangle i = {v_{i+1}, v_{i+2}, v_0}
    for (std::size_t i = 0; i + 2 < idx.size(); ++i) {
      tris.push_back(idx[i + 1]);
      tris.push_back(idx[i + 2]);
      tris.push_back(idx[0]);
    }
  }
  return tris;
}

}  // namespace

std::optional<TriangleMesh> convert_primitive(const AccessorReader& reader,
                                              const tinygltf::Primitive& prim,
                                              const std::string& what,
                                              std::vector<std::string>& warnings) {
  const int mode = prim.mode < 0 ? TINYGLTF_MODE_TRIANGLES : prim.mode;
  if (mode < TINYGLTF_MODE_TRIANGLES) {
    warnings.push_back("points and lines are not rendered; such primitives were skipped");
    return std::nullopt;
  }
  if (mode > TINYGLTF_MODE_TRIANGLE_FAN)
    throw SceneLoadError(reader.file, fmt::format("{} has unknown mode {} (glTF modes are 0 to 6)",
                                                  what, mode));

  auto attribute = [&](const char* name) {
    auto it = prim.attributes.find(name);
    return it == prim.attributes.end() ? -1 : it->second;
  };
  const int position = attribute("POSITION");
  if (position < 0)
    throw SceneLoadError(reader.file, what + " has no POSITION attribute");

  TriangleMesh mesh;
  mesh.positions = to_vectors<glm::vec3, 3>(reader.floats(position, 3, "POSITION of " + what));
  const std::size_t n = mesh.positions.size();
  auto sized = [&](auto&& values, int a, const char* name) {
    if (values.size() != n)
      throw SceneLoadError(reader.file,
                           fmt::format("accessor {} ({} of {}) has {} elements, but POSITION "
                                       "(accessor {}) has {}",
                                       a, name, what, values.size(), position, n));
    return std::move(values);
  };
  if (int a = attribute("NORMAL"); a >= 0)
    mesh.normals = sized(to_vectors<glm::vec3, 3>(reader.floats(a, 3, "NORMAL of " + what)), a, "NORMAL");
  if (int a = attribute("TANGENT"); a >= 0)
    mesh.tangents = sized(to_vectors<glm::vec4, 4>(reader.floats(a, 4, "TANGENT of " + what)), a, "TANGENT");
  if (int a = attribute("TEXCOORD_0"); a >= 0)
    mesh.texcoords0 = sized(to_vectors<glm::vec2, 2>(reader.floats(a, 2, "TEXCOORD_0 of " + what)), a, "TEXCOORD_0");
  if (int a = attribute("TEXCOORD_1"); a >= 0)
    mesh.texcoords1 = sized(to_vectors<glm::vec2, 2>(reader.floats(a, 2, "TEXCOORD_1 of " + what)), a, "TEXCOORD_1");
  if (int a = attribute("COLOR_0"); a >= 0) {
    const int components = gltf_component_count(reader.accessor(a, "COLOR_0 of " + what).type);
    if (components == 3) {
      for (const glm::vec3& c : to_vectors<glm::vec3, 3>(reader.floats(a, 3, "COLOR_0 of " + what)))
        mesh.colors.emplace_back(c, 1.0f);
    } else {
      mesh.colors = to_vectors<glm::vec4, 4>(reader.floats(a, 4, "COLOR_0 of " + what));
    }
    sized(MeshArray<glm::vec4>(mesh.colors), a, "COLOR_0");
  }

  std::vector<std::uint32_t> idx;
  if (prim.indices >= 0) {
    idx = reader.indices(prim.indices, "indices of " + what);
    for (std::size_t i = 0; i < idx.size(); ++i)
      if (idx[i] >= n)
        throw SceneLoadError(reader.file, fmt::format("accessor {} (indices of {}) holds index {} "
                                                      "at element {}, but the primitive has {}",
                                                      prim.indices, what, idx[i], i,
                                                      count_of(n, "vertex", "vertices")));
  } else {
    idx.resize(n);
    for (std::size_t i = 0; i < n; ++i) idx[i] = static_cast<std::uint32_t>(i);
  }
  mesh.indices = triangulate(idx, mode, what, warnings);
  mesh.material = prim.material;
  return mesh;
}

void apply_morph_targets(const AccessorReader& reader, const tinygltf::Primitive& prim, const std::vector<float>& weights,
                         const std::string& what, TriangleMesh& mesh) {
  if (prim.targets.empty()) return;
  if (weights.size() != prim.targets.size())
    throw SceneLoadError(reader.file, fmt::format("{} has {} but {} morph weights", what,
                                                  count_of(prim.targets.size(), "morph target"), weights.size()));
  const std::size_t n = mesh.positions.size();
  for (std::size_t t = 0; t < prim.targets.size(); ++t) {
    if (weights[t] == 0.0f) continue;
    for (const auto& [name, accessor] : prim.targets[t]) {
      const std::string use = fmt::format("{} of morph target {} of {}", name, t, what);
      const int width = name == "POSITION" || name == "NORMAL" || name == "TANGENT" ? 3 : 0;
      if (width == 0) continue;  // other attributes (TEXCOORD_n, COLOR_n) are not morphed here
      const std::vector<float> d = reader.floats(accessor, 3, use);
      if (d.size() != 3 * n)
        throw SceneLoadError(reader.file, fmt::format("accessor {} ({}) has {} elements, but POSITION has {}", accessor,
                                                      use, d.size() / 3, n));
      auto delta = [&](std::size_t i) { return weights[t] * glm::vec3(d[3 * i], d[3 * i + 1], d[3 * i + 2]); };
      if (name == "POSITION")
        for (std::size_t i = 0; i < n; ++i) mesh.positions[i] += delta(i);
      else if (name == "NORMAL" && !mesh.normals.empty())
        for (std::size_t i = 0; i < n; ++i) mesh.normals[i] += delta(i);
      else if (name == "TANGENT" && !mesh.tangents.empty())
        for (std::size_t i = 0; i < n; ++i) mesh.tangents[i] += glm::vec4(delta(i), 0.0f);
    }
  }
  for (glm::vec3& v : mesh.normals) v = glm::length(v) > 0.0f ? glm::normalize(v) : v;
  for (glm::vec4& v : mesh.tangents) {
    const float len = glm::length(glm::vec3(v));
    if (len > 0.0f) v = glm::vec4(glm::vec3(v) / len, v.w);
  }
}

}  // namespace tessera
