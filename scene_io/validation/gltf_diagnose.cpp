#include "scene_io/validation/gltf_diagnose.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene_io/base/gltf_data_uri.h"
#include "scene_io/base/gltf_json.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using Problem = std::optional<std::string>;

// Media types whose data URIs tessera reads (tinygltf's, and WebP images).
bool readable_media_type(const std::string& type) {
  static const char* kTypes[] = {"application/octet-stream", "application/gltf-buffer", "image/png", "image/jpeg",
                                 "image/bmp", "image/gif", "image/webp", "text/plain"};
  return std::any_of(std::begin(kTypes), std::end(kTypes), [&](const char* t) { return type == t; });
}

// `what` is "buffer 2" or "image 0"; `expected_size` is checked when given.
Problem check_data_uri(const std::string& what, const std::string& uri,
                       std::optional<std::uint64_t> expected_size) {
  std::string why;
  const std::optional<DataUri> data = decode_data_uri(uri, why);
  if (!data) return what + " has a data URI " + why;
  if (!readable_media_type(data->media_type))
    return fmt::format("{} has a data URI of media type '{}' that tessera cannot read (it reads data URIs of "
                       "application/octet-stream, application/gltf-buffer, image/png, image/jpeg and image/webp)",
                       what, shorten(data->media_type));
  if (expected_size && data->bytes.size() != *expected_size)
    return fmt::format("{} has a data URI holding {} bytes, but its byteLength is {}", what, data->bytes.size(),
                       *expected_size);
  return std::nullopt;
}

Problem check_arrays(const Json& j) {
  for (const auto& [key, noun] : kGltfArrays) {
    const Json* a = member(j, key);
    if (a && !a->is_array()) return fmt::format("its \"{}\" is not a JSON array", key);
  }
  return std::nullopt;
}

Problem check_asset(const Json& j) {
  const Json* asset = member(j, "asset");
  if (!asset || !asset->is_object()) return "has no \"asset\" object (glTF requires one with a version)";
  const Json* version = member(*asset, "version");
  if (!version || !version->is_string()) return "its asset has no version string";
  const std::string v = version->get<std::string>();
  if (v.rfind("2.", 0) != 0) return fmt::format("is glTF version '{}'; tessera reads version 2.x", shorten(v));
  return std::nullopt;
}

Problem check_buffer(const Json& b, std::size_t i, const std::string& base_dir) {
  const std::string what = fmt::format("buffer {}", i);
  if (index_of(b, "byteLength") < 0) return what + " has no valid byteLength";
  if (index_of(b, "byteLength") == 0) return what + " has byteLength 0; it must be at least 1";
  const auto length = static_cast<std::uint64_t>(index_of(b, "byteLength"));
  const Json* uri_json = member(b, "uri");
  if (uri_json && !uri_json->is_string()) return what + " has a uri that is not a string";
  const std::string uri = uri_json ? uri_json->get<std::string>() : "";
  if (uri.empty()) return std::nullopt;  // a defect of the buffer alone (gltf_prepare.cpp)
  if (is_data_uri(uri)) return check_data_uri(what, uri, length);
  if (is_remote_uri(uri)) return fmt::format("{}: tessera reads local files only: {}", what, shorten(uri));
  const std::string path = resolve_gltf_uri(base_dir, uri);
  if (const std::string why = unreadable_reason(path); !why.empty())
    return fmt::format("{} refers to {}, which cannot be opened: {}", what, shorten(uri), why);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size != length)
    return fmt::format("{} ({}) has {} bytes, but its byteLength is {}", what, shorten(uri), size,
                       length);
  return std::nullopt;
}

