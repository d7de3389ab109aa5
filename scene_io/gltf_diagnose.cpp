#include "scene_io/gltf_diagnose.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include <fmt/format.h>
#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene_io/load_error.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;
using Problem = std::optional<std::string>;

std::string shorten(const std::string& s, std::size_t most = 60) {
  return s.size() <= most ? s : s.substr(0, most - 3) + "...";
}

const Json* member(const Json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

std::size_t array_size(const Json& j, const char* key) {
  const Json* a = member(j, key);
  return a && a->is_array() ? a->size() : 0;
}

// An optional index property: -1 when absent, -2 when present but not a valid index.
long long index_of(const Json& object, const char* key) {
  const Json* v = member(object, key);
  if (!v) return -1;
  return v->is_number_unsigned() ? static_cast<long long>(v->get<std::uint64_t>()) : -2;
}

// Offset of the first character that is not valid base64, or npos.
std::size_t invalid_base64_at(std::string_view s) {
  std::size_t end = s.size();
  while (end > 0 && s.size() - end < 2 && s[end - 1] == '=') --end;
  for (std::size_t i = 0; i < end; ++i)
    if (!std::isalnum(static_cast<unsigned char>(s[i])) && s[i] != '+' && s[i] != '/') return i;
  return std::string_view::npos;
}

std::size_t base64_decoded_size(std::string_view s) {
  while (!s.empty() && s.back() == '=') s.remove_suffix(1);
  return s.size() / 4 * 3 + (s.size() % 4 == 3 ? 2 : s.size() % 4 == 2 ? 1 : 0);
}

// `what` is "buffer 2" or "image 0"; `expected_size` is checked when given.
Problem check_data_uri(const std::string& what, const std::string& uri,
                       std::optional<std::uint64_t> expected_size) {
  const std::size_t comma = uri.find(',');
  if (comma == std::string::npos)
    return what + " has a data URI without the ',' that ends its header (data:[media type][;base64],data)";
  const std::string header = uri.substr(0, comma);
  if (header.size() < 7 || header.compare(header.size() - 7, 7, ";base64") != 0)
    return fmt::format("{} has a data URI whose header '{}' does not end in ';base64' (tessera reads base64 data "
                       "URIs only)",
                       what, shorten(header));
  if (!tinygltf::IsDataURI(uri.substr(0, comma + 1))) {
    const std::string media = uri.substr(5, uri.find_first_of(";,") - 5);
    return fmt::format("{} has a data URI of media type '{}' that tessera cannot read (it reads "
                       "base64 data URIs of application/octet-stream, application/gltf-buffer, "
                       "image/png and image/jpeg)",
                       what, shorten(media));
  }
  const std::string_view payload = std::string_view(uri).substr(comma + 1);
  if (const std::size_t bad = invalid_base64_at(payload); bad != std::string_view::npos)
    return fmt::format("{} has a data URI that is not valid base64 (character {} of its data is "
                       "'{}')",
                       what, bad, payload[bad]);
  const std::size_t size = base64_decoded_size(payload);
  if (expected_size && size != *expected_size)
    return fmt::format("{} has a data URI holding {} bytes, but its byteLength is {}", what, size,
                       *expected_size);
  return std::nullopt;
}

Problem check_arrays(const Json& j) {
  static const std::pair<const char*, const char*> kArrays[] = {
      {"buffers", "buffer"},     {"bufferViews", "bufferView"}, {"accessors", "accessor"},
      {"meshes", "mesh"},        {"nodes", "node"},             {"scenes", "scene"},
      {"materials", "material"}, {"images", "image"},           {"textures", "texture"},
      {"samplers", "sampler"},   {"cameras", "camera"},         {"skins", "skin"},
      {"animations", "animation"}};
  for (const auto& [key, noun] : kArrays) {
    const Json* a = member(j, key);
    if (!a) continue;
    if (!a->is_array()) return fmt::format("its \"{}\" is not a JSON array", key);
    for (std::size_t i = 0; i < a->size(); ++i)
      if (!(*a)[i].is_object()) return fmt::format("{} {} is not a JSON object", noun, i);
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

Problem check_buffer(const Json& b, std::size_t i, const GltfDiagnoseInput& in) {
  const std::string what = fmt::format("buffer {}", i);
  const Json* length_json = member(b, "byteLength");
  if (!length_json || !length_json->is_number_unsigned()) return what + " has no valid byteLength";
  const std::uint64_t length = length_json->get<std::uint64_t>();
  const Json* uri_json = member(b, "uri");
  if (uri_json && !uri_json->is_string()) return what + " has a uri that is not a string";
  const std::string uri = uri_json ? uri_json->get<std::string>() : "";
  if (uri.empty()) return std::nullopt;  // a defect of the buffer alone (gltf_prepare.cpp)
  if (uri.rfind("data:", 0) == 0) return check_data_uri(what, uri, length);
  if (is_remote_uri(uri)) return fmt::format("{}: tessera reads local files only: {}", what, shorten(uri));
  const std::string path = resolve_gltf_uri(in.base_dir, uri);
  if (const std::string why = unreadable_reason(path); !why.empty())
    return fmt::format("{} refers to {}, which cannot be opened: {}", what, shorten(uri), why);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (!ec && size != length)
    return fmt::format("{} ({}) has {} bytes, but its byteLength is {}", what, shorten(uri), size,
                       length);
  return std::nullopt;
}

Problem check_buffer_view(const Json& v, std::size_t i) {
  const long long buffer = index_of(v, "buffer");
  if (buffer < 0) return fmt::format("bufferView {} has no valid buffer index", i);
  if (const Json* stride = member(v, "byteStride")) {
    const bool ok = stride->is_number_unsigned() && stride->get<std::uint64_t>() <= 252 &&
                    stride->get<std::uint64_t>() % 4 == 0;
    if (!ok)
      return fmt::format("bufferView {} has byteStride {}; it must be a multiple of 4, at most 252",
                         i, shorten(stride->dump()));
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
  return std::nullopt;
}

Problem check_mesh_indices(const Json& j) {
  const Json* meshes = member(j, "meshes");
  if (!meshes) return std::nullopt;
  const std::size_t accessors = array_size(j, "accessors"), views = array_size(j, "bufferViews");
  for (std::size_t m = 0; m < meshes->size(); ++m) {
    const Json* prims = member((*meshes)[m], "primitives");
    if (!prims || !prims->is_array() || prims->empty())
      return fmt::format("mesh {} has no primitives", m);
    for (std::size_t p = 0; p < prims->size(); ++p) {
      const long long a = index_of((*prims)[p], "indices");
      if (a == -1) continue;
      const std::string what = fmt::format("mesh {} primitive {}", m, p);
      if (a < 0 || a >= static_cast<long long>(accessors))
        return fmt::format("{} refers to accessor {} for its indices, but the file has {}", what,
                           shorten(member((*prims)[p], "indices")->dump()), count_of(accessors, "accessor"));
      const long long v = index_of((*member(j, "accessors"))[a], "bufferView");
      if (v >= static_cast<long long>(views))
        return fmt::format("accessor {} (indices of {}) refers to bufferView {}, but the file has {}",
                           a, what, v, count_of(views, "bufferView"));
    }
  }
  return std::nullopt;
}

Problem check_image(const Json& image, std::size_t i, std::size_t views) {
  const std::string what = fmt::format("image {}", i);
  const Json* uri = member(image, "uri");
  const long long view = index_of(image, "bufferView");
  if (!uri && view == -1) return what + " has neither a uri nor a bufferView";
  if (uri && !uri->is_string()) return what + " has a uri that is not a string";
  if (uri && uri->get<std::string>().rfind("data:", 0) == 0)
    return check_data_uri(what, uri->get<std::string>(), std::nullopt);
  if (!uri && (view < 0 || view >= static_cast<long long>(views)))
    return fmt::format("{} refers to bufferView {}, but the file has {}", what,
                       shorten(member(image, "bufferView")->dump()), count_of(views, "bufferView"));
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
  return std::nullopt;
}

// The first sampler of the animation without its input or output accessor, named once.
Problem check_animation(const Json& animation, std::size_t i) {
  const Json* samplers = member(animation, "samplers");
  if (!samplers || !samplers->is_array()) return std::nullopt;
  std::size_t incomplete = 0, first = 0;
  for (std::size_t s = samplers->size(); s-- > 0;)
    if (index_of((*samplers)[s], "input") < 0 || index_of((*samplers)[s], "output") < 0) ++incomplete, first = s;
  if (incomplete == 0) return std::nullopt;
  return fmt::format("animation {} sampler {}{} has no valid input and output accessors (glTF requires both)", i,
                     first, incomplete > 1 ? fmt::format(" (and {} more)", incomplete - 1) : "");
}

template <typename Check>
Problem each(const Json& j, const char* key, Check check) {
  const Json* a = member(j, key);
  if (!a) return std::nullopt;
  for (std::size_t i = 0; i < a->size(); ++i)
    if (Problem p = check((*a)[i], i)) return p;
  return std::nullopt;
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

std::optional<std::string> diagnose_gltf_json(const GltfDiagnoseInput& in) {
  const Json j = Json::parse(in.json.begin(), in.json.end(), nullptr, false);
  if (j.is_discarded()) return std::nullopt;
  if (!j.is_object()) return "is not glTF: its top-level JSON value is not an object";
  if (Problem p = check_asset(j)) return p;
  if (Problem p = check_arrays(j)) return p;
  const std::size_t views = array_size(j, "bufferViews");
  if (Problem p = each(j, "buffers", [&](const Json& b, std::size_t i) { return check_buffer(b, i, in); }))
    return p;
  if (Problem p = each(j, "bufferViews", check_buffer_view)) return p;
  if (Problem p = each(j, "accessors", check_accessor)) return p;
  if (Problem p = check_mesh_indices(j)) return p;
  if (Problem p = each(j, "images", [&](const Json& im, std::size_t i) { return check_image(im, i, views); }))
    return p;
  if (Problem p = each(j, "skins", check_skin)) return p;
  if (Problem p = each(j, "animations", check_animation)) return p;
  return each(j, "cameras", check_camera);
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
