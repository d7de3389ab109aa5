// glTF 2.0 -> SceneDescription: parsing (tinygltf), extension policy, scene and node
// traversal, cameras and punctual lights. Meshes and materials live in their own files.
#include "scene_io/gltf_loader.h"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "scene_io/gltf_accessor.h"
#include "scene_io/gltf_hierarchy.h"
#include "scene_io/gltf_material.h"
#include "scene_io/gltf_mesh.h"
#include "scene_io/gltf_parse.h"
#include "scene_io/gltf_variants.h"
#include "scene_io/load_error.h"

namespace tessera {

const std::vector<std::string>& supported_gltf_extensions() {
  static const std::vector<std::string> names = {
      "KHR_lights_punctual",
      "KHR_materials_anisotropy",
      "KHR_materials_clearcoat",
      "KHR_materials_diffuse_transmission",
      "KHR_materials_dispersion",
      "KHR_materials_emissive_strength",
      "KHR_materials_ior",
      "KHR_materials_iridescence",
      "KHR_materials_sheen",
      "KHR_materials_specular",
      "KHR_materials_transmission",
      "KHR_materials_unlit",
      "KHR_materials_variants",
      "KHR_materials_volume",
      "KHR_mesh_quantization",
      "KHR_texture_transform"};
  return names;
}

bool is_supported_gltf_extension(const std::string& name) {
  const auto& s = supported_gltf_extensions();
  return std::find(s.begin(), s.end(), name) != s.end();
}

namespace {

template <typename Vector>
bool fits_float(const Vector& values) {
  return std::all_of(values.begin(), values.end(), [](double x) {
    return std::isfinite(x) && std::abs(x) <= std::numeric_limits<float>::max();
  });
}

bool finite_matrix(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    if (!all_finite(m[c])) return false;
  return true;
}

class Converter {
 public:
  Converter(const tinygltf::Model& model, const std::string& file, GltfLoadResult& result)
      : model_(model), file_(file), result_(result), out_(result.scene), warnings_(result.warnings),
        reader_{model, file} {}

