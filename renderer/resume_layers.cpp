#include "renderer/resume_layers.h"

#include <cstdio>
#include <cstring>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>

#include "renderer/tile_scheduler.h"

namespace tessera {

namespace {

const char* const kRgb[3] = {"R", "G", "B"};
const char* const kXyz[3] = {"X", "Y", "Z"};

std::string sum_channel(int c, bool hi) { return std::string("tessera.sum.") + kRgb[c] + (hi ? ".hi" : ".lo"); }

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
  std::vector<std::pair<std::string, std::vector<std::uint32_t>>> uints;
  std::vector<std::pair<std::string, std::vector<float>>> floats;
};

ResumeLayers::ResumeLayers(const FilmState& film, std::string settings)
    : buffers_(std::make_unique<Buffers>()), settings_(std::move(settings)) {
  Buffers& b = *buffers_;
  b.width = film.width;
  const std::size_t n = film.pixel_count();
  b.uints.push_back({"tessera.samples", film.samples});
  for (int c = 0; c < 3; ++c) {
    std::vector<std::uint32_t> hi(n), lo(n);
    for (std::size_t i = 0; i < n; ++i) {
      const std::uint64_t bits = bits_of(film.radiance[i][c]);
      hi[i] = static_cast<std::uint32_t>(bits >> 32);
      lo[i] = static_cast<std::uint32_t>(bits);
    }
    b.uints.push_back({sum_channel(c, true), std::move(hi)});
    b.uints.push_back({sum_channel(c, false), std::move(lo)});
  }
  auto planar = [&](const std::vector<vec3>& v, const char* const names[3], const std::string& layer) {
    for (int c = 0; c < 3; ++c) {
      std::vector<float> out(n);
      for (std::size_t i = 0; i < n; ++i) out[i] = v[i][c];
      b.floats.push_back({layer + names[c], std::move(out)});
    }
  };
  if (film.aovs.albedo) planar(film.albedo, kRgb, "tessera.albedo.");
  if (film.aovs.normal) planar(film.normal, kXyz, "tessera.normal.");
  if (film.aovs.depth) {
    b.floats.push_back({"tessera.depth", film.depth});
    b.uints.push_back({"tessera.hits", film.hits});
  }
}

ResumeLayers::~ResumeLayers() = default;

void ResumeLayers::insert_into(Imf::Header& header, Imf::FrameBuffer& fb) {
  const Buffers& b = *buffers_;
  for (const auto& [name, data] : b.uints) {
    header.channels().insert(name, Imf::Channel(Imf::UINT));
    fb.insert(name, Imf::Slice(Imf::UINT, reinterpret_cast<char*>(const_cast<std::uint32_t*>(data.data())),
                               sizeof(std::uint32_t), sizeof(std::uint32_t) * b.width));
  }
  for (const auto& [name, data] : b.floats) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(data.data())), sizeof(float),
                               sizeof(float) * b.width));
  }
  header.insert("tesseraResume", Imf::StringAttribute(settings_));
  header.insert("tesseraFingerprint", Imf::StringAttribute(fnv1a_hex(settings_)));
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

