#include "scene_io/base/gltf_accessor.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <fmt/format.h>

#include "scene_io/base/load_error.h"

namespace tessera {

int gltf_component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

const char* gltf_type_name(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    case TINYGLTF_TYPE_MAT2: return "MAT2";
    case TINYGLTF_TYPE_MAT3: return "MAT3";
    case TINYGLTF_TYPE_MAT4: return "MAT4";
    default: return "unknown";
  }
}

const char* gltf_component_type_name(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return "BYTE";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return "UNSIGNED_BYTE";
    case TINYGLTF_COMPONENT_TYPE_SHORT: return "SHORT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return "UNSIGNED_SHORT";
    case TINYGLTF_COMPONENT_TYPE_INT: return "INT";
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return "UNSIGNED_INT";
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return "FLOAT";
    case TINYGLTF_COMPONENT_TYPE_DOUBLE: return "DOUBLE";
    default: return "unknown";
  }
}

int gltf_component_size(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;  // INT and DOUBLE are not valid glTF 2.0 accessor types
  }
}

namespace {

template <typename T>
T load(const std::uint8_t* p) {
  T v;
  std::memcpy(&v, p, sizeof(T));
  return v;
}

// One component as a double; normalized integers as the glTF specification maps them.
double decode(const std::uint8_t* p, int component_type, bool normalized) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      double v = load<std::int8_t>(p);
      return normalized ? std::max(v / 127.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: {
      double v = load<std::uint8_t>(p);
      return normalized ? v / 255.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      double v = load<std::int16_t>(p);
      return normalized ? std::max(v / 32767.0, -1.0) : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      double v = load<std::uint16_t>(p);
      return normalized ? v / 65535.0 : v;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: {
      double v = load<std::uint32_t>(p);
      return normalized ? v / 4294967295.0 : v;
    }
    default: return load<float>(p);
  }
}

}  // namespace

void AccessorReader::fail(const std::string& problem) const { throw SceneLoadError(file, problem); }

const tinygltf::Accessor& AccessorReader::accessor(int index, const std::string& what) const {
  if (index < 0 || index >= static_cast<int>(model.accessors.size()))
    fail(fmt::format("{} refers to accessor {}, but the file has {}", what, index,
                     count_of(model.accessors.size(), "accessor")));
  if (defects) defects->check_used(fmt::format("accessor {}", index), file);
  if (read_log) read_log->insert(index);
  return model.accessors[index];
}

const std::uint8_t* AccessorReader::view_bytes(int view, std::size_t offset, std::size_t stride,
                                               std::size_t count, std::size_t element_size,
                                               const std::string& what) const {
  if (view < 0 || view >= static_cast<int>(model.bufferViews.size()))
    fail(fmt::format("{} refers to bufferView {}, but the file has {}", what, view,
                     count_of(model.bufferViews.size(), "bufferView")));
  if (defects) defects->check_used(fmt::format("bufferView {}", view), file);
  const tinygltf::BufferView& bv = model.bufferViews[view];
  if (bv.buffer < 0 || bv.buffer >= static_cast<int>(model.buffers.size()))
    fail(fmt::format("bufferView {} refers to buffer {}, but the file has {}", view, bv.buffer,
                     count_of(model.buffers.size(), "buffer")));
  if (defects) defects->check_used(fmt::format("buffer {}", bv.buffer), file);
  const std::vector<unsigned char>& data = model.buffers[bv.buffer].data;
  if (bv.byteOffset > data.size() || bv.byteLength > data.size() - bv.byteOffset)
    fail(fmt::format("bufferView {} spans bytes {}..{} of buffer {}, which has only {} bytes",
                     view, bv.byteOffset, bv.byteOffset + bv.byteLength, bv.buffer, data.size()));
  if (count == 0) return data.data() + bv.byteOffset;
  // Last byte read: offset + stride * (count - 1) + element_size, computed without overflow.
  const std::size_t limit = bv.byteLength;
  if (offset > limit)
    fail(fmt::format("{} starts at byte {} of bufferView {}, which has only {} bytes", what, offset,
                     view, limit));
  if ((count - 1) > (limit - offset) / std::max<std::size_t>(stride, 1) ||
      offset + stride * (count - 1) + element_size > limit) {
    // count <= 2^31 and stride, element_size < 2^16: no overflow in 64 bits.
    const std::uint64_t end = std::uint64_t{offset} + std::uint64_t{stride} * (count - 1) + element_size;
    fail(fmt::format("{} needs bytes {}..{} of bufferView {}, which has only {} bytes", what, offset,
                     end, view, limit));
  }
  return data.data() + bv.byteOffset + offset;
}