  void run(const GltfLoadParams& params) {
    check_extensions();
    out_.materials = convert_materials(model_, file_, warnings_);
    result_.material_variants = read_material_variants(model_, file_);
    if (!params.variant.empty())
      result_.material_variant = choose_material_variant(result_.material_variants, params.variant, file_);
    out_.images = convert_images(model_, file_);
    const std::vector<int> parent = check_node_hierarchy(model_, file_);
    result_.animations = read_animations(model_, reader_, file_);
    result_.playing = choose_animations(result_.animations, params.animation, file_);
    poses_ = pose_nodes(result_.animations, result_.playing, params.time, model_.nodes.size());
    for (const tinygltf::Mesh& m : model_.meshes)
      result_.morph_meshes += std::any_of(m.primitives.begin(), m.primitives.end(),
                                          [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
    result_.skins = model_.skins.size();
    if (result_.skins > 0) warnings_.push_back("skins are not applied yet: skinned meshes render in their bind pose");
    traverse(scene_roots(model_, choose_scene(params.scene), parent, file_));
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw SceneLoadError(file_, problem); }

  // The morph weights node `index` gives its mesh: animated, else the node's, else the mesh's,
  // else zero. Empty when the mesh has no targets or every weight is 0 (the base shape).
  std::vector<float> morph_weights(const tinygltf::Node& node, int index) const {
    const tinygltf::Mesh& mesh = model_.meshes[node.mesh];
    std::size_t targets = 0;
    for (const tinygltf::Primitive& p : mesh.primitives) targets = std::max(targets, p.targets.size());
    if (targets == 0) return {};
    std::vector<float> w(targets, 0.0f);
    if (!poses_[index].weights.empty()) w = poses_[index].weights;
    else if (!node.weights.empty()) w.assign(node.weights.begin(), node.weights.end());
    else if (!mesh.weights.empty()) w.assign(mesh.weights.begin(), mesh.weights.end());
    if (!fits_float(w)) fail(fmt::format("node {} has morph weights beyond the range of 32-bit floats", index));
    return std::all_of(w.begin(), w.end(), [](float x) { return x == 0.0f; }) ? std::vector<float>{} : w;
  }

  void check_extensions() {
    out_.extensions_used = model_.extensionsUsed;
    out_.extensions_required = model_.extensionsRequired;
    for (const std::string& ext : model_.extensionsRequired)
      if (!is_supported_gltf_extension(ext))
        fail(fmt::format("requires extension {}, which tessera does not support", ext));
    for (const std::string& ext : model_.extensionsUsed)
      if (!is_supported_gltf_extension(ext))
        warnings_.push_back(fmt::format("extension {} is not supported and is ignored", ext));
  }

  // The scene to load: `wanted` by name, else by index; empty = the default scene, else 0.
  // -1 when the file has no scenes (then every parentless node is a root).
  int choose_scene(const std::string& wanted) {
    const auto& scenes = model_.scenes;
    if (scenes.empty()) {
      if (!wanted.empty()) fail(fmt::format("has no scenes, so scene '{}' cannot be chosen", wanted));
      return -1;
    }
    int index = model_.defaultScene >= 0 ? model_.defaultScene : 0;
    if (!wanted.empty()) {
      index = -1;
      for (std::size_t i = 0; i < scenes.size() && index < 0; ++i)
        if (scenes[i].name == wanted) index = static_cast<int>(i);
      const bool numeric = std::all_of(wanted.begin(), wanted.end(), ::isdigit);
      if (index < 0 && numeric && wanted.size() < 9) index = std::stoi(wanted);
      if (index < 0 || index >= static_cast<int>(scenes.size())) {
        std::string names;
        for (std::size_t i = 0; i < scenes.size(); ++i)
          names += fmt::format("{}{}{}", i ? ", " : "", i,
                               scenes[i].name.empty() ? "" : " '" + scenes[i].name + "'");
        fail(fmt::format("has no scene '{}' (it has {}: {})", wanted,
                         count_of(scenes.size(), "scene"), names));
      }
    } else if (index >= static_cast<int>(scenes.size())) {
      fail(fmt::format("its default scene is {}, but the file has {}", index,
                       count_of(scenes.size(), "scene")));
    }
    out_.scene_name = scenes[index].name.empty() ? std::to_string(index) : scenes[index].name;
    return index;
  }

  // Depth first, children in order, without recursion: hierarchies can be deep.
  void traverse(const std::vector<int>& roots) {
    std::vector<std::pair<int, glm::mat4>> stack;
    for (auto r = roots.rbegin(); r != roots.rend(); ++r) stack.emplace_back(*r, glm::mat4(1.0f));
    while (!stack.empty()) {
      const auto [index, parent_to_world] = stack.back();
      stack.pop_back();
      const tinygltf::Node& node = model_.nodes[index];
      const glm::mat4 world = parent_to_world * local_transform(node, index);
      if (!finite_matrix(world))
        fail(fmt::format("node {} has a world transform (its own composed with its ancestors') "
                         "beyond the range of 32-bit floats", index));
      if (node.mesh >= 0) add_instance(node, index, world);
      if (node.camera >= 0) add_camera(node, index, world);
      if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end())
        add_light(it->second, index, world);
      for (auto c = node.children.rbegin(); c != node.children.rend(); ++c) stack.emplace_back(*c, world);
    }
  }

  glm::mat4 local_transform(const tinygltf::Node& node, int index) const {
    auto check = [&](const std::vector<double>& v, const char* what, std::size_t size) {
      if (!v.empty() && v.size() != size)
        fail(fmt::format("node {} has a {} of {} numbers; it needs {}", index, what, v.size(), size));
      if (!fits_float(v))
        fail(fmt::format("node {} has a {} beyond the range of 32-bit floats", index, what));
    };
    if (!node.matrix.empty()) {
      check(node.matrix, "matrix", 16);
      return glm::mat4(glm::make_mat4(node.matrix.data()));  // column-major, as glTF stores it
    }
    check(node.translation, "translation", 3);
    check(node.rotation, "rotation", 4);
    check(node.scale, "scale", 3);
    glm::dvec3 t(0.0), s(1.0);
    glm::dquat r(1.0, 0.0, 0.0, 0.0);
    if (!node.translation.empty()) t = glm::make_vec3(node.translation.data());
    if (!node.scale.empty()) s = glm::make_vec3(node.scale.data());
    const NodePose& pose = poses_[index];  // what the playing animations drive
    if (pose.translated) t = glm::dvec3(pose.translation);
    if (pose.scaled) s = glm::dvec3(pose.scale);
    if (pose.rotated) {
      r = glm::dquat(pose.rotation);
      if (!(glm::length(r) > 1e-6)) fail(fmt::format("node {} is animated to a rotation of length 0", index));
      r = glm::normalize(r);
    } else if (!node.rotation.empty()) {  // glTF stores x, y, z, w
      r = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      if (!(glm::length(r) > 1e-6))
        fail(fmt::format("node {} has a rotation quaternion of length {}; it must be a unit quaternion",
                         index, glm::length(r)));
      r = glm::normalize(r);
    }
    glm::dmat4 m = glm::mat4_cast(r);
    m[0] *= s.x;
    m[1] *= s.y;
    m[2] *= s.z;
    m[3] = glm::dvec4(t, 1.0);
    const glm::mat4 local(m);
    if (!finite_matrix(local))
      fail(fmt::format("node {} has a transform beyond the range of 32-bit floats", index));
    return local;
  }

  void add_instance(const tinygltf::Node& node, int index, const glm::mat4& world) {
    if (node.mesh >= static_cast<int>(model_.meshes.size()))
      fail(fmt::format("node {} refers to mesh {}, but the file has {}", index, node.mesh,
                       count_of(model_.meshes.size(), "mesh")));
    // A mesh with no triangles (only points or lines) is neither stored nor placed. A morphed
    // mesh is the node's own (another node may weigh its targets differently).
    const std::vector<float> weights = morph_weights(node, index);
    auto [it, inserted] = mesh_slot_.try_emplace(weights.empty() ? node.mesh : -1 - index, -1);
    if (inserted) {
      Mesh mesh = convert_mesh(node.mesh, weights);
      if (!mesh.primitives.empty()) {
        it->second = static_cast<int>(out_.meshes.size());
        out_.meshes.push_back(std::move(mesh));
      }
    }
    if (it->second < 0) return;
    out_.instances.push_back({it->second, world, node.name});
    Bounds3 placed;  // finite matrices and positions can still overflow together
    for (const TriangleMesh& prim : out_.meshes[it->second].primitives)
      for (const glm::vec3& p : prim.positions) placed.extend(glm::vec3(world * glm::vec4(p, 1.0f)));
    if (!all_finite(placed.lo) || !all_finite(placed.hi))
      fail(fmt::format("node {} places mesh {} beyond the range of 32-bit floats", index, node.mesh));
    out_.bounds.extend(placed);
  }

  Mesh convert_mesh(int index, const std::vector<float>& weights) {
    const tinygltf::Mesh& src = model_.meshes[index];
    Mesh mesh;
    mesh.name = src.name.empty() ? fmt::format("mesh {}", index) : src.name;
    for (std::size_t p = 0; p < src.primitives.size(); ++p) {
      const std::string what = fmt::format("mesh {} primitive {}", index, p);
      auto prim = convert_primitive(reader_, src.primitives[p], what, warnings_);
      if (!prim) continue;
      if (!weights.empty()) apply_morph_targets(reader_, src.primitives[p], weights, what, *prim);
      prim->material = material_for_variant(src.primitives[p], result_.material_variant,
                                            result_.material_variants.size(), out_.materials.size(), file_, what);
      if (prim->material >= static_cast<int>(out_.materials.size()))
        fail(fmt::format("{} refers to material {}, but the file has {}", what, prim->material,
                         count_of(out_.materials.size(), "material")));
      if (!prim->indices.empty()) mesh.primitives.push_back(std::move(*prim));
    }
    return mesh;
  }

  void add_camera(const tinygltf::Node& node, int index, const glm::mat4& world) {
    if (node.camera >= static_cast<int>(model_.cameras.size()))
      fail(fmt::format("node {} refers to camera {}, but the file has {}", index, node.camera,
                       count_of(model_.cameras.size(), "camera")));
    const tinygltf::Camera& src = model_.cameras[node.camera];
    Camera cam;
    cam.name = !src.name.empty() ? src.name : !node.name.empty() ? node.name
                                                                 : fmt::format("camera {}", node.camera);
    // Cameras ignore the node's scale: keep an orthonormal frame and the position.
    glm::vec3 x = glm::vec3(world[0]), y = glm::vec3(world[1]);
    glm::vec3 z = glm::normalize(glm::cross(x, y));
    x = glm::normalize(x);
    y = glm::cross(z, x);
    if (!all_finite((z)))
      fail(fmt::format("node {} places camera {} with a degenerate transform", index, node.camera));
    cam.camera_to_world = glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), world[3]);
    if (src.type == "orthographic") {
      cam.projection = Camera::Projection::Orthographic;
      cam.xmag = static_cast<float>(std::abs(src.orthographic.xmag));
      cam.ymag = static_cast<float>(std::abs(src.orthographic.ymag));
      cam.znear = static_cast<float>(src.orthographic.znear);
      cam.zfar = static_cast<float>(src.orthographic.zfar);
      if (!(cam.xmag > 0 && cam.ymag > 0 && std::isfinite(cam.xmag) && std::isfinite(cam.ymag)))
        fail(fmt::format("camera {} has invalid xmag/ymag", node.camera));
    } else if (src.type == "perspective") {
      cam.yfov = static_cast<float>(src.perspective.yfov);
      cam.aspect_ratio = static_cast<float>(src.perspective.aspectRatio);
      cam.znear = static_cast<float>(src.perspective.znear);
      cam.zfar = static_cast<float>(src.perspective.zfar);
      if (!(cam.yfov > 0 && cam.yfov < 3.1415926f))
        fail(fmt::format("camera {} has yfov {}; a perspective camera needs 0 < yfov < pi radians",
                         node.camera, src.perspective.yfov));
      if (!(cam.aspect_ratio >= 0 && std::isfinite(cam.aspect_ratio)))
        fail(fmt::format("camera {} has an invalid aspectRatio", node.camera));
    } else {
      fail(fmt::format("camera {} has unknown type '{}'", node.camera, src.type));
    }
    out_.cameras.push_back(cam);
  }

