// What a resumable EXR records about how it was made, and the check that a render asked to
// --resume it is the same render: the same scene file (a hash of its bytes), the same
// settings that affect pixels (size, spp, bounces, seed, the resolved camera and lens, the
// background or environment map and its bytes, the AOVs, the noise threshold and minimum
// of adaptive sampling). Threads, tile size, scheduler,
// tile order, --half and --exposure may differ: they never change the sums.
#pragma once

#include <string>

#include "app/cli/options.h"
#include "renderer/camera/camera.h"
#include "renderer/lights/environment.h"
#include "renderer/render/render.h"

namespace tessera {

// "key=value" lines, one per setting, in a fixed order. `variant`: the material variant
// applied (-1: none), named `variant_name`.
std::string resume_settings(const RenderOptions& options, const RenderSettings& settings, const RenderCamera& camera,
                            const EnvironmentParams& environment, int variant = -1,
                            const std::string& variant_name = "");

// Throws UsageError naming `path` and the first setting that differs; a higher spp than the
// stored one is no difference (a fixed-count render continues to the new target).
void check_resume_settings(const std::string& path, const std::string& stored, const std::string& current);

// The target spp of the render that wrote `stored` (0: none recorded).
int stored_spp(const std::string& stored);

// A 64-bit FNV-1a hash of a file's bytes, as hex. Throws UsageError when it cannot be read.
std::string hash_file(const std::string& path);

}  // namespace tessera
