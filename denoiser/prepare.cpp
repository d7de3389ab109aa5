#include "denoiser/prepare.h"

#include <algorithm>

#include <cmath>
#include <stdexcept>
#include <string>

#include "denoiser/outliers.h"

namespace tessera::denoiser {

namespace {

float compress(float c) { return std::log1p(std::max(c, 0.0f)); }

void check_size(const std::vector<float>& v, std::size_t expected, const char* name, bool optional) {
  if (optional && v.empty()) return;
  if (v.size() != expected)
    throw std::invalid_argument(std::string("denoise: ") + name + " has " + std::to_string(v.size()) +
                                " values, expected " + std::to_string(expected));
}

bool finite3(const std::vector<float>& v, std::size_t i) {
  return std::isfinite(v[3 * i]) && std::isfinite(v[3 * i + 1]) && std::isfinite(v[3 * i + 2]);
}

// Per-pixel sample counts of the even (ceil(n/2)) and odd (floor(n/2)) halves.
void sample_counts(const DenoiseInput& in, std::vector<float>& even, std::vector<float>& odd) {
  const std::size_t n = static_cast<std::size_t>(in.width) * in.height;
  even.assign(n, 1.0f);
  odd.assign(n, 1.0f);
  if (in.samples.empty()) return;
  for (std::size_t i = 0; i < n; ++i) {
    const float s = std::isfinite(in.samples[i]) && in.samples[i] > 0.0f ? std::floor(in.samples[i]) : 0.0f;
    odd[i] = std::floor(s / 2);
    even[i] = s - odd[i];
  }
}

// Where a half is missing it takes the other half's values, so the guides stay meaningful.
void fill_missing(Half& a, const Half& b) {
  for (std::size_t i = 0; i < a.valid.size(); ++i)
    if (a.valid[i] == 0.0f && b.valid[i] != 0.0f)
      for (int c = 0; c < 3; ++c) a.color.at(c, i) = b.color.at(c, i);
}

// Per-sample variance sigma^2 from the two half means: E[(A - B)^2] = sigma^2 (1/nA + 1/nB),
// one degree of freedom per pixel, so it is averaged over a box of pixels where both exist.
// Of the colours as given, or (log_domain) of log(1 + max(c, 0)). `raw` (optional) receives
// the per-pixel estimates before the box.
Planes sample_variance(const Half& a, const Half& b, int radius, bool log_domain, Planes* raw = nullptr) {
  const std::size_t n = a.valid.size();
  Planes s2(a.color.width, a.color.height, 3);
  std::vector<float> both(n);
  for (std::size_t i = 0; i < n; ++i) {
    both[i] = a.valid[i] * b.valid[i];
    if (both[i] == 0.0f) continue;
    const float scale = 1.0f / (1.0f / a.count[i] + 1.0f / b.count[i]);
    for (int c = 0; c < 3; ++c) {
      const float ca = a.color.at(c, i), cb = b.color.at(c, i);
      const float d = log_domain ? compress(ca) - compress(cb) : ca - cb;
      s2.at(c, i) = d * d * scale;
    }
  }
  if (raw) *raw = s2;
  return box_mean(s2, radius, &both);
}

// The NL-means guide, on the range-compressed colour t = log(1 + max(c, 0)): the 3x3 patch
// mean of t (over pixels with any colour) and its variance, the mean of the 9 variances of t
// divided by 9 (independent pixels). In the compressed range a bright, noisy highlight has a
// moderate variance (its relative one), so it is far from a dark, quiet neighbour; with the
// linear colour the highlight's variance, spread by the variance box, made dark pixels beside
// it "similar" to it, and its energy leaked into their fits (halos).
void make_guide(Half& h, const Planes& log_variance, const std::vector<float>& any) {
  Planes t = h.color;
  for (float& v : t.data) v = compress(v);
  h.guide = box_mean(t, 1, &any);
  h.guide_variance = box_mean(log_variance, 1, &any);
  for (float& v : h.guide_variance.data) v /= 9.0f;
}

// The colour outliers lose (`excess`, at the pixels flagged in `outlier`), given back to the valid pixels of a half within
// kOutlierSpreadRadius in proportion to their luminance: pixel j receives l_j times the sum,
// over the outliers i whose box holds j, of excess_i / (the luminance summed over i's box). The
// boxes are symmetric, so that is a box sum over j's own box, and every outlier's excess is
// given back whole (unless its box holds no light at all). In proportion to what is there, the
// energy raises the light of the surfaces around it rather than adding a flat glow, which on
// dark pixels beside a glint would be a halo.
void spread_excess(Half& h, const Planes& excess, const std::vector<std::uint8_t>& outlier) {
  const int w = h.color.width, ht = h.color.height, r = kOutlierSpreadRadius;
  const std::size_t n = h.valid.size();
  auto area = [&](std::size_t i) {  // pixels of i's box, clipped to the image
    const int x = static_cast<int>(i % w), y = static_cast<int>(i / w);
    return float((std::min(w - 1, x + r) - std::max(0, x - r) + 1) * (std::min(ht - 1, y + r) - std::max(0, y - r) + 1));
  };
  Planes weight(w, ht, 1);  // a valid pixel's luminance: its share
  for (std::size_t i = 0; i < n; ++i)
    weight.at(0, i) = h.valid[i] * outlier_luminance(h.color, i);
  const Planes weight_mean = box_mean(weight, r);
  Planes shares(w, ht, 3);
  for (std::size_t i = 0; i < n; ++i) {
    if (!outlier[i]) continue;
    const float total = weight_mean.at(0, i) * area(i);
    if (!(total > 0.0f)) continue;  // no light near: nowhere to give it
    for (int c = 0; c < 3; ++c) shares.at(c, i) = excess.at(c, i) / total;
  }
  const Planes received = box_mean(shares, r);  // per pixel: the shares over its box's area
  for (std::size_t j = 0; j < n; ++j) {
    if (h.valid[j] == 0.0f) continue;
    for (int c = 0; c < 3; ++c) h.color.at(c, j) += received.at(c, j) * area(j) * weight.at(0, j);
  }
}

// Fireflies (denoiser/outliers.h): both halves are detected first, on the colours as given;
// a pixel confirmed only by the other half's outlier is one too. Then each outlier is scaled
// down to its reference luminance and stops being data, and what it loses is given back to
// the valid pixels nearby, in both halves.
void remove_outliers(Halves& halves, const std::vector<float>& sigma) {
  std::vector<float> ref[2];
  for (int k = 0; k < 2; ++k)
    halves.h[k].outlier = detect_outliers(halves.h[k].color, halves.h[1 - k].color, halves.h[k].valid, sigma, ref[k]);
  const std::size_t n = halves.h[0].valid.size();
  for (std::size_t i = 0; i < n; ++i)
    for (int k = 0; k < 2; ++k)
      if (ref[k][i] > 0.0f && halves.h[1 - k].outlier[i]) halves.h[k].outlier[i] = 1;  // candidates both
  // What the outliers of both halves lose, and where they are.
  Planes lost(halves.h[0].color.width, halves.h[0].color.height, 3);
  std::vector<std::uint8_t> any(n, 0);
  for (int k = 0; k < 2; ++k) {
    Half& h = halves.h[k];
    h.excess.assign(n, 0.0f);
    for (std::size_t i = 0; i < n; ++i) {
      if (!h.outlier[i]) continue;
      const float l = outlier_luminance(h.color, i);
      const float scale = ref[k][i] / l;  // l > ref >= 0
      h.excess[i] = l / ref[k][i];  // inf for a reference of 0
      for (int c = 0; c < 3; ++c) {
        lost.at(c, i) += 0.5f * h.color.at(c, i) * (1.0f - scale);
        h.color.at(c, i) *= scale;
      }
      h.valid[i] = 0.0f;
      any[i] = 1;
    }
  }
  // Half of it to each half: the beauty (their mean) gets all of it back, and the halves
  // agree about it, so the regression takes it for light, not for noise.
  for (Half& h : halves.h) spread_excess(h, lost, any);
}

}  // namespace

void validate(const DenoiseInput& in, const DenoiseParams& p) {
  if (in.width <= 0 || in.height <= 0) throw std::invalid_argument("denoise: the image is empty");
  const std::size_t n = static_cast<std::size_t>(in.width) * in.height;
  check_size(in.color_even, 3 * n, "color_even", false);
  check_size(in.color_odd, 3 * n, "color_odd", false);
  check_size(in.albedo, 3 * n, "albedo", false);
  check_size(in.normal, 3 * n, "normal", false);
  check_size(in.albedo_even, 3 * n, "albedo_even", true);
  check_size(in.albedo_odd, 3 * n, "albedo_odd", true);
  check_size(in.normal_even, 3 * n, "normal_even", true);
  check_size(in.normal_odd, 3 * n, "normal_odd", true);
  check_size(in.depth, n, "depth", true);
  check_size(in.samples, n, "samples", true);
  check_size(in.variance, 3 * n, "variance", true);
  const bool any_half = !in.albedo_even.empty() || !in.albedo_odd.empty() || !in.normal_even.empty() || !in.normal_odd.empty();
  const bool all_halves = !in.albedo_even.empty() && !in.albedo_odd.empty() && !in.normal_even.empty() && !in.normal_odd.empty();
  if (any_half && !all_halves)
    throw std::invalid_argument("denoise: the feature half buffers must be given all four or none");
  if (p.radius < 1 || p.radius > 32) throw std::invalid_argument("denoise: radius must be in [1, 32]");
  if (p.stride < 1 || p.stride > p.radius + 1) throw std::invalid_argument("denoise: stride must be in [1, radius + 1]");
  if (p.wide_radius < 0 || p.wide_radius > 32) throw std::invalid_argument("denoise: wide_radius must be in [0, 32]");
  if (p.wide_radius > 0 && (p.wide_stride < 1 || p.wide_stride > p.wide_radius + 1))
    throw std::invalid_argument("denoise: wide_stride must be in [1, wide_radius + 1]");
  if (p.feature_radius < 0 || p.feature_radius > 16) throw std::invalid_argument("denoise: feature_radius must be in [0, 16]");
  if (p.variance_radius < 0 || p.selection_radius < 0 || p.selection_blend_radius < 0) throw std::invalid_argument("denoise: radii must be >= 0");
  for (float k : p.bandwidths)
    if (!(k > 0.0f)) throw std::invalid_argument("denoise: bandwidths must be > 0");
  if (!(p.feature_bandwidth > 0.0f)) throw std::invalid_argument("denoise: feature_bandwidth must be > 0");
  if (!(p.ridge >= 0.0f)) throw std::invalid_argument("denoise: ridge must be >= 0");
  if (!(p.demodulation_epsilon > 0.0f)) throw std::invalid_argument("denoise: demodulation_epsilon must be > 0");
  if (p.threads < 0) throw std::invalid_argument("denoise: threads must be >= 0");
}

Halves prepare_halves(const DenoiseInput& in, const DenoiseParams& p) {
  const std::size_t n = static_cast<std::size_t>(in.width) * in.height;
  Halves out;
  const std::vector<float>* src[2] = {&in.color_even, &in.color_odd};
  sample_counts(in, out.h[0].count, out.h[1].count);
  for (int k = 0; k < 2; ++k) {
    Half& h = out.h[k];
    h.color = to_planes(*src[k], in.width, in.height, 3);
    h.valid.resize(n);
    for (std::size_t i = 0; i < n; ++i) h.valid[i] = h.count[i] > 0.0f && finite3(*src[k], i) ? 1.0f : 0.0f;
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i) h.color.at(c, i) *= h.valid[i];
  }
  fill_missing(out.h[0], out.h[1]);
  fill_missing(out.h[1], out.h[0]);
  remove_outliers(out, outlier_sigma(in.variance));
  Planes s2_raw;
  const Planes s2 = sample_variance(out.h[0], out.h[1], p.variance_radius, false, &s2_raw);
  const Planes s2_log = sample_variance(out.h[0], out.h[1], p.variance_radius, true);
  std::vector<float> any(n);
  for (std::size_t i = 0; i < n; ++i) any[i] = out.h[0].valid[i] + out.h[1].valid[i] > 0.0f ? 1.0f : 0.0f;
  for (Half& h : out.h) {
    h.variance = s2;
    h.pixel_variance = s2_raw;
    Planes log_variance = s2_log;
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i) {
        const float count = std::max(h.count[i], 1.0f);
        h.variance.at(c, i) /= count;
        h.pixel_variance.at(c, i) /= count;
        log_variance.at(c, i) /= count;
      }
    make_guide(h, log_variance, any);
  }
  return out;
}

