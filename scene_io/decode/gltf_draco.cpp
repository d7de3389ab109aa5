#include "scene_io/decode/gltf_draco.h"

#include <cmath>
#include <cstring>
#include <limits>

#include <draco/compression/decode.h>
#include <fmt/format.h>

#include "scene_io/base/gltf_accessor.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

class DracoPrimitive {
 public:
  DracoPrimitive(tinygltf::Model& model, const std::string& file, std::string what)
      : model_(model), file_(file), what_(std::move(what)) {}

  void decode(const tinygltf::Value& ext, tinygltf::Primitive& prim) {
    decode_stream(view_of(ext));
    if (prim.indices >= 0) write_indices(prim.indices);
    if (!ext.Has("attributes") || !ext.Get("attributes").IsObject()) fail("has no attributes map");
    const tinygltf::Value& map = ext.Get("attributes");
    for (const std::string& name : map.Keys()) {
      auto it = prim.attributes.find(name);
      if (it == prim.attributes.end()) continue;  // the extension maps only what the primitive has
      const tinygltf::Value& id = map.Get(name);
      if (!id.IsNumber()) fail(fmt::format("maps {} to a Draco attribute id that is not a number", name));
      write_attribute(name, it->second, id.GetNumberAsInt());
    }
    model_.buffers.push_back(std::move(buffer_));
  }

 private:
  [[noreturn]] void fail(const std::string& problem) const {
    throw SceneLoadError(file_, fmt::format("{} (KHR_draco_mesh_compression) {}", what_, problem));
  }