// The layers of `film` (sized, AOVs chosen) that `header` must have, read into it.
void read_layers(Imf::InputFile& file, FilmState& film, const std::string& path) {
  const Imf::ChannelList& channels = file.header().channels();
  const std::size_t n = film.pixel_count();
  std::vector<std::vector<std::uint32_t>> sum_bits(6, std::vector<std::uint32_t>(n));
  std::vector<std::vector<float>> planes;
  Imf::FrameBuffer fb;
  auto slice_u = [&](const std::string& name, std::uint32_t* data) {
    const Imf::Channel* ch = channels.findChannel(name);
    if (!ch || ch->type != Imf::UINT) throw ResumeError(path + ": resume layer " + name + " is missing or not UINT");
    fb.insert(name, Imf::Slice(Imf::UINT, reinterpret_cast<char*>(data), sizeof(std::uint32_t),
                               sizeof(std::uint32_t) * film.width));
  };
  auto slice_f = [&](const std::string& name, float* data) {
    const Imf::Channel* ch = channels.findChannel(name);
    if (!ch || ch->type != Imf::FLOAT) throw ResumeError(path + ": resume layer " + name + " is missing or not FLOAT");
    fb.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(data), sizeof(float), sizeof(float) * film.width));
  };
  slice_u("tessera.samples", film.samples.data());
  for (int c = 0; c < 3; ++c) {
    slice_u(sum_channel(c, true), sum_bits[2 * c].data());
    slice_u(sum_channel(c, false), sum_bits[2 * c + 1].data());
  }
  auto planar3 = [&](const char* const names[3], const std::string& layer) {
    for (int c = 0; c < 3; ++c) {
      planes.emplace_back(n);
      slice_f(layer + names[c], planes.back().data());
    }
  };
  planes.reserve(7);  // slices point into them: no reallocation
  if (film.aovs.albedo) planar3(kRgb, "tessera.albedo.");
  if (film.aovs.normal) planar3(kXyz, "tessera.normal.");
  if (film.aovs.depth) {
    slice_f("tessera.depth", film.depth.data());
    slice_u("tessera.hits", film.hits.data());
  }
  file.setFrameBuffer(fb);
  file.readPixels(0, film.height - 1);
  for (std::size_t i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c)
      film.radiance[i][c] = double_of(std::uint64_t(sum_bits[2 * c][i]) << 32 | sum_bits[2 * c + 1][i]);
  std::size_t p = 0;
  auto unplanar3 = [&](std::vector<vec3>& out) {
    for (int c = 0; c < 3; ++c, ++p)
      for (std::size_t i = 0; i < n; ++i) out[i][c] = planes[p][i];
  };
  if (film.aovs.albedo) unplanar3(film.albedo);
  if (film.aovs.normal) unplanar3(film.normal);
}

// Every count must be where a wave ends: what a render stopped between tiles leaves.
void check_counts(const FilmState& film, int spp, const std::string& path) {
  std::vector<bool> wave_end(static_cast<std::size_t>(spp) + 1, false);
  wave_end[0] = true;
  for (const SampleWave& w : make_sample_waves(spp)) wave_end[w.end] = true;
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

}  // namespace

std::string read_resume_settings(const std::string& path) {
  return rethrow_as_resume_error(path, [&] {
    Imf::InputFile file(path.c_str());
    const Imf::Header& h = file.header();
    const auto* settings = h.findTypedAttribute<Imf::StringAttribute>("tesseraResume");
    if (settings) return settings->value();
    const auto* partial = h.findTypedAttribute<Imf::IntAttribute>("partial");
    if (partial && partial->value() == 0) throw ResumeError(path + ": is a finished render: nothing to resume");
    throw ResumeError(path + ": has no resume data (only an EXR that tessera wrote partial, or as a checkpoint, has)");
  });
}

FilmState read_resume_film(const std::string& path, int width, int height, AovSelection aovs, int spp) {
  return rethrow_as_resume_error(path, [&] {
    Imf::InputFile file(path.c_str());
    const Imf::Header& h = file.header();
    const Imath::Box2i dw = h.dataWindow();
    if (dw.min.x != 0 || dw.min.y != 0 || dw.max.x + 1 != width || dw.max.y + 1 != height)
      throw ResumeError(path + ": its pixels are not a " + std::to_string(width) + "x" + std::to_string(height) + " image");
    FilmState film = FilmState::empty(width, height, aovs);
    read_layers(file, film, path);
    check_counts(film, spp, path);
    if (const auto* dropped = h.findTypedAttribute<Imf::DoubleAttribute>("droppedSamples"))
      film.dropped = static_cast<std::uint64_t>(dropped->value());
    return film;
  });
}

}  // namespace tessera
