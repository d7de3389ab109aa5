// Before the big allocations of a render (film, image buffers, textures, BVH, environment),
// an estimate of what they take, refused with the numbers when it exceeds the memory the
// machine has available, instead of being killed by the kernel hours later.
#pragma once

#include <cstdint>
#include <string>

#include "renderer/film/film.h"
#include "renderer/description/scene.h"

namespace tessera {

struct MemoryEstimate {
  std::uint64_t film = 0;  // per-pixel sums and counts, the resolved image, the EXR buffers
  std::uint64_t textures = 0;  // the images as the renderer prepares them
  std::uint64_t bvh = 0;  // Embree's BVH and the baked geometry, per triangle
  std::uint64_t environment = 0;  // the environment image and its sampling tables
  std::uint64_t total() const { return film + textures + bvh + environment; }
};

// `adaptive`: adaptive sampling keeps the odd half's sums even without the halves AOV.
MemoryEstimate estimate_render_memory(const SceneDescription& scene, int width, int height, AovSelection aovs,
                                      const std::string& envmap_path, bool adaptive = false);

// What the machine can give: TESSERA_MEMORY_AVAILABLE (bytes) when set, to cap tessera
// below the machine or to test this check; else MemAvailable from /proc/meminfo; 0 when
// unknown (then nothing is refused).
std::uint64_t available_memory();

// Throws UsageError with the estimate, its parts and what is available when it does not fit.
void check_render_memory(const MemoryEstimate& estimate);

}  // namespace tessera
