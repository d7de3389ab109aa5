#include "scene_io/decode/gltf_prepare.h"

#include <algorithm>
#include <iterator>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene_io/base/gltf_data_uri.h"
#include "scene_io/base/gltf_defects.h"
#include "scene_io/validation/gltf_diagnose.h"
#include "scene_io/base/gltf_extensions.h"
#include "scene_io/decode/gltf_images.h"
#include "scene_io/base/gltf_json.h"
#include "scene_io/validation/gltf_rules.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

using Json = nlohmann::json;

const Json* extension(const Json& object, const char* name) {
  const Json* ext = member(object, "extensions");
  return ext ? member(*ext, name) : nullptr;
}

void check_required(const Json& j, const std::string& name) {
  const Json* required = member(j, "extensionsRequired");
  if (!required || !required->is_array()) return;
  for (const Json& ext : *required)
    if (ext.is_string() && !is_supported_gltf_extension(ext.get<std::string>()))
      throw SceneLoadError(name, fmt::format("requires extension {}, which tessera does not support",
                                             ext.get<std::string>()));
}

// A fallback buffer without a uri has no bytes; the views that point into it are decoded
// from their compressed form (gltf_meshopt.cpp), so 4 zero bytes stand in for it.
bool fill_fallback_buffers(Json& j) {
  Json* buffers = j.contains("buffers") ? &j["buffers"] : nullptr;
  if (!buffers || !buffers->is_array()) return false;
  bool changed = false;
  for (Json& b : *buffers) {
    const Json* ext = extension(b, "EXT_meshopt_compression");
    const Json* fallback = ext ? member(*ext, "fallback") : nullptr;
    if (!fallback || *fallback != true || member(b, "uri")) continue;
    b["uri"] = "data:application/octet-stream;base64,AAAAAA==";
    b["byteLength"] = 4;
    changed = true;
  }
  return changed;
}

// tinygltf refuses an indices accessor without a bufferView, which a Draco primitive's has.
bool point_draco_indices(Json& j) {
  Json* meshes = j.contains("meshes") ? &j["meshes"] : nullptr;
  Json* accessors = j.contains("accessors") ? &j["accessors"] : nullptr;
  if (!meshes || !meshes->is_array() || !accessors || !accessors->is_array()) return false;
  bool changed = false;
  for (const Json& mesh : *meshes) {
    const Json* prims = member(mesh, "primitives");
    if (!prims || !prims->is_array()) continue;
    for (const Json& prim : *prims) {
      const Json* draco = extension(prim, "KHR_draco_mesh_compression");
      const Json* view = draco ? member(*draco, "bufferView") : nullptr;
      const Json* indices = member(prim, "indices");
      if (!view || !view->is_number_unsigned() || !indices || !indices->is_number_unsigned()) continue;
      const auto a = indices->get<std::uint64_t>();
      if (a >= accessors->size() || !(*accessors)[a].is_object() || (*accessors)[a].contains("bufferView"))
        continue;
      (*accessors)[a]["bufferView"] = *view;
      changed = true;
    }
  }
  return changed;
}

// Why buffer `i` has no data tessera can read, or empty when it has.
std::string dataless_buffer(const Json& b, std::size_t i, const GltfJsonContext& context) {
  if (member(b, "uri")) return "";
  const Json* length = member(b, "byteLength");
  if (!context.binary) return fmt::format("buffer {} has no uri (only a .glb's buffer 0 may omit it)", i);
  if (i > 0) return fmt::format("buffer {} has no uri, but only buffer 0 of a .glb may use the BIN chunk", i);
  if (context.bin_chunk_size == 0)
    return "buffer 0 has no uri, so its data is the BIN chunk, but the file has no BIN chunk";
  if (length && length->is_number_unsigned() && length->get<std::uint64_t>() > context.bin_chunk_size)
    return fmt::format("buffer 0 has byteLength {}, but the BIN chunk holds only {} bytes",
                       length->get<std::uint64_t>(), context.bin_chunk_size);
  return "";
}

// Buffers without data become 4-byte placeholders (gltf_parse.cpp empties them again).
bool replace_dataless_buffers(Json& j, const GltfJsonContext& context, GltfDefects& defects) {
  Json* buffers = j.contains("buffers") ? &j["buffers"] : nullptr;
  if (!buffers || !buffers->is_array()) return false;
  bool changed = false;
  for (std::size_t i = 0; i < buffers->size(); ++i) {
    Json& b = (*buffers)[i];
    if (!b.is_object() || extension(b, "EXT_meshopt_compression")) continue;  // fill_fallback_buffers' case
    const std::string problem = dataless_buffer(b, i, context);
    if (problem.empty()) continue;
    // Without a uri, a buffer is valid glTF (its data may come from an extension) until used.
    const bool invalid = context.binary && i == 0;
    defects.add(fmt::format("buffer {}", i), problem, invalid);
    b["uri"] = "data:application/octet-stream;base64,AAAAAA==";
    b["byteLength"] = 4;
    changed = true;
  }
  return changed;
}

