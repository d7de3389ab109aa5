#include "tests/same_bits.h"

#include <gtest/gtest.h>

#include "imageio/exr_layers.h"

namespace tessera::test {

void expect_same_film(const FilmState& a, const FilmState& b) {
  EXPECT_TRUE(same_bits(a.radiance, b.radiance));
  EXPECT_TRUE(same_bits(a.albedo, b.albedo));
  EXPECT_TRUE(same_bits(a.normal, b.normal));
  EXPECT_TRUE(same_bits(a.depth, b.depth));
  EXPECT_TRUE(same_bits(a.samples, b.samples));
  EXPECT_TRUE(same_bits(a.hits, b.hits));
  EXPECT_TRUE(same_bits(a.radiance_odd, b.radiance_odd));
  EXPECT_TRUE(same_bits(a.albedo_odd, b.albedo_odd));
  EXPECT_TRUE(same_bits(a.normal_odd, b.normal_odd));
  EXPECT_TRUE(same_bits(a.converged, b.converged));
  EXPECT_EQ(a.checked_at, b.checked_at);
  EXPECT_EQ(a.dropped, b.dropped);
}

void expect_same_image(const FrameImage& a, const FrameImage& b) {
  EXPECT_EQ(a.samples_per_pixel, b.samples_per_pixel);
  for (const ExrLayer& layer : exr_layers()) EXPECT_TRUE(same_bits(a.*layer.pixels, b.*layer.pixels)) << layer.channels[0];
  EXPECT_TRUE(same_bits(a.pixel_samples, b.pixel_samples));
}

}  // namespace tessera::test