Problem check_buffer_view(const Json& v, std::size_t i, const Json& j) {
  const long long buffer = index_of(v, "buffer");
  if (buffer < 0) return fmt::format("bufferView {} has no valid buffer index", i);
  const long long length = index_of(v, "byteLength");
  if (length < 0) return fmt::format("bufferView {} has no valid byteLength", i);
  if (length == 0) return fmt::format("bufferView {} has byteLength 0; it must be at least 1", i);
  const std::size_t buffers = array_size(j, "buffers");
  if (buffer >= static_cast<long long>(buffers))
    return fmt::format("bufferView {} refers to buffer {}, but the file has {}", i, buffer, count_of(buffers, "buffer"));
  // Its span, against the buffer's byteLength (an EXT_meshopt_compression view's data is decoded).
  const long long offset = std::max(index_of(v, "byteOffset"), 0LL);
  const long long buffer_length = index_of((*member(j, "buffers"))[buffer], "byteLength");
  const Json* extensions = member(v, "extensions");
  if (buffer_length >= 0 && offset + length > buffer_length && !(extensions && member(*extensions, "EXT_meshopt_compression")))
    return fmt::format("bufferView {} spans bytes {}..{} of buffer {}, which has only {} bytes", i, offset,
                       offset + length, buffer, buffer_length);
  if (const Json* stride = member(v, "byteStride")) {
    const bool ok = stride->is_number_unsigned() && stride->get<std::uint64_t>() <= 252 &&
                    stride->get<std::uint64_t>() % 4 == 0;
    if (!ok)
      return fmt::format("bufferView {} has byteStride {}; it must be a multiple of 4, at most 252",
                         i, shorten(stride->dump()));
    if (static_cast<long long>(stride->get<std::uint64_t>()) > length)
      return fmt::format("bufferView {} has byteStride {}, more than its byteLength {}", i,
                         stride->get<std::uint64_t>(), length);
  }
  return std::nullopt;
}

