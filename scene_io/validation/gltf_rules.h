// Rules of glTF 2.0 that the Khronos glTF-Validator makes errors and tinygltf does not check:
// a POSITION accessor without bounds, morph targets that do not match their primitive, a matrix
// that is not a TRS, a skin without a common root, an extension its file does not declare or
// puts where the extension does not go, ... (docs/reliability.md lists them). A problem in one
// object is that object's (refused when the scene uses it, else a warning); one of the file as a
// whole (an empty array, a minVersion above the version) is a warning.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene_io/validation/gltf_diagnose.h"

namespace tessera {

struct GltfRuleProblems {
  std::vector<GltfObjectProblem> objects;
  std::vector<std::string> file;
};

GltfRuleProblems find_rule_problems(const nlohmann::json& j);

// Its part for mesh `m` (gltf_mesh_rules.cpp): a primitive's attributes and morph targets, the
// mesh's bufferViews. The problem, or nullopt.
std::optional<std::string> check_mesh_rules(const nlohmann::json& mesh, std::size_t m, const nlohmann::json& j);

// Its part for the file as a whole and for extensions (gltf_file_rules.cpp): empty arrays, a
// minVersion above the version, KHR_mesh_quantization not required, an extension object that
// extensionsUsed does not declare or that sits where its extension does not go.
void find_file_and_extension_problems(const nlohmann::json& j, GltfRuleProblems& out);

}  // namespace tessera
