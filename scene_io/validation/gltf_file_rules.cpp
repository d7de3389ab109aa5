// The file-wide and extension part of gltf_rules.h.
#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "scene_io/base/gltf_json.h"
#include "scene_io/validation/gltf_rules.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

using Json = nlohmann::json;

// Where the extensions tessera reads go: on an object of `array` itself (`where` empty), on a
// mesh primitive, or on a textureInfo (an object with an "index", in a material).
struct Placement {
  const char* extension;
  const char* array;
  const char* where;
};
constexpr Placement kPlacements[] = {
    {"EXT_texture_webp", "textures", ""},           {"KHR_texture_basisu", "textures", ""},
    {"KHR_lights_punctual", "nodes", ""},           {"EXT_mesh_gpu_instancing", "nodes", ""},
    {"EXT_meshopt_compression", "bufferViews", ""}, {"EXT_meshopt_compression", "buffers", ""},
    {"KHR_draco_mesh_compression", "meshes", "primitive"},
    {"KHR_materials_variants", "meshes", "primitive"},
    {"KHR_texture_transform", "materials", "textureInfo"}};

bool placed_right(const std::string& name, const std::string& array, const std::vector<std::string>& path,
                  const Json& holder) {
  const bool material_extension = name.rfind("KHR_materials_", 0) == 0 && name != "KHR_materials_variants";
  if (material_extension) return array == "materials" && path.empty();
  bool known = false;
  for (const Placement& p : kPlacements) {
    if (name != p.extension) continue;
    known = true;
    const std::string where = p.where;
    if (array != p.array) continue;
    if (where.empty() ? path.empty()
                      : where == "primitive" ? path == std::vector<std::string>{"primitives", "#"}
                                             : member(holder, "index") != nullptr)
      return true;
  }
  return !known;  // an extension tessera does not read goes wherever it says
}

struct ExtensionWalk {
  const std::vector<std::string>& used;
  GltfRuleProblems& out;
  std::string array, noun;
  std::size_t index = 0;

  void problem(const std::string& text) {
    if (std::none_of(out.objects.begin(), out.objects.end(),
                     [&](const GltfObjectProblem& p) { return p.array == array && p.index == index; }))
      out.objects.push_back({array, index, fmt::format("{} {}", noun, index), text});
  }

  void visit(const Json& value, std::vector<std::string>& path) {
    if (value.is_array()) {
      path.push_back("#");
      for (const Json& v : value) visit(v, path);
      path.pop_back();
      return;
    }
    if (!value.is_object()) return;
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (it.key() == "extras") continue;
      if (it.key() == "extensions" && it->is_object())
        for (auto e = it->begin(); e != it->end(); ++e) check(e.key(), path, value);
      path.push_back(it.key());
      visit(*it, path);
      path.pop_back();
    }
  }

  void check(const std::string& name, const std::vector<std::string>& path, const Json& holder) {
    const std::string what = fmt::format("{} {} has extension {}", noun, index, shorten(name));
    if (std::find(used.begin(), used.end(), name) == used.end())
      return problem(what + ", which extensionsUsed does not declare (glTF requires it there)");
    if (placed_right(name, array, path, holder)) return;
    std::string at;
    for (const std::string& key : path)
      if (key != "#") at += (at.empty() ? "" : ".") + key;
    problem(path.empty() ? fmt::format("{}, which glTF does not define for a {}", what, noun)
                         : fmt::format("{} in its {}, where glTF does not define it", what, at));
  }
};

std::vector<std::string> strings_of(const Json* array) {
  std::vector<std::string> out;
  if (array && array->is_array())
    for (const Json& v : *array)
      if (v.is_string()) out.push_back(v.get<std::string>());
  return out;
}

void find_empty_arrays(const Json& j, std::vector<std::string>& notes) {
  const std::string rule = " (glTF requires at least one element where an array is given)";
  std::vector<const char*> keys = {"extensionsUsed", "extensionsRequired"};
  for (const GltfObjectArray& a : kGltfArrays) keys.push_back(a.key);
  for (const char* key : keys)
    if (const Json* a = member(j, key); a && a->is_array() && a->empty())
      notes.push_back(fmt::format("its \"{}\" array is empty{}", key, rule));
  const Json* ext = member(j, "extensions");
  const Json* lights = ext ? member(*ext, "KHR_lights_punctual") : nullptr;
  if (lights && member(*lights, "lights") && (*lights)["lights"].is_array() && (*lights)["lights"].empty())
    notes.push_back("its KHR_lights_punctual \"lights\" array is empty" + rule);
  const Json* nodes = member(j, "nodes");
  for (std::size_t n = 0; nodes && nodes->is_array() && n < nodes->size(); ++n)
    if (const Json* c = member((*nodes)[n], "children"); c && c->is_array() && c->empty())
      notes.push_back(fmt::format("node {} has an empty \"children\" array{}", n, rule));
}

// "2.1" -> {2, 1}; {-1, -1} when it is not major.minor.
std::pair<int, int> version_of(const Json* v) {
  int major = -1, minor = -1;
  if (v && v->is_string() && std::sscanf(v->get<std::string>().c_str(), "%d.%d", &major, &minor) == 2)
    return {major, minor};
  return {-1, -1};
}

}  // namespace

void find_file_and_extension_problems(const Json& j, GltfRuleProblems& out) {
  find_empty_arrays(j, out.file);
  const Json* asset = member(j, "asset");
  const auto version = version_of(asset ? member(*asset, "version") : nullptr);
  const auto min_version = version_of(asset ? member(*asset, "minVersion") : nullptr);
  if (min_version.first >= 0 && version.first >= 0 && min_version > version)
    out.file.push_back(fmt::format("its asset minVersion {}.{} is greater than its version {}.{}", min_version.first,
                                   min_version.second, version.first, version.second));
  const std::vector<std::string> used = strings_of(member(j, "extensionsUsed"));
  const std::vector<std::string> required = strings_of(member(j, "extensionsRequired"));
  const std::string quantization = "KHR_mesh_quantization";
  if (std::count(used.begin(), used.end(), quantization) && !std::count(required.begin(), required.end(), quantization))
    out.file.push_back("its extensionsUsed lists KHR_mesh_quantization, which glTF requires in extensionsRequired too");
  if (const Json* root = member(j, "extensions"); root && root->is_object())
    for (auto e = root->begin(); e != root->end(); ++e)
      if (std::find(used.begin(), used.end(), e.key()) == used.end())
        out.file.push_back(fmt::format("it has extension {}, which extensionsUsed does not declare (glTF requires it "
                                       "there)",
                                       shorten(e.key())));
  for (const GltfObjectArray& a : kGltfArrays) {
    const Json* array = member(j, a.key);
    for (std::size_t i = 0; array && array->is_array() && i < array->size(); ++i) {
      ExtensionWalk walk{used, out, a.key, a.noun, i};
      std::vector<std::string> path;
      walk.visit((*array)[i], path);
    }
  }
}

}  // namespace tessera
