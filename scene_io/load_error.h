// The one exception a scene loader throws: the file and what is wrong with it.
#pragma once

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

}  // namespace tessera
