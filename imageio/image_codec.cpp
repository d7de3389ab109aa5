#include "imageio/image_codec.h"

#include <dlfcn.h>

#include <filesystem>
#include <mutex>
#include <stdexcept>

#ifndef TESSERA_MODULE_DIR
#define TESSERA_MODULE_DIR ""
#endif

namespace tessera {

namespace {

// Beside the program (where the build puts it, and where an installed tree keeps it), then
// the build directory (the test programs live in its subdirectories).
std::vector<std::string> module_candidates() {
  std::vector<std::string> out;
  std::error_code ec;
  const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) out.push_back((exe.parent_path() / kImageCodecModule).string());
  if (*TESSERA_MODULE_DIR) out.push_back(std::string(TESSERA_MODULE_DIR) + "/" + kImageCodecModule);
  return out;
}

const ImageCodec* load() {
  std::string reasons;
  for (const std::string& path : module_candidates()) {
    void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!handle) {
      reasons += std::string(reasons.empty() ? "" : "; ") + dlerror();
      continue;
    }
    auto entry = reinterpret_cast<ImageCodecEntry>(dlsym(handle, kImageCodecEntry));
    if (!entry) throw std::runtime_error(path + ": not tessera's image module (no " + kImageCodecEntry + ")");
    return entry();  // kept loaded for the process: the codec lives in it
  }
  throw std::runtime_error(std::string("cannot load the image module ") + kImageCodecModule +
                           " (OpenImageIO), needed for non-EXR images: " + reasons);
}

}  // namespace

const ImageCodec& image_codec() {
  static std::once_flag once;
  static const ImageCodec* codec = nullptr;
  std::call_once(once, [] { codec = load(); });
  return *codec;
}

}  // namespace tessera
