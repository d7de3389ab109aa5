#include "renderer/profile/traversal_ceiling.h"

#include <atomic>
#include <chrono>
#include <cmath>

#include <tbb/blocked_range2d.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "renderer/camera/camera_coverage.h"
#include "renderer/bsdfs/bsdf.h"
#include "renderer/sampling/sampler.h"

namespace tessera {
namespace {

// The next ray of a diffuse path: cosine-distributed about the geometric normal, on the side
// the ray came from, leaving from the hit moved off the surface as the renderer's rays leave
// (offset_ray_origin, with the point's own largest coordinate standing in for its triangle's).
Ray diffuse_bounce(const Ray& ray, float t, vec3 normal, const vec2& u) {
  const vec3 p = ray.origin + t * ray.direction;
  normal = glm::normalize(normal);
  if (glm::dot(normal, ray.direction) > 0.0f) normal = -normal;
  const vec3 wi = Frame::from_normal(normal).to_world(sample_cosine_hemisphere(u));
  return Ray{offset_ray_origin(p, normal, max_component(glm::abs(p))), wi};
}

std::uint64_t trace_pixel(const RenderScene& scene, const RenderCamera& camera, const TraversalCeilingParams& p, int x,
                          int y) {
  std::uint64_t rays = 0;
  for (int s = 0; s < p.spp; ++s) {
    Sampler rng(SamplerKind::independent, x, y, s, p.seed);
    const vec2 jitter = rng.next2();
    Ray ray = camera.generate_ray({(x + jitter.x) / p.width, (y + jitter.y) / p.height}, vec2(0.5f));
    for (int bounce = 0; bounce <= p.max_bounces; ++bounce) {
      HitRecord hit;
      vec3 ng;
      ++rays;
      if (!scene.geometry->intersect(ray, hit, &ng) || !(glm::dot(ng, ng) > 0.0f)) break;
      ray = diffuse_bounce(ray, hit.t, ng, rng.next2());
    }
  }
  return rays;
}

}  // namespace

TraversalCeilingResult trace_traversal_ceiling(const RenderScene& scene, const RenderCamera& camera,
                                               const TraversalCeilingParams& p) {
  scene.check_camera(camera);
  std::atomic<std::uint64_t> rays{0};
  const auto start = std::chrono::steady_clock::now();
  CameraCoverage coverage;
  if (p.cull_camera_rays) {
    CameraCoverageParams cp;
    cp.full_width = cp.width = p.width;
    cp.full_height = cp.height = p.height;
    cp.filter_radius = p.filter_radius;
    coverage = CameraCoverage(camera, *scene.geometry, cp);
  }
  tbb::task_arena arena(p.threads > 0 ? p.threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range2d<int>(0, p.height, 32, 0, p.width, 32), [&](const tbb::blocked_range2d<int>& r) {
      std::uint64_t local = 0;
      for (int y = r.rows().begin(); y < r.rows().end(); ++y)
        for (int x = r.cols().begin(); x < r.cols().end(); ++x)
          if (coverage.may_hit(x, y)) local += trace_pixel(scene, camera, p, x, y);
      rays += local;
    });
  });
  return {rays.load(), std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
          coverage.empty_pixels() * static_cast<std::uint64_t>(p.spp)};
}

}  // namespace tessera
