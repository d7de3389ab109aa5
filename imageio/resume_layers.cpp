#include "imageio/resume_layers.h"

#include "imageio/exr_layers.h"

#include <cstdio>
#include <cstring>
#include <deque>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputPart.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>

#include "renderer/sampling/adaptive_sampling.h"
#include "renderer/parallel/tile_scheduler.h"

namespace tessera {

namespace {

const char* const kRgb[3] = {"R", "G", "B"};
const char* const kXyz[3] = {"X", "Y", "Z"};

// `prefix` "tessera.sum." for the radiance sums, "tessera.odd." for the odd half's,
// "tessera.sq." for the squares'.
std::string sum_channel(const std::string& prefix, int c, bool hi) {
  return prefix + kRgb[c] + (hi ? ".hi" : ".lo");
}

std::uint64_t bits_of(double d) {
  std::uint64_t b;
  std::memcpy(&b, &d, sizeof b);
  return b;
}

double double_of(std::uint64_t b) {
  double d;
  std::memcpy(&d, &b, sizeof d);
  return d;
}

}  // namespace

// One buffer per channel, planar, so every slice has the plain stride of its type.
struct ResumeLayers::Buffers {
  int width = 0;
  bool adaptive = false;
  std::uint32_t checked_at = 0;
  std::vector<std::pair<std::string, std::vector<std::uint32_t>>> uints;
  std::vector<std::pair<std::string, std::vector<float>>> floats;
};

namespace {

// Each double's 64 bits as two UINT channels.
void add_double_sums(ResumeLayers::Buffers& b, const std::vector<glm::dvec3>& sums, const std::string& prefix);
void add_float_sums(ResumeLayers::Buffers& b, const std::vector<vec3>& sums, const char* const names[3],
                    const std::string& layer);

}  // namespace

ResumeLayers::ResumeLayers(const FilmState& film, std::string settings, std::string options)
    : buffers_(std::make_unique<Buffers>()), settings_(std::move(settings)), options_(std::move(options)) {
  Buffers& b = *buffers_;
  b.width = film.width;
  b.checked_at = film.checked_at;
  b.uints.push_back({"tessera.samples", film.samples});
  add_double_sums(b, film.radiance, "tessera.sum.");
  if (film.aovs.albedo) add_float_sums(b, film.albedo, kRgb, "tessera.albedo.");
  if (film.aovs.normal) add_float_sums(b, film.normal, kXyz, "tessera.normal.");
  if (film.aovs.depth) b.floats.push_back({"tessera.depth", film.depth});
  if (film.aovs.counts_hits()) b.uints.push_back({"tessera.hits", film.hits});
  if (film.keeps_odd()) {
    add_double_sums(b, film.radiance_odd, "tessera.odd.");
    if (film.aovs.albedo) add_float_sums(b, film.albedo_odd, kRgb, "tessera.odd.albedo.");
    if (film.aovs.normal) add_float_sums(b, film.normal_odd, kXyz, "tessera.odd.normal.");
  }
  if (!film.radiance_sq.empty()) add_double_sums(b, film.radiance_sq, "tessera.sq.");
  if (film.adaptive()) {
    b.adaptive = true;
    b.uints.push_back({"tessera.converged", std::vector<std::uint32_t>(film.converged.begin(), film.converged.end())});
  }
}

namespace {

void add_double_sums(ResumeLayers::Buffers& b, const std::vector<glm::dvec3>& sums, const std::string& prefix) {
  const std::size_t n = sums.size();
  for (int c = 0; c < 3; ++c) {
    std::vector<std::uint32_t> hi(n), lo(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t bits = bits_of(sums[i][c]);
      hi[i] = static_cast<std::uint32_t>(bits >> 32);
      lo[i] = static_cast<std::uint32_t>(bits);
    }
    b.uints.push_back({sum_channel(prefix, c, true), std::move(hi)});
    b.uints.push_back({sum_channel(prefix, c, false), std::move(lo)});
  }
}

void add_float_sums(ResumeLayers::Buffers& b, const std::vector<vec3>& sums, const char* const names[3],
                    const std::string& layer) {
  for (int c = 0; c < 3; ++c) {
    std::vector<float> out(sums.size());
    for (std::size_t i = 0; i < sums.size(); ++i) out[i] = sums[i][c];
    b.floats.push_back({layer + names[c], std::move(out)});
  }
}

}  // namespace

ResumeLayers::~ResumeLayers() = default;

void ResumeLayers::insert_into(Imf::Header& header, Imf::FrameBuffer& fb, const Imath::Box2i& data_window) {
  const Buffers& b = *buffers_;
  for (const auto& [name, data] : b.uints) {
    header.channels().insert(name, Imf::Channel(Imf::UINT));
    fb.insert(name, Imf::Slice::Make(Imf::UINT, data.data(), data_window, sizeof(std::uint32_t),
                                     sizeof(std::uint32_t) * b.width));
  }
  for (const auto& [name, data] : b.floats) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice::Make(Imf::FLOAT, data.data(), data_window, sizeof(float), sizeof(float) * b.width));
  }
  header.insert("tesseraResume", Imf::StringAttribute(settings_));
  header.insert("tesseraFingerprint", Imf::StringAttribute(fnv1a_hex(settings_)));
  if (!options_.empty()) header.insert("tesseraOptions", Imf::StringAttribute(options_));
  if (b.adaptive) header.insert("tesseraCheckedAt", Imf::IntAttribute(static_cast<int>(b.checked_at)));
}

