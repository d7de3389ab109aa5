// Problems in single objects of a glTF file, found before conversion. The policy
// (docs/reliability.md): a problem in an object the chosen scene uses refuses the file; the
// same problem in an object it does not use is a warning. The objects are kept as harmless
// placeholders, and conversion asks here before it reads one.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "scene_io/base/load_error.h"

namespace tessera {

// How a warning about an object the scene does not use begins.
inline constexpr const char* kUnusedPrefix = "ignored, as the scene does not use it: ";

struct GltfDefects {
  struct Problem {
    std::string text;  // "accessor 3 has unknown type 'VEC5'"
    bool invalid;  // against the specification: a warning when unused; else silent then
  };
  std::map<std::string, Problem> problems;  // by object: "accessor 3"
  std::vector<std::string> notes;  // file-level warnings (trailing bytes of a .glb)

  void add(const std::string& object, const std::string& problem, bool invalid = true) {
    problems.emplace(object, Problem{problem, invalid});
  }
  // Throws SceneLoadError(file, problem) when `object` has one: the scene uses it.
  void check_used(const std::string& object, const std::string& file) const;
  // After a conversion that threw nothing, every problem was in an object nothing used: the
  // notes, and a warning per invalid one.
  std::vector<std::string> unused_warnings() const;

  // Converts `object` ("skin 2") with `read`. When the scene uses it, its defect or what
  // `read` throws refuses the file. When not, an object with a defect is not read (the defect
  // is among unused_warnings), and what `read` throws becomes a warning in `warnings`; either
  // way `placeholder` stands in for it.
  template <typename T, typename Read>
  T read_object(bool used, const std::string& object, const std::string& file, std::vector<std::string>& warnings,
                Read read, T placeholder) const {
    if (used) {
      check_used(object, file);
      return read();
    }
    if (problems.count(object)) return placeholder;
    try {
      return read();
    } catch (const SceneLoadError& e) {
      warnings.push_back(kUnusedPrefix + e.problem());
    }
    return placeholder;
  }
};

}  // namespace tessera
