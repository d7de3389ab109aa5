// tessera render --pixel X,Y: one pixel traced alone, its paths printed on stdout (each
// vertex: position, normal, material, throughput, what it adds, the lobe sampled and its
// pdf), then the pixel's mean, which is the value the full render gives that pixel.
#pragma once

#include "app/cli/options.h"
#include "scene_io/gltf_loader.h"

namespace tessera {

// Throws UsageError for a malformed X,Y or a pixel outside the frame.
int run_pixel_report(const RenderOptions& o, const GltfDocument& document);

}  // namespace tessera
