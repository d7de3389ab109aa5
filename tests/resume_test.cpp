// Resuming a stopped render gives the same pixels, bit for bit, as rendering it in one go:
// from a wave boundary, from a film whose pixels stopped at different waves, and through
// the EXR that carries the film. Time limits and checkpoints stop and report where expected.
#include <gtest/gtest.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfMultiPartInputFile.h>
#include <OpenEXR/ImfOutputFile.h>

#include "imageio/image_output.h"
#include "renderer/render/render.h"
#include "imageio/resume_layers.h"
#include "tests/scene_builders.h"
#include "tests/same_bits.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

// A floor, a sphere, an emitter and a point light: every kind of path takes part.
const RenderScene& scene() {
  static const RenderScene* s = [] {
    SceneDescription d = test::lit_floor_and_sphere();
    PunctualLight point;
    point.position = {1, 1, 1};
    point.intensity = 3.0f;
    d.lights.push_back(point);
    EnvironmentParams env;
    env.background = vec3(0.1f);
    return new RenderScene(std::move(d), env);
  }();
  return *s;
}

RenderSettings settings() {
  RenderSettings s;
  s.width = 37;
  s.height = 23;
  s.spp = 20;  // waves end at 1, 3, 7, 15, 20
  s.max_bounces = 6;
  s.seed = 99;
  s.tile_size = 8;
  s.aovs = {true, true, true};
  return s;
}

const RenderCamera& camera() {
  static const RenderCamera cam = make_camera(test::look_at({0, 0, 4}, {0, -0.5f, 0}, 40.0f), 37, 23, {});
  return cam;
}

// The film after each wave but the last, as checkpoints see it.
std::vector<FilmState> checkpoints_of(RenderSettings s) {
  std::vector<FilmState> states;
  s.checkpoint_interval = 0.0;
  s.on_checkpoint = [&](const Film& film, const RenderStats&) { states.push_back(film.state()); };
  render_frame(scene(), camera(), s);
  return states;
}

using test::expect_same_film;
using test::expect_same_image;
using test::same_bits;

TEST(Resume, FromAWaveBoundaryGivesTheSameBits) {
  const RenderResult whole = render_frame(scene(), camera(), settings());
  std::vector<FilmState> states = checkpoints_of(settings());
  ASSERT_EQ(states.size(), 4u);
  EXPECT_EQ(Film(states[1]).min_samples(), 3u);
  RenderSettings s = settings();
  s.threads = 1;  // another thread count and tile size: still the same sums
  s.tile_size = 5;
  const RenderResult resumed = render_frame(scene(), camera(), s, nullptr, &states[1]);
  EXPECT_EQ(resumed.stats.resumed_samples, 3u * 37 * 23);
  EXPECT_EQ(resumed.stats.camera_samples, 17u * 37 * 23);
  expect_same_image(whole.image, resumed.image);
  expect_same_film(whole.film, resumed.film);
}

// An interrupt between tiles leaves some pixels a wave ahead of others.
TEST(Resume, FromPixelsStoppedAtDifferentWavesGivesTheSameBits) {
  const RenderResult whole = render_frame(scene(), camera(), settings());
  std::vector<FilmState> states = checkpoints_of(settings());
  FilmState mixed = states[1];  // 3 samples everywhere, 7 in the top rows
  for (std::size_t i = 0; i < mixed.pixel_count() / 2; ++i) {
    mixed.radiance[i] = states[2].radiance[i];
    mixed.albedo[i] = states[2].albedo[i];
    mixed.normal[i] = states[2].normal[i];
    mixed.depth[i] = states[2].depth[i];
    mixed.samples[i] = states[2].samples[i];
    mixed.hits[i] = states[2].hits[i];
  }
  const RenderResult resumed = render_frame(scene(), camera(), settings(), nullptr, &mixed);
  expect_same_image(whole.image, resumed.image);
}

TEST(Resume, TheExrCarriesTheFilmLosslessly) {
  std::vector<FilmState> states = checkpoints_of(settings());
  FilmState film = states[2];
  film.dropped = 12345;
  const std::string path = test::make_temp_dir("resume-exr") + "/frame.exr";
  ImageWriteParams params;
  params.half = true;  // the image in half floats; the film still exact
  params.metadata.partial = true;
  params.metadata.dropped_samples = film.dropped;
  params.resume_film = &film;
  params.resume_settings = "format=1\nspp=20\n";
  write_image(path, Film(film).resolve(), params);
  EXPECT_EQ(read_resume_settings(path), params.resume_settings);
  expect_same_film(read_resume_film(path, {37, 23, film.aovs, 20}), film);
  EXPECT_THROW(read_resume_film(path, {36, 23, film.aovs, 20}), ResumeError);  // another size
}

