// Enums chosen by name on the command line (schedulers, tile orders, samplers): each keeps
// its names in one list, names[i] naming the value i, and converts through these two.
#pragma once

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

template <typename Enum>
const char* enum_name(const std::vector<std::string>& names, Enum value) {
  return names[static_cast<std::size_t>(value)].c_str();
}

// Throws std::invalid_argument("unknown WHAT 'NAME'").
template <typename Enum>
Enum parse_enum(const std::vector<std::string>& names, const std::string& name, const char* what) {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw std::invalid_argument("unknown " + std::string(what) + " '" + name + "'");
  return static_cast<Enum>(it - names.begin());
}

}  // namespace tessera
