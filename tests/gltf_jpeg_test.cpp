// JPEG images decoded by libjpeg-turbo (scene_io/decode/gltf_jpeg.cpp) against a second decoder,
// the stb_image inside tinygltf (tinygltf::LoadImageData), which decoded them before.
// The test images are made here with TurboJPEG's encoder.
//
// The tolerance: both decoders read the same coefficients exactly, then differ in integer
// arithmetic: the inverse DCT (libjpeg's 13-bit "islow", stb's 12-bit; ISO/IEC 10918-2 lets a
// decoder's IDCT differ from the reference by one level per sample), the rounding of the
// YCbCr to RGB conversion (libjpeg's 16-bit tables, stb's 20-bit products) and of the
// triangle-filter chroma upsampling both use (libjpeg alternates a bias of 7 and 8, stb adds
// 8). These add to at most a few 8-bit levels on any channel, and well under one on average.
// One place is outside any standard: the last column of an odd-width 4:2:2 image, whose
// chroma the decoders extrapolate differently (69 levels apart at a sharp edge there, each
// as far from the source as the other on average); its pixels count in the mean only.
#include <gtest/gtest.h>
#include <turbojpeg.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <tiny_gltf.h>

#include "scene_io/decode/gltf_jpeg.h"
#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

constexpr int kMostLevels = 3;          // per channel, per pixel
constexpr double kMostMeanLevels = 0.5;  // over all channels and pixels

// A smooth colour field with a sharp diagonal edge and fine stripes: chroma that varies, so
// upsampling matters, and detail that gives every DCT frequency something to do.
std::vector<std::uint8_t> test_pattern(int w, int h, int channels) {
  std::vector<std::uint8_t> px(static_cast<std::size_t>(w) * h * channels);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const bool edge = x + 2 * y > w;
      const int v[4] = {(x * 255) / (w - 1), (y * 255) / (h - 1), edge ? 40 : 210, (x / 3) % 2 ? 255 : 60};
      for (int c = 0; c < channels; ++c) px[(static_cast<std::size_t>(y) * w + x) * channels + c] = std::uint8_t(v[c]);
    }
  return px;
}

std::vector<std::uint8_t> encode(const std::vector<std::uint8_t>& px, int w, int h, int pixel_format, int subsampling,
                                 int quality, int flags = 0) {
  const std::unique_ptr<void, int (*)(tjhandle)> tj(tjInitCompress(), &tjDestroy);
  unsigned char* out = nullptr;
  unsigned long size = 0;
  EXPECT_EQ(tjCompress2(tj.get(), px.data(), w, 0, h, pixel_format, &out, &size, subsampling, quality, flags), 0)
      << tjGetErrorStr2(tj.get());
  std::vector<std::uint8_t> bytes(out, out + size);
  tjFree(out);
  return bytes;
}

tinygltf::Image with_libjpeg_turbo(const std::vector<std::uint8_t>& jpeg) {
  tinygltf::Image image;
  EXPECT_EQ(decode_jpeg(&image, jpeg.data(), static_cast<int>(jpeg.size())), "");
  return image;
}

tinygltf::Image with_stb(const std::vector<std::uint8_t>& jpeg) {
  tinygltf::Image image;
  std::string err, warn;
  EXPECT_TRUE(tinygltf::LoadImageData(&image, 0, &err, &warn, 0, 0, jpeg.data(), static_cast<int>(jpeg.size()),
                                      nullptr))
      << err;
  return image;
}

void expect_close(const tinygltf::Image& a, const tinygltf::Image& b, const std::string& what,
                  bool odd_last_column = false) {
  ASSERT_EQ(a.width, b.width) << what;
  ASSERT_EQ(a.height, b.height) << what;
  ASSERT_EQ(a.component, 4) << what;
  ASSERT_EQ(b.component, 4) << what;
  ASSERT_EQ(a.bits, 8) << what;
  ASSERT_EQ(a.image.size(), b.image.size()) << what;
  int most = 0;
  double sum = 0.0;
  for (std::size_t i = 0; i < a.image.size(); ++i) {
    const int d = std::abs(int(a.image[i]) - int(b.image[i]));
    const bool last_column = (i / 4) % a.width == static_cast<std::size_t>(a.width - 1);
    if (!(odd_last_column && last_column)) most = std::max(most, d);
    sum += d;
  }
  EXPECT_LE(most, kMostLevels) << what;
  EXPECT_LE(sum / a.image.size(), kMostMeanLevels) << what;
}

