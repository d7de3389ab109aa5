#include "denoiser/feature_filter.h"

#include <algorithm>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

namespace tessera::denoiser {

namespace {

constexpr float kEpsilon = 1e-10f;  // keeps noise-free, identical features at distance 0

struct Group {
  int first, count;
};

// Albedo and normal. Depth has no half buffers, so no variance to normalise a distance by;
// it is passed through as it is (a pinhole camera's first-hit depth is nearly noise-free).
const std::vector<Group> kGroups = {{0, 3}, {3, 3}};
constexpr int kFiltered = 6;

// One output row: accumulates every window offset over the whole row, so the inner loop runs
// along contiguous memory.
void filter_row(const Features& f, const Planes& guide, const Planes& gvar, int y, int r, float k2, Planes& out) {
  const int w = f.values.width, h = f.values.height, C = kFiltered;
  const std::size_t row = static_cast<std::size_t>(y) * w;
  std::vector<float> acc(static_cast<std::size_t>(C) * w, 0.0f), wsum(w, 0.0f), dist(w), gd(w);
  for (int dy = -r; dy <= r; ++dy) {
    if (y + dy < 0 || y + dy >= h) continue;
    const std::size_t qrow = static_cast<std::size_t>(y + dy) * w;
    for (int dx = -r; dx <= r; ++dx) {
      const int x0 = std::max(0, -dx), x1 = std::min(w, w - dx);
      std::fill(dist.begin(), dist.end(), 0.0f);
      for (const Group& g : kGroups) {
        std::fill(gd.begin(), gd.end(), 0.0f);
        for (int c = g.first; c < g.first + g.count; ++c) {
          const float* gp = guide.plane(c) + row;
          const float* gq = guide.plane(c) + qrow + dx;
          const float* vp = gvar.plane(c) + row;
          const float* vq = gvar.plane(c) + qrow + dx;
          for (int x = x0; x < x1; ++x) {
            const float d = gp[x] - gq[x];
            gd[x] += (d * d - (vp[x] + std::min(vp[x], vq[x]))) / (kEpsilon + k2 * (vp[x] + vq[x]));
          }
        }
        const float inv = 1.0f / g.count;
        for (int x = x0; x < x1; ++x) dist[x] = std::max(dist[x], gd[x] * inv);
      }
      for (int x = x0; x < x1; ++x) {
        const float wt = exp_neg(-dist[x]);  // dist >= 0 here: the max starts at 0
        wsum[x] += wt;
        for (int c = 0; c < C; ++c) acc[static_cast<std::size_t>(c) * w + x] += wt * f.values.plane(c)[qrow + x + dx];
      }
    }
  }
  for (int c = 0; c < C; ++c)
    for (int x = 0; x < w; ++x) out.plane(c)[row + x] = acc[static_cast<std::size_t>(c) * w + x] / wsum[x];
}

}  // namespace

Planes prefilter_features(const Features& f, int radius, float bandwidth) {
  if (f.variance.data.empty() || radius == 0) return f.values;
  const Planes guide = box_mean(f.values, 1);
  Planes gvar = box_mean(f.variance, 1);
  for (float& v : gvar.data) v /= 9.0f;
  Planes out = f.values;  // depth, when present, stays as it is
  tbb::parallel_for(tbb::blocked_range<int>(0, f.values.height), [&](const tbb::blocked_range<int>& rows) {
    for (int y = rows.begin(); y < rows.end(); ++y)
      filter_row(f, guide, gvar, y, radius, bandwidth * bandwidth, out);
  });
  return out;
}

}  // namespace tessera::denoiser
