#include "denoiser/selection.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "denoiser/outliers.h"

namespace tessera::denoiser {

namespace {

constexpr float kRelativeEpsilon = 1e-2f;  // relMSE's: (x - ref)^2 / (ref^2 + 0.01)
// Each candidate's error is floored at this share of the unfiltered one's before weighing:
// it caps a filter's weight at 100x the unfiltered colour's. 0.05 to 0.2 measured alike.
constexpr float kErrorFloor = 0.1f;
constexpr float kTinyError = 1e-10f;  // the unfiltered error where the colour is noise-free
// The filters' weights are divided by their number over 2: two candidates per pass, so one
// pass weighs as before and a second does not crowd out the noisy colour by number alone
// (with both passes and the bias above, DamagedHelmet 1.81e-3 without, 1.73e-3 with; the
// Cornell box 5.18e-4 and 5.36e-4).
constexpr float kFilterShare = 2.0f;

// fn(i) for every pixel, in parallel (each pixel's result is its own: any thread count gives
// the same bits).
template <typename Fn>
void each_pixel(std::size_t n, const Fn& fn) {
  tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, 4096), [&](const tbb::blocked_range<std::size_t>& r) {
    for (std::size_t i = r.begin(); i < r.end(); ++i) fn(i);
  });
}

// The weight of half A in a combination: each half weighs as its samples; a half without
// samples here still carries its neighbours' fit, so equal weights when neither has any.
float weight_a(const Halves& halves, std::size_t i) {
  const float na = halves.h[0].count[i], nb = halves.h[1].count[i];
  return na + nb > 0.0f ? na / (na + nb) : 0.5f;
}

// A filtered candidate's colour, halves combined.
Planes combined(const Halves& halves, const Planes& half_a, const Planes& half_b) {
  Planes out(half_a.width, half_a.height, 3);
  each_pixel(out.pixels(), [&](std::size_t i) {
    const float wa = weight_a(halves, i);
    for (int k = 0; k < 3; ++k) out.at(k, i) = wa * half_a.at(k, i) + (1.0f - wa) * half_b.at(k, i);
  });
  return out;
}

struct Candidates {
  std::vector<const Planes*> half[2];  // each filter's halves (null for the unfiltered colour)
  std::vector<Planes> filtered;  // the filters' halves combined
  std::vector<const Planes*> colour;  // candidate 0 the unfiltered colour, then the filters'
};

Candidates candidates(const Halves& halves, const std::vector<Filtered>& passes, const Planes& unfiltered) {
  Candidates out;
  for (int h = 0; h < 2; ++h) out.half[h].push_back(nullptr);
  for (const Filtered& f : passes)
    for (int band = 0; band < 2; ++band) {
      out.filtered.push_back(combined(halves, f.filtered[0][band], f.filtered[1][band]));
      for (int h = 0; h < 2; ++h) out.half[h].push_back(&f.filtered[h][band]);
    }
  out.colour.push_back(&unfiltered);
  // Pointers into `filtered`, now complete (moving a Candidates keeps its elements in place).
  for (const Planes& p : out.filtered) out.colour.push_back(&p);
  return out;
}

// Per pixel and candidate: the estimated relative squared error, summed over channels.
Planes pixel_errors(const Halves& halves, const Candidates& cand, float half_variance_bias) {
  const Half& a = halves.h[0];
  const Half& b = halves.h[1];
  const int count = static_cast<int>(cand.colour.size());
  Planes err(a.color.width, a.color.height, count);
  each_pixel(err.pixels(), [&](std::size_t i) {
    const float wa = weight_a(halves, i), wb = 1.0f - wa;
    for (int k = 0; k < 3; ++k) {
      float s = cand.colour[0]->at(k, i);
      for (int c = 1; c < count; ++c) s = std::min(s, cand.colour[c]->at(k, i));
      s = std::max(s, 0.0f);
      const float inv = 1.0f / (s * s + kRelativeEpsilon);
      const float va = a.pixel_variance.at(k, i) / half_variance_bias, vb = b.pixel_variance.at(k, i) / half_variance_bias;
      err.at(kUnfiltered, i) += (wa * wa * va + wb * wb * vb) * inv;
      for (int c = 1; c < count; ++c) {
        const float da = cand.half[0][c]->at(k, i) - b.color.at(k, i);
        const float db = cand.half[1][c]->at(k, i) - a.color.at(k, i);
        err.at(c, i) += 0.5f * (da * da - vb + db * db - va) * inv;
      }
    }
  });
  return err;
}