struct Variant {
  const char* name;
  int subsampling, flags;
};

TEST(GltfJpeg, MatchesStbImageWithinTheDecodersTolerance) {
  const int w = 67, h = 45;  // not a multiple of the 16-pixel MCU: partial blocks at the edges
  const std::vector<std::uint8_t> rgb = test_pattern(w, h, 3);
  for (const Variant& v : {Variant{"4:2:0", TJSAMP_420, 0}, Variant{"4:2:2", TJSAMP_422, 0},
                           Variant{"4:4:4", TJSAMP_444, 0}, Variant{"progressive 4:2:0", TJSAMP_420, TJFLAG_PROGRESSIVE},
                           Variant{"progressive 4:4:4", TJSAMP_444, TJFLAG_PROGRESSIVE}}) {
    const std::vector<std::uint8_t> jpeg = encode(rgb, w, h, TJPF_RGB, v.subsampling, 90, v.flags);
    expect_close(with_libjpeg_turbo(jpeg), with_stb(jpeg), v.name, v.subsampling == TJSAMP_422);
  }
  const std::vector<std::uint8_t> grey = test_pattern(w, h, 1);
  const tinygltf::Image g = with_libjpeg_turbo(encode(grey, w, h, TJPF_GRAY, TJSAMP_GRAY, 90));
  expect_close(g, with_stb(encode(grey, w, h, TJPF_GRAY, TJSAMP_GRAY, 90)), "greyscale");
  EXPECT_EQ(g.image[0], g.image[1]);  // grey to RGBA: R = G = B, alpha opaque
  EXPECT_EQ(g.image[0], g.image[2]);
  EXPECT_EQ(g.image[3], 255);
}

TEST(GltfJpeg, CmykMatchesStbImage) {
  const int w = 40, h = 24;
  const std::vector<std::uint8_t> cmyk = test_pattern(w, h, 4);
  const std::vector<std::uint8_t> jpeg = encode(cmyk, w, h, TJPF_CMYK, TJSAMP_444, 95);  // YCCK, Adobe marker
  const tinygltf::Image image = with_libjpeg_turbo(jpeg);
  expect_close(image, with_stb(jpeg), "CMYK");
  EXPECT_EQ(image.image[3], 255);
}

TEST(GltfJpeg, FlatColourDecodesToItself) {
  // A flat image is only DC coefficients: at quality 100 every decoder returns the colour to
  // within the YCbCr round trip's rounding (one level per conversion).
  const int w = 16, h = 16;
  std::vector<std::uint8_t> rgb(w * h * 3);
  for (std::size_t i = 0; i < rgb.size(); i += 3) rgb[i] = 200, rgb[i + 1] = 100, rgb[i + 2] = 50;
  const tinygltf::Image image = with_libjpeg_turbo(encode(rgb, w, h, TJPF_RGB, TJSAMP_444, 100));
  for (int p = 0; p < w * h; ++p)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(image.image[4 * p + c], rgb[3 * p + c], 2) << "pixel " << p;
}

// An APP1 Exif segment whose IFD0 holds Orientation = 6 ("rotate 90 degrees clockwise").
std::vector<std::uint8_t> exif_orientation_6() {
  const std::vector<std::uint8_t> tiff = {'I', 'I', 42, 0, 8, 0, 0, 0,  // little-endian, IFD0 at 8
                                          1, 0,                          // one entry
                                          0x12, 0x01, 3, 0, 1, 0, 0, 0, 6, 0, 0, 0,  // 0x0112 SHORT 1 = 6
                                          0, 0, 0, 0};                   // no next IFD
  std::vector<std::uint8_t> seg = {0xFF, 0xE1, 0, 0, 'E', 'x', 'i', 'f', 0, 0};
  seg.insert(seg.end(), tiff.begin(), tiff.end());
  const std::size_t length = seg.size() - 2;
  seg[2] = std::uint8_t(length >> 8), seg[3] = std::uint8_t(length & 0xFF);
  return seg;
}

