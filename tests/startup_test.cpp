// OpenImageIO is loaded only when an image needs it (imageio/image_codec.h): the program
// that writes an EXR never maps its libraries, one that writes a PNG does and writes it right.
// Checked through the dynamic linker's own record of the files it opens (LD_DEBUG=files).
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <string>

#include "tests/test_support.h"

namespace tessera {
namespace {

std::string quote(const std::string& s) { return "'" + s + "'"; }

// `tessera ARGS` with the dynamic linker reporting every library it loads on stderr.
test::CommandResult traced_tessera(const std::string& args) {
  return test::run_command("LD_DEBUG=files timeout 120 " + quote(test::tessera_exe()) + " " + args);
}

// A line "file=NAME" or "file=/some/dir/NAME" (dlopen by path).
bool loaded(const test::CommandResult& r, const std::string& library) {
  return r.err.find("file=" + library) != std::string::npos || r.err.find("/" + library + " [") != std::string::npos;
}

std::string cornell_render(const std::string& out) {
  return "render " + quote(test::scene_path("cornell-box/cornell-box.gltf")) + " --width 8 --height 8 --spp 1 -q -o " +
         quote(out);
}

TEST(Startup, VersionAndAnExrRenderNeverLoadOpenImageIO) {
  const auto version = traced_tessera("--version");
  ASSERT_EQ(version.exit_code, 0) << version.err;
  EXPECT_TRUE(loaded(version, "libembree3.so"));  // the trace works: linked libraries show
  EXPECT_FALSE(loaded(version, "libOpenImageIO.so"));
  const std::string dir = test::make_temp_dir("startup-exr");
  const auto render = traced_tessera(cornell_render(dir + "/c.exr"));
  ASSERT_EQ(render.exit_code, 0) << render.err;
  EXPECT_FALSE(loaded(render, "libOpenImageIO.so"));
  EXPECT_FALSE(loaded(render, "libtessera_oiio.so"));
}

TEST(Startup, APngOutputLoadsTheImageModuleAndReadsBack) {
  const std::string dir = test::make_temp_dir("startup-png");
  const auto render = traced_tessera(cornell_render(dir + "/c.png"));
  ASSERT_EQ(render.exit_code, 0) << render.err;
  EXPECT_TRUE(loaded(render, "libtessera_oiio.so"));
  auto in = OIIO::ImageInput::open(dir + "/c.png");
  ASSERT_TRUE(in);
  EXPECT_EQ(in->spec().width, 8);
  EXPECT_EQ(in->spec().height, 8);
  EXPECT_EQ(in->spec().nchannels, 3);
}

}  // namespace
}  // namespace tessera
