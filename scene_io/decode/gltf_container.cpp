#include "scene_io/decode/gltf_container.h"

#include <algorithm>
#include <cctype>
#include <cstring>

#include <fmt/format.h>

#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

constexpr std::uint32_t kChunkJson = 0x4E4F534A;  // "JSON"
constexpr std::uint32_t kChunkBin = 0x004E4942;  // "BIN\0"

std::uint32_t le32(const std::uint8_t* p) {
  return static_cast<std::uint32_t>(p[0]) | static_cast<std::uint32_t>(p[1]) << 8 |
         static_cast<std::uint32_t>(p[2]) << 16 | static_cast<std::uint32_t>(p[3]) << 24;
}

// Up to four bytes as they would read in a hex editor's text column: 'gLTF', '\x89PNG'.
std::string quoted(const std::uint8_t* p, std::size_t n) {
  std::string out = "'";
  for (std::size_t i = 0; i < n; ++i)
    out += std::isprint(p[i]) ? std::string(1, static_cast<char>(p[i])) : fmt::format("\\x{:02x}", p[i]);
  return out + "'";
}

std::string chunk_type(std::uint32_t type) {
  std::uint8_t b[4] = {static_cast<std::uint8_t>(type), static_cast<std::uint8_t>(type >> 8),
                       static_cast<std::uint8_t>(type >> 16), static_cast<std::uint8_t>(type >> 24)};
  return quoted(b, 4);
}

bool ends_with_glb(const std::string& name) {
  if (name.size() < 4) return false;
  std::string ext = name.substr(name.size() - 4);
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".glb";
}

GltfContainer check_glb(const std::vector<std::uint8_t>& b, const std::string& name) {
  auto fail = [&](const std::string& problem) { throw SceneLoadError(name, problem); };
  std::size_t size = b.size();
  if (size < 12)
    fail(fmt::format("is truncated: it has {} bytes, fewer than the 12-byte binary glTF header", size));
  const std::uint32_t version = le32(&b[4]), length = le32(&b[8]);
  if (version != 2) fail(fmt::format("is binary glTF version {}; tessera reads version 2", version));
  if (length > size)
    fail(fmt::format("is truncated: its header gives a length of {} bytes, but the file has {}", length, size));
  const std::size_t trailing = size - length;  // the stream ends at `length`; the rest is ignored
  size = length;
  const char* end = trailing ? "the length its header gives" : "the end of the file";
  if (size < 20) fail("is truncated: it ends before the header of its JSON chunk");
  const std::uint32_t json_length = le32(&b[12]), json_type = le32(&b[16]);
  if (json_type != kChunkJson)
    fail(fmt::format("starts with a chunk of type {}; binary glTF starts with a 'JSON' chunk",
                     chunk_type(json_type)));
  if (json_length > size - 20)
    fail(fmt::format("has a JSON chunk of {} bytes, which runs past {} ({} bytes)",
                     json_length, end, size));
  if (json_length == 0) fail("has an empty JSON chunk");
  GltfContainer c;
  c.binary = true;
  c.json = std::string_view(reinterpret_cast<const char*>(&b[20]), json_length);
  c.trailing_bytes = trailing;
  const std::size_t next = 20 + std::size_t{json_length};
  if (next == size) return c;
  if (size - next < 8)
    fail(fmt::format("is truncated: it ends {} bytes after the JSON chunk, inside a chunk header",
                     size - next));
  const std::uint32_t bin_length = le32(&b[next]), bin_type = le32(&b[next + 4]);
  if (bin_type != kChunkBin)
    fail(fmt::format("has a second chunk of type {}; tessera reads only a 'BIN' chunk there",
                     chunk_type(bin_type)));
  if (bin_length > size - next - 8)
    fail(fmt::format("has a BIN chunk of {} bytes, which runs past {} ({} bytes)",
                     bin_length, end, size));
  if (bin_length == 0) fail("has an empty BIN chunk");
  if (bin_length % 4 != 0)
    fail(fmt::format("has a BIN chunk of {} bytes, not padded to a multiple of 4", bin_length));
  c.bin_chunk_size = bin_length;
  return c;
}

}  // namespace

GltfContainer check_gltf_container(const std::vector<std::uint8_t>& bytes,
                                   const std::string& display_name) {
  if (bytes.empty()) throw SceneLoadError(display_name, "is empty");
  if (bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0)
    return check_glb(bytes, display_name);
  std::size_t first = 0;
  if (bytes.size() >= 3 && bytes[0] == 0xEF && bytes[1] == 0xBB && bytes[2] == 0xBF) first = 3;  // BOM
  while (first < bytes.size() && std::isspace(bytes[first])) ++first;
  if (first == bytes.size()) throw SceneLoadError(display_name, "holds only white space");
  if (bytes[first] == '{' || bytes[first] == '[') {  // JSON; tinygltf says what is wrong
    GltfContainer c;
    c.json = std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size());
    return c;
  }
  if (ends_with_glb(display_name))
    throw SceneLoadError(display_name,
                         fmt::format("is not binary glTF: it starts with {}, not 'glTF'",
                                     quoted(bytes.data(), std::min<std::size_t>(4, bytes.size()))));
  throw SceneLoadError(display_name,
                       fmt::format("is not glTF: it starts with {}, neither '{{' (glTF JSON) nor "
                                   "'glTF' (binary glTF)",
                                   quoted(bytes.data() + first, std::min<std::size_t>(4, bytes.size() - first))));
}

namespace {
void put_le32(std::vector<std::uint8_t>& out, std::size_t at, std::uint32_t v) {
  for (int i = 0; i < 4; ++i) out[at + i] = static_cast<std::uint8_t>(v >> (8 * i));
}
}  // namespace

std::vector<std::uint8_t> replace_glb_json(const std::vector<std::uint8_t>& glb, std::string_view json) {
  const std::size_t rest = 20 + std::size_t{le32(&glb[12])};  // the BIN chunk, if any
  const std::size_t padded = (json.size() + 3) / 4 * 4;  // JSON chunks pad with spaces
  std::vector<std::uint8_t> out(glb.begin(), glb.begin() + 20);  // header; lengths set below
  out.resize(20 + padded, ' ');
  std::memcpy(out.data() + 20, json.data(), json.size());
  out.insert(out.end(), glb.begin() + static_cast<std::ptrdiff_t>(rest), glb.end());
  put_le32(out, 8, static_cast<std::uint32_t>(out.size()));
  put_le32(out, 12, static_cast<std::uint32_t>(padded));
  put_le32(out, 16, kChunkJson);
  return out;
}

}  // namespace tessera
