// Pearson's chi-square goodness-of-fit test of a direction sampler against its pdf, as
// Mitsuba's test suite does it: histogram the sampled directions over a grid in
// (cos theta, phi) (bins of equal solid angle), integrate the pdf over each bin, pool the
// bins expecting fewer than 5 samples, and compute the p-value of the statistic.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace tessera::test {

// Regularised upper incomplete gamma function Q(a, x) (Numerical Recipes 6.2).
inline double gamma_q(double a, double x) {
  if (x <= 0.0) return 1.0;
  const double gln = std::lgamma(a);
  if (x < a + 1.0) {  // series for P, then Q = 1 - P
    double ap = a, sum = 1.0 / a, del = sum;
    for (int n = 0; n < 10000 && std::fabs(del) > std::fabs(sum) * 1e-15; ++n) sum += del *= x / ++ap;
    return 1.0 - sum * std::exp(-x + a * std::log(x) - gln);
  }
  double b = x + 1.0 - a, c = 1.0 / 1e-300, d = 1.0 / b, h = d;  // continued fraction for Q
  for (int i = 1; i < 10000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::fabs(d) < 1e-300) d = 1e-300;
    c = b + an / c;
    if (std::fabs(c) < 1e-300) c = 1e-300;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::fabs(del - 1.0) < 1e-15) break;
  }
  return std::exp(-x + a * std::log(x) - gln) * h;
}

// Integral of f(direction) over the patch [c0,c1] x [p0,p1] of (cos theta, phi): midpoint
// rules of 4x4 and 8x8 points, split into quarters until they agree. Narrow lobes need it.
inline double integrate_patch(const std::function<float(const glm::vec3&)>& f, double c0, double c1, double p0,
                              double p1, int depth = 0) {
  auto midpoint = [&](int n) {
    double sum = 0.0;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b) {
        const double c = c0 + (a + 0.5) / n * (c1 - c0), phi = p0 + (b + 0.5) / n * (p1 - p0);
        const double s = std::sqrt(std::max(0.0, 1.0 - c * c));
        sum += f(glm::vec3(s * std::cos(phi), s * std::sin(phi), c));
      }
    return sum * (c1 - c0) * (p1 - p0) / (n * n);
  };
  const double coarse = midpoint(4), fine = midpoint(8);
  if (depth >= 6 || std::fabs(fine - coarse) <= 1e-4 * std::fabs(fine) + 1e-9) return fine;
  const double cm = 0.5 * (c0 + c1), pm = 0.5 * (p0 + p1);
  return integrate_patch(f, c0, cm, p0, pm, depth + 1) + integrate_patch(f, cm, c1, p0, pm, depth + 1) +
         integrate_patch(f, c0, cm, pm, p1, depth + 1) + integrate_patch(f, cm, c1, pm, p1, depth + 1);
}

struct ChiSquareResult {
  double statistic = 0.0, p_value = 1.0;
  int dof = 0;
  double sampled_fraction = 0.0;  // successful samples / attempts
  double pdf_integral = 0.0;  // integral of the pdf over the sphere
};

// `sample` returns a unit direction (or nothing when the sampler fails), `pdf` its density.
inline ChiSquareResult chi_square_test(const std::function<std::optional<glm::vec3>(int)>& sample,
                                       const std::function<float(const glm::vec3&)>& pdf, int samples,
                                       int theta_bins = 24, int phi_bins = 48) {
  const double pi = 3.14159265358979323846;
  std::vector<double> observed(theta_bins * phi_bins, 0.0), expected(theta_bins * phi_bins, 0.0);
  int successes = 0;
  for (int i = 0; i < samples; ++i) {
    const std::optional<glm::vec3> w = sample(i);
    if (!w) continue;
    ++successes;
    const double c = std::clamp(static_cast<double>(w->z), -1.0, 1.0);
    double phi = std::atan2(w->y, w->x);
    if (phi < 0) phi += 2 * pi;
    const int ti = std::min(theta_bins - 1, static_cast<int>((c + 1.0) / 2.0 * theta_bins));
    const int pi_ = std::min(phi_bins - 1, static_cast<int>(phi / (2 * pi) * phi_bins));
    observed[ti * phi_bins + pi_] += 1;
  }
  ChiSquareResult r;
  r.sampled_fraction = static_cast<double>(successes) / samples;
  const double dc = 2.0 / theta_bins, dphi = 2 * pi / phi_bins;
  for (int ti = 0; ti < theta_bins; ++ti)
    for (int pj = 0; pj < phi_bins; ++pj) {
      const double integral = integrate_patch(pdf, -1.0 + ti * dc, -1.0 + (ti + 1) * dc, pj * dphi, (pj + 1) * dphi);
      r.pdf_integral += integral;
      expected[ti * phi_bins + pj] = integral * samples;
    }
  // Pool the sparse bins into one, then sum (O - E)^2 / E.
  double pooled_o = 0.0, pooled_e = 0.0;
  for (std::size_t i = 0; i < observed.size(); ++i) {
    if (expected[i] < 5.0) {
      pooled_o += observed[i];
      pooled_e += expected[i];
      continue;
    }
    r.statistic += (observed[i] - expected[i]) * (observed[i] - expected[i]) / expected[i];
    ++r.dof;
  }
  if (pooled_e >= 5.0) {
    r.statistic += (pooled_o - pooled_e) * (pooled_o - pooled_e) / pooled_e;
    ++r.dof;
  } else if (pooled_o > 20.0) {
    r.statistic = 1e30;  // samples where the pdf says there can be almost none
  }
  r.dof -= 1;
  r.p_value = r.dof > 0 ? gamma_q(0.5 * r.dof, 0.5 * r.statistic) : 0.0;
  return r;
}

}  // namespace tessera::test