  const tinygltf::BufferView& view_of(const tinygltf::Value& ext) const {
    const int view = ext.Has("bufferView") && ext.Get("bufferView").IsNumber() ? ext.Get("bufferView").GetNumberAsInt() : -1;
    if (view < 0 || view >= static_cast<int>(model_.bufferViews.size()))
      fail(fmt::format("refers to bufferView {}, but the file has {}", view, count_of(model_.bufferViews.size(), "bufferView")));
    const tinygltf::BufferView& bv = model_.bufferViews[view];
    if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model_.buffers.size()))
      fail(fmt::format("uses bufferView {}, which refers to a buffer the file does not have", view));
    const std::size_t size = model_.buffers[bv.buffer].data.size();
    if (bv.byteOffset > size || bv.byteLength > size - bv.byteOffset)
      fail(fmt::format("uses bufferView {}, which spans bytes {}..{} of buffer {}, which has only {} bytes", view,
                       bv.byteOffset, bv.byteOffset + bv.byteLength, bv.buffer, size));
    return bv;
  }

  void decode_stream(const tinygltf::BufferView& bv) {
    draco::DecoderBuffer in;
    in.Init(reinterpret_cast<const char*>(model_.buffers[bv.buffer].data.data() + bv.byteOffset), bv.byteLength);
    draco::Decoder decoder;
    auto decoded = decoder.DecodeMeshFromBuffer(&in);
    if (!decoded.ok()) {
      std::string why = decoded.status().error_msg_string();
      if (!why.empty() && why.back() == '.') why.pop_back();  // Draco's messages end in one
      fail(fmt::format("could not be decoded: {}", why));
    }
    mesh_ = std::move(decoded).value();
    if (!mesh_) fail("could not be decoded: the Draco stream holds no mesh");
  }

  // Appends `bytes` to the primitive's new buffer as a new bufferView for accessor `a`.
  void place(int a, const std::vector<unsigned char>& bytes) {
    tinygltf::BufferView view;
    view.buffer = static_cast<int>(model_.buffers.size());  // buffer_, pushed last
    view.byteOffset = buffer_.data.size();
    view.byteLength = bytes.size();
    buffer_.data.insert(buffer_.data.end(), bytes.begin(), bytes.end());
    buffer_.data.resize((buffer_.data.size() + 3) / 4 * 4, 0);
    model_.bufferViews.push_back(view);
    tinygltf::Accessor& acc = model_.accessors[a];
    acc.bufferView = static_cast<int>(model_.bufferViews.size()) - 1;
    acc.byteOffset = 0;
    acc.sparse.isSparse = false;
  }

  const tinygltf::Accessor& accessor(int a, const std::string& use) const {
    if (a < 0 || a >= static_cast<int>(model_.accessors.size()))
      fail(fmt::format("has {} accessor {}, but the file has {}", use, a, count_of(model_.accessors.size(), "accessor")));
    return model_.accessors[a];
  }

  void write_indices(int a) {
    const tinygltf::Accessor& acc = accessor(a, "indices");
    const std::size_t size = gltf_component_size(acc.componentType);
    const std::size_t faces = mesh_->num_faces();
    if (acc.count != faces * 3)
      fail(fmt::format("decodes {} triangles, but its indices accessor {} has count {}", faces, a, acc.count));
    if (acc.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || size == 0 || acc.type != TINYGLTF_TYPE_SCALAR)
      fail(fmt::format("has indices accessor {} of an invalid type", a));
    const std::uint64_t most = size == 4 ? 0xFFFFFFFFull : (1ull << (8 * size)) - 1;
    std::vector<unsigned char> bytes(faces * 3 * size);
    for (std::size_t f = 0; f < faces; ++f)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t v = mesh_->face(draco::FaceIndex(static_cast<std::uint32_t>(f)))[k].value();
        if (v > most) fail(fmt::format("decodes index {}, more than its indices accessor {} can hold", v, a));
        std::memcpy(&bytes[(f * 3 + k) * size], &v, size);  // little-endian: the low bytes
      }
    place(a, bytes);
  }

  void write_attribute(const std::string& name, int a, int id) {
    const tinygltf::Accessor& acc = accessor(a, name);
    const draco::PointAttribute* att = mesh_->GetAttributeByUniqueId(static_cast<std::uint32_t>(id));
    if (!att) fail(fmt::format("maps {} to Draco attribute {}, which the stream does not hold", name, id));
    const std::size_t points = mesh_->num_points();
    if (acc.count != points)
      fail(fmt::format("decodes {} points, but accessor {} ({}) has count {}", points, a, name, acc.count));
    const int components = gltf_component_count(acc.type);
    const std::size_t size = gltf_component_size(acc.componentType);
    if (components == 0 || components > 4 || size == 0)
      fail(fmt::format("has accessor {} ({}) of an invalid type", a, name));
    std::vector<unsigned char> bytes(points * components * size);
    for (std::size_t i = 0; i < points; ++i) {
      const draco::AttributeValueIndex v = att->mapped_index(draco::PointIndex(static_cast<std::uint32_t>(i)));
      if (!convert(*att, v, acc, components, &bytes[i * components * size]))
        fail(fmt::format("decodes {} values that accessor {} ({} {}) cannot hold", name, a,
                         gltf_type_name(acc.type), gltf_component_type_name(acc.componentType)));
    }
    place(a, bytes);
  }

  // One value in the accessor's component type. A float attribute becomes a normalized
  // integer by rounding value * max, as glTF's normalisation inverts.
  template <typename T>
  static bool as(const draco::PointAttribute& att, draco::AttributeValueIndex v, bool normalized, int n,
                 unsigned char* out) {
    T values[4] = {};
    if (std::is_integral<T>::value && normalized && att.data_type() == draco::DT_FLOAT32) {
      float f[4] = {};
      if (!att.ConvertValue<float>(v, static_cast<std::int8_t>(n), f)) return false;
      for (int c = 0; c < n; ++c) {
        const double lo = std::is_signed<T>::value ? -1.0 : 0.0;
        if (!std::isfinite(f[c])) return false;
        values[c] = static_cast<T>(std::lround(std::clamp<double>(f[c], lo, 1.0) * std::numeric_limits<T>::max()));
      }
    } else if (!att.ConvertValue<T>(v, static_cast<std::int8_t>(n), values)) {
      return false;
    }
    std::memcpy(out, values, sizeof(T) * n);
    return true;
  }

  static bool convert(const draco::PointAttribute& att, draco::AttributeValueIndex v, const tinygltf::Accessor& acc,
                      int n, unsigned char* out) {
    switch (acc.componentType) {
      case TINYGLTF_COMPONENT_TYPE_BYTE: return as<std::int8_t>(att, v, acc.normalized, n, out);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return as<std::uint8_t>(att, v, acc.normalized, n, out);
      case TINYGLTF_COMPONENT_TYPE_SHORT: return as<std::int16_t>(att, v, acc.normalized, n, out);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return as<std::uint16_t>(att, v, acc.normalized, n, out);
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return as<std::uint32_t>(att, v, acc.normalized, n, out);
      default: return as<float>(att, v, false, n, out);
    }
  }

  tinygltf::Model& model_;
  const std::string& file_;
  const std::string what_;
  std::unique_ptr<draco::Mesh> mesh_;
  tinygltf::Buffer buffer_;
};

}  // namespace

void decode_draco_primitives(tinygltf::Model& model, const std::string& file) {
  for (std::size_t m = 0; m < model.meshes.size(); ++m)
    for (std::size_t p = 0; p < model.meshes[m].primitives.size(); ++p) {
      tinygltf::Primitive& prim = model.meshes[m].primitives[p];
      auto it = prim.extensions.find("KHR_draco_mesh_compression");
      if (it == prim.extensions.end()) continue;
      DracoPrimitive(model, file, fmt::format("mesh {} primitive {}", m, p)).decode(it->second, prim);
    }
}

}  // namespace tessera
