// KHR_materials_variants: reading the root's variants, choosing one, mapping primitives.
// The extension objects are read from their JSON text (tinygltf keeps it when the file names
// the extension, see gltf_parse.cpp): tinygltf's own Value drops empty arrays and objects,
// which would shift variant indices, and cuts integers to int, which would wrap indices.
#include "scene_io/materials/gltf_variants.h"

#include <algorithm>
#include <cctype>
#include <cstdint>
#include <optional>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

using Json = nlohmann::json;

// `extensions_json` is an object's whole "extensions" JSON text; its KHR_materials_variants
// member, or nullopt when it has none.
std::optional<Json> extension_json(const tinygltf::ExtensionMap& extensions, const std::string& extensions_json) {
  if (extensions.find(kMaterialsVariants) == extensions.end()) return std::nullopt;
  const Json all = Json::parse(extensions_json, nullptr, false);
  if (all.is_discarded() || !all.is_object() || !all.contains(kMaterialsVariants)) return Json::object();
  return all[kMaterialsVariants];
}

const Json* member(const Json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  const auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

std::string shown(const Json& v) {
  const std::string text = v.dump();
  return text.size() <= 40 ? text : text.substr(0, 37) + "...";
}

}  // namespace

std::vector<std::string> read_material_variants(const tinygltf::Model& model, const std::string& file) {
  std::vector<std::string> names;
  const std::optional<Json> ext = extension_json(model.extensions, model.extensions_json_string);
  if (!ext) return names;
  auto fail = [&](const std::string& problem) {
    throw SceneLoadError(file, fmt::format("its {} extension {}", kMaterialsVariants, problem));
  };
  const Json* variants = member(*ext, "variants");
  if (!variants || !variants->is_array() || variants->empty())
    fail("has no \"variants\" array of {\"name\": ...} objects");
  for (std::size_t i = 0; i < variants->size(); ++i) {
    const Json* name = member((*variants)[i], "name");
    if (!name || !name->is_string())
      fail(fmt::format("has variant {} without a name (each variant is {{\"name\": ...}})", i));
    names.push_back(name->get<std::string>());
  }
  return names;
}

int choose_material_variant(const std::vector<std::string>& names, const std::string& wanted,
                            const std::string& file) {
  if (names.empty())
    throw SceneLoadError(file, fmt::format("has no material variants ({}), so variant '{}' cannot be chosen",
                                           kMaterialsVariants, wanted));
  for (std::size_t i = 0; i < names.size(); ++i)
    if (names[i] == wanted) return static_cast<int>(i);
  const bool numeric = !wanted.empty() && std::all_of(wanted.begin(), wanted.end(), ::isdigit);
  if (numeric && wanted.size() < 9 && std::stoi(wanted) < static_cast<int>(names.size())) return std::stoi(wanted);
  std::string listed;
  for (std::size_t i = 0; i < names.size(); ++i) listed += fmt::format("{}{} '{}'", i ? ", " : "", i, names[i]);
  throw SceneLoadError(file, fmt::format("has no material variant '{}' (it has {}: {})", wanted,
                                         count_of(names.size(), "variant"), listed));
}

int material_for_variant(const tinygltf::Primitive& prim, int variant, std::size_t variant_count,
                         std::size_t material_count, const std::string& file, const std::string& what) {
  const std::optional<Json> ext = extension_json(prim.extensions, prim.extensions_json_string);
  if (!ext) return prim.material;
  auto fail = [&](const std::string& problem) {
    throw SceneLoadError(file, fmt::format("{}: {} {}", what, kMaterialsVariants, problem));
  };
  const Json* mappings = member(*ext, "mappings");
  if (!mappings || !mappings->is_array() || mappings->empty())
    fail("has no \"mappings\" array of {\"material\": ..., \"variants\": [...]} objects");
  std::vector<int> mapped_by(variant_count, -1);  // variant -> the mapping that lists it
  int material = prim.material;
  for (std::size_t m = 0; m < mappings->size(); ++m) {
    const Json& mapping = (*mappings)[m];
    if (!mapping.is_object()) fail(fmt::format("mapping {} is not a JSON object", m));
    const Json* mat = member(mapping, "material");
    if (!mat) fail(fmt::format("mapping {} has no material", m));
    if (!mat->is_number_unsigned())
      fail(fmt::format("mapping {} has material {}, which is not an index", m, shown(*mat)));
    if (mat->get<std::uint64_t>() >= material_count)
      fail(fmt::format("mapping {} refers to material {}, but the file has {}", m, mat->get<std::uint64_t>(),
                       count_of(material_count, "material")));
    const Json* variants = member(mapping, "variants");
    if (!variants || !variants->is_array() || variants->empty())
      fail(fmt::format("mapping {} has no \"variants\" array of variant indices", m));
    for (const Json& v : *variants) {
      if (!v.is_number_unsigned()) fail(fmt::format("mapping {} lists variant {}, which is not an index", m, shown(v)));
      const std::uint64_t index = v.get<std::uint64_t>();
      if (index >= variant_count)
        fail(fmt::format("mapping {} refers to variant {}, but the file has {}", m, index,
                         count_of(variant_count, "variant")));
      int& first = mapped_by[index];
      if (first == static_cast<int>(m)) fail(fmt::format("mapping {} lists variant {} twice", m, index));
      if (first >= 0)
        fail(fmt::format("mappings {} and {} both list variant {}; a primitive may map each variant once",
                         first, m, index));
      first = static_cast<int>(m);
      if (static_cast<int>(index) == variant) material = static_cast<int>(mat->get<std::uint64_t>());
    }
  }
  return material;
}

std::vector<int> mapped_materials(const tinygltf::Primitive& prim) {
  std::vector<int> out;
  const std::optional<Json> ext = extension_json(prim.extensions, prim.extensions_json_string);
  const Json* mappings = ext ? member(*ext, "mappings") : nullptr;
  if (!mappings || !mappings->is_array()) return out;
  for (const Json& mapping : *mappings)
    if (const Json* mat = member(mapping, "material"); mat && mat->is_number_unsigned() &&
                                                       mat->get<std::uint64_t>() < static_cast<std::uint64_t>(INT32_MAX))
      out.push_back(static_cast<int>(mat->get<std::uint64_t>()));
  return out;
}

}  // namespace tessera
