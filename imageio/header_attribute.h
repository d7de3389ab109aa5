// One attribute of an EXR header, of the value types tessera's frames use: strings, 32-bit
// integers, floats, doubles and 4x4 float matrices (worldToCamera, worldToNDC). How the
// Python module hands a frame's metadata out and back.
#pragma once

#include <string>
#include <variant>
#include <vector>

#include <glm/glm.hpp>

namespace tessera {

struct HeaderAttribute {
  std::string name;
  std::variant<std::string, int, float, double, glm::mat4> value;
};

}  // namespace tessera
