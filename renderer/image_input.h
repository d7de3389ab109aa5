// Reads an OpenEXR frame back as named float channels (any pixel type converted to FLOAT):
// what `tessera denoise` needs of a frame tessera wrote.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace tessera {

// The file cannot be read as an EXR, or lacks what the caller needs: bad input (exit 2).
class ImageInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExrChannels {
  int width = 0, height = 0;
  std::map<std::string, std::vector<float>> channels;  // by name, one float per pixel, row-major

  bool has(const std::string& name) const { return channels.count(name) != 0; }
  // Interleaves the named channels (3 per pixel for {"R", "G", "B"}). Empty when any is missing.
  std::vector<float> interleave(const std::vector<std::string>& names) const;
};

// Every channel of the first part of `path`'s data window. Throws ImageInputError naming the
// file when it cannot be read.
ExrChannels read_exr_channels(const std::string& path);

}  // namespace tessera
