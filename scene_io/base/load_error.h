// The one exception a scene loader throws: the file and what is wrong with it.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <string>

namespace tessera {

class SceneLoadError : public std::runtime_error {
 public:
  SceneLoadError(const std::string& file, const std::string& problem)
      : std::runtime_error(file + ": " + problem), file_(file), problem_(problem) {}
  const std::string& file() const { return file_; }
  const std::string& problem() const { return problem_; }

 private:
  std::string file_, problem_;
};

// "no nodes", "1 node", "3 meshes": for messages such as "the file has 1 node".
inline std::string count_of(std::size_t n, const std::string& noun, std::string plural = "") {
  if (plural.empty()) {
    const bool es = noun.size() > 1 && (noun.back() == 's' || noun.compare(noun.size() - 2, 2, "sh") == 0);
    plural = noun + (es ? "es" : "s");
  }
  if (n == 0) return "no " + plural;
  return std::to_string(n) + " " + (n == 1 ? noun : plural);
}

// `s` cut to at most `most` characters, for quoting a value of the file in a message.
inline std::string shorten(const std::string& s, std::size_t most = 60) {
  return s.size() <= most ? s : s.substr(0, most - 3) + "...";
}

}  // namespace tessera