  void add_light(const tinygltf::Value& ext, int index, const glm::mat4& world) {
    const int light = ext.Has("light") ? ext.Get("light").GetNumberAsInt() : -1;
    if (light < 0 || light >= static_cast<int>(model_.lights.size()))
      fail(fmt::format("node {} refers to light {}, but the file has {}", index, light,
                       count_of(model_.lights.size(), "light")));
    const tinygltf::Light& src = model_.lights[light];
    PunctualLight l;
    l.name = src.name.empty() ? fmt::format("light {}", light) : src.name;
    if (src.type == "point") l.type = PunctualLight::Type::Point;
    else if (src.type == "spot") l.type = PunctualLight::Type::Spot;
    else if (src.type == "directional") l.type = PunctualLight::Type::Directional;
    else fail(fmt::format("light {} has unknown type '{}' (expected 'directional', 'point' or 'spot')",
                          light, src.type));
    if (src.color.size() == 3) l.color = {src.color[0], src.color[1], src.color[2]};
    l.intensity = static_cast<float>(src.intensity);
    l.range = static_cast<float>(src.range);
    l.inner_cone_angle = static_cast<float>(src.spot.innerConeAngle);
    l.outer_cone_angle = static_cast<float>(src.spot.outerConeAngle);
    l.position = glm::vec3(world[3]);
    l.direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    const bool finite = all_finite((l.color)) && std::isfinite(l.intensity) &&
                        all_finite((l.direction)) && l.intensity >= 0;
    if (!finite) fail(fmt::format("light {} has an invalid color, intensity or direction", light));
    out_.lights.push_back(l);
  }

