// glTF 2.0 -> SceneDescription: parsing (tinygltf), extension policy, scene and node
// traversal, cameras and punctual lights. Meshes and materials live in their own files.
#include "scene_io/gltf_loader.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <set>

#include <fmt/format.h>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "renderer/util/math.h"
#include "scene_io/base/gltf_accessor.h"
#include "scene_io/nodes/gltf_hierarchy.h"
#include "scene_io/decode/gltf_images.h"
#include "scene_io/nodes/gltf_instancing.h"
#include "scene_io/materials/gltf_material.h"
#include "scene_io/nodes/gltf_mesh.h"
#include "scene_io/gltf_parse.h"
#include "scene_io/nodes/gltf_usage.h"
#include "scene_io/materials/gltf_variants.h"
#include "scene_io/base/load_error.h"

namespace tessera {

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
  Converter(const GltfDocument& document, GltfLoadResult& result)
      : model_(document.model), images_(*document.images), file_(document.path),
        defects_(document.defects), result_(result),
        out_(result.scene), warnings_(result.warnings), reader_{model_, file_, &defects_, &read_accessors_} {}

  void run(const GltfLoadParams& params) {
    check_extensions();
    parent_ = check_node_hierarchy(model_, file_);
    const std::vector<int> roots = scene_roots(model_, choose_scene(params.scene), parent_, file_);
    result_.animations = animation_names(model_);
    result_.playing = choose_animations(result_.animations, params.animation, file_);
    // What the scene does not use may be broken: a warning (docs/reliability.md).
    const GltfUsage used = find_used_objects(model_, roots, parent_, result_.playing);
    // The file's variant names are used when one is chosen or a used primitive maps variants.
    result_.material_variants = defects_.read_object(
        !params.variant.empty() || maps_variants(used), kMaterialsVariants, file_, warnings_,
        [&] { return read_material_variants(model_, file_); }, std::vector<std::string>{});
    if (!params.variant.empty())
      result_.material_variant = choose_material_variant(result_.material_variants, params.variant, file_);
    out_.materials = convert_materials(model_, file_, defects_, images_, used.materials, warnings_);
    out_.images = convert_images(model_, images_, images_shown(out_.materials, used.materials), file_);
    for (std::size_t a = 0; a < model_.animations.size(); ++a)
      result_.animations[a] = defects_.read_object(
          used.animations[a], fmt::format("animation {}", a), file_, warnings_,
          [&] { return read_animation(model_, a, reader_, file_); }, result_.animations[a]);
    for (std::size_t s = 0; s < model_.skins.size(); ++s)
      if (used.skins[s]) check_joints_in_scene(s, used);
    for (std::size_t s = 0; s < model_.skins.size(); ++s)
      result_.skins.push_back(defects_.read_object(used.skins[s], fmt::format("skin {}", s), file_, warnings_,
                                                   [&] { return read_skin(model_, s, reader_, file_); },
                                                   Skin{skin_name(model_, s), {}, {}, -1}));
    pose_steps(params);
    out_.animated = std::any_of(result_.playing.begin(), result_.playing.end(),
                                [&](int a) { return !result_.animations[a].channels.empty(); });
    for (const tinygltf::Mesh& m : model_.meshes)
      result_.morph_meshes += std::any_of(m.primitives.begin(), m.primitives.end(),
                                          [](const tinygltf::Primitive& p) { return !p.targets.empty(); });
    traverse(roots);
    check_clipping();
    check_unused_objects(used);
    for (std::string& w : defects_.unused_warnings()) warnings_.push_back(std::move(w));
    check_unread_accessors();
  }