Unfiltered unfiltered_colour(const DenoiseInput& in) {
  const std::size_t n = static_cast<std::size_t>(in.width) * in.height;
  std::vector<float> count[2];
  sample_counts(in, count[0], count[1]);
  const std::vector<float>* src[2] = {&in.color_even, &in.color_odd};
  Unfiltered out{Planes(in.width, in.height, 3), std::vector<float>(n)};
  for (std::size_t i = 0; i < n; ++i) {
    float total = 0.0f;
    for (int h = 0; h < 2; ++h) {
      if (!(count[h][i] > 0.0f) || !finite3(*src[h], i)) continue;
      total += count[h][i];
      for (int c = 0; c < 3; ++c) out.rgb.at(c, i) += count[h][i] * (*src[h])[3 * i + c];
    }
    bool finite = total > 0.0f;
    for (int c = 0; c < 3; ++c) finite = finite && std::isfinite(out.rgb.at(c, i) /= total);
    out.present[i] = finite ? 1.0f : 0.0f;  // a sum that overflowed is missing too
    if (!finite)
      for (int c = 0; c < 3; ++c) out.rgb.at(c, i) = 0.0f;
  }
  return out;
}

Features prepare_features(const DenoiseInput& in, const DenoiseParams& p, const Halves& halves) {
  const int w = in.width, h = in.height;
  const Planes albedo = to_planes(in.albedo, w, h, 3), normal = to_planes(in.normal, w, h, 3);
  Features f;
  if (in.depth.empty()) f.values = stack({&albedo, &normal});
  else {
    const Planes depth = to_planes(in.depth, w, h, 1);
    f.values = stack({&albedo, &normal, &depth});
  }
  if (in.albedo_even.empty()) return f;
  // Feature variance of the mean: (even - odd)^2 / (1/nA + 1/nB) / (nA + nB), smoothed; for
  // albedo and normal only (depth has no halves).
  const Planes halves_even[2] = {to_planes(in.albedo_even, w, h, 3), to_planes(in.normal_even, w, h, 3)};
  const Planes halves_odd[2] = {to_planes(in.albedo_odd, w, h, 3), to_planes(in.normal_odd, w, h, 3)};
  const std::size_t n = albedo.pixels();
  Planes var(w, h, 6);
  const std::vector<float>& ne = halves.h[0].count;
  const std::vector<float>& no = halves.h[1].count;
  std::vector<float> both(n);
  for (std::size_t i = 0; i < n; ++i) both[i] = ne[i] > 0.0f && no[i] > 0.0f ? 1.0f : 0.0f;
  for (int g = 0; g < 2; ++g)
    for (int c = 0; c < 3; ++c)
      for (std::size_t i = 0; i < n; ++i) {
        if (both[i] == 0.0f) continue;
        const float d = halves_even[g].at(c, i) - halves_odd[g].at(c, i);
        var.at(3 * g + c, i) = d * d / (1.0f / ne[i] + 1.0f / no[i]) / (ne[i] + no[i]);
      }
  f.variance = box_mean(var, p.variance_radius, &both);
  return f;
}

}  // namespace tessera::denoiser