// tinygltf hands an image's bufferView to the image decoder without checking that the view
// lies inside its buffer (a buffer replaced by a placeholder above, or a byteLength too small
// for the view): such an image becomes a defect and its data an undecodable stub, so no
// decoder reads past the buffer.
bool replace_images_past_their_buffers(Json& j, GltfDefects& defects) {
  Json* images = j.contains("images") ? &j["images"] : nullptr;
  const Json* views = member(j, "bufferViews");
  const Json* buffers = member(j, "buffers");
  if (!images || !images->is_array() || !views || !views->is_array() || !buffers || !buffers->is_array()) return false;
  auto number = [](const Json* v) { return v && v->is_number_unsigned() ? v->get<std::uint64_t>() : 0; };
  bool changed = false;
  for (std::size_t i = 0; i < images->size(); ++i) {
    Json& image = (*images)[i];
    const Json* view_index = member(image, "bufferView");
    if (!view_index || !view_index->is_number_unsigned() || view_index->get<std::uint64_t>() >= views->size()) continue;
    const Json& view = (*views)[view_index->get<std::size_t>()];
    const Json* buffer_index = member(view, "buffer");
    if (!buffer_index || !buffer_index->is_number_unsigned() || buffer_index->get<std::uint64_t>() >= buffers->size())
      continue;
    const std::uint64_t end = number(member(view, "byteOffset")) + number(member(view, "byteLength"));
    const std::uint64_t size = number(member((*buffers)[buffer_index->get<std::size_t>()], "byteLength"));
    if (end <= size) continue;
    defects.add(fmt::format("image {}", i), fmt::format("image {}'s bufferView {} ends at byte {}, past the {} bytes of "
                                                        "buffer {}'s data", i, view_index->get<std::uint64_t>(), end,
                                                        size, buffer_index->get<std::uint64_t>()));
    image = Json{{"uri", "data:image/png;base64,AAAA"}};  // three bytes no decoder takes for an image
    changed = true;
  }
  return changed;
}

// Data URIs tinygltf cannot decode although RFC 2397 allows them (percent-encoded data, not
// base64; percent escapes in base64; parameters in the header) are handed to it as plain base64.
// Those that cannot be decoded at all were replaced above.
bool reencode_data_uris(Json& j) {
  bool changed = false;
  for (const char* array : {"buffers", "images"}) {
    Json* objects = j.contains(array) ? &j[array] : nullptr;
    if (!objects || !objects->is_array()) continue;
    for (Json& object : *objects) {
      const Json* uri = member(object, "uri");
      if (!uri || !uri->is_string() || !is_data_uri(uri->get<std::string>())) continue;
      const std::string& text = uri->get_ref<const std::string&>();
      const std::size_t comma = text.find(',');
      const bool plain = comma != std::string::npos && text.find('%') == std::string::npos &&
                         (tinygltf::IsDataURI(text.substr(0, comma + 1)) || text.rfind("data:image/webp;base64,", 0) == 0);
      std::string problem;
      const std::optional<DataUri> data = plain ? std::nullopt : decode_data_uri(text, problem);
      if (!data) continue;
      object["uri"] = encode_data_uri(data->media_type, data->bytes);
      changed = true;
    }
  }
  return changed;
}

// An indices accessor without a bufferView (zeros, bar sparse ones) is valid glTF, but
// tinygltf refuses it: it waits in kIndicesWithoutView.
bool hand_over_viewless_indices(Json& j) {
  Json* meshes = j.contains("meshes") ? &j["meshes"] : nullptr;
  const Json* accessors = member(j, "accessors");
  if (!meshes || !meshes->is_array() || !accessors || !accessors->is_array()) return false;
  bool changed = false;
  for (Json& mesh : *meshes) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (Json& prim : mesh["primitives"]) {
      const Json* indices = member(prim, "indices");
      if (!indices || !indices->is_number_unsigned() || indices->get<std::uint64_t>() >= accessors->size()) continue;
      const Json& a = (*accessors)[indices->get<std::size_t>()];
      if (!a.is_object() || a.contains("bufferView")) continue;
      prim["extensions"][kIndicesWithoutView] = Json{{"accessor", *indices}};
      prim.erase("indices");
      changed = true;
    }
  }
  return changed;
}

