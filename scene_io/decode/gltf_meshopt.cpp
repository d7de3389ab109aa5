#include "scene_io/decode/gltf_meshopt.h"

#include <meshoptimizer.h>

#include <fmt/format.h>

#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

// The extension's properties of one bufferView.
struct MeshoptView {
  int buffer = -1;
  std::size_t offset = 0, length = 0, stride = 0, count = 0;
  std::string mode, filter = "NONE";
};

std::size_t unsigned_of(const tinygltf::Value& ext, const char* key, std::size_t fallback) {
  if (!ext.Has(key)) return fallback;
  const tinygltf::Value& v = ext.Get(key);
  if (!v.IsNumber() || v.GetNumberAsDouble() < 0 || v.GetNumberAsDouble() > 4294967295.0) return SIZE_MAX;
  return static_cast<std::size_t>(v.GetNumberAsDouble());
}

std::string string_of(const tinygltf::Value& ext, const char* key, const std::string& fallback) {
  return ext.Has(key) && ext.Get(key).IsString() ? ext.Get(key).Get<std::string>() : fallback;
}

MeshoptView read_extension(const tinygltf::Value& ext) {
  MeshoptView v;
  const std::size_t buffer = unsigned_of(ext, "buffer", SIZE_MAX);
  v.buffer = buffer > INT32_MAX ? -1 : static_cast<int>(buffer);
  v.offset = unsigned_of(ext, "byteOffset", 0);
  v.length = unsigned_of(ext, "byteLength", SIZE_MAX);
  v.stride = unsigned_of(ext, "byteStride", SIZE_MAX);
  v.count = unsigned_of(ext, "count", SIZE_MAX);
  v.mode = string_of(ext, "mode", "");
  v.filter = string_of(ext, "filter", "NONE");
  return v;
}

// Why the extension's properties are unusable (the specification's constraints, which
// meshoptimizer asserts rather than checks), or empty.
std::string invalid(const MeshoptView& v, const tinygltf::Model& model) {
  if (v.buffer < 0 || v.buffer >= static_cast<int>(model.buffers.size()))
    return fmt::format("refers to buffer {}, but the file has {}", v.buffer, count_of(model.buffers.size(), "buffer"));
  if (v.length == SIZE_MAX || v.stride == SIZE_MAX || v.count == SIZE_MAX || v.offset == SIZE_MAX)
    return "lacks a valid byteLength, byteStride or count";
  const std::size_t size = model.buffers[v.buffer].data.size();
  if (v.offset > size || v.length > size - v.offset)
    return fmt::format("spans bytes {}..{} of buffer {}, which has only {} bytes", v.offset, v.offset + v.length,
                       v.buffer, size);
  if (v.mode == "ATTRIBUTES") {
    if (v.stride == 0 || v.stride % 4 != 0 || v.stride > 256) return fmt::format("has byteStride {}; ATTRIBUTES needs a multiple of 4 up to 256", v.stride);
  } else if (v.mode == "TRIANGLES" || v.mode == "INDICES") {
    if (v.stride != 2 && v.stride != 4) return fmt::format("has byteStride {}; {} needs 2 or 4", v.stride, v.mode);
    if (v.mode == "TRIANGLES" && v.count % 3 != 0) return fmt::format("has count {}; TRIANGLES needs a multiple of 3", v.count);
  } else {
    return fmt::format("has mode '{}' (expected ATTRIBUTES, TRIANGLES or INDICES)", v.mode);
  }
  if (v.filter != "NONE" && v.mode != "ATTRIBUTES") return fmt::format("has filter {} with mode {}; filters need ATTRIBUTES", v.filter, v.mode);
  if (v.filter == "OCTAHEDRAL" && v.stride != 4 && v.stride != 8) return fmt::format("has byteStride {}; OCTAHEDRAL needs 4 or 8", v.stride);
  if (v.filter == "QUATERNION" && v.stride != 8) return fmt::format("has byteStride {}; QUATERNION needs 8", v.stride);
  if (v.filter != "NONE" && v.filter != "OCTAHEDRAL" && v.filter != "QUATERNION" && v.filter != "EXPONENTIAL")
    return fmt::format("has filter '{}' (expected NONE, OCTAHEDRAL, QUATERNION or EXPONENTIAL)", v.filter);
  // The codecs spend at least 1/64 of a byte on a decoded byte (an all-zero vertex byte group
  // costs 2 bits for 16 bytes), so a larger ratio is a corrupt file asking for gigabytes.
  constexpr std::size_t kMostRatio = 128;
  if (v.count > (std::size_t{1} << 31) || v.count * v.stride > kMostRatio * v.length + 4096)
    return fmt::format("decodes to {} elements of {} bytes from only {} bytes", v.count, v.stride, v.length);
  return "";
}

