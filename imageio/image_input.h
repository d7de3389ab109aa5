// Reads an OpenEXR frame back as named float channels (any pixel type converted to FLOAT):
// what `tessera denoise` needs of a frame tessera wrote.
#pragma once

#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "imageio/header_attribute.h"
#include "renderer/film/film.h"

namespace tessera {

// The file cannot be read as an EXR, or lacks what the caller needs: bad input (exit 2).
class ImageInputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

struct ExrChannels {
  int width = 0, height = 0;
  FrameWindow window;  // where the pixels lie in the file's display window (a crop)
  std::map<std::string, std::vector<float>> channels;  // by name, one float per pixel, row-major
  std::string sampler;  // the header's `sampler` (tessera's frames name theirs); empty: none
  std::vector<HeaderAttribute> attributes;  // the header's, but its layout (exr_header.h)

  bool has(const std::string& name) const { return channels.count(name) != 0; }
  // Interleaves the named channels (3 per pixel for {"R", "G", "B"}). Empty when any is missing.
  std::vector<float> interleave(const std::vector<std::string>& names) const;
};

// Every channel of the first part of `path`'s data window. Throws ImageInputError naming the
// file when it cannot be read.
ExrChannels read_exr_channels(const std::string& path);

// A frame tessera wrote, read back: every layer of imageio/exr_layers.h that the file has
// complete, the per-pixel sample counts, and any other channel in extra_channels (but A and
// the `tessera.` resume layers). samples_per_pixel is the fewest count, when counts are there.
// Throws ImageInputError as read_exr_channels does.
FrameImage read_frame_exr(const std::string& path);
FrameImage frame_from_exr(ExrChannels exr);

}  // namespace tessera