TEST(GltfJpeg, ExifOrientationIsNotApplied) {
  // glTF 2.0, 2.6: "Exif chunks MAY be ignored by client implementations" (its note warns that
  // "Orientation" hurts portability); tessera ignores them, as stb_image did: texture
  // coordinate (0, 0) is the first stored pixel, whatever the Exif orientation says.
  const int w = 32, h = 16;
  const std::vector<std::uint8_t> plain = encode(test_pattern(w, h, 3), w, h, TJPF_RGB, TJSAMP_420, 90);
  std::vector<std::uint8_t> rotated = plain;
  const std::vector<std::uint8_t> exif = exif_orientation_6();
  rotated.insert(rotated.begin() + 2, exif.begin(), exif.end());  // right after SOI
  const tinygltf::Image a = with_libjpeg_turbo(plain), b = with_libjpeg_turbo(rotated);
  EXPECT_EQ(b.width, w);
  EXPECT_EQ(b.height, h);
  EXPECT_TRUE(a.image == b.image);
}

std::string gltf_with_image(const std::vector<std::uint8_t>& jpeg) {
  return R"({"asset": {"version": "2.0"}, "images": [{"uri": "data:image/jpeg;base64,)" + test::base64(jpeg) +
         R"("}], "textures": [{"source": 0}], "materials": [{"pbrMetallicRoughness": {"baseColorTexture": {"index": 0}}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "material": 0}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                   "min": [0, 0, 0], "max": [1, 1, 0]}],
    "bufferViews": [{"buffer": 0, "byteLength": 36}],
    "buffers": [{"byteLength": 36, "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}],
    "nodes": [{"mesh": 0}], "scenes": [{"nodes": [0]}], "scene": 0})";
}

GltfLoadResult load(const std::string& json) {
  return load_gltf_from_memory({json.begin(), json.end()}, "jpeg.gltf", ".");
}

TEST(GltfJpeg, GltfImageIsTheDecodedJpeg) {
  const std::vector<std::uint8_t> jpeg = encode(test_pattern(24, 20, 3), 24, 20, TJPF_RGB, TJSAMP_420, 90);
  const GltfLoadResult r = load(gltf_with_image(jpeg));
  ASSERT_EQ(r.scene.images.size(), 1u);
  const Image& image = r.scene.images[0];
  EXPECT_EQ(image.width, 24);
  EXPECT_EQ(image.height, 20);
  EXPECT_EQ(image.channels, 4);
  EXPECT_EQ(image.bits_per_channel, 8);
  ASSERT_TRUE(image.pixels);
  EXPECT_TRUE(*image.pixels == with_libjpeg_turbo(jpeg).image);
}

// Junk between two segments (here two bytes before the start-of-scan marker, outside any
// entropy-coded data) is skipped with a warning by libjpeg; every pixel is still there, the
// same as without it.
TEST(GltfJpeg, StrayBytesBetweenSegmentsDecodeToTheSamePixels) {
  const std::vector<std::uint8_t> clean = encode(test_pattern(32, 24, 3), 32, 24, TJPF_RGB, TJSAMP_420, 90);
  std::size_t sos = 2;
  while (sos + 1 < clean.size() && !(clean[sos] == 0xFF && clean[sos + 1] == 0xDA)) ++sos;
  ASSERT_LT(sos + 1, clean.size()) << "no start-of-scan marker";
  std::vector<std::uint8_t> stray = clean;
  stray.insert(stray.begin() + static_cast<std::ptrdiff_t>(sos), {0x12, 0x34});
  tinygltf::Image image;
  ASSERT_EQ(decode_jpeg(&image, stray.data(), static_cast<int>(stray.size())), "");
  EXPECT_TRUE(image.image == with_libjpeg_turbo(clean).image);
}

TEST(GltfJpeg, TruncatedJpegIsRefusedNamingTheImage) {
  std::vector<std::uint8_t> jpeg = encode(test_pattern(64, 64, 3), 64, 64, TJPF_RGB, TJSAMP_420, 90);
  jpeg.resize(jpeg.size() / 2);
  try {
    load(gltf_with_image(jpeg));
    FAIL() << "a truncated JPEG loaded";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(),
              "image 0 (data URI) could not be decoded: its JPEG data is corrupt (Premature end of JPEG file)");
  }
}

}  // namespace
}  // namespace tessera
