// Problems in single objects of a glTF file, found before conversion. The policy
// (docs/reliability.md): a problem in an object the chosen scene uses refuses the file; the
// same problem in an object it does not use is a warning. The objects are kept as harmless
// placeholders, and conversion asks here before it reads one.
#pragma once

#include <map>
#include <string>
#include <vector>

namespace tessera {

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
};

}  // namespace tessera