void AccessorReader::read_dense(const tinygltf::Accessor& acc, int components,
                                const std::string& what, std::vector<double>& out) const {
  if (acc.bufferView < 0) {  // all zeros (only sparse values, if any)
    out.assign(acc.count * components, 0.0);
    return;
  }
  const int csize = gltf_component_size(acc.componentType);
  const std::size_t element = static_cast<std::size_t>(csize) * components;
  std::size_t stride = element;
  const auto& views = model.bufferViews;
  if (acc.bufferView < static_cast<int>(views.size()) && views[acc.bufferView].byteStride != 0) {
    stride = views[acc.bufferView].byteStride;
    if (stride < element)
      fail(fmt::format("{} has {}-byte elements, but its bufferView {} has byteStride {}", what,
                       element, acc.bufferView, stride));
    if (stride % csize != 0)
      fail(fmt::format("{} has {}-byte components, but its bufferView {} has byteStride {}, not "
                       "a multiple of {}",
                       what, csize, acc.bufferView, stride, csize));
  }
  const std::uint8_t* base = view_bytes(acc.bufferView, acc.byteOffset, stride, acc.count,
                                        element, what);
  out.resize(acc.count * components);  // only now: the count is known to fit the buffer
  for (std::size_t i = 0; i < acc.count; ++i)
    for (int c = 0; c < components; ++c)
      out[i * components + c] =
          decode(base + i * stride + c * csize, acc.componentType, acc.normalized);
}

void AccessorReader::apply_sparse(const tinygltf::Accessor& acc, int components,
                                  const std::string& what, std::vector<double>& out) const {
  const auto& sp = acc.sparse;
  if (sp.count <= 0 || static_cast<std::size_t>(sp.count) > acc.count)
    fail(fmt::format("{}: sparse count {} is not within 1..{}", what, sp.count, acc.count));
  const int itype = sp.indices.componentType;
  if (itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      itype != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(fmt::format("{}: sparse indices have invalid componentType {}", what, itype));
  const std::size_t isize = gltf_component_size(itype);
  const std::size_t csize = gltf_component_size(acc.componentType);
  const std::uint8_t* idx = view_bytes(sp.indices.bufferView, sp.indices.byteOffset, isize,
                                       sp.count, isize, what + " (sparse indices)");
  const std::uint8_t* val = view_bytes(sp.values.bufferView, sp.values.byteOffset,
                                       csize * components, sp.count, csize * components,
                                       what + " (sparse values)");
  for (int i = 0; i < sp.count; ++i) {
    const double target = decode(idx + i * isize, itype, false);
    if (target >= static_cast<double>(acc.count))
      fail(fmt::format("{} has sparse index {} (sparse element {}), but only {}", what,
                       static_cast<std::uint64_t>(target), i, count_of(acc.count, "element")));
    for (int c = 0; c < components; ++c)
      out[static_cast<std::size_t>(target) * components + c] =
          decode(val + (i * components + c) * csize, acc.componentType, acc.normalized);
  }
}

std::vector<double> AccessorReader::read(int index, int components, const std::string& what) const {
  const tinygltf::Accessor& acc = accessor(index, what);
  const std::string name = fmt::format("accessor {} ({})", index, what);
  if (gltf_component_size(acc.componentType) == 0)
    fail(fmt::format("{} has componentType {} ({}), which glTF 2.0 does not allow", name,
                     acc.componentType, gltf_component_type_name(acc.componentType)));
  if (gltf_component_count(acc.type) != components)
    fail(fmt::format("{} has type {}, but {} is needed", name, gltf_type_name(acc.type),
                     components == 1 ? "SCALAR" : fmt::format("VEC{}", components)));
  if (acc.count > (std::size_t{1} << 31))
    fail(fmt::format("{} has an implausible count {}", name, acc.count));
  // Without a bufferView the elements are zeros (bar the sparse ones) that the file does not
  // store: a few bytes of JSON could otherwise ask for gigabytes.
  constexpr std::size_t kMostUnstored = std::size_t{1} << 24;
  if (acc.bufferView < 0 && acc.count > kMostUnstored)
    fail(fmt::format("{} has no bufferView and {} elements; tessera reads at most {} elements "
                     "that the file does not store",
                     name, acc.count, kMostUnstored));
  std::vector<double> out;
  read_dense(acc, components, name, out);
  if (acc.sparse.isSparse) apply_sparse(acc, components, name, out);
  return out;
}

std::vector<float> AccessorReader::floats(int index, int components, const std::string& what) const {
  std::vector<double> values = read(index, components, what);
  std::vector<float> out(values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i]))
      fail(fmt::format("accessor {} ({}) holds {} at element {}", index, what,
                       std::isnan(values[i]) ? "NaN" : values[i] > 0 ? "+infinity" : "-infinity",
                       i / components));
    out[i] = static_cast<float>(values[i]);
  }
  return out;
}

std::vector<std::uint32_t> AccessorReader::indices(int index, const std::string& what) const {
  const tinygltf::Accessor& acc = accessor(index, what);
  if (acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE &&
      acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT &&
      acc.componentType != TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT)
    fail(fmt::format("accessor {} ({}) has componentType {} ({}); indices must be UNSIGNED_BYTE, "
                     "UNSIGNED_SHORT or UNSIGNED_INT",
                     index, what, acc.componentType, gltf_component_type_name(acc.componentType)));
  std::vector<double> values = read(index, 1, what);
  return std::vector<std::uint32_t>(values.begin(), values.end());
}

}  // namespace tessera
