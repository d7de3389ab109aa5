// Bounds-checked reading of glTF accessors: every component type, normalized integers,
// byte strides and sparse substitution. Errors throw SceneLoadError with the file's name.
#pragma once

#include <cstdint>
#include <set>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene_io/base/gltf_defects.h"

namespace tessera {

struct AccessorReader {
  const tinygltf::Model& model;
  const std::string& file;  // for error messages
  const GltfDefects* defects{};  // accessors and buffers that are placeholders
  std::set<int>* read_log{};  // when given, every accessor index asked for is added

  // Reads accessor `index` as `components` floats per element. `what` names the use
  // ("POSITION of mesh 2 primitive 0") in errors. Normalized integers map to [0,1] or
  // [-1,1] as the specification says; other integers convert to their value.
  std::vector<float> floats(int index, int components, const std::string& what) const;

  // Reads a scalar unsigned-integer accessor (indices).
  std::vector<std::uint32_t> indices(int index, const std::string& what) const;

  const tinygltf::Accessor& accessor(int index, const std::string& what) const;

 private:
  void read_dense(const tinygltf::Accessor& acc, int components, const std::string& what,
                  std::vector<double>& out) const;
  void apply_sparse(const tinygltf::Accessor& acc, int components, const std::string& what,
                    std::vector<double>& out) const;
  const std::uint8_t* view_bytes(int view, std::size_t offset, std::size_t stride,
                                 std::size_t count, std::size_t element_size,
                                 const std::string& what) const;
  std::vector<double> read(int index, int components, const std::string& what) const;
  [[noreturn]] void fail(const std::string& problem) const;
};

int gltf_component_count(int type);  // TINYGLTF_TYPE_* -> 1..16, 0 if invalid
int gltf_component_size(int component_type);  // bytes, 0 if invalid
const char* gltf_type_name(int type);  // "VEC3"
const char* gltf_component_type_name(int component_type);  // "UNSIGNED_SHORT"

}  // namespace tessera
