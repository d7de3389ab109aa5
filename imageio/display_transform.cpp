#include "imageio/display_transform.h"

#include <algorithm>
#include <cmath>

#include <OpenColorIO/OpenColorIO.h>

#include "renderer/util/named_enum.h"

namespace tessera {

namespace OCIO = OCIO_NAMESPACE;

namespace {

// The shaper's range: 10 stops below middle grey (0.18) to 6.5 above (0.00018 to 16.3).
constexpr double kGrey = 0.18, kStopsBelow = 10.0, kStops = 16.5;
constexpr unsigned kLutSize = 4096;

OCIO::TransformRcPtr srgb_encoding() {
  auto t = OCIO::ExponentWithLinearTransform::Create();  // the sRGB curve: 2.4 with a linear toe
  t->setGamma({2.4, 2.4, 2.4, 1.0});
  t->setOffset({0.055, 0.055, 0.055, 0.0});
  t->setDirection(OCIO::TRANSFORM_DIR_INVERSE);
  return t;
}

// Scene-linear to display: shaper (log2, grey at kStopsBelow / kStops), the tone curve tabulated
// over the shaper's range, then the sRGB encoding.
OCIO::ConstProcessorRcPtr builtin_processor(ViewTransform view) {
  auto group = OCIO::GroupTransform::Create();
  if (view == ViewTransform::filmic) {
    auto shaper = OCIO::LogAffineTransform::Create();
    shaper->setBase(2.0);
    shaper->setLinSideSlopeValue({1.0 / kGrey, 1.0 / kGrey, 1.0 / kGrey});
    shaper->setLogSideSlopeValue({1.0 / kStops, 1.0 / kStops, 1.0 / kStops});
    shaper->setLogSideOffsetValue({kStopsBelow / kStops, kStopsBelow / kStops, kStopsBelow / kStops});
    group->appendTransform(shaper);
    auto curve = OCIO::Lut1DTransform::Create(kLutSize, false);
    for (unsigned i = 0; i < kLutSize; ++i) {
      const double t = static_cast<double>(i) / (kLutSize - 1);
      const float y = filmic_curve(static_cast<float>(kGrey * std::exp2(kStops * t - kStopsBelow)));
      curve->setValue(i, y, y, y);
    }
    group->appendTransform(curve);
  } else {
    auto clip = OCIO::RangeTransform::Create();
    clip->setMinInValue(0.0), clip->setMinOutValue(0.0);
    clip->setMaxInValue(1.0), clip->setMaxOutValue(1.0);
    group->appendTransform(clip);
  }
  group->appendTransform(srgb_encoding());
  return OCIO::Config::CreateRaw()->getProcessor(group);
}

std::string list(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
  return out;
}

// The config's scene_linear role to `display` / `view`, each its default when empty.
OCIO::ConstProcessorRcPtr config_processor(const DisplayParams& p) {
  OCIO::ConstConfigRcPtr config;
  try {
    config = OCIO::Config::CreateFromFile(p.ocio_config.c_str());
  } catch (const OCIO::Exception& e) {
    throw DisplayTransformError("--ocio-config " + p.ocio_config + ": not a usable OpenColorIO config: " + e.what());
  }
  std::vector<std::string> displays;
  for (int i = 0; i < config->getNumDisplays(); ++i) displays.push_back(config->getDisplay(i));
  const std::string display = p.ocio_display.empty() ? config->getDefaultDisplay() : p.ocio_display;
  if (std::find(displays.begin(), displays.end(), display) == displays.end())
    throw DisplayTransformError("--ocio-config " + p.ocio_config + ": has no display '" + display + "' (it has " +
                                list(displays) + ")");
  std::vector<std::string> views;
  for (int i = 0; i < config->getNumViews(display.c_str()); ++i) views.push_back(config->getView(display.c_str(), i));
  const std::string view = p.ocio_view.empty() ? config->getDefaultView(display.c_str()) : p.ocio_view;
  if (std::find(views.begin(), views.end(), view) == views.end())
    throw DisplayTransformError("--ocio-config " + p.ocio_config + ": display '" + display + "' has no view '" + view +
                                "' (it has " + list(views) + ")");
  try {
    return config->getProcessor(OCIO::ROLE_SCENE_LINEAR, display.c_str(), view.c_str(), OCIO::TRANSFORM_DIR_FORWARD);
  } catch (const OCIO::Exception& e) {
    throw DisplayTransformError("--ocio-config " + p.ocio_config + ": view '" + view + "' of display '" + display +
                                "' cannot be applied to its scene_linear role: " + e.what());
  }
}

OCIO::ConstCPUProcessorRcPtr cpu_processor(const DisplayParams& p) {
  const OCIO::ConstProcessorRcPtr processor = p.ocio_config.empty() ? builtin_processor(p.view) : config_processor(p);
  return processor->getDefaultCPUProcessor();
}

}  // namespace

const std::vector<std::string>& view_transform_names() {
  static const std::vector<std::string> names = {"filmic", "standard"};
  return names;
}

const char* view_transform_name(ViewTransform view) { return enum_name(view_transform_names(), view); }

ViewTransform parse_view_transform(const std::string& name) {
  return parse_enum<ViewTransform>(view_transform_names(), name, "view transform");
}

float filmic_curve(float x) {
  x = std::max(x, 0.0f);
  return std::clamp(x * (2.51f * x + 0.03f) / (x * (2.43f * x + 0.59f) + 0.14f), 0.0f, 1.0f);
}

void check_display_transform(const DisplayParams& params) { cpu_processor(params); }

std::vector<std::uint8_t> to_display_rgb8(const std::vector<float>& rgb, float exposure, const DisplayParams& params) {
  const float scale = std::exp2(exposure);
  std::vector<float> pixels(rgb.size());
  std::transform(rgb.begin(), rgb.end(), pixels.begin(), [&](float v) { return v * scale; });
  if (!pixels.empty()) {
    OCIO::PackedImageDesc image(pixels.data(), static_cast<long>(pixels.size() / 3), 1, 3);
    cpu_processor(params)->apply(image);
  }
  std::vector<std::uint8_t> out(pixels.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = static_cast<std::uint8_t>((pixels[i] > 0.0f ? std::min(pixels[i], 1.0f) : 0.0f) * 255.0f + 0.5f);  // NaN: 0
  return out;
}

}  // namespace tessera
