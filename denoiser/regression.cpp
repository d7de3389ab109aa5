#include "denoiser/regression.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>
#include <tbb/parallel_for.h>

namespace tessera::denoiser {

namespace {

constexpr int P = 10;  // regressors: 1, x, y, albedo (3), normal (3), depth
constexpr int V = 4;  // variants: v = 2 half + candidate
constexpr int Z = P + 6;  // a design row followed by the colour of both halves
constexpr float kEpsilon = 1e-10f;  // NL-means: noise-free equal colours are at distance 0
// Weight of a pixel's own noisy value in its average: negligible beside the windows' fits
// (each covers it with weight up to 1), it only decides pixels that no window accepts, such
// as noise-free detail whose neighbours all differ.
constexpr float kSelfWeight = 1e-3f;
// A pixel whose windows' weights sum to less than this (with no data of its own) keeps its
// filled colour: below it, weight x fit products are denormal and their ratio meaningless.
constexpr float kMinWeightSum = 1e-30f;
// The smallest ratio of the Cholesky pivots L_ii^2 of the Jacobi-scaled (unit diagonal)
// normal matrix, min / max (a cheap stand-in for its reciprocal condition number: no extra
// solves), below which a window's first-order fit is not trusted and its weighted mean is
// used instead; so is a matrix that is not positive definite (Cholesky fails). The default
// ridge alone keeps the smallest pivot above ~ridge = 1e-3 (the largest is at most P); this
// guards ridge = 0 and degenerate windows (collinear or constant features). Cholesky (LLT)
// rather than the pivoting LDLT: the regression 10% faster, the results alike.
constexpr double kMinPivotRatio = 1e-7;

using RowMatrix = Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic>;

struct Scratch {
  RowMatrix design, weighted, moments, fits;  // n x Z, n x V P, V P x Z, n x 3 V
  Eigen::Matrix<float, Eigen::Dynamic, V> data_w, recon_w;  // n x V
  Eigen::Matrix<float, P, 3 * V> beta;
  float lo[V][3], hi[V][3];  // per variant and channel: the range of the colours the fit saw
  std::vector<std::size_t> index;  // pixel of each window row
  explicit Scratch(int n)
      : design(n, Z), weighted(n, V * P), moments(V * P, Z), fits(n, 3 * V), data_w(n, V), recon_w(n, V), index(n) {}
};

struct Accumulator {
  Planes sum[V];  // 3 channels: sum of weight x fit
  Planes weight[V];  // 1 channel
};

struct Context {
  const Halves& halves;
  const Planes& features;
  const DenoiseParams& p;
  int radius;
  float k2[2];
  Accumulator& acc;
};

// The design rows: features relative to the centre's, so the intercept is the centre's fit.
// Depth is scaled by 2% of the centre's depth: a relative change, comparable to the others.
int fill_design(const Context& ctx, int cx, int cy, Scratch& s) {
  const Planes& f = ctx.features;
  const int w = f.width, h = f.height, r = ctx.radius;
  const bool has_depth = f.channels > 6;
  const std::size_t c = static_cast<std::size_t>(cy) * w + cx;
  const float zc = has_depth ? f.at(6, c) : 0.0f, zscale = 1.0f / (0.02f * std::abs(zc) + 1e-6f);
  int n = 0;
  for (int y = std::max(0, cy - r); y <= std::min(h - 1, cy + r); ++y)
    for (int x = std::max(0, cx - r); x <= std::min(w - 1, cx + r); ++x, ++n) {
      const std::size_t q = static_cast<std::size_t>(y) * w + x;
      s.index[n] = q;
      auto row = s.design.row(n);
      row(0) = 1.0f;
      row(1) = static_cast<float>(x - cx) / r;
      row(2) = static_cast<float>(y - cy) / r;
      for (int k = 0; k < 6; ++k) row(3 + k) = f.at(k, q) - f.at(k, c);
      row(9) = has_depth ? (f.at(6, q) - zc) * zscale : 0.0f;
      for (int half = 0; half < 2; ++half)
        for (int k = 0; k < 3; ++k) row(P + 3 * half + k) = ctx.halves.h[half].color.at(k, q);
    }
  return n;
}

// NL-means weights (Rousselle et al. 2012) of every window pixel, from the guide of the other
// half: d = mean over channels of ((u_c - u_q)^2 - (V_c + min(V_c, V_q))) / (k^2 (V_c + V_q + eps)).
// Row by row along contiguous memory, branch-free: the compiler vectorises it.
void fill_weights(const Context& ctx, int cx, int cy, Scratch& s) {
  const Planes& f = ctx.features;
  const int w = f.width, h = f.height, r = ctx.radius;
  const std::size_t plane = f.pixels(), c = static_cast<std::size_t>(cy) * w + cx;
  const int x0 = std::max(0, cx - r), x1 = std::min(w - 1, cx + r), len = x1 - x0 + 1;
  const float inv_k2[2] = {1.0f / (3.0f * ctx.k2[0]), 1.0f / (3.0f * ctx.k2[1])};  // with the channel mean
  for (int half = 0; half < 2; ++half) {
    const Half& guide = ctx.halves.h[1 - half];
    const float* g = guide.guide.data.data();
    const float* v = guide.guide_variance.data.data();
    float gc[3], vc[3];
    for (int k = 0; k < 3; ++k) gc[k] = g[k * plane + c], vc[k] = v[k * plane + c];
    float* recon[2] = {s.recon_w.col(2 * half).data(), s.recon_w.col(2 * half + 1).data()};
    float* data[2] = {s.data_w.col(2 * half).data(), s.data_w.col(2 * half + 1).data()};
    int i = 0;
    for (int y = std::max(0, cy - r); y <= std::min(h - 1, cy + r); ++y, i += len) {
      const std::size_t row = static_cast<std::size_t>(y) * w + x0;
      const float* valid = ctx.halves.h[half].valid.data() + row;
      for (int x = 0; x < len; ++x) {
        float d = 0.0f;
        for (int k = 0; k < 3; ++k) {
          const float diff = gc[k] - g[k * plane + row + x], vq = v[k * plane + row + x];
          d += (diff * diff - (vc[k] + std::min(vc[k], vq))) / (vc[k] + vq + kEpsilon);
        }
        for (int cand = 0; cand < 2; ++cand) {
          const float wt = exp_neg(-std::max(0.0f, d * inv_k2[cand]));
          recon[cand][i + x] = wt;
          data[cand][i + x] = wt * valid[x];
        }
      }
    }
  }
}

// Weighted least squares per variant, ridge-regularised on the feature coefficients in
// proportion to each one's own moment (scale-free) plus a floor for constant features. The
// normal matrix is solved Jacobi-scaled (unit diagonal), whose conditioning is then checked:
// a poorly conditioned or non-finite solve falls back to the zero-order fit (the weighted
// mean). Either way accumulate() bounds the fit by the range of the colours it was fitted to,
// so a window can never extrapolate beyond its own data (an isolated bright pixel with
// leverage on the features used to throw its neighbours to +-100x the level).
void solve(const Context& ctx, int n, Scratch& s) {
  for (int v = 0; v < V; ++v)
    s.weighted.block(0, v * P, n, P) = s.design.topLeftCorner(n, P).array().colwise() * s.data_w.col(v).head(n).array();
  s.moments.noalias() = s.weighted.topRows(n).transpose() * s.design.topRows(n);
  for (int v = 0; v < V; ++v) {
    const int half = v / 2;
    Eigen::Matrix<double, P, P> G = s.moments.block<P, P>(v * P, 0).cast<double>();
    const Eigen::Matrix<double, P, 3> b = s.moments.block<P, 3>(v * P, P + 3 * half).cast<double>();
    const double total = G(0, 0);
    if (!(total > 0.0)) {  // this half has no data in the window: it reconstructs nothing
      s.beta.middleCols<3>(3 * v).setZero();
      s.recon_w.col(v).head(n).setZero();
      continue;
    }
    for (int k = 0; k < 3; ++k) s.lo[v][k] = INFINITY, s.hi[v][k] = -INFINITY;
    for (int i = 0; i < n; ++i) {
      if (!(s.data_w(i, v) > 0.0f)) continue;
      for (int k = 0; k < 3; ++k) {
        const float c = s.design(i, P + 3 * half + k);
        s.lo[v][k] = std::min(s.lo[v][k], c), s.hi[v][k] = std::max(s.hi[v][k], c);
      }
    }
    for (int j = 1; j < P; ++j) G(j, j) += ctx.p.ridge * G(j, j) + 1e-6 * total;
    const Eigen::Matrix<double, P, 1> d = G.diagonal().cwiseSqrt().cwiseInverse();
    const Eigen::LLT<Eigen::Matrix<double, P, P>> llt(d.asDiagonal() * G * d.asDiagonal());
    const Eigen::Matrix<double, P, 3> beta = d.asDiagonal() * llt.solve(d.asDiagonal() * b);
    const Eigen::Matrix<double, P, 1> pivots = llt.matrixLLT().diagonal().cwiseAbs2();  // Cholesky's pivots
    if (llt.info() == Eigen::Success && pivots.minCoeff() >= kMinPivotRatio * pivots.maxCoeff() && beta.allFinite()) {
      s.beta.middleCols<3>(3 * v) = beta.cast<float>();
    } else {
      s.beta.middleCols<3>(3 * v).setZero();
      s.beta.block<1, 3>(0, 3 * v) = (b.row(0) / total).cast<float>();
    }
  }
}

void accumulate(const Context& ctx, int n, Scratch& s) {
  s.fits.topRows(n).noalias() = s.design.topLeftCorner(n, P) * s.beta;
  for (int v = 0; v < V; ++v) {
    Planes& sum = ctx.acc.sum[v];
    float* wsum = ctx.acc.weight[v].plane(0);
    if (!(s.recon_w.col(v).head(n).maxCoeff() > 0.0f)) continue;  // no data: no fit, no range
    for (int i = 0; i < n; ++i) {
      const float wt = s.recon_w(i, v);
      const std::size_t q = s.index[i];
      wsum[q] += wt;
      for (int k = 0; k < 3; ++k) sum.at(k, q) += wt * std::min(s.hi[v][k], std::max(s.lo[v][k], s.fits(i, 3 * v + k)));  // NaN: lo  // NaN: lo
    }
  }
}

void process_centre(const Context& ctx, int cx, int cy, Scratch& s) {
  const int n = fill_design(ctx, cx, cy, s);
  fill_weights(ctx, cx, cy, s);
  solve(ctx, n, s);
  accumulate(ctx, n, s);
}

// Centres every `stride` pixels from 0, plus the last pixel, so every pixel is within
// stride / 2 <= radius of one.
std::vector<int> centres(int size, int stride) {
  std::vector<int> out;
  for (int i = 0; i < size; i += stride) out.push_back(i);
  if (out.back() != size - 1) out.push_back(size - 1);
  return out;
}

// The fewest phases such that centre rows of one phase have disjoint windows.
int phase_count(const std::vector<int>& rows, int radius) {
  for (int m = 1;; ++m) {
    bool ok = true;
    for (std::size_t j = 0; j + m < rows.size() && ok; ++j) ok = rows[j + m] - rows[j] > 2 * radius;
    if (ok) return m;
  }
}

Planes normalise(const Accumulator& acc, int v, const Half& half) {
  Planes out = half.color;
  const std::size_t n = out.pixels();
  const float* wsum = acc.weight[v].plane(0);
  for (std::size_t i = 0; i < n; ++i) {
    const float self = kSelfWeight * half.valid[i];
    const float total = wsum[i] + self;
    // No window reaches it (or only with negligible weight) and it has no data: keep the fill.
    if (!(total >= kMinWeightSum)) continue;
    for (int k = 0; k < 3; ++k) out.at(k, i) = (acc.sum[v].at(k, i) + self * half.color.at(k, i)) / total;
  }
  return out;
}

}  // namespace

Filtered regress(const Halves& halves, const Planes& features, int radius, int stride, const DenoiseParams& p) {
  const int w = features.width, h = features.height;
  Accumulator acc;
  for (int v = 0; v < V; ++v) acc.sum[v] = Planes(w, h, 3), acc.weight[v] = Planes(w, h, 1);
  const Context ctx{halves, features, p, radius, {p.bandwidths[0] * p.bandwidths[0], p.bandwidths[1] * p.bandwidths[1]}, acc};
  const std::vector<int> xs = centres(w, stride), ys = centres(h, stride);
  const int phases = phase_count(ys, radius);
  const int window = (2 * radius + 1) * (2 * radius + 1);
  // Phase by phase, rows of one phase in parallel: each pixel receives its windows' fits in
  // the same order (phase, then row, then column) whatever the thread count.
  for (int phase = 0; phase < phases; ++phase) {
    const int rows = (static_cast<int>(ys.size()) - phase + phases - 1) / phases;
    tbb::parallel_for(0, rows, [&](int j) {
      Scratch s(window);
      const int cy = ys[phase + j * phases];
      for (int cx : xs) process_centre(ctx, cx, cy, s);
    });
  }
  Filtered out;
  for (int v = 0; v < V; ++v) out.filtered[v / 2][v % 2] = normalise(acc, v, halves.h[v / 2]);
  return out;
}

}  // namespace tessera::denoiser