// The placeholder an object with a problem becomes: what tinygltf reads without complaint and
// conversion never reads (it asks GltfDefects first). A buffer's 4 bytes are emptied again by
// gltf_parse.cpp; an image's 3 bytes decode as no image.
Json placeholder(const std::string& array, const Json& original) {
  if (array == "buffers") return Json{{"byteLength", 4}, {"uri", "data:application/octet-stream;base64,AAAAAA=="}};
  if (array == "bufferViews") return Json{{"buffer", 0}, {"byteLength", 0}};
  if (array == "accessors") return Json{{"componentType", 5126}, {"type", "SCALAR"}, {"count", 1}};
  if (array == "meshes") return Json{{"primitives", Json::array()}};
  if (array == "images") return Json{{"uri", "data:image/png;base64,AAAA"}};
  if (array == "cameras") return Json{{"type", "perspective"}, {"perspective", {{"yfov", 1}, {"znear", 1}}}};
  if (array == "skins") return Json{{"joints", Json::array()}};
  if (array == "lights") return Json{{"type", "point"}};
  if (array == "scenes") return Json{{"nodes", Json::array()}};
  if (array != "animations") return Json::object();
  // An animation keeps the nodes its channels target: whether it is used depends on them.
  Json channels = Json::array();
  const Json* original_channels = member(original, "channels");
  if (original_channels && original_channels->is_array())
    for (const Json& c : *original_channels) {
      const Json* target = member(c, "target");
      const Json* node = target ? member(*target, "node") : nullptr;
      if (node && node->is_number_integer())
        channels.push_back({{"sampler", 0}, {"target", {{"node", *node}, {"path", "translation"}}}});
    }
  return Json{{"channels", channels}, {"samplers", Json::array()}};
}

Json* object_array(Json& j, const std::string& array) {
  if (array != "lights") return j.contains(array) ? &j[array] : nullptr;
  return &j["extensions"]["KHR_lights_punctual"]["lights"];
}

// Objects tinygltf would refuse the file for, or misread in silence (gltf_diagnose.h), become
// placeholders with their problem in `defects`; so do images in a bufferView that did.
bool replace_unreadable_objects(Json& j, const GltfJsonContext& context, GltfDefects& defects) {
  std::vector<GltfObjectProblem> problems = find_object_problems(j, context.base_dir);
  GltfRuleProblems rules = find_rule_problems(j);
  problems.insert(problems.end(), rules.objects.begin(), rules.objects.end());
  defects.notes.insert(defects.notes.end(), rules.file.begin(), rules.file.end());
  for (const GltfObjectProblem& p : problems) {
    defects.add(p.object, p.text);
    Json& object = (*object_array(j, p.array))[p.index];
    if (p.array == "nodes" && object.is_object()) continue;  // tinygltf reads it; its children stay its own
    object = placeholder(p.array, object);
  }
  Json* images = j.contains("images") ? &j["images"] : nullptr;
  if (!images || !images->is_array()) return !problems.empty();
  for (std::size_t i = 0; i < images->size(); ++i) {
    const Json* view = member((*images)[i], "bufferView");
    if (!view || !view->is_number_unsigned()) continue;
    const std::string view_object = fmt::format("bufferView {}", view->get<std::uint64_t>());
    auto it = defects.problems.find(view_object);
    if (it == defects.problems.end()) continue;
    defects.add(fmt::format("image {}", i), fmt::format("image {} is in {}, which tessera cannot read: {}", i,
                                                        view_object, it->second.text));
    (*images)[i] = placeholder("images", (*images)[i]);
  }
  return true;
}

}  // namespace

std::optional<std::string> prepare_gltf_json(std::string_view json, const std::string& name,
                                             const GltfJsonContext& context, GltfDefects& defects,
                                             std::vector<DeclaredMediaTypes>& image_types) {
  Json j = Json::parse(json.begin(), json.end(), nullptr, /*allow_exceptions=*/false);
  if (!j.is_object()) return std::nullopt;
  check_required(j, name);
  image_types = declared_media_types(j);  // first: the rewrites below replace images
  bool changed = false;
  if (json.find("EXT_meshopt_compression") != std::string_view::npos) changed |= fill_fallback_buffers(j);
  if (json.find("KHR_draco_mesh_compression") != std::string_view::npos) changed |= point_draco_indices(j);
  if (const Json* ext = extension(j, "KHR_lights_punctual"); ext && !(member(*ext, "lights") && (*ext)["lights"].is_array()))
    defects.notes.push_back("its KHR_lights_punctual extension has no \"lights\" array");
  changed |= replace_unreadable_objects(j, context, defects);  // first: a buffer {} lacks its byteLength too
  changed |= replace_dataless_buffers(j, context, defects);
  changed |= reencode_data_uris(j);
  changed |= replace_images_past_their_buffers(j, defects);
  changed |= hand_over_viewless_indices(j);
  if (!changed) return std::nullopt;
  return j.dump();
}

}  // namespace tessera
