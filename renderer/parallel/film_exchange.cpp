#include "renderer/parallel/film_exchange.h"

#include <stdexcept>

#include "renderer/util/byte_stream.h"

namespace tessera {
namespace {

// Visits every per-pixel array of the film with the pixel's index: one list of fields for
// packing and unpacking alike.
template <typename Film, typename Visit>
void each_field(Film& film, std::size_t i, Visit&& visit) {
  auto field = [&](auto& values) {
    if (!values.empty()) visit(values[i]);
  };
  field(film.radiance);
  field(film.albedo);
  field(film.normal);
  field(film.depth);
  field(film.samples);
  field(film.hits);
  field(film.radiance_odd);
  field(film.albedo_odd);
  field(film.normal_odd);
  field(film.radiance_sq);
  field(film.converged);
}

template <typename Body>
void each_pixel(const Tile& t, int width, Body&& body) {
  for (int y = t.y0; y < t.y1; ++y)
    for (int x = t.x0; x < t.x1; ++x) body(static_cast<std::size_t>(y) * width + x);
}

}  // namespace

std::vector<char> pack_tiles(const FilmState& film, const std::vector<Tile>& tiles, const std::vector<std::size_t>& taken) {
  ByteWriter out;
  auto put = [&](const auto& value) { out.put(value); };
  out.put(taken.size());
  for (std::size_t item : taken) {
    out.put(item);
    each_pixel(tiles[item], film.width, [&](std::size_t i) { each_field(film, i, put); });
  }
  return out.take();
}

void unpack_tiles(FilmState& film, const std::vector<Tile>& tiles, const std::vector<char>& bytes) {
  ByteReader in(bytes, "a rank's tile data");
  auto get = [&](auto& value) { in.get(value); };
  const auto count = in.get<std::size_t>();
  for (std::size_t k = 0; k < count; ++k) {
    const auto item = in.get<std::size_t>();
    if (item >= tiles.size()) throw std::runtime_error("a rank sent a tile the plan does not have");
    each_pixel(tiles[item], film.width, [&](std::size_t i) { each_field(film, i, get); });
  }
}

}  // namespace tessera