// 0 on success, else meshoptimizer's negative error code.
int decode(const MeshoptView& v, const unsigned char* src, std::vector<unsigned char>& out) {
  unsigned char* dst = out.data();
  if (v.mode == "TRIANGLES") return meshopt_decodeIndexBuffer(dst, v.count, v.stride, src, v.length);
  if (v.mode == "INDICES") return meshopt_decodeIndexSequence(dst, v.count, v.stride, src, v.length);
  const int rc = meshopt_decodeVertexBuffer(dst, v.count, v.stride, src, v.length);
  if (rc != 0) return rc;
  if (v.filter == "OCTAHEDRAL") meshopt_decodeFilterOct(dst, v.count, v.stride);
  if (v.filter == "QUATERNION") meshopt_decodeFilterQuat(dst, v.count, v.stride);
  if (v.filter == "EXPONENTIAL") meshopt_decodeFilterExp(dst, v.count, v.stride);
  return 0;
}

// " of POSITION of mesh 0 primitive 1": the first use of bufferView `view` by a mesh, if any.
std::string mesh_use(const tinygltf::Model& model, int view) {
  auto uses = [&](int accessor) {
    return accessor >= 0 && accessor < static_cast<int>(model.accessors.size()) &&
           model.accessors[accessor].bufferView == view;
  };
  for (std::size_t m = 0; m < model.meshes.size(); ++m)
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      const tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      if (uses(prim.indices)) return fmt::format(" (indices of mesh {} primitive {})", m, p);
      for (const auto& [name, accessor] : prim.attributes)
        if (uses(accessor)) return fmt::format(" ({} of mesh {} primitive {})", name, m, p);
    }
  return "";
}

}  // namespace

void decode_meshopt_views(tinygltf::Model& model, const std::string& file) {
  for (std::size_t i = 0; i < model.bufferViews.size(); ++i) {
    tinygltf::BufferView& bv = model.bufferViews[i];
    auto it = bv.extensions.find("EXT_meshopt_compression");
    if (it == bv.extensions.end()) continue;
    const MeshoptView v = read_extension(it->second);
    const std::string what =
        fmt::format("EXT_meshopt_compression bufferView {}{}", i, mesh_use(model, static_cast<int>(i)));
    if (const std::string why = invalid(v, model); !why.empty())
      throw SceneLoadError(file, fmt::format("{} {}", what, why));
    if (v.count * v.stride > bv.byteLength)
      throw SceneLoadError(file, fmt::format("{} decodes to {} bytes, but the bufferView has byteLength {}", what,
                                             v.count * v.stride, bv.byteLength));
    tinygltf::Buffer decoded;  // sized by what decodes, never by the JSON's byteLength alone
    decoded.data.assign(v.count * v.stride, 0);
    const int rc = decode(v, model.buffers[v.buffer].data.data() + v.offset, decoded.data);
    if (rc != 0)
      throw SceneLoadError(file, fmt::format("{} could not be decoded: its {} data is corrupt (meshoptimizer error {})",
                                             what, v.mode, rc));
    const std::size_t decoded_size = decoded.data.size();
    model.buffers.push_back(std::move(decoded));
    bv.buffer = static_cast<int>(model.buffers.size()) - 1;
    bv.byteOffset = 0;
    bv.byteLength = decoded_size;
  }
}

}  // namespace tessera
