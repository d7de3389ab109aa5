#include "renderer/render_scene.h"

#include <chrono>
#include <stdexcept>

namespace tessera {

EmbreeDevice::EmbreeDevice() {
  device_ = rtcNewDevice("verbose=0");
  if (!device_) throw std::runtime_error("Embree could not create a device (unsupported CPU?)");
}

EmbreeDevice::~EmbreeDevice() { rtcReleaseDevice(device_); }

RenderScene::RenderScene(SceneDescription scene, const EnvironmentParams& env)
    : description(std::move(scene)), environment(env), materials(description) {
  const auto start = std::chrono::steady_clock::now();
  geometry = std::make_unique<SceneGeometry>(description, device.get(), &materials);
  bvh_build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  area_lights = std::make_unique<AreaLights>(description, *geometry, materials);
}

}  // namespace tessera