 private:
  // A camera whose clipping planes leave out every surface shows only the background: znear
  // beyond the farthest corner of the scene's bounds, or zfar short of the nearest point (as a
  // scene scaled down under a camera with znear 0.01, which the node's scale does not scale).
  void check_clipping() {
    const Bounds3& b = out_.bounds;
    if (b.empty()) return;
    for (const Camera& cam : out_.cameras) {
      const glm::vec3 eye(cam.camera_to_world[3]);
      const glm::vec3 nearest = glm::clamp(eye, b.lo, b.hi), farthest = glm::mix(b.lo, b.hi, glm::lessThan(eye, b.center()));
      const float near = glm::distance(eye, nearest), far = glm::distance(eye, farthest);
      if (cam.znear > far)
        warnings_.push_back(fmt::format("camera '{}' shows only the background: its znear {:g} lies beyond the whole "
                                        "scene (at most {:.3g} from it)", cam.name, cam.znear, far));
      else if (cam.zfar > 0.0f && cam.zfar < near)
        warnings_.push_back(fmt::format("camera '{}' shows only the background: its zfar {:g} falls short of the "
                                        "whole scene (at least {:.3g} from it)", cam.name, cam.zfar, near));
    }
  }

  // A used skin's joints must be in the scene that uses it (the validator's NODE_SKIN_NO_SCENE).
  void check_joints_in_scene(std::size_t s, const GltfUsage& used) const {
    for (int j : model_.skins[s].joints)
      if (j >= 0 && static_cast<std::size_t>(j) < used.nodes.size() && !used.nodes[j])
        throw SceneLoadError(file_, fmt::format("skin {} has joint node {}, which is not in the scene (glTF requires "
                                                "a skin's joints in the scene of the node it skins)",
                                                s, j));
  }

  [[noreturn]] void fail(const std::string& problem) const { throw SceneLoadError(file_, problem); }

  // True when a primitive of a used mesh has KHR_materials_variants mappings.
  bool maps_variants(const GltfUsage& used) const {
    for (std::size_t m = 0; m < model_.meshes.size(); ++m)
      for (const tinygltf::Primitive& prim : model_.meshes[m].primitives)
        if (used.meshes[m] && prim.extensions.count(kMaterialsVariants)) return true;
    return false;
  }

  // The policy for meshes, cameras, lights and textures the scene does not use: each is read as a whole
  // (a texture the used materials showed reads again without a problem), and what would refuse
  // a used one is a warning.
  void check_unused_objects(const GltfUsage& used) {
    for (std::size_t m = 0; m < model_.meshes.size(); ++m)
      if (!used.meshes[m])
        defects_.read_object(false, fmt::format("mesh {}", m), file_, warnings_,
                             [&] { return convert_mesh(static_cast<int>(m), Deformation{}); }, Mesh{});
    for (std::size_t c = 0; c < model_.cameras.size(); ++c)
      if (!used.cameras[c])
        defects_.read_object(false, fmt::format("camera {}", c), file_, warnings_,
                             [&] { return camera_projection(static_cast<int>(c)); }, Camera{});
    for (std::size_t l = 0; l < model_.lights.size(); ++l)
      if (!used.lights[l])
        defects_.read_object(false, fmt::format("light {}", l), file_, warnings_,
                             [&] { return light_properties(static_cast<int>(l)); }, PunctualLight{});
    for (std::size_t t = 0; t < model_.textures.size(); ++t)
      defects_.read_object(false, fmt::format("texture {}", t), file_, warnings_,
                           [&] {
                             texture_image(model_, file_, static_cast<int>(t), defects_, images_);
                             return texture_sampler(model_, file_, static_cast<int>(t), defects_);
                           },
                           static_cast<const tinygltf::Sampler*>(nullptr));
  }

  // The policy for accessors nothing read: what would refuse a used one (NaN, a range past its
  // bufferView) is a warning. Read as a whole, without the reader's log.
  void check_unread_accessors() {
    const AccessorReader whole{model_, file_, &defects_};
    for (std::size_t i = 0; i < model_.accessors.size(); ++i) {
      const int components = gltf_component_count(model_.accessors[i].type);
      if (read_accessors_.count(static_cast<int>(i)) || components == 0) continue;
      try {
        whole.floats(static_cast<int>(i), components, "unused");
      } catch (const SceneLoadError& e) {
        warnings_.push_back(kUnusedPrefix + e.problem());
      }
    }
  }

  int steps() const { return static_cast<int>(poses_.size()); }

