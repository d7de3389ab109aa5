// What a partial or checkpointed EXR carries so that `--resume` continues it bit for bit:
// the film's per-pixel sums and sample counts, losslessly, and the settings it was made
// with. The radiance sums are doubles; EXR has no double channels, so each double's 64 bits
// are stored as two UINT channels (high and low word): exact, unlike a hi/lo float pair,
// whose 48 bits of mantissa drop 5. The first-hit sums are floats and stored as FLOAT. All
// live in the second part of a two-part EXR, named "tessera.resume" (the first, "rgba",
// holds only the channels compositors show: see image_output), in the layer `tessera.`:
//   tessera.samples (UINT)                    samples each pixel got
//   tessera.sum.{R,G,B}.{hi,lo} (UINT)        radiance sums, the bits of a double
//   tessera.albedo.{R,G,B}, tessera.normal.{X,Y,Z}, tessera.depth (FLOAT), tessera.hits (UINT)
//                                             first-hit sums, when those AOVs are on (hits
//                                             also with --film-transparent)
//   tessera.odd.{R,G,B}.{hi,lo} (UINT)        sums of the odd-numbered samples, with the
//   tessera.odd.albedo.{R,G,B}, tessera.odd.normal.{X,Y,Z} (FLOAT)   halves AOV or adaptive sampling
//   tessera.converged (UINT)                  adaptive sampling: 1 where the pixel stopped
// and in the header: tesseraResume (the settings, "key=value" lines), tesseraFingerprint (a
// hash of those lines), tesseraOptions (the command's options, see app/cli/resume_options.h), droppedSamples and, with adaptive sampling, tesseraCheckedAt (the
// sample count of the wave after which the convergence flags were decided). Partials written
// before the two-part layout (one part, these channels beside RGBA) are still read.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>

#include "renderer/film/film.h"

#include <ImathBox.h>
#include <OpenEXR/ImfForward.h>

namespace tessera {

// The file cannot be resumed: not tessera's, no resume data, damaged. Bad input (exit 2).
class ResumeError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// The name of the EXR part that holds the resume channels.
inline const char* const kResumePartName = "tessera.resume";

// The EXR channels of a film, converted for writing; keeps the buffers the frame buffer
// points into alive until the file is written.
class ResumeLayers {
 public:
  // `options`: the command's options, stored as they are for a later `--resume FILE` alone
  // (the attribute tesseraOptions; empty: not written).
  ResumeLayers(const FilmState& film, std::string settings, std::string options = "");
  ~ResumeLayers();
  void insert_into(Imf::Header& header, Imf::FrameBuffer& frame_buffer, const Imath::Box2i& data_window);
  struct Buffers;  // the converted channels, defined in the .cpp

 private:
  std::unique_ptr<Buffers> buffers_;
  std::string settings_, options_;
};

// A 64-bit FNV-1a hash, printed as 16 hex digits: the fingerprint of settings and files.
std::string fnv1a_hex(const std::string& bytes);

// The settings lines `path` was written with (its header only). Throws ResumeError naming
// the file when it has none.
std::string read_resume_settings(const std::string& path);

// The options lines `path` was written with ("" from a file older than them). Throws
// ResumeError as read_resume_settings.
std::string read_resume_options(const std::string& path);

// What the film in a resumable file must be: its size and AOVs, and the render whose sample
// waves its counts must end on.
struct ResumeFilmSpec {
  int width = 0, height = 0;
  AovSelection aovs;
  int spp = 0;
  int adaptive_min_spp = 0;  // 0: not an adaptive render
  FrameWindow window{};  // where the film lies in its frame (--crop)
  int written_spp = 0;  // the target of the render that wrote it, if lower than spp (0: spp)
};

// The film `path` carries, which must match `spec`, every pixel's count the end of one of
// its sample waves (as a stopped render leaves them). Read once the settings matched.
// Throws ResumeError naming the file.
FilmState read_resume_film(const std::string& path, const ResumeFilmSpec& spec);

}  // namespace tessera