  const tinygltf::Model& model_;
  const std::string& file_;
  GltfLoadResult& result_;
  SceneDescription& out_;
  std::vector<std::string>& warnings_;
  AccessorReader reader_;
  std::map<int, int> mesh_slot_;  // glTF mesh index (-1 - node for a morphed one) -> index in out_.meshes
  std::vector<NodePose> poses_;  // per node, at the requested time
};

std::string directory_of(const std::string& path) {
  const auto slash = path.find_last_of('/');
  return slash == std::string::npos ? std::string(".") : path.substr(0, slash);
}

void deduplicate(std::vector<std::string>& warnings) {
  std::set<std::string> seen;
  std::vector<std::string> unique;
  for (auto& w : warnings)
    if (seen.insert(w).second) unique.push_back(std::move(w));
  warnings = std::move(unique);
}

}  // namespace

GltfLoadResult load_gltf_from_memory(const std::vector<std::uint8_t>& bytes,
                                     const std::string& display_name, const std::string& base_dir,
                                     const GltfLoadParams& params) {
  const tinygltf::Model model = parse_gltf(bytes, display_name, base_dir);
  GltfLoadResult result;
  result.scene.source_path = display_name;
  Converter(model, display_name, result).run(params);
  deduplicate(result.warnings);
  return result;
}

GltfLoadResult load_gltf(const std::string& path, const GltfLoadParams& params) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneLoadError(path, "is a directory, not a glTF file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw SceneLoadError(path, std::string("cannot be opened: ") + std::strerror(errno));
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  if (in.bad()) throw SceneLoadError(path, "could not be read");
  return load_gltf_from_memory(bytes, path, directory_of(path), params);
}

}  // namespace tessera