// The unfiltered candidate: the colour as given, but where one half is an implausible firefly
// (denoiser/outliers.h, kImplausibleExcess) and the other half holds data, that other half.
Planes unfiltered_candidate(const Halves& halves, const Unfiltered& noisy) {
  Planes out = noisy.rgb;
  each_pixel(out.pixels(), [&](std::size_t i) {
    for (int h = 0; h < 2; ++h) {
      const Half &self = halves.h[h], &other = halves.h[1 - h];
      if (!(self.excess[i] >= kImplausibleExcess) || other.valid[i] == 0.0f) continue;
      for (int k = 0; k < 3; ++k) out.at(k, i) = other.color.at(k, i);
    }
  });
  return out;
}

// Whether the noisy colour is a candidate at pixel i: where it exists and its box holds an
// estimate; and where a half was taken out as a firefly (or is missing), only if that
// estimate is the least: a legitimate glint keeps its value where the neighbourhood says the
// filters are worse, and a firefly on a surface the filters explain gets no weight at all.
bool offered(const Unfiltered& noisy, const Planes& estimated, const std::vector<float>& both, const Planes& error,
             std::size_t i) {
  if (noisy.present[i] == 0.0f || estimated.at(0, i) == 0.0f) return false;
  if (both[i] != 0.0f) return true;
  for (int c = 0; c < error.channels; ++c)
    if (c != kUnfiltered && !(error.at(kUnfiltered, i) < error.at(c, i))) return false;
  return true;
}

}  // namespace

Selection select_and_combine(const Halves& halves, const std::vector<Filtered>& passes, const Unfiltered& noisy,
                             int radius, int blend_radius, float half_variance_bias) {
  const Half& a = halves.h[0];
  const Half& b = halves.h[1];
  const Planes noisy_candidate = unfiltered_candidate(halves, noisy);
  const Candidates cand = candidates(halves, passes, noisy_candidate);
  const int count = static_cast<int>(cand.colour.size());
  if (count > kMaxCandidates) throw std::invalid_argument("denoise: at most 2 regression passes");
  const std::size_t n = a.valid.size();
  const int w = a.color.width, h = a.color.height;

  // The estimates hold where both halves hold data; a pixel without (a firefly, a missing
  // half) takes its box's.
  std::vector<float> both(n);
  for (std::size_t i = 0; i < n; ++i) both[i] = a.valid[i] * b.valid[i];
  Planes both_plane(w, h, 1);
  both_plane.data = both;
  const Planes estimated = box_mean(both_plane, radius);
  Selection out{Planes(w, h, 3), std::vector<std::uint8_t>(n), box_mean(pixel_errors(halves, cand, half_variance_bias), radius, &both)};

  // Weights relative to the unfiltered colour's, so they lie in [0, 1 / kErrorFloor^2] and
  // the box sums stay exact (1 / error^2 spans too many decades for a running sum). The
  // filters' share is divided among them (kFilterShare), so that more filters do not crowd out
  // the unfiltered colour by their number.
  const float share = kFilterShare / (count - 1);
  Planes weight(w, h, count);
  each_pixel(n, [&](std::size_t i) {
    const float unfiltered = std::max(out.error.at(kUnfiltered, i), kTinyError);
    for (int c = 0; c < count; ++c) {
      const float ratio = unfiltered / std::max(out.error.at(c, i), kErrorFloor * unfiltered);
      weight.at(c, i) = std::isfinite(ratio) ? ratio * ratio * (c == kUnfiltered ? 1.0f : share) : 0.0f;  // NaN, inf: none
    }
  });
  const Planes blended = box_mean(weight, blend_radius);
  each_pixel(n, [&](std::size_t i) {
    float wt[kMaxCandidates];
    for (int c = 0; c < count; ++c) wt[c] = blended.at(c, i);
    if (!offered(noisy, estimated, both, out.error, i)) wt[kUnfiltered] = 0.0f;
    float total = 0.0f;
    for (int c = 0; c < count; ++c) total += wt[c];
    if (!(total > 0.0f)) {  // no usable estimate: the filters alike
      for (int c = 0; c < count; ++c) wt[c] = c == kUnfiltered ? 0.0f : 1.0f;
      total = static_cast<float>(count - 1);
    }
    out.chosen[i] = static_cast<std::uint8_t>(std::max_element(wt, wt + count) - wt);
    for (int k = 0; k < 3; ++k) {
      float v = 0.0f;
      for (int c = 0; c < count; ++c) v += wt[c] * cand.colour[c]->at(k, i);
      out.rgb.at(k, i) = v / total;
    }
  });
  return out;
}

}  // namespace tessera::denoiser
