// Reading the glTF JSON before tinygltf does (nlohmann::json): what a key holds, when it is there.
#pragma once

#include <cstdint>

#include <nlohmann/json.hpp>

namespace tessera {

// `object[key]`, or null when `object` is not an object or lacks the key.
inline const nlohmann::json* member(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) return nullptr;
  auto it = object.find(key);
  return it == object.end() ? nullptr : &*it;
}

// The size of the array `j[key]`; 0 when there is none.
inline std::size_t array_size(const nlohmann::json& j, const char* key) {
  const nlohmann::json* a = member(j, key);
  return a && a->is_array() ? a->size() : 0;
}

// An optional index property: -1 when absent, -2 when present but not a valid index.
inline long long index_of(const nlohmann::json& object, const char* key) {
  const nlohmann::json* v = member(object, key);
  if (!v) return -1;
  // (A number this program wrote into the JSON is signed: gltf_prepare.cpp's placeholders.)
  if (v->is_number_integer() && !v->is_number_unsigned()) return v->get<std::int64_t>() >= 0 ? v->get<std::int64_t>() : -2;
  return v->is_number_unsigned() ? static_cast<long long>(v->get<std::uint64_t>()) : -2;
}

// `j[array][index]`, or null when there is no such element.
inline const nlohmann::json& element(const nlohmann::json& j, const char* array, long long index) {
  static const nlohmann::json none;
  const nlohmann::json* a = member(j, array);
  return a && a->is_array() && index >= 0 && static_cast<std::size_t>(index) < a->size() ? (*a)[index] : none;
}

// True when an accessor gives both `min` and `max`.
inline bool has_min_max(const nlohmann::json& accessor) { return member(accessor, "min") && member(accessor, "max"); }

// The number of morph targets of a mesh primitive.
inline std::size_t morph_target_count(const nlohmann::json& primitive) {
  const nlohmann::json* targets = member(primitive, "targets");
  return targets && targets->is_array() ? targets->size() : 0;
}

}  // namespace tessera
