// libFuzzer entry point: any bytes, as a .gltf (JSON) or .glb (they start with "glTF"),
// through the loader. The only acceptable outcomes are a scene or a SceneLoadError; anything
// else (a crash, a sanitizer report, another exception, a hang) is a bug to fix and to keep
// as a file in tests/data/fuzz-regressions/.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <vector>

#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::uint8_t> bytes(data, data + size);
  // External URIs resolve in TESSERA_FUZZ_BASE_DIR (tools/fuzz.sh: tests/data, whose .bin
  // files the seeds name), else in a directory that does not exist.
  static const std::string base_dir = [] {
    const char* dir = std::getenv("TESSERA_FUZZ_BASE_DIR");
    return std::string(dir ? dir : "/nonexistent-fuzz-dir");
  }();
  try {
    tessera::load_gltf_from_memory(bytes, "fuzz-input", base_dir);
  } catch (const tessera::SceneLoadError&) {
  }
  return 0;
}