Problem check_accessor(const Json& a, std::size_t i) {
  static const char* kTypes[] = {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"};
  const Json* type = member(a, "type");
  if (!type || !type->is_string()) return fmt::format("accessor {} has no type", i);
  if (std::none_of(std::begin(kTypes), std::end(kTypes),
                   [&](const char* t) { return *type == t; }))
    return fmt::format("accessor {} has unknown type '{}'", i, shorten(type->get<std::string>()));
  const long long component = index_of(a, "componentType");
  if (component < TINYGLTF_COMPONENT_TYPE_BYTE || component > TINYGLTF_COMPONENT_TYPE_DOUBLE)
    return fmt::format("accessor {} has no valid componentType", i);
  if (index_of(a, "count") < 0) return fmt::format("accessor {} has no valid count", i);
  if (member(a, "byteOffset") && !member(a, "bufferView"))
    return fmt::format("accessor {} has a byteOffset but no bufferView", i);
  const Json* sparse = member(a, "sparse");
  if (!sparse) return std::nullopt;
  const Json* indices = member(*sparse, "indices");
  const Json* values = member(*sparse, "values");
  if (index_of(*sparse, "count") < 0 || index_of(indices ? *indices : Json(), "bufferView") < 0 ||
      index_of(indices ? *indices : Json(), "componentType") < 0 || index_of(values ? *values : Json(), "bufferView") < 0)
    return fmt::format("accessor {} has a sparse object without a count, or indices or values without a bufferView "
                       "(and the indices a componentType)", i);
  return std::nullopt;
}

// POSITION, NORMAL, TANGENT, TEXCOORD_n, COLOR_n, JOINTS_n, WEIGHTS_n, or an application's _NAME.
bool known_attribute(const std::string& name) {
  if (name == "POSITION" || name == "NORMAL" || name == "TANGENT" || (!name.empty() && name[0] == '_')) return true;
  for (const char* set : {"TEXCOORD_", "COLOR_", "JOINTS_", "WEIGHTS_"}) {
    const std::size_t n = std::strlen(set);
    if (name.size() > n && name.compare(0, n, set) == 0 &&
        std::all_of(name.begin() + static_cast<std::ptrdiff_t>(n), name.end(), [](char c) { return std::isdigit(static_cast<unsigned char>(c)); }))
      return true;
  }
  return false;
}

// Transforms tinygltf reads one way although the specification forbids them: a matrix with TRS
// (tinygltf keeps the matrix), a rotation that is not a unit quaternion (tessera normalises it).
Problem check_node(const Json& node, std::size_t i) {
  if (member(node, "matrix") && (member(node, "translation") || member(node, "rotation") || member(node, "scale")))
    return fmt::format("node {} has both a matrix and translation, rotation or scale", i);
  const Json* rotation = member(node, "rotation");
  if (rotation && rotation->is_array() && rotation->size() == 4 &&
      std::all_of(rotation->begin(), rotation->end(), [](const Json& v) { return v.is_number(); })) {
    double squared = 0;
    for (const Json& v : *rotation) squared += v.get<double>() * v.get<double>();
    if (std::abs(std::sqrt(squared) - 1.0) > 0.01)
      return fmt::format("node {} has a rotation quaternion of length {:.4g}; it must be a unit quaternion", i,
                         std::sqrt(squared));
  }
  return std::nullopt;
}

Problem check_mesh(const Json& mesh, std::size_t m, const Json& j) {
  const Json* prims = member(mesh, "primitives");
  if (!prims || !prims->is_array() || prims->empty())
    return fmt::format("mesh {} has {}; glTF requires an array of at least one primitive", m,
                       !prims ? "no \"primitives\"" : prims->is_array() ? "an empty \"primitives\" array"
                                                                        : "a \"primitives\" that is not an array");
  const std::size_t accessors = array_size(j, "accessors"), views = array_size(j, "bufferViews");
  for (std::size_t p = 0; p < prims->size(); ++p) {
    const std::string what = fmt::format("mesh {} primitive {}", m, p);
    const Json* attributes = member((*prims)[p], "attributes");
    if (!attributes || !attributes->is_object()) return what + " has no \"attributes\" object";
    for (auto it = attributes->begin(); it != attributes->end(); ++it) {
      if (!it->is_number_integer())
        return fmt::format("{} has attribute {} that is not an accessor index", what, shorten(it.key()));
      if (!known_attribute(it.key()))
        return fmt::format("{} has attribute {}, which glTF does not define (an application's own begins with '_')",
                           what, shorten(it.key()));
    }
    const long long a = index_of((*prims)[p], "indices");
    if (a == -1) continue;
    if (a < 0 || a >= static_cast<long long>(accessors))
      return fmt::format("{} refers to accessor {} for its indices, but the file has {}", what,
                         shorten(member((*prims)[p], "indices")->dump()), count_of(accessors, "accessor"));
    const long long v = index_of((*member(j, "accessors"))[a], "bufferView");
    if (v >= static_cast<long long>(views))
      return fmt::format("accessor {} (indices of {}) refers to bufferView {}, but the file has {}", a, what, v,
                         count_of(views, "bufferView"));
  }
  return std::nullopt;
}

// Texture references tinygltf reads as none: a textureInfo without an index, or a negative one.
Problem check_texture_infos(const Json& material, std::size_t m) {
  std::vector<std::pair<std::string, const Json*>> stack = {{"", &material}};
  while (!stack.empty()) {  // every textureInfo, in the core material and its extensions
    const auto [key, object] = stack.back();
    stack.pop_back();
    if (!object->is_object()) continue;
    const Json* index = member(*object, "index");
    const bool texture_info = key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0;
    if (texture_info && (!index || !index->is_number_integer()))
      return fmt::format("material {} has a {} without an index", m, key);
    if (index && index->is_number_integer() && index->get<std::int64_t>() < 0)
      return fmt::format("material {} has {} index {}, which names no texture", m, key, index->get<std::int64_t>());
    for (auto it = object->begin(); it != object->end(); ++it) stack.emplace_back(it.key(), &*it);
  }
  return std::nullopt;
}

Problem check_material(const Json& material, std::size_t m) {
  const Json* pbr = member(material, "pbrMetallicRoughness");
  const Json* base = pbr ? member(*pbr, "baseColorFactor") : nullptr;
  if (base && (!base->is_array() || base->size() != 4))
    return fmt::format("material {} has a baseColorFactor that is not 4 numbers", m);
  const Json* emissive = member(material, "emissiveFactor");
  if (emissive && (!emissive->is_array() || emissive->size() != 3))
    return fmt::format("material {} has an emissiveFactor that is not 3 numbers", m);
  return check_texture_infos(material, m);
}

Problem check_image(const Json& image, std::size_t i, std::size_t views) {
  const std::string what = fmt::format("image {}", i);
  const Json* uri = member(image, "uri");
  const long long view = index_of(image, "bufferView");
  if (!uri && view == -1) return what + " has neither a uri nor a bufferView";
  if (uri && view != -1) return what + " has both a uri and a bufferView";
  if (uri && !uri->is_string()) return what + " has a uri that is not a string";
  if (uri && uri->get<std::string>().rfind("data:", 0) == 0)
    return check_data_uri(what, uri->get<std::string>(), std::nullopt);
  if (!uri && (view < 0 || view >= static_cast<long long>(views)))
    return fmt::format("{} refers to bufferView {}, but the file has {}", what,
                       shorten(member(image, "bufferView")->dump()), count_of(views, "bufferView"));
  if (!uri && !member(image, "mimeType"))
    return fmt::format("{} is in bufferView {} but has no mimeType (glTF requires one for an image in a bufferView)",
                       what, view);
  return std::nullopt;
}

Problem check_camera(const Json& camera, std::size_t i) {
  const Json* type = member(camera, "type");
  if (!type || !type->is_string()) return fmt::format("camera {} has no type", i);
  const std::string t = type->get<std::string>();
  if (t != "perspective" && t != "orthographic")
    return fmt::format("camera {} has unknown type '{}' (expected 'perspective' or 'orthographic')",
                       i, shorten(t));
  const Json* params = member(camera, t.c_str());
  if (!params || !params->is_object())
    return fmt::format("camera {} is {} but has no \"{}\" object", i, t, t);
  const std::vector<const char*> required = t == "perspective"
                                                ? std::vector<const char*>{"yfov", "znear"}
                                                : std::vector<const char*>{"xmag", "ymag", "znear", "zfar"};
  for (const char* key : required) {
    const Json* v = member(*params, key);
    if (!v || !v->is_number()) return fmt::format("camera {} has no {} number", i, key);
  }
  return std::nullopt;
}

Problem check_skin(const Json& skin, std::size_t i) {
  const Json* joints = member(skin, "joints");
  if (!joints || !joints->is_array() || joints->empty())
    return fmt::format("skin {} has no joints (glTF requires a \"joints\" array of at least one node)", i);
  if (!std::all_of(joints->begin(), joints->end(), [](const Json& n) { return n.is_number_integer(); }))
    return fmt::format("skin {} has a joint that is not a node index", i);
  return std::nullopt;
}

// The first sampler of the animation without its input or output accessor, named once.
Problem check_animation(const Json& animation, std::size_t i) {
  const Json* channels = member(animation, "channels");
  const Json* samplers = member(animation, "samplers");
  if (!channels || !channels->is_array() || channels->empty() || !samplers || !samplers->is_array() ||
      samplers->empty())
    return fmt::format("animation {} has no channels or no samplers (glTF requires at least one of each)", i);
  for (std::size_t c = 0; c < channels->size(); ++c) {
    const Json* target = member((*channels)[c], "target");
    const Json* path = target ? member(*target, "path") : nullptr;
    if (index_of((*channels)[c], "sampler") < 0 || !path || !path->is_string())
      return fmt::format("animation {} channel {} has no {}", i, c,
                         index_of((*channels)[c], "sampler") < 0 ? "sampler index" : "target path");
  }
  std::size_t incomplete = 0, first = 0;
  for (std::size_t s = samplers->size(); s-- > 0;)
    if (index_of((*samplers)[s], "input") < 0 || index_of((*samplers)[s], "output") < 0) ++incomplete, first = s;
  if (incomplete == 0) return std::nullopt;
  return fmt::format("animation {} sampler {}{} has no valid input and output accessors (glTF requires both)", i,
                     first, incomplete > 1 ? fmt::format(" (and {} more)", incomplete - 1) : "");
}

Problem check_scene(const Json& scene, std::size_t i) {
  const Json* nodes = member(scene, "nodes");
  if (nodes && (!nodes->is_array() || nodes->empty()))
    return fmt::format("scene {} has a \"nodes\" that is not an array of at least one node", i);
  return std::nullopt;
}

Problem check_light(const Json& light, std::size_t i) {
  const Json* type = member(light, "type");
  if (!type || !type->is_string()) return fmt::format("light {} has no type", i);
  const Json* spot = member(light, "spot");
  if (*type == "spot" && (!spot || !spot->is_object()))
    return fmt::format("light {} is a spot light but has no \"spot\" object", i);
  return std::nullopt;
}

const Json* lights_of(const Json& j) {
  const Json* extensions = member(j, "extensions");
  const Json* punctual = extensions ? member(*extensions, "KHR_lights_punctual") : nullptr;
  const Json* lights = punctual ? member(*punctual, "lights") : nullptr;
  return lights && lights->is_array() ? lights : nullptr;
}

// "line 27, column 5: syntax error ... invalid literal; last read: '0,<U+000A>    N'" names
// the token at the position instead, which also covers NaN and Infinity as some writers emit.
std::string json_syntax_error(const std::string& what, std::string_view json) {
  int line = 0, column = 0;
  const bool located = std::sscanf(what.c_str(), "line %d, column %d", &line, &column) == 2;
  if (!located || what.find("invalid literal") == std::string::npos) return "is not valid JSON: " + what;
  std::size_t at = 0;
  for (int l = 1; l < line && at != std::string_view::npos; ++l) {
    at = json.find('\n', at);
    if (at != std::string_view::npos) ++at;
  }
  if (at == std::string_view::npos || column < 1) return "is not valid JSON: " + what;
  at += column - 1;
  std::size_t end = at;
  while (end < json.size() && (std::isalnum(static_cast<unsigned char>(json[end])) || json[end] == '-' ||
                               json[end] == '+' || json[end] == '.'))
    ++end;
  if (at >= json.size() || end == at) return "is not valid JSON: " + what;
  const std::string token(json.substr(at, end - at));
  std::string lower = token;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  const bool nan_or_inf = lower.find("nan") != std::string::npos || lower.find("inf") != std::string::npos;
  return fmt::format("is not valid JSON: line {}, column {}: '{}' is not a JSON value{}", line, column,
                     shorten(token), nan_or_inf ? " (JSON has no NaN or Infinity)" : "");
}

}  // namespace

