#include "app/commands/pixel_report.h"

#include <cstdio>

#include <fmt/format.h>

#include "app/cli/exit_codes.h"
#include "app/frame/frame_pipeline.h"
#include "renderer/render/pixel_trace.h"

namespace tessera {

namespace {

std::string triple(const vec3& v) { return fmt::format("({:.6g}, {:.6g}, {:.6g})", v.x, v.y, v.z); }

PixelTraceParams parse_pixel(const std::string& text, int width, int height) {
  PixelTraceParams p;
  char tail;
  if (std::sscanf(text.c_str(), "%d,%d%c", &p.x, &p.y, &tail) != 2)
    throw UsageError("--pixel " + text + ": expected X,Y, two whole numbers (0,0 is the top left pixel)");
  if (p.x < 0 || p.y < 0 || p.x >= width || p.y >= height)
    throw UsageError(fmt::format("--pixel {}: outside the {}x{} frame (X 0 to {}, Y 0 to {})", text, width, height,
                                 width - 1, height - 1));
  return p;
}

std::string material_name(const SceneDescription& scene, int material) {
  if (material < 0 || material >= static_cast<int>(scene.materials.size())) return "default material";
  return fmt::format("material {} '{}'", material, scene.materials[material].name);
}

// Positions in world coordinates: the render frame's moved back by its origin.
void print_path(const RenderScene& scene, int sample, const PathRecord& path, const vec3& radiance) {
  fmt::print("sample {}: radiance {}\n", sample, triple(radiance));
  for (std::size_t i = 0; i < path.vertices.size(); ++i) {
    const PathVertex& v = path.vertices[i];
    fmt::print("  vertex {}: position {}  normal {}  {}\n", i + 1, triple(v.position + scene.origin), triple(v.normal),
               material_name(scene.description, v.material));
    fmt::print("    throughput {}  emitted {}  direct light {}\n", triple(v.throughput), triple(v.emitted),
               triple(v.direct));
    if (!v.lobe.empty()) fmt::print("    sampled {}, pdf {:.6g}\n", v.lobe, v.pdf);
  }
  if (path.vertices.empty() || path.end == "left the scene")
    fmt::print("  end: left the scene, background adds {}\n", triple(path.escaped));
  else
    fmt::print("  end: {}\n", path.end);
}

}  // namespace

int run_pixel_report(const RenderOptions& o, const GltfDocument& document) {
  LoadedScene loaded = load_scene(o, document);
  FramePlan plan = plan_frame(o, loaded.gltf);
  const RenderSettings& settings = plan.settings;
  const PixelTraceParams params = parse_pixel(o.pixel, settings.width, settings.height);
  const BuiltFrame built = build_frame(std::move(loaded), plan);
  const PixelTrace trace = trace_pixel(*built.scene, built.camera, settings, params);
  fmt::print("pixel {},{} of {}x{}: {} spp, seed {}, {} sampler, camera '{}', background {}\n", params.x, params.y,
             settings.width, settings.height, settings.spp, settings.seed, sampler_name(settings.sampler),
             plan.camera.name, plan.background);
  for (std::size_t s = 0; s < trace.paths.size(); ++s) print_path(*built.scene, static_cast<int>(s), trace.paths[s], trace.radiance[s]);
  if (trace.samples > static_cast<int>(trace.paths.size()))
    fmt::print("({} more samples not shown)\n", trace.samples - static_cast<int>(trace.paths.size()));
  fmt::print("mean of {} samples: ({:.6g}, {:.6g}, {:.6g}){}\n", trace.samples, trace.mean.x, trace.mean.y, trace.mean.z,
             trace.dropped ? fmt::format(", {} non-finite samples counted as black", trace.dropped) : "");
  return kExitSuccess;
}

}  // namespace tessera
