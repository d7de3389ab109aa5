#include "imageio/exr_header.h"

#include <OpenEXR/ImfDoubleAttribute.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>
#include <OpenEXR/ImfStandardAttributes.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <set>

#include "renderer/util/isa.h"

namespace tessera {

namespace {

Imath::M44f to_imath(const glm::mat4& m) {
  // Imath multiplies row vectors (v * M): its [i][j] is glm's column i, row j.
  Imath::M44f out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i][j] = m[i][j];
  return out;
}

glm::mat4 from_imath(const Imath::M44f& m) {
  glm::mat4 out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) out[i][j] = m[i][j];
  return out;
}

}  // namespace

// Who made the file, when, from what, and for whom: the standard attributes first.
void insert_provenance(Imf::Header& header, const FrameMetadata& m) {
  // The film's RGB is linear Rec.709 / sRGB primaries with a D65 white (the glTF colour
  // space), which Imf::Chromaticities' defaults are.
  Imf::addChromaticities(header, Imf::Chromaticities());
  const std::time_t now = std::time(nullptr);
  Imf::addCapDate(header, exr_cap_date(now));
  Imf::addUtcOffset(header, exr_utc_offset(now));
  if (!m.owner.empty()) Imf::addOwner(header, m.owner);
  if (!m.comments.empty()) Imf::addComments(header, m.comments);
  if (!m.command_line.empty()) header.insert("tesseraCommandLine", Imf::StringAttribute(m.command_line));
  header.insert("software", Imf::StringAttribute("tessera " + tessera_version()));
  header.insert("tesseraVersion", Imf::StringAttribute(tessera_version()));
  header.insert("tesseraIsa", Imf::StringAttribute(std::string(compiled_isa())));
}

bool is_layout_attribute(const std::string& name) {
  static const std::set<std::string> kLayout = {"channels", "compression", "dataWindow", "displayWindow", "lineOrder",
                                                "pixelAspectRatio", "screenWindowCenter", "screenWindowWidth", "tiles",
                                                "type", "name", "version", "chunkCount"};
  return kLayout.count(name) != 0;
}

std::vector<HeaderAttribute> header_attributes(const Imf::Header& header) {
  std::vector<HeaderAttribute> out;
  for (auto it = header.begin(); it != header.end(); ++it) {
    const Imf::Attribute& a = it.attribute();
    if (is_layout_attribute(it.name())) continue;
    if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&a)) out.push_back({it.name(), s->value()});
    else if (const auto* i = dynamic_cast<const Imf::IntAttribute*>(&a)) out.push_back({it.name(), i->value()});
    else if (const auto* f = dynamic_cast<const Imf::FloatAttribute*>(&a)) out.push_back({it.name(), f->value()});
    else if (const auto* d = dynamic_cast<const Imf::DoubleAttribute*>(&a)) out.push_back({it.name(), d->value()});
    else if (const auto* m = dynamic_cast<const Imf::M44fAttribute*>(&a)) out.push_back({it.name(), from_imath(m->value())});
  }
  return out;
}

void insert_attributes(Imf::Header& header, const std::vector<HeaderAttribute>& attributes) {
  for (const HeaderAttribute& a : attributes) {
    if (const auto* s = std::get_if<std::string>(&a.value)) header.insert(a.name, Imf::StringAttribute(*s));
    else if (const auto* i = std::get_if<int>(&a.value)) header.insert(a.name, Imf::IntAttribute(*i));
    else if (const auto* f = std::get_if<float>(&a.value)) header.insert(a.name, Imf::FloatAttribute(*f));
    else if (const auto* d = std::get_if<double>(&a.value)) header.insert(a.name, Imf::DoubleAttribute(*d));
    else header.insert(a.name, Imf::M44fAttribute(to_imath(std::get<glm::mat4>(a.value))));
  }
}

std::vector<HeaderAttribute> frame_header_attributes(const FrameMetadata& m, int samples_per_pixel) {
  Imf::Header header;
  insert_frame_metadata(header, m, samples_per_pixel);
  return header_attributes(header);
}

std::string exr_cap_date(std::time_t t) {
  std::tm local{};
  localtime_r(&t, &local);
  char text[32];
  std::strftime(text, sizeof text, "%Y:%m:%d %H:%M:%S", &local);
  return text;
}

float exr_utc_offset(std::time_t t) {
  std::tm local{};
  localtime_r(&t, &local);
  return static_cast<float>(-local.tm_gmtoff);  // UTC == local time + utcOffset
}

void insert_frame_metadata(Imf::Header& header, const FrameMetadata& m, int samples_per_pixel) {
  insert_provenance(header, m);
  header.insert("samplesPerPixel", Imf::IntAttribute(samples_per_pixel));
  header.insert("renderTimeSeconds", Imf::DoubleAttribute(m.render_seconds));
  header.insert("seed", Imf::IntAttribute(static_cast<int>(m.seed)));
  if (!m.sampler.empty()) header.insert("sampler", Imf::StringAttribute(m.sampler));
  if (!m.pixel_filter.empty()) header.insert("pixelFilter", Imf::StringAttribute(m.pixel_filter));
  header.insert("threads", Imf::IntAttribute(m.threads));
  header.insert("tileSize", Imf::IntAttribute(m.tile_size));
  header.insert("maxBounces", Imf::IntAttribute(m.max_bounces));
  header.insert("droppedSamples", Imf::DoubleAttribute(static_cast<double>(m.dropped_samples)));
  header.insert("worldToCamera", Imf::M44fAttribute(to_imath(m.world_to_camera)));
  header.insert("worldToNDC", Imf::M44fAttribute(to_imath(m.world_to_ndc)));
  header.insert("partial", Imf::IntAttribute(m.partial ? 1 : 0));
  if (m.target_spp > 0) header.insert("targetSamplesPerPixel", Imf::IntAttribute(m.target_spp));
  if (m.noise_threshold > 0.0f) {
    header.insert("noiseThreshold", Imf::FloatAttribute(m.noise_threshold));
    header.insert("minSamplesPerPixel", Imf::IntAttribute(m.min_spp));
    header.insert("convergedPixels", Imf::DoubleAttribute(static_cast<double>(m.converged_pixels)));
  }
  if (m.denoised) header.insert("denoised", Imf::IntAttribute(1));
  if (m.film_transparent) header.insert("filmTransparent", Imf::IntAttribute(1));
  if (!m.scene_path.empty()) header.insert("scene", Imf::StringAttribute(m.scene_path));
  if (!m.camera_name.empty()) header.insert("camera", Imf::StringAttribute(m.camera_name));
  if (!m.material_variant.empty()) header.insert("materialVariant", Imf::StringAttribute(m.material_variant));
  if (m.animated) header.insert("sceneTime", Imf::FloatAttribute(m.scene_time));
  if (m.shutter_open < m.shutter_close) {  // motion blur: what the samples' times spanned
    header.insert("shutterOpen", Imf::FloatAttribute(m.shutter_open));
    header.insert("shutterClose", Imf::FloatAttribute(m.shutter_close));
  }
  if (m.frame >= 0) {
    header.insert("frame", Imf::IntAttribute(m.frame));
    header.insert("framesPerSecond", Imf::FloatAttribute(m.frames_per_second));
  }
}

}  // namespace tessera
