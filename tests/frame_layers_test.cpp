// imageio/frame_layers.h: a frame's channels grouped into the layers compositors show, named
// back from layers, and a film-transparent frame's coverage carried through an EXR read.
#include <gtest/gtest.h>

#include <stdexcept>

#include "imageio/frame_layers.h"
#include "imageio/image_input.h"
#include "imageio/image_output.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

using Names = std::vector<std::string>;

TEST(FrameLayers, ChannelsGoToTheLayerBeforeTheirLastDot) {
  EXPECT_EQ(layer_of_channel("R"), "RGBA");
  EXPECT_EQ(layer_of_channel("A"), "RGBA");
  EXPECT_EQ(layer_of_channel("Z"), "Z");
  EXPECT_EQ(layer_of_channel("N.X"), "N");
  EXPECT_EQ(layer_of_channel("even.Albedo.G"), "even.Albedo");
  EXPECT_EQ(layer_of_channel("cost.time"), "cost");
}

TEST(FrameLayers, AFramesLayersAreRgbaThenItsAovsInTheWritersOrder) {
  FrameImage image;
  image.width = 2, image.height = 1;
  image.rgb = {1, 2, 3, 4, 5, 6};
  image.depth = {7, 8};
  image.normal = {0, 0, 1, 0, 1, 0};
  image.alpha = {0.25f, 1.0f};
  image.pixel_samples = {3, 4};
  const std::vector<ImageLayer> layers = frame_layers(image);
  ASSERT_EQ(layers.size(), 4u);
  EXPECT_EQ(layers[0].name, "RGBA");
  EXPECT_EQ(layers[0].channels, (Names{"R", "G", "B", "A"}));
  EXPECT_EQ(layers[0].pixels, (std::vector<float>{1, 2, 3, 0.25f, 4, 5, 6, 1}));
  EXPECT_EQ(layers[1].name, "N");
  EXPECT_EQ(layers[1].channels, (Names{"N.X", "N.Y", "N.Z"}));
  EXPECT_EQ(layers[2].name, "Z");
  EXPECT_EQ(layers[3].name, "spp");
  EXPECT_EQ(layers[3].pixels, (std::vector<float>{3, 4}));
}

TEST(FrameLayers, ChannelsReadBackGroupInColourThenVectorOrder) {
  ExrChannels exr;
  exr.width = 1, exr.height = 1;
  for (const char* name : {"B", "A", "G", "R", "Z", "mask.B", "mask.R", "mask.G", "uv.Y", "uv.X", "N.Z", "N.X", "N.Y",
                           "tessera.film"})
    exr.channels[name] = {1.0f};
  const std::vector<ImageLayer> layers = channel_layers(exr);
  Names names, rgba;
  for (const ImageLayer& l : layers) names.push_back(l.name);
  // tessera's layers first, in the writer's order, then the others by name; no resume layers.
  EXPECT_EQ(names, (Names{"RGBA", "N", "Z", "mask", "uv"}));
  EXPECT_EQ(layers[0].channels, (Names{"R", "G", "B", "A"}));
  EXPECT_EQ(layers[1].channels, (Names{"N.X", "N.Y", "N.Z"}));
  EXPECT_EQ(layers[3].channels, (Names{"mask.R", "mask.G", "mask.B"}));
  EXPECT_EQ(layers[4].channels, (Names{"uv.X", "uv.Y"}));
}

TEST(FrameLayers, LayersAreNamedTheWayCompositorsReadThem) {
  EXPECT_EQ(layer_channel_names("RGBA", 4), (Names{"R", "G", "B", "A"}));
  EXPECT_EQ(layer_channel_names("RGB", 3), (Names{"R", "G", "B"}));
  EXPECT_EQ(layer_channel_names("N", 3), (Names{"N.X", "N.Y", "N.Z"}));
  EXPECT_EQ(layer_channel_names("cost", 1), (Names{"cost.time"}));
  EXPECT_EQ(layer_channel_names("Z", 1), (Names{"Z"}));
  EXPECT_EQ(layer_channel_names("mask", 1), (Names{"mask"}));
  EXPECT_EQ(layer_channel_names("uv", 2), (Names{"uv.X", "uv.Y"}));
  EXPECT_EQ(layer_channel_names("N", 4), (Names{"N.R", "N.G", "N.B", "N.A"}));  // not tessera's N: generic
  EXPECT_THROW(layer_channel_names("RGBA", 2), std::invalid_argument);
  EXPECT_THROW(layer_channel_names("mask", 5), std::invalid_argument);
}

TEST(FrameLayers, ChannelsGivenTwiceOrOfTheWrongSizeAreRefused) {
  EXPECT_THROW(layers_to_channels({{"a", {"x"}, {1}}, {"b", {"x"}, {2}}}, 1, 1), std::invalid_argument);
  EXPECT_THROW(layers_to_channels({{"a", {"x"}, {1, 2}}}, 1, 1), std::invalid_argument);
  const ExrChannels exr = layers_to_channels({{"uv", {"uv.X", "uv.Y"}, {1, 2, 3, 4}}}, 2, 1);
  EXPECT_EQ(exr.channels.at("uv.X"), (std::vector<float>{1, 3}));
  EXPECT_EQ(exr.channels.at("uv.Y"), (std::vector<float>{2, 4}));
}

TEST(FrameLayers, CoverageSurvivesAnExrRoundTripAndAnOpaqueAlphaIsNone) {
  const std::string dir = test::make_temp_dir("frame_layers");
  FrameImage image;
  image.width = 2, image.height = 1;
  image.rgb = {1, 2, 3, 4, 5, 6};
  image.alpha = {0.5f, 1.0f};
  write_image(dir + "/a.exr", image, {});
  EXPECT_EQ(read_frame_exr(dir + "/a.exr").alpha, (std::vector<float>{0.5f, 1.0f}));
  image.alpha.clear();
  write_image(dir + "/b.exr", image, {});
  EXPECT_TRUE(read_frame_exr(dir + "/b.exr").alpha.empty());
}

}  // namespace
}  // namespace tessera
