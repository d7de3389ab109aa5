#include "tests/exr_read.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFloatAttribute.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>
#include <OpenEXR/ImfMatrixAttribute.h>

namespace tessera::test {

std::vector<float> exr_rgb(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i dw = file.header().dataWindow();
  const int w = dw.max.x - dw.min.x + 1, h = dw.max.y - dw.min.y + 1;
  std::vector<float> px(static_cast<std::size_t>(3) * w * h);
  Imf::FrameBuffer fb;
  for (int c = 0; c < 3; ++c)
    fb.insert(std::string(1, "RGB"[c]), Imf::Slice::Make(Imf::FLOAT, px.data() + c, dw, 3 * sizeof(float), 3 * sizeof(float) * w));
  file.setFrameBuffer(fb);
  file.readPixels(dw.min.y, dw.max.y);
  return px;
}

int exr_int(const std::string& path, const char* attribute) {
  Imf::InputFile file(path.c_str());
  return file.header().typedAttribute<Imf::IntAttribute>(attribute).value();
}

std::string exr_string(const std::string& path, const char* attribute) {
  Imf::InputFile file(path.c_str());
  return file.header().typedAttribute<Imf::StringAttribute>(attribute).value();
}

ExrWindows exr_windows(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const Imath::Box2i d = file.header().dataWindow(), s = file.header().displayWindow();
  return {{d.min.x, d.min.y, d.max.x, d.max.y}, {s.min.x, s.min.y, s.max.x, s.max.y}};
}

std::vector<float> exr_m44f(const std::string& path, const char* attribute) {
  Imf::InputFile file(path.c_str());
  const Imath::M44f& m = file.header().typedAttribute<Imf::M44fAttribute>(attribute).value();
  return std::vector<float>(&m[0][0], &m[0][0] + 16);
}

float exr_float(const std::string& path, const char* attribute) {
  Imf::InputFile file(path.c_str());
  return file.header().typedAttribute<Imf::FloatAttribute>(attribute).value();
}

}  // namespace tessera::test
