// A glTF file's images, kept encoded until a scene shows them. Decoding is most of a textured
// model's load time and memory (DamagedHelmet: five 2048^2 JPEGs, 16 MiB each decoded), and
// a file's images are not all shown: its occlusion maps (which a path tracer does not read),
// the images of materials or scenes not chosen. Each image is decoded at most once, on first
// need, and shared by every scene converted from the document after that (frames, ranks).
#pragma once

#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include <tiny_gltf.h>

namespace tessera {

using SharedPixels = std::shared_ptr<const std::vector<std::uint8_t>>;

// An image decoded, as tinygltf describes one: 8, 16 or 32 bits per channel, 1 to 4 channels.
struct DecodedImage {
  SharedPixels pixels;  // null when it could not be decoded
  int width = 0, height = 0, channels = 0, bits = 0;
  std::string problem;  // "image 2 (bufferView 4) could not be decoded: ...", when it could not
};

class GltfImageStore {
 public:
  // Keeps image `index`'s encoded bytes (tinygltf's image callback, a WebP data URI).
  void keep(int index, std::vector<unsigned char> bytes);
  // Were bytes kept for image `index`?
  bool kept(int index) const;

  // Decodes every image of `indices` kept and not yet decoded: in parallel (TBB), largest
  // first, so that one large image (DamagedHelmet's progressive JPEG) does not decide alone
  // when the last thread finishes. Thread-safe; `model` names the images in messages.
  void decode(const tinygltf::Model& model, const std::vector<int>& indices) const;
  // Image `index` as decode() left it; an image never kept has no pixels and no problem.
  DecodedImage decoded(int index) const;

 private:
  struct Entry {
    bool kept = false;
    std::vector<unsigned char> bytes;  // freed once decoded
    bool done = false;
    DecodedImage image;
  };
  Entry* find(int index) const;  // null for an image not kept

  mutable std::vector<Entry> entries_;  // by image index
  mutable std::mutex mutex_;
};

}  // namespace tessera
