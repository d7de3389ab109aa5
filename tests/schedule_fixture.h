// A small lit room rendered with any scheduler, tile order and thread count, for the
// scheduler and profile tests. Header only: included by those tests alone.
#pragma once

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/render/render.h"
#include "tests/scene_builders.h"

namespace tessera::test {

// Walls, an emitter and two instanced spheres: paths of every length, and tiles of very
// different cost (the spheres and the light against the empty background).
inline const RenderScene& schedule_room() {
  static const RenderScene* scene = [] {
    SceneDescription d;
    const int white = add_material(d, diffuse(vec3(0.7f)));
    const int green = add_material(d, diffuse(vec3(0.1f, 0.7f, 0.1f)));
    const int light = add_material(d, emitter(vec3(6.0f)));
    add_mesh(d, make_quad({0, -1, 0}, {1, 0, 0}, {0, 0, -1}, white));
    add_mesh(d, make_quad({0, 0, -1}, {1, 0, 0}, {0, 1, 0}, white));
    add_mesh(d, make_quad({1, 0, 0}, {0, 0, -1}, {0, 1, 0}, green));
    add_mesh(d, make_quad({0, 0.99f, 0}, {0.3f, 0, 0}, {0, 0, 0.3f}, light));
    const glm::mat4 one(1.0f);
    add_mesh(d, make_sphere({0, 0, 0}, 0.25f, 2, white),
             {glm::translate(one, {-0.4f, -0.7f, 0.2f}), glm::translate(one, {0.5f, 0.5f, -0.3f})});
    EnvironmentParams env;
    env.background = vec3(0.1f);
    return new RenderScene(std::move(d), env);
  }();
  return *scene;
}

struct ScheduleCase {
  SchedulerKind scheduler = SchedulerKind::tiles;
  TileOrder order = TileOrder::scanline;
  int threads = 1;
  int tile_size = 8;
  bool record_tiles = false;
};

// 45x37 pixels (partial tiles at the edges), 7 samples (waves of 1, 2 and 4).
inline RenderResult render_schedule_case(const ScheduleCase& c) {
  RenderSettings s;
  s.width = 45;
  s.height = 37;
  s.spp = 7;
  s.max_bounces = 6;
  s.threads = c.threads;
  s.tile_size = c.tile_size;
  s.seed = 99;
  s.aovs = {true, true, true};
  s.scheduler = c.scheduler;
  s.tile_order = c.order;
  s.record_tiles = c.record_tiles;
  const RenderCamera cam = make_camera(look_at({0, 0, 3}, {0, 0, 0}, 45.0f), s.width, s.height, {});
  return render_frame(schedule_room(), cam, s);
}

inline const std::vector<SchedulerKind>& all_schedulers() {
  static const std::vector<SchedulerKind> all = {SchedulerKind::tiles, SchedulerKind::chunks, SchedulerKind::counter,
                                                 SchedulerKind::interleaved};
  return all;
}

inline const std::vector<TileOrder>& all_tile_orders() {
  static const std::vector<TileOrder> all = {TileOrder::scanline, TileOrder::spiral, TileOrder::hilbert};
  return all;
}

}  // namespace tessera::test