  // The times the scene is described at: `time` alone, or motion_steps across the shutter.
  void pose_steps(const GltfLoadParams& params) {
    const int steps = std::max(params.motion_steps, 1);
    out_.motion_steps = steps;
    out_.shutter_open = params.time + (steps > 1 ? params.shutter_open : 0.0f);
    out_.shutter_close = params.time + (steps > 1 ? params.shutter_close : 0.0f);
    for (int k = 0; k < steps; ++k) {
      const float f = steps > 1 ? static_cast<float>(k) / static_cast<float>(steps - 1) : 0.0f;
      const float t = out_.shutter_open + f * (out_.shutter_close - out_.shutter_open);
      poses_.push_back(pose_nodes(result_.animations, result_.playing, t, model_.nodes.size()));
    }
    world_.assign(steps, std::vector<glm::mat4>(model_.nodes.size()));
    world_known_.assign(steps, std::vector<bool>(model_.nodes.size(), false));
  }

  // Node `index`'s world transform at motion step `step`: its parents' composed with its own.
  // Without recursion (hierarchies can be deep): up to the nearest known ancestor, then down.
  const glm::mat4& world(int index, int step) {
    std::vector<int> chain;
    for (int n = index; n >= 0 && !world_known_[step][n]; n = parent_[n]) chain.push_back(n);
    for (auto n = chain.rbegin(); n != chain.rend(); ++n) {
      const int p = parent_[*n];
      const glm::mat4 w = (p >= 0 ? world_[step][p] : glm::mat4(1.0f)) * local_transform(model_.nodes[*n], *n, step);
      if (!finite_matrix(w))
        fail(fmt::format("node {} has a world transform (its own composed with its ancestors') "
                         "beyond the range of 32-bit floats", *n));
      world_[step][*n] = w;
      world_known_[step][*n] = true;
    }
    return world_[step][index];
  }

  // A node's world transform at every motion step.
  std::vector<glm::mat4> worlds(int index) {
    std::vector<glm::mat4> w;
    for (int k = 0; k < steps(); ++k) w.push_back(world(index, k));
    return w;
  }

  // The morph weights node `index` gives its mesh at motion step `step`: animated, else the
  // node's, else the mesh's, else zero. Empty when the mesh has no targets or every weight is
  // 0 (the base shape).
  std::vector<float> morph_weights(const tinygltf::Node& node, int index, int step) const {
    const tinygltf::Mesh& mesh = model_.meshes[node.mesh];
    std::size_t targets = 0;
    for (const tinygltf::Primitive& p : mesh.primitives) targets = std::max(targets, p.targets.size());
    if (targets == 0) return {};
    std::vector<float> w(targets, 0.0f);
    if (!poses_[step][index].weights.empty()) w = poses_[step][index].weights;
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
      if (model_.defaultScene >= 0)
        fail(fmt::format("its default scene is {}, but the file has no scenes", model_.defaultScene));
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
    defects_.check_used(fmt::format("scene {}", index), file_);
    out_.scene_name = scenes[index].name.empty() ? std::to_string(index) : scenes[index].name;
    return index;
  }

  // Depth first, children in order, without recursion: hierarchies can be deep.
  void traverse(const std::vector<int>& roots) {
    std::vector<int> stack(roots.rbegin(), roots.rend());
    while (!stack.empty()) {
      const int index = stack.back();
      stack.pop_back();
      defects_.check_used(fmt::format("node {}", index), file_);
      const tinygltf::Node& node = model_.nodes[index];
      for (int k = 0; k < steps(); ++k) world(index, k);
      if (node.mesh >= 0) add_instance(node, index);
      if (node.camera >= 0) add_camera(node, index);
      if (auto it = node.extensions.find("KHR_lights_punctual"); it != node.extensions.end())
        add_light(it->second, index);
      stack.insert(stack.end(), node.children.rbegin(), node.children.rend());
    }
  }

