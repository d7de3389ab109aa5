#include "scene_io/base/gltf_defects.h"

namespace tessera {

void GltfDefects::check_used(const std::string& object, const std::string& file) const {
  if (auto it = problems.find(object); it != problems.end()) throw SceneLoadError(file, it->second.text);
}

std::vector<std::string> GltfDefects::unused_warnings() const {
  std::vector<std::string> out = notes;
  for (const auto& [object, problem] : problems)
    if (problem.invalid) out.push_back(kUnusedPrefix + problem.text);
  return out;
}

}  // namespace tessera