// The resume data is the file's second part, which layer lists built from the first never
// show; a partial written before (one part, the tessera.* channels beside RGB) still reads.
TEST(Resume, TheFilmIsTheSecondPartAndOldSinglePartFilesStillRead) {
  FilmState film = checkpoints_of(settings())[1];
  const std::string dir = test::make_temp_dir("resume-parts");
  ImageWriteParams params;
  params.metadata.partial = true;
  params.resume_film = &film;
  params.resume_settings = "format=1\nspp=20\n";
  write_image(dir + "/two.exr", Film(film).resolve(), params);
  {
    Imf::MultiPartInputFile two((dir + "/two.exr").c_str());
    ASSERT_EQ(two.parts(), 2);
    EXPECT_EQ(two.header(0).name(), "rgba");
    EXPECT_EQ(two.header(1).name(), kResumePartName);
    for (auto it = two.header(0).channels().begin(); it != two.header(0).channels().end(); ++it)
      EXPECT_NE(std::string(it.name()).rfind("tessera.", 0), 0u) << it.name();
  }
  // The layout of before: one part, RGB and the resume layers together.
  const std::string old = dir + "/one.exr";
  {
    Imf::Header header(film.width, film.height);
    std::vector<float> red(film.pixel_count(), 0.5f);
    Imf::FrameBuffer fb;
    header.channels().insert("R", Imf::Channel(Imf::FLOAT));
    fb.insert("R", Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(red.data()), sizeof(float), sizeof(float) * film.width));
    ResumeLayers layers(film, params.resume_settings);
    layers.insert_into(header, fb, header.dataWindow());
    Imf::OutputFile file(old.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(film.height);
  }
  EXPECT_EQ(read_resume_settings(old), params.resume_settings);
  expect_same_film(read_resume_film(old, {37, 23, film.aovs, 20}), film);
  expect_same_film(read_resume_film(dir + "/two.exr", {37, 23, film.aovs, 20}), film);
}

TEST(Resume, CountsNoRenderStopsAtAreRefused) {
  FilmState film = FilmState::empty(4, 4, {});
  film.samples.assign(16, 3);
  film.samples[5] = 2;  // waves of spp 20 end at 1, 3, 7, 15, 20
  const std::string path = test::make_temp_dir("resume-damaged") + "/frame.exr";
  ImageWriteParams params;
  params.resume_film = &film;
  params.resume_settings = "format=1\n";
  write_image(path, Film(film).resolve(), params);
  try {
    read_resume_film(path, {4, 4, {}, 20});
    ADD_FAILURE() << "damaged counts were accepted";
  } catch (const ResumeError& e) {
    EXPECT_EQ(std::string(e.what()),
              path + ": pixel 1,1 has 2 samples, which no render of 20 spp stops at: the file is damaged");
  }
}

TEST(Resume, AFrameWithoutResumeDataIsRefused) {
  const std::string path = test::make_temp_dir("resume-plain") + "/frame.exr";
  ImageWriteParams params;
  write_image(path, Film(4, 4, {}).resolve(), params);
  EXPECT_THROW(read_resume_settings(path), ResumeError);
}

TEST(TimeLimit, StopsAfterTheFirstWaveWhenTheTimeIsUp) {
  RenderSettings s = settings();
  s.time_limit = 1e-9;
  const RenderResult r = render_frame(scene(), camera(), s);
  EXPECT_EQ(r.image.samples_per_pixel, 1);
  EXPECT_TRUE(r.stats.time_limited);
  EXPECT_FALSE(r.stats.cancelled);
  // What it did is the start of the whole render: resuming it finishes it.
  FilmState film = r.film;
  const RenderResult resumed = render_frame(scene(), camera(), settings(), nullptr, &film);
  expect_same_image(render_frame(scene(), camera(), settings()).image, resumed.image);
}

TEST(Checkpoint, IsCalledBetweenWavesButNotAfterTheLast) {
  RenderSettings s = settings();
  std::vector<int> spp;
  s.checkpoint_interval = 0.0;
  s.on_checkpoint = [&](const Film& film, const RenderStats&) { spp.push_back(static_cast<int>(film.min_samples())); };
  render_frame(scene(), camera(), s);
  EXPECT_EQ(spp, (std::vector<int>{1, 3, 7, 15}));
  spp.clear();
  s.checkpoint_interval = 1e9;  // never due
  render_frame(scene(), camera(), s);
  EXPECT_TRUE(spp.empty());
}

}  // namespace
}  // namespace tessera