bool is_remote_uri(const std::string& uri) {
  const std::size_t colon = uri.find("://");
  return colon != std::string::npos && colon > 0 &&
         std::all_of(uri.begin(), uri.begin() + static_cast<std::ptrdiff_t>(colon),
                     [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '+' || c == '-' || c == '.'; });
}

std::string resolve_gltf_uri(const std::string& base_dir, const std::string& uri) {
  std::string decoded;
  for (std::size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      decoded += static_cast<char>(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      decoded += uri[i];
    }
  }
  if (base_dir.empty()) return decoded;
  return base_dir.back() == '/' ? base_dir + decoded : base_dir + "/" + decoded;
}

std::string unreadable_reason(const std::string& path) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (fs::is_directory(status)) return "it is a directory";
  // A device or pipe (a URI that climbs to /dev/zero or names a FIFO) would never end.
  if (fs::exists(status) && !fs::is_regular_file(status)) return "it is not a regular file (a device or pipe)";
  const int fd = ::open(path.c_str(), O_RDONLY);
  if (fd < 0) return std::strerror(errno);
  ::close(fd);
  return "";
}

std::vector<GltfObjectProblem> find_object_problems(const nlohmann::json& j, const std::string& base_dir) {
  std::vector<GltfObjectProblem> out;
  auto check_all = [&](const char* key, const char* noun, const Json* array, const auto& check) {
    if (!array || !array->is_array()) return;
    for (std::size_t i = 0; i < array->size(); ++i) {
      Problem p = (*array)[i].is_object() ? check((*array)[i], i) : fmt::format("{} {} is not a JSON object", noun, i);
      if (p) out.push_back({key, i, fmt::format("{} {}", noun, i), std::move(*p)});
    }
  };
  const std::size_t views = array_size(j, "bufferViews");
  const auto none = [](const Json&, std::size_t) { return Problem(); };
  for (const auto& [key, noun] : kGltfArrays) {
    const Json* array = member(j, key);
    const std::string k = key;
    if (k == "buffers") check_all(key, noun, array, [&](const Json& b, std::size_t i) { return check_buffer(b, i, base_dir); });
    else if (k == "bufferViews") check_all(key, noun, array, [&](const Json& v, std::size_t i) { return check_buffer_view(v, i, j); });
    else if (k == "accessors") check_all(key, noun, array, check_accessor);
    else if (k == "meshes") check_all(key, noun, array, [&](const Json& m, std::size_t i) { return check_mesh(m, i, j); });
    else if (k == "materials") check_all(key, noun, array, check_material);
    else if (k == "images") check_all(key, noun, array, [&](const Json& im, std::size_t i) { return check_image(im, i, views); });
    else if (k == "cameras") check_all(key, noun, array, check_camera);
    else if (k == "skins") check_all(key, noun, array, check_skin);
    else if (k == "animations") check_all(key, noun, array, check_animation);
    else if (k == "scenes") check_all(key, noun, array, check_scene);
    else if (k == "nodes") check_all(key, noun, array, check_node);
    else check_all(key, noun, array, none);
  }
  check_all("lights", "light", lights_of(j), check_light);
  return out;
}

