// Writes frames: OpenEXR (float or half RGBA, AOV layers, render metadata in the header)
// and, through OpenImageIO, display formats (PNG, JPEG, PPM, ...: exposure, sRGB, 8 bit) or
// float formats (.hdr, .tif, .pfm). Every file is written under a temporary name beside
// its destination and renamed into place, so a failed run never truncates or replaces it.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

#include <glm/glm.hpp>

#include "imageio/display_transform.h"
#include "imageio/header_attribute.h"
#include "renderer/film/film.h"

namespace tessera {

// Writing failed (disk full, I/O error): a failure of the system, exit code 1.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The output path itself is unusable (unknown format, missing or read-only directory):
// bad usage, exit code 2.
class OutputPathError : public OutputError {
 public:
  using OutputError::OutputError;
};

struct FrameMetadata {
  double render_seconds = 0.0;
  std::uint32_t seed = 0;
  std::string sampler;  // the sample pattern's name
  std::string pixel_filter;  // "NAME WIDTH"
  int threads = 0, tile_size = 0, max_bounces = 0;
  std::uint64_t dropped_samples = 0;
  glm::mat4 world_to_camera{1.0f}, world_to_ndc{1.0f};
  std::string scene_path, camera_name;
  std::string material_variant;  // the scene's material variant rendered (empty: none, not written)
  bool animated = false;  // animations posed the scene: sceneTime written
  float scene_time = 0.0f;  // seconds
  int frame = -1;  // --frame (-1: not given, not written), with frames_per_second
  float frames_per_second = 0.0f;
  float shutter_open = 0.0f, shutter_close = 0.0f;  // scene seconds; written when open < close
  bool partial = false;  // stopped early: samplesPerPixel tells how far it got
  int target_spp = 0;  // --spp: what a finished render reaches (0: not written)
  float noise_threshold = 0.0f;  // adaptive sampling (0: off, not written)
  int min_spp = 0;  // adaptive sampling: the minimum in effect
  std::uint64_t converged_pixels = 0;  // adaptive sampling: pixels stopped before target_spp
  bool denoised = false;  // RGB is denoised; noisy.R/G/B holds the beauty as rendered
  bool film_transparent = false;  // A is the camera rays' coverage; RGB has no background
  std::string owner, comments;  // OpenEXR's standard attributes (empty: not written)
  std::string command_line;  // the tessera command that made the frame
};

struct ImageWriteParams {
  bool half = false;  // EXR: 16-bit half floats for the colour channels (Z, N and counts stay 32-bit)
  FrameWindow window;  // EXR: where the image lies in its frame (data and display windows)
  float exposure = 0.0f;  // non-EXR formats: stops applied (before the view of display formats)
  DisplayParams display;  // display formats (8-bit): the view from scene-linear to the display
  FrameMetadata metadata;  // EXR header
  // EXR: also store the film losslessly with these settings lines, in a second part of the
  // file, so that --resume can continue it (see imageio/resume_layers.h). Null: a plain frame.
  const FilmState* resume_film = nullptr;
  std::string resume_settings;
  std::string resume_options;  // the options it was rendered with, for `--resume FILE` alone
  // EXR: also copy the header attributes of this EXR (not its layout: channels, windows,
  // compression), over tessera's own. A denoised frame keeps its render's metadata.
  std::string header_from;
  // EXR: false writes only who made the file (software, version, chromaticities, capDate,
  // owner, comments) and `attributes`, not the render's settings: layers that tessera did not
  // render (the Python module's tessera.write_exr).
  bool render_metadata = true;
  std::vector<HeaderAttribute> attributes;  // EXR: written last, over tessera's own
};

// Throws OutputPathError when `path` cannot be written: unknown format, missing or read-only
// directory, a directory in the way. Call it before rendering.
void check_output_path(const std::string& path);

// True when `path` names an OpenEXR file (by its extension, in any case).
bool is_exr_path(const std::string& path);

// True when `path` names a display format (8 bit, through the view transform): neither EXR
// nor a float format (.hdr, .tif, .tiff, .pfm).
bool is_display_format_path(const std::string& path);

// Writes `image` to `path`, choosing the format by extension. Throws OutputError.
void write_image(const std::string& path, const FrameImage& image, const ImageWriteParams& params);

// Writes 8-bit RGB pixels as they are (a chart, a heat map) through OpenImageIO, row-major,
// top row first, atomically like write_image. Throws OutputError.
void write_rgb8_image(const std::string& path, int width, int height, const std::vector<std::uint8_t>& rgb);

std::string tessera_version();

// Lets OpenEXR compress and decompress scanline blocks on every core (once per process): a
// 1080p frame with its layers is over 100 MB of floats, slow to ZIP on one.
void enable_exr_threads();

}  // namespace tessera
