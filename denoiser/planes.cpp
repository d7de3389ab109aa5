#include "denoiser/planes.h"

#include <algorithm>
#include <cmath>

namespace tessera::denoiser {

namespace {

// Larger magnitudes are clipped so that squares and window sums stay finite.
constexpr float kMaxMagnitude = 1e15f;

float sanitize(float v) {
  if (!std::isfinite(v)) return 0.0f;
  return std::clamp(v, -kMaxMagnitude, kMaxMagnitude);
}

// Sliding-window sums of a row over [i - r, i + r] clipped to [0, n).
void row_sums(const float* in, int n, int r, float* out) {
  double sum = 0.0;  // double: the running sum adds and removes, floats would drift
  for (int i = 0; i < std::min(r, n); ++i) sum += in[i];
  for (int i = 0; i < n; ++i) {
    if (i + r < n) sum += in[i + r];
    if (i - r - 1 >= 0) sum -= in[i - r - 1];
    out[i] = static_cast<float>(sum);
  }
}

// Box sums of one plane: rows, then columns with a running sum per column (row by row, so
// memory is read in order).
void box_sum_plane(const float* in, int w, int h, int r, float* out, std::vector<float>& tmp) {
  const std::size_t W = w;
  tmp.resize(W * h);
  for (int y = 0; y < h; ++y) row_sums(in + y * W, w, r, tmp.data() + y * W);
  std::vector<double> column(W, 0.0);
  for (int y = 0; y < std::min(r, h); ++y)
    for (std::size_t x = 0; x < W; ++x) column[x] += tmp[y * W + x];
  for (int y = 0; y < h; ++y) {
    if (y + r < h)
      for (std::size_t x = 0; x < W; ++x) column[x] += tmp[(y + r) * W + x];
    if (y - r - 1 >= 0)
      for (std::size_t x = 0; x < W; ++x) column[x] -= tmp[(y - r - 1) * W + x];
    for (std::size_t x = 0; x < W; ++x) out[y * W + x] = static_cast<float>(column[x]);
  }
}

}  // namespace

Planes to_planes(const std::vector<float>& interleaved, int width, int height, int stride) {
  Planes out(width, height, stride);
  const std::size_t n = out.pixels();
  for (int c = 0; c < stride; ++c) {
    float* dst = out.plane(c);
    for (std::size_t i = 0; i < n; ++i) dst[i] = sanitize(interleaved[i * stride + c]);
  }
  return out;
}

Planes stack(const std::vector<const Planes*>& parts) {
  int channels = 0;
  for (const Planes* p : parts) channels += p->channels;
  Planes out(parts.front()->width, parts.front()->height, channels);
  auto dst = out.data.begin();
  for (const Planes* p : parts) dst = std::copy(p->data.begin(), p->data.end(), dst);
  return out;
}

Planes box_mean(const Planes& in, int r, const std::vector<float>* mask) {
  const int w = in.width, h = in.height;
  const std::size_t n = in.pixels();
  Planes out(w, h, in.channels);
  std::vector<float> tmp, weight_sum(n), weighted(n);
  if (mask) box_sum_plane(mask->data(), w, h, r, weight_sum.data(), tmp);
  else box_sum_plane(std::vector<float>(n, 1.0f).data(), w, h, r, weight_sum.data(), tmp);
  for (int c = 0; c < in.channels; ++c) {
    const float* src = in.plane(c);
    for (std::size_t i = 0; i < n; ++i) weighted[i] = mask ? src[i] * (*mask)[i] : src[i];
    float* dst = out.plane(c);
    box_sum_plane(weighted.data(), w, h, r, dst, tmp);
    for (std::size_t i = 0; i < n; ++i) dst[i] = weight_sum[i] > 0.5f ? dst[i] / weight_sum[i] : 0.0f;
  }
  return out;
}

}  // namespace tessera::denoiser