std::string fnv1a_hex(const std::string& bytes) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  char text[17];
  std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(h));
  return text;
}

namespace {

// Slices of the channels `film` (sized, AOVs chosen) must have, each checked for its type;
// the doubles and the vec3 sums are read into planes and put together afterwards.
class LayerReader {
 public:
  LayerReader(const Imf::Header& header, const FilmState& film, const std::string& path)
      : channels_(header.channels()), window_(header.dataWindow()), width_(film.width), n_(film.pixel_count()),
        path_(path) {}

  void uints(const std::string& name, std::uint32_t* data) {
    check(name, Imf::UINT, "UINT");
    fb_.insert(name, Imf::Slice::Make(Imf::UINT, data, window_, sizeof(std::uint32_t), sizeof(std::uint32_t) * width_));
  }
  void floats(const std::string& name, float* data) {
    check(name, Imf::FLOAT, "FLOAT");
    fb_.insert(name, Imf::Slice::Make(Imf::FLOAT, data, window_, sizeof(float), sizeof(float) * width_));
  }
  void doubles(const std::string& prefix, std::vector<glm::dvec3>* out) {
    for (int c = 0; c < 3; ++c)
      for (bool hi : {true, false}) uints(sum_channel(prefix, c, hi), plane_u());
    doubles_.push_back(out);
  }
  void vec3s(const char* const names[3], const std::string& layer, std::vector<vec3>* out) {
    for (int c = 0; c < 3; ++c) floats(layer + names[c], plane_f());
    vec3s_.push_back(out);
  }
  // Reads the pixels and assembles the doubles and vec3 sums in the order they were asked for.
  void read(Imf::InputPart& file) {
    file.setFrameBuffer(fb_);
    file.readPixels(window_.min.y, window_.max.y);
    for (std::size_t k = 0; k < doubles_.size(); ++k)
      for (std::size_t i = 0; i < n_; ++i)
        for (int c = 0; c < 3; ++c) {
          const auto& hi = u_planes_[6 * k + 2 * c];
          const auto& lo = u_planes_[6 * k + 2 * c + 1];
          (*doubles_[k])[i][c] = double_of(std::uint64_t(hi[i]) << 32 | lo[i]);
        }
    for (std::size_t k = 0; k < vec3s_.size(); ++k)
      for (int c = 0; c < 3; ++c)
        for (std::size_t i = 0; i < n_; ++i) (*vec3s_[k])[i][c] = f_planes_[3 * k + c][i];
  }

 private:
  void check(const std::string& name, Imf::PixelType type, const char* type_name) const {
    const Imf::Channel* ch = channels_.findChannel(name);
    if (!ch || ch->type != type)
      throw ResumeError(path_ + ": resume layer " + name + " is missing or not " + type_name);
  }
  std::uint32_t* plane_u() { return u_planes_.emplace_back(n_).data(); }  // a deque: no moves
  float* plane_f() { return f_planes_.emplace_back(n_).data(); }

