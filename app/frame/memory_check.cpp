#include "app/frame/memory_check.h"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "imageio/image_codec.h"

namespace tessera {

namespace {

// Per pixel: the film (radiance sums 24 B, count 4 B), the resolved RGB (12 B), the EXR's
// RGBA channels (16 B) and the resume layers of a partial frame (count and sum bits, 28 B).
constexpr std::uint64_t kFilmBytesPerPixel = 24 + 4 + 12 + 16 + 28;
// Per AOV channel: its sum in the film, the resolved value, the EXR channel, the resume layer.
constexpr std::uint64_t kAovChannelBytes = 4 * 4;
// With the halves AOV or adaptive sampling, per pixel: the odd radiance sums (24 B) and their
// resume layer (24 B), the even and odd means resolved and in the EXR (48 B), the count
// (spp layer, 12 B) and the converged flag (5 B); per albedo or normal channel, its odd sum,
// resume layer, two means and two EXR channels (24 B).
constexpr std::uint64_t kOddBytesPerPixel = 24 + 24 + 48 + 12 + 5;
constexpr std::uint64_t kOddAovChannelBytes = 6 * 4;
// Embree's BVH with its triangle leaves, the baked world-space vertices and the hit
// attributes: measured near 100-150 B on the shipped scenes; rounded up.
constexpr std::uint64_t kBvhBytesPerTriangle = 160;
// The environment image as float RGB plus its sampling distribution, per texel.
constexpr std::uint64_t kEnvironmentBytesPerTexel = 12 + 8;

std::string gib(std::uint64_t bytes) { return fmt::format("{:.1f} GiB", bytes / double(1ull << 30)); }

std::uint64_t environment_texels(const std::string& path) {
  if (path.empty()) return 0;
  FloatImage size;  // the header only; unreadable files fail later, named
  if (!image_codec().read_size(path, size)) return 0;
  return static_cast<std::uint64_t>(size.width) * size.height;
}

}  // namespace

MemoryEstimate estimate_render_memory(const SceneDescription& scene, int width, int height, AovSelection aovs,
                                      const std::string& envmap_path, bool adaptive) {
  MemoryEstimate m;
  const std::uint64_t pixels = static_cast<std::uint64_t>(width) * height;
  const int aov_channels = (aovs.albedo ? 3 : 0) + (aovs.normal ? 3 : 0) + (aovs.depth ? 1 : 0) + (aovs.counts_hits() ? 1 : 0);
  m.film = pixels * (kFilmBytesPerPixel + aov_channels * kAovChannelBytes);
  if (aovs.halves || adaptive)
    m.film += pixels * (kOddBytesPerPixel + ((aovs.albedo ? 3 : 0) + (aovs.normal ? 3 : 0)) * kOddAovChannelBytes);
  for (const Image& img : scene.images)  // 8-bit stays RGBA8, deeper becomes float RGBA
    m.textures += static_cast<std::uint64_t>(img.width) * img.height * (img.bits_per_channel == 8 ? 4 : 16);
  std::uint64_t triangles = 0;  // a deforming mesh counts once per motion step: Embree's
  for (const Mesh& mesh : scene.meshes)  // motion BVH and vertex buffers grow with them
    for (const TriangleMesh& p : mesh.primitives) triangles += p.triangle_count() * (1 + p.motion_positions.size());
  m.bvh = triangles * kBvhBytesPerTriangle;
  m.environment = environment_texels(envmap_path) * kEnvironmentBytesPerTexel;
  return m;
}

std::uint64_t available_memory() {
  if (const char* cap = std::getenv("TESSERA_MEMORY_AVAILABLE")) return std::strtoull(cap, nullptr, 10);
  std::ifstream in("/proc/meminfo");
  for (std::string line; std::getline(in, line);) {
    std::istringstream fields(line);
    std::string key;
    std::uint64_t kib = 0;
    if (fields >> key >> kib && key == "MemAvailable:") return kib * 1024;
  }
  return 0;
}

void check_render_memory(const MemoryEstimate& m) {
  const std::uint64_t available = available_memory();
  if (available == 0 || m.total() <= available) return;
  throw UsageError(fmt::format("this render needs about {} of memory (image {}, textures {}, BVH {}, environment "
                               "{}) but {} is available: use a smaller --width/--height or fewer --aov layers",
                               gib(m.total()), gib(m.film), gib(m.textures), gib(m.bvh), gib(m.environment),
                               gib(available)));
}

}  // namespace tessera