  glm::mat4 local_transform(const tinygltf::Node& node, int index, int step) const {
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
    const NodePose& pose = poses_[step][index];  // what the playing animations drive
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

  // What deforms node `index`'s mesh at each motion step: morph weights, joint matrices.
  struct Deformation {
    std::vector<std::vector<float>> weights;  // per step; empty: the base shape
    const Skin* skin = nullptr;
    std::vector<std::vector<glm::mat4>> joints;  // per step, with a skin
    bool any() const {
      return skin || std::any_of(weights.begin(), weights.end(), [](const auto& w) { return !w.empty(); });
    }
  };

  Deformation deformation(const tinygltf::Node& node, int index) {
    Deformation d;
    for (int k = 0; k < steps(); ++k) d.weights.push_back(morph_weights(node, index, k));
    if (node.skin < 0) return d;
    if (node.skin >= static_cast<int>(result_.skins.size()))
      fail(fmt::format("node {} refers to skin {}, but the file has {}", index, node.skin,
                       count_of(result_.skins.size(), "skin")));
    d.skin = &result_.skins[node.skin];
    for (int k = 0; k < steps(); ++k) {
      std::vector<glm::mat4> joint_world;
      for (int j : d.skin->joints) joint_world.push_back(world(j, k));
      d.joints.push_back(joint_matrices(*d.skin, joint_world));
    }
    return d;
  }

  void add_instance(const tinygltf::Node& node, int index) {
    if (node.mesh >= static_cast<int>(model_.meshes.size()))
      fail(fmt::format("node {} refers to mesh {}, but the file has {}", index, node.mesh,
                       count_of(model_.meshes.size(), "mesh")));
    defects_.check_used(fmt::format("mesh {}", node.mesh), file_);
    // A mesh with no triangles (only points or lines) is neither stored nor placed. A morphed
    // or skinned mesh is the node's own (another node may deform it differently).
    const Deformation deform = deformation(node, index);
    auto [it, inserted] = mesh_slot_.try_emplace(deform.any() ? -1 - index : node.mesh, -1);
    if (inserted) {
      Mesh mesh = convert_mesh(node.mesh, deform);
      if (!mesh.primitives.empty()) {
        it->second = static_cast<int>(out_.meshes.size());
        out_.meshes.push_back(std::move(mesh));
      }
    }
    if (it->second < 0) return;
    // A skinned mesh is in world space already: the specification ignores its node's transform.
    const std::vector<glm::mat4> placed =
        deform.skin ? std::vector<glm::mat4>(steps(), glm::mat4(1.0f)) : worlds(index);
    const std::vector<glm::mat4> locals = read_gpu_instances(node, index, reader_);
    if (locals.empty()) {
      place(it->second, placed, node, index, exact_reach(out_.meshes[it->second], placed));
      return;
    }
    // Many placements of one mesh: bounds from its box's corners, not every vertex of each.
    const Bounds3 box = exact_reach(out_.meshes[it->second], std::vector<glm::mat4>(steps(), glm::mat4(1.0f)));
    std::vector<glm::mat4> at(steps());
    for (const glm::mat4& local : locals) {
      for (int k = 0; k < steps(); ++k) at[k] = placed[k] * local;
      place(it->second, at, node, index, corner_reach(box, at));
    }
  }

  // Puts mesh `slot` at `placed` (one matrix per motion step), reaching `reach`.
  void place(int slot, const std::vector<glm::mat4>& placed, const tinygltf::Node& node, int index,
             const Bounds3& reach) {
    Instance instance{slot, placed[0], node.name, {}};
    if (std::any_of(placed.begin(), placed.end(), [&](const glm::mat4& m) { return m != placed[0]; }))
      instance.motion.assign(placed.begin() + 1, placed.end());
    out_.instances.push_back(std::move(instance));
    if (!all_finite(reach.lo) || !all_finite(reach.hi))  // finite matrices and positions can still overflow together
      fail(fmt::format("node {} places mesh {} beyond the range of 32-bit floats", index, node.mesh));
    out_.bounds.extend(reach);
  }

  // Where `mesh`'s vertices go under `placed`, at every motion step.
  Bounds3 exact_reach(const Mesh& mesh, const std::vector<glm::mat4>& placed) const {
    Bounds3 reach;
    for (const TriangleMesh& prim : mesh.primitives)
      for (int k = 0; k < steps(); ++k) {
        const auto& positions = k == 0 || !prim.deforms() ? prim.positions : prim.motion_positions[k - 1];
        for (const glm::vec3& p : positions) reach.extend(glm::vec3(placed[k] * glm::vec4(p, 1.0f)));
      }
    return reach;
  }

  // Where the corners of `box` go under `placed`: a box around the placed mesh.
  static Bounds3 corner_reach(const Bounds3& box, const std::vector<glm::mat4>& placed) {
    Bounds3 reach;
    for (const glm::mat4& m : placed)
      for (int c = 0; c < 8; ++c) {
        const glm::vec3 p(c & 1 ? box.hi.x : box.lo.x, c & 2 ? box.hi.y : box.lo.y, c & 4 ? box.hi.z : box.lo.z);
        reach.extend(glm::vec3(m * glm::vec4(p, 1.0f)));
      }
    return reach;
  }

  Mesh convert_mesh(int index, const Deformation& deform) {
    const tinygltf::Mesh& src = model_.meshes[index];
    Mesh mesh;
    mesh.name = src.name.empty() ? fmt::format("mesh {}", index) : src.name;
    for (std::size_t p = 0; p < src.primitives.size(); ++p) {
      const std::string what = fmt::format("mesh {} primitive {}", index, p);
      auto prim = convert_primitive(reader_, src.primitives[p], what, warnings_);
      if (!prim) continue;
      if (deform.any()) deform_primitive(src.primitives[p], deform, what, *prim);
      prim->material = material_for_variant(src.primitives[p], result_.material_variant,
                                            result_.material_variants.size(), out_.materials.size(), file_, what);
      if (prim->material >= static_cast<int>(out_.materials.size()))
        fail(fmt::format("{} refers to material {}, but the file has {}", what, prim->material,
                         count_of(out_.materials.size(), "material")));
      if (!prim->indices.empty()) mesh.primitives.push_back(std::move(*prim));
    }
    return mesh;
  }

  // Morphs, then skins, the primitive's shape at every motion step: step 0 in place, the
  // others as its motion (dropped when nothing moves).
  void deform_primitive(const tinygltf::Primitive& src, const Deformation& deform, const std::string& what,
                        TriangleMesh& prim) {
    SkinInfluences influences;
    if (deform.skin) {
      influences = read_skin_influences(reader_, src, prim.positions.size(), deform.skin->joints.size(), what);
      if (influences.per_vertex == 0) fail(fmt::format("{} is skinned but has no JOINTS_0 and WEIGHTS_0", what));
    }
    TriangleMesh base;
    base.positions = prim.positions, base.normals = prim.normals, base.tangents = prim.tangents;
    for (int k = 0; k < steps(); ++k) {
      TriangleMesh shape = base;
      if (!deform.weights[k].empty()) apply_morph_targets(reader_, src, deform.weights[k], what, shape);
      if (deform.skin) apply_skin(influences, deform.joints[k], shape);
      if (k == 0) {
        prim.positions = std::move(shape.positions);
        prim.normals = std::move(shape.normals);
        prim.tangents = std::move(shape.tangents);
      } else {
        prim.motion_positions.push_back(std::move(shape.positions));  // normals, tangents: only those it has
        if (!shape.normals.empty()) prim.motion_normals.push_back(std::move(shape.normals));
        if (!shape.tangents.empty()) prim.motion_tangents.push_back(std::move(shape.tangents));
      }
    }
    const auto differs = [](const auto& steps, const auto& first) {
      return std::any_of(steps.begin(), steps.end(), [&](const auto& s) { return s != first; });
    };
    if (!differs(prim.motion_positions, prim.positions) && !differs(prim.motion_normals, prim.normals) &&
        !differs(prim.motion_tangents, prim.tangents)) {
      prim.motion_positions.clear();
      prim.motion_normals.clear();
      prim.motion_tangents.clear();
    }
  }

  void add_camera(const tinygltf::Node& node, int index) {
    if (node.camera >= static_cast<int>(model_.cameras.size()))
      fail(fmt::format("node {} refers to camera {}, but the file has {}", index, node.camera,
                       count_of(model_.cameras.size(), "camera")));
    defects_.check_used(fmt::format("camera {}", node.camera), file_);
    Camera cam = camera_projection(node.camera);
    if (model_.cameras[node.camera].name.empty() && !node.name.empty()) cam.name = node.name;
    std::vector<glm::mat4> frames;
    for (const glm::mat4& w : worlds(index)) frames.push_back(camera_frame(w, index, node.camera));
    cam.camera_to_world = frames[0];
    if (std::any_of(frames.begin(), frames.end(), [&](const glm::mat4& m) { return m != frames[0]; }))
      cam.motion.assign(frames.begin() + 1, frames.end());
    out_.cameras.push_back(cam);
  }

  // Camera `index`'s projection, checked; named by the file or "camera N".
  Camera camera_projection(int index) const {
    const tinygltf::Camera& src = model_.cameras[index];
    Camera cam;
    cam.name = !src.name.empty() ? src.name : fmt::format("camera {}", index);
    if (src.type == "orthographic") {
      cam.projection = Camera::Projection::Orthographic;
      cam.xmag = static_cast<float>(std::abs(src.orthographic.xmag));
      cam.ymag = static_cast<float>(std::abs(src.orthographic.ymag));
      cam.znear = static_cast<float>(src.orthographic.znear);
      cam.zfar = static_cast<float>(src.orthographic.zfar);
      if (!(cam.xmag > 0 && cam.ymag > 0 && std::isfinite(cam.xmag) && std::isfinite(cam.ymag)))
        fail(fmt::format("camera {} has invalid xmag/ymag", index));
    } else if (src.type == "perspective") {
      cam.yfov = static_cast<float>(src.perspective.yfov);
      cam.aspect_ratio = static_cast<float>(src.perspective.aspectRatio);
      cam.znear = static_cast<float>(src.perspective.znear);
      cam.zfar = static_cast<float>(src.perspective.zfar);
      if (!(cam.yfov > 0 && cam.yfov < 3.1415926f))
        fail(fmt::format("camera {} has yfov {}; a perspective camera needs 0 < yfov < pi radians",
                         index, src.perspective.yfov));
      if (!(cam.aspect_ratio >= 0 && std::isfinite(cam.aspect_ratio)))
        fail(fmt::format("camera {} has an invalid aspectRatio", index));
    } else {
      fail(fmt::format("camera {} has unknown type '{}'", index, src.type));
    }
    if (cam.zfar > 0 && !(cam.zfar > cam.znear))
      fail(fmt::format("camera {} has zfar {} not beyond its znear {}", index, cam.zfar, cam.znear));
    return cam;
  }

  // Cameras ignore the node's scale: an orthonormal frame and the position.
  glm::mat4 camera_frame(const glm::mat4& world, int index, int camera) const {
    glm::vec3 x = glm::vec3(world[0]), y = glm::vec3(world[1]);
    glm::vec3 z = glm::normalize(glm::cross(x, y));
    x = glm::normalize(x);
    y = glm::cross(z, x);
    if (!all_finite((z))) fail(fmt::format("node {} places camera {} with a degenerate transform", index, camera));
    return glm::mat4(glm::vec4(x, 0), glm::vec4(y, 0), glm::vec4(z, 0), world[3]);
  }

  void add_light(const tinygltf::Value& ext, int index) {
    const std::vector<glm::mat4> placed = worlds(index);
    const glm::mat4& world = placed[0];
    const int light = ext.Has("light") ? ext.Get("light").GetNumberAsInt() : -1;
    if (light < 0 || light >= static_cast<int>(model_.lights.size()))
      fail(fmt::format("node {} refers to light {}, but the file has {}", index, light,
                       count_of(model_.lights.size(), "light")));
    defects_.check_used(fmt::format("light {}", light), file_);
    PunctualLight l = light_properties(light);
    l.position = glm::vec3(world[3]);
    l.direction = glm::normalize(glm::vec3(world * glm::vec4(0, 0, -1, 0)));
    l.light_to_world = world;
    bool finite = true;
    for (const glm::mat4& w : placed) finite = finite && all_finite(glm::normalize(glm::vec3(w * glm::vec4(0, 0, -1, 0))));
    if (!finite) fail(fmt::format("light {} has an invalid color, intensity or direction", light));
    if (std::any_of(placed.begin(), placed.end(), [&](const glm::mat4& m) { return m != world; }))
      l.motion.assign(placed.begin() + 1, placed.end());
    out_.lights.push_back(l);
  }

  // Light `index` of KHR_lights_punctual as the file gives it, checked; not yet placed.
  PunctualLight light_properties(int index) const {
    const tinygltf::Light& src = model_.lights[index];
    PunctualLight l;
    l.name = src.name.empty() ? fmt::format("light {}", index) : src.name;
    if (src.type == "point") l.type = PunctualLight::Type::Point;
    else if (src.type == "spot") l.type = PunctualLight::Type::Spot;
    else if (src.type == "directional") l.type = PunctualLight::Type::Directional;
    else fail(fmt::format("light {} has unknown type '{}' (expected 'directional', 'point' or 'spot')",
                          index, src.type));
    if (src.color.size() == 3) l.color = {src.color[0], src.color[1], src.color[2]};
    l.intensity = static_cast<float>(src.intensity);
    l.range = static_cast<float>(src.range);
    l.inner_cone_angle = static_cast<float>(src.spot.innerConeAngle);
    l.outer_cone_angle = static_cast<float>(src.spot.outerConeAngle);
    if (!(all_finite(l.color) && std::isfinite(l.intensity) && l.intensity >= 0))
      fail(fmt::format("light {} has an invalid color, intensity or direction", index));
    const double inner = src.spot.innerConeAngle, outer = src.spot.outerConeAngle;
    if (l.type == PunctualLight::Type::Spot && !(inner >= 0 && inner < outer && outer <= glm::half_pi<double>()))
      fail(fmt::format("light {} has spot cone angles {} (inner) and {} (outer); glTF requires 0 <= inner < outer "
                       "<= pi/2", index, inner, outer));
    return l;
  }

  const tinygltf::Model& model_;
  const GltfImageStore& images_;
  const std::string& file_;
  const GltfDefects& defects_;
  GltfLoadResult& result_;
  SceneDescription& out_;
  std::vector<std::string>& warnings_;
  std::set<int> read_accessors_;  // by reader_, so used (declared before it)
  AccessorReader reader_;
  std::map<int, int> mesh_slot_;  // glTF mesh index (-1 - node for a deformed one) -> index in out_.meshes
  std::vector<int> parent_;  // per node, -1 for roots
  std::vector<std::vector<NodePose>> poses_;  // per motion step, per node
  std::vector<std::vector<glm::mat4>> world_;  // per motion step, per node, once known
  std::vector<std::vector<bool>> world_known_;
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

GltfDocument read_gltf_from_memory(const std::vector<std::uint8_t>& bytes, const std::string& display_name,
                                   const std::string& base_dir) {
  GltfDocument document{display_name, {}, {}, std::make_shared<GltfImageStore>()};
  document.model = parse_gltf(bytes, display_name, base_dir, document.defects, *document.images);
  return document;
}

GltfDocument read_gltf(const std::string& path) {
  const auto start = std::chrono::steady_clock::now();
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw SceneLoadError(path, "is a directory, not a glTF file");
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw SceneLoadError(path, std::string("cannot be opened: ") + std::strerror(errno));
  const std::streamoff size = in.tellg();
  std::vector<std::uint8_t> bytes;
  if (size > 0) {  // a pipe or device reports no size: read to its end instead
    bytes.resize(static_cast<std::size_t>(size));
    in.seekg(0);
    in.read(reinterpret_cast<char*>(bytes.data()), size);
    if (in.gcount() != size) throw SceneLoadError(path, "could not be read");
  } else {
    in.clear();
    in.seekg(0);
    bytes.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  }
  if (in.bad()) throw SceneLoadError(path, "could not be read");
  GltfDocument document = read_gltf_from_memory(bytes, path, directory_of(path));
  document.read_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return document;
}

GltfLoadResult convert_gltf(const GltfDocument& document, const GltfLoadParams& params) {
  GltfLoadResult result;
  result.scene.source_path = document.path;
  Converter(document, result).run(params);
  deduplicate(result.warnings);
  return result;
}

GltfLoadResult load_gltf_from_memory(const std::vector<std::uint8_t>& bytes,
                                     const std::string& display_name, const std::string& base_dir,
                                     const GltfLoadParams& params) {
  return convert_gltf(read_gltf_from_memory(bytes, display_name, base_dir), params);
}

GltfLoadResult load_gltf(const std::string& path, const GltfLoadParams& params) {
  return convert_gltf(read_gltf(path), params);
}

}  // namespace tessera