std::optional<std::string> diagnose_gltf_json(const GltfDiagnoseInput& in) {
  const Json j = Json::parse(in.json.begin(), in.json.end(), nullptr, false);
  if (j.is_discarded()) return std::nullopt;
  if (!j.is_object()) return "is not glTF: its top-level JSON value is not an object";
  if (Problem p = check_asset(j)) return p;
  if (Problem p = check_arrays(j)) return p;
  const std::vector<GltfObjectProblem> problems = find_object_problems(j, in.base_dir);
  if (!problems.empty()) return problems.front().text;
  return std::nullopt;
}

std::string reword_tinygltf_error(const std::string& err, std::string_view json) {
  static const std::string kJsonPrefix = "[json.exception.";
  if (err.rfind(kJsonPrefix, 0) == 0) {  // nlohmann's exception text, one line
    std::string what = err.substr(err.find("] ") == std::string::npos ? 0 : err.find("] ") + 2);
    while (!what.empty() && std::isspace(static_cast<unsigned char>(what.back()))) what.pop_back();
    if (what.rfind("parse error at ", 0) == 0) return json_syntax_error(what.substr(15), json);
    static const std::string kOverflow = "number overflow parsing '";
    if (what.rfind(kOverflow, 0) == 0) {
      const std::string number = what.substr(kOverflow.size(), what.size() - kOverflow.size() - 1);
      const std::size_t at = json.find(number);
      const auto line = 1 + std::count(json.begin(), json.begin() + std::min(at, json.size()), '\n');
      return fmt::format("holds the number {} (line {}), too large for a 64-bit float",
                         shorten(number), line);
    }
    return "is not valid JSON: " + what;
  }
  try {  // tinygltf's own checks ("JSON string too short") come before nlohmann's precise ones
    const Json parsed = Json::parse(json.begin(), json.end());
  } catch (const Json::exception& e) {
    return reword_tinygltf_error(e.what(), json);
  }
  std::string joined;
  std::size_t start = 0;
  while (start < err.size()) {
    std::size_t end = err.find('\n', start);
    if (end == std::string::npos) end = err.size();
    std::string line = err.substr(start, end - start);
    while (!line.empty() && (std::isspace(static_cast<unsigned char>(line.back())) || line.back() == '.'))
      line.pop_back();
    if (!line.empty()) joined += (joined.empty() ? "" : "; ") + shorten(line, 160);
    start = end + 1;
  }
  return "is not valid glTF: " + (joined.empty() ? std::string("tinygltf could not read it") : joined);
}

}  // namespace tessera