  const Imf::ChannelList& channels_;
  Imath::Box2i window_;
  int width_;
  std::size_t n_;
  std::string path_;
  Imf::FrameBuffer fb_;
  std::deque<std::vector<std::uint32_t>> u_planes_;
  std::deque<std::vector<float>> f_planes_;
  std::vector<std::vector<glm::dvec3>*> doubles_;
  std::vector<std::vector<vec3>*> vec3s_;
};

void read_layers(Imf::InputPart& file, FilmState& film, const std::string& path) {
  LayerReader r(file.header(), film, path);
  r.uints("tessera.samples", film.samples.data());
  r.doubles("tessera.sum.", &film.radiance);
  if (film.aovs.albedo) r.vec3s(kRgb, "tessera.albedo.", &film.albedo);
  if (film.aovs.normal) r.vec3s(kXyz, "tessera.normal.", &film.normal);
  if (film.aovs.depth) r.floats("tessera.depth", film.depth.data());
  if (film.aovs.counts_hits()) r.uints("tessera.hits", film.hits.data());
  if (film.keeps_odd()) {
    r.doubles("tessera.odd.", &film.radiance_odd);
    if (film.aovs.albedo) r.vec3s(kRgb, "tessera.odd.albedo.", &film.albedo_odd);
    if (film.aovs.normal) r.vec3s(kXyz, "tessera.odd.normal.", &film.normal_odd);
  }
  if (!film.radiance_sq.empty()) r.doubles("tessera.sq.", &film.radiance_sq);
  std::vector<std::uint32_t> converged(film.adaptive() ? film.pixel_count() : 0);
  if (film.adaptive()) r.uints("tessera.converged", converged.data());
  r.read(file);
  for (std::size_t i = 0; i < converged.size(); ++i) {
    if (converged[i] > 1) throw ResumeError(path + ": tessera.converged holds " + std::to_string(converged[i]) + ": the file is damaged");
    film.converged[i] = static_cast<std::uint8_t>(converged[i]);
  }
}

// Every count must be where a wave ends: what a render stopped between tiles leaves.
void check_counts(const FilmState& film, const ResumeFilmSpec& spec, const std::string& path) {
  const int spp = spec.written_spp > 0 ? spec.written_spp : spec.spp;  // whose waves the counts end
  std::vector<bool> wave_end(static_cast<std::size_t>(spp) + 1, false);
  wave_end[0] = true;
  const std::vector<SampleWave> waves =
      spec.adaptive_min_spp > 0 ? make_adaptive_waves(spp, spec.adaptive_min_spp) : make_sample_waves(spp);
  for (const SampleWave& w : waves) wave_end[w.end] = true;
  for (std::size_t i = 0; i < film.pixel_count(); ++i) {
    const std::uint32_t s = film.samples[i];
    if (s > static_cast<std::uint32_t>(spp) || !wave_end[s])
      throw ResumeError(path + ": pixel " + std::to_string(i % film.width) + "," + std::to_string(i / film.width) +
                        " has " + std::to_string(s) + " samples, which no render of " + std::to_string(spp) +
                        " spp stops at: the file is damaged");
  }
}

template <typename F>
auto rethrow_as_resume_error(const std::string& path, F&& body) {
  try {
    return body();
  } catch (const ResumeError&) {
    throw;
  } catch (const std::exception& e) {
    throw ResumeError(path + ": cannot be read for resuming: " + e.what());
  }
}

// The part holding the resume data: the second of a two-part file, or the only part of a
// partial written before that layout. -1: none.
int resume_part(const Imf::MultiPartInputFile& file) {
  for (int i = 0; i < file.parts(); ++i)
    if (file.header(i).findTypedAttribute<Imf::StringAttribute>("tesseraResume")) return i;
  return -1;
}

}  // namespace

std::string read_resume_settings(const std::string& path) {
  return rethrow_as_resume_error(path, [&] {
    Imf::MultiPartInputFile file(path.c_str());
    const int part = resume_part(file);
    if (part >= 0) return file.header(part).typedAttribute<Imf::StringAttribute>("tesseraResume").value();
    const auto* partial = file.header(0).findTypedAttribute<Imf::IntAttribute>("partial");
    if (partial && partial->value() == 0) throw ResumeError(path + ": is a finished render: nothing to resume");
    throw ResumeError(path + ": has no resume data (only an EXR that tessera wrote partial, or as a checkpoint, has)");
  });
}

std::string read_resume_options(const std::string& path) {
  read_resume_settings(path);  // a resumable file, or its error
  return rethrow_as_resume_error(path, [&] {
    Imf::MultiPartInputFile file(path.c_str());
    const auto* options = file.header(resume_part(file)).findTypedAttribute<Imf::StringAttribute>("tesseraOptions");
    return options ? options->value() : std::string();
  });
}

FilmState read_resume_film(const std::string& path, const ResumeFilmSpec& spec) {
  return rethrow_as_resume_error(path, [&] {
    Imf::MultiPartInputFile file(path.c_str());
    const int part_index = resume_part(file);
    if (part_index < 0) throw ResumeError(path + ": has no resume data");
    Imf::InputPart part(file, part_index);
    const Imf::Header& h = part.header();
    const Imath::Box2i dw = h.dataWindow();
    if (dw != exr_data_window(spec.window, spec.width, spec.height))
      throw ResumeError(path + ": its pixels are not the " + std::to_string(spec.width) + "x" +
                        std::to_string(spec.height) + " image at (" + std::to_string(spec.window.x) + ", " +
                        std::to_string(spec.window.y) + ") this render makes");
    FilmState film = FilmState::empty(spec.width, spec.height, spec.aovs, spec.adaptive_min_spp > 0);
    read_layers(part, film, path);
    check_counts(film, spec, path);
    if (const auto* dropped = h.findTypedAttribute<Imf::DoubleAttribute>("droppedSamples"))
      film.dropped = static_cast<std::uint64_t>(dropped->value());
    if (film.adaptive()) {
      const auto* checked = h.findTypedAttribute<Imf::IntAttribute>("tesseraCheckedAt");
      if (!checked || checked->value() < 0 || checked->value() > spec.spp)
        throw ResumeError(path + ": tesseraCheckedAt is missing or out of range: the file is damaged");
      film.checked_at = static_cast<std::uint32_t>(checked->value());
    }
    return film;
  });
}

}  // namespace tessera
