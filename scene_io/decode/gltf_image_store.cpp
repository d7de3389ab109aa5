#include "scene_io/decode/gltf_image_store.h"

#include <algorithm>

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include "scene_io/decode/gltf_images.h"

namespace tessera {

void GltfImageStore::keep(int index, std::vector<unsigned char> bytes) {
  if (index < 0) return;
  if (static_cast<std::size_t>(index) >= entries_.size()) entries_.resize(static_cast<std::size_t>(index) + 1);
  entries_[static_cast<std::size_t>(index)] = Entry{true, std::move(bytes), false, {}};
}

bool GltfImageStore::kept(int index) const { return find(index) != nullptr; }

GltfImageStore::Entry* GltfImageStore::find(int index) const {
  if (index < 0 || static_cast<std::size_t>(index) >= entries_.size()) return nullptr;
  Entry& e = entries_[static_cast<std::size_t>(index)];
  return e.kept ? &e : nullptr;
}

void GltfImageStore::decode(const tinygltf::Model& model, const std::vector<int>& indices) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  std::vector<std::pair<int, Entry*>> todo;
  std::vector<char> queued(entries_.size());
  for (int i : indices)
    if (Entry* e = find(i); e && !e->done && !queued[static_cast<std::size_t>(i)]) {
      queued[static_cast<std::size_t>(i)] = 1;
      todo.emplace_back(i, e);
    }
  std::stable_sort(todo.begin(), todo.end(),
                   [](const auto& a, const auto& b) { return a.second->bytes.size() > b.second->bytes.size(); });
  tbb::parallel_for(std::size_t{0}, todo.size(), std::size_t{1}, [&](std::size_t n) {
    const int index = todo[n].first;
    Entry& e = *todo[n].second;
    tinygltf::Image image;
    const std::string problem = decode_image(&image, index, e.bytes.data(), static_cast<int>(e.bytes.size()));
    if (problem.empty()) {
      e.image = {std::make_shared<const std::vector<std::uint8_t>>(std::move(image.image)), image.width, image.height,
                 image.component, image.bits, ""};
    } else {
      e.image.problem = fmt::format("image {} ({}) could not be decoded: {}", index,
                                    gltf_image_source(model.images.at(static_cast<std::size_t>(index))), problem);
    }
    std::vector<unsigned char>().swap(e.bytes);
    e.done = true;
  });
}

DecodedImage GltfImageStore::decoded(int index) const {
  const std::lock_guard<std::mutex> lock(mutex_);
  const Entry* e = find(index);
  return e ? e->image : DecodedImage{};
}

}  // namespace tessera
