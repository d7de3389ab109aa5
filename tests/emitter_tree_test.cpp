// The light tree over emissive triangles (AreaLights::tree, renderer/lights/light_tree.h): each
// triangle's probability at a shading point is the product of the branch probabilities the
// bounds' importance gives (checked against the same product worked out here from the
// documented construction: median splits, four children a node), the probabilities sum to 1, AreaLights::pdf is that probability
// times the point's density that sampling gives, sampling chooses each triangle as often as
// its probability (chi-square), and a floor under a grid of small emitters renders the closed
// form sum of their form factors (Lambert's polygon formula) with the tree and without.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "renderer/integrator/emitter_pick.h"
#include "renderer/lights/area_lights.h"
#include "renderer/render/render.h"
#include "tests/pixel_stats.h"
#include "tests/scene_builders.h"

namespace tessera {
namespace {

// Bounds of a small flat light at `c` facing `axis` (one-sided) with `power`.
LightBounds small_light(const vec3& c, const vec3& axis, float power, bool two_sided = false) {
  LightBounds b;
  b.lo = c - vec3(0.05f, 0.05f, 0.0f);
  b.hi = c + vec3(0.05f, 0.05f, 0.0f);
  b.axis = glm::normalize(axis);
  b.cos_spread = two_sided ? -1.0f : 1.0f;
  b.cos_emit = std::cos(0.5f * kPi);
  b.power = power;
  return b;
}

// The probability of each light (sorted along x, the longest axis of their centres) by the
// tree's documented rule, worked out independently: the binary tree halves at the median down
// to leaves of up to `leaf` lights; a node of the walk has as children its binary node's
// grandchildren (a leaf child stays itself), each chosen in proportion to its merged bounds'
// importance; in a leaf of several, a light by its share of the leaf's power.
struct ExpectedTree {
  const std::vector<LightBounds>& sorted;
  std::size_t leaf;
  vec3 p, n;
  std::vector<double> out;

  LightBounds merged(std::size_t a, std::size_t b) const {
    LightBounds m = sorted[a];
    for (std::size_t i = a + 1; i < b; ++i) m = LightBounds::merge(m, sorted[i]);
    return m;
  }
  bool is_leaf(std::size_t a, std::size_t b) const { return b - a <= leaf; }
  void leaf_shares(std::size_t a, std::size_t b, double pmf) {
    const double total = merged(a, b).power;
    for (std::size_t i = a; i < b; ++i) out[i] = b - a == 1 ? pmf : pmf * sorted[i].power / total;
  }
  // [a, b): a binary node that is not a leaf, reached with probability pmf.
  void node(std::size_t a, std::size_t b, double pmf) {
    std::vector<std::pair<std::size_t, std::size_t>> slots;
    const std::size_t mid = a + (b - a) / 2;
    for (auto [c0, c1] : {std::pair{a, mid}, std::pair{mid, b}}) {
      if (is_leaf(c0, c1)) {
        slots.emplace_back(c0, c1);
      } else {
        const std::size_t m = c0 + (c1 - c0) / 2;
        slots.emplace_back(c0, m);
        slots.emplace_back(m, c1);
      }
    }
    // The tree merges bottom-up, here left to right: the same boxes and powers, the cones the
    // same but for rounding, so the comparison below has a tolerance.
    std::vector<double> imp;
    double total = 0.0;
    for (auto [c0, c1] : slots) total += imp.emplace_back(merged(c0, c1).importance(p, n));
    for (std::size_t k = 0; k < slots.size(); ++k) {
      const double q = total > 0.0 ? pmf * imp[k] / total : 0.0;
      if (is_leaf(slots[k].first, slots[k].second)) leaf_shares(slots[k].first, slots[k].second, q);
      else node(slots[k].first, slots[k].second, q);
    }
  }
  std::vector<double> run() {
    out.assign(sorted.size(), 0.0);
    // A root that is a leaf: the walk's one level, one child, chosen where it can reach p.
    if (is_leaf(0, sorted.size())) leaf_shares(0, sorted.size(), merged(0, sorted.size()).importance(p, n) > 0.0f ? 1.0 : 0.0);
    else node(0, sorted.size(), 1.0);
    return out;
  }
};

TEST(EmitterTree, EveryProbabilityIsTheProductOfItsBranchesOnSmallTrees) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (std::size_t leaf : {1u, 2u, 4u})
    for (std::size_t count : {1u, 2u, 3u, 5u, 8u, 13u, 40u}) {
      // Along x, 1 m apart (the longest axis of their centres), facing down or sideways.
      std::vector<LightBounds> lights;
      for (std::size_t i = 0; i < count; ++i)
        lights.push_back(small_light({float(i), 2.0f + 0.1f * unit(rng), 0.3f * unit(rng)},
                                     i % 3 == 2 ? vec3(1, -0.2f, 0) : vec3(0.1f * unit(rng), -1, 0), 0.5f + unit(rng),
                                     i % 4 == 3));
      const LightTree tree(lights, int(leaf));
      ASSERT_EQ(tree.size(), count);
      for (const vec3& p : {vec3(0, 0, 0), vec3(3.5f, 0.5f, 1), vec3(-2, 4, 0), vec3(10, 2, -1)}) {
        const vec3 n(0, 1, 0);
        const std::vector<double> expected = ExpectedTree{lights, leaf, p, n, {}}.run();
        double sum = 0.0;
        for (std::uint32_t i = 0; i < count; ++i) {
          const float pmf = tree.pmf(p, n, i);
          sum += pmf;
          EXPECT_NEAR(pmf, expected[i], 1e-5 + 1e-4 * expected[i]) << count << " lights, leaf " << leaf << ", light " << i;
        }
        EXPECT_LE(sum, 1.0 + 1e-5);
      }
    }
}

// A scene of emitters: `rows` x `cols` small squares of side 2 half_side at height h over a
// diffuse floor, their radiance varying, facing down (every third one double-sided, every
// fifth one tilted) unless `flat`.
struct EmitterGrid {
  int rows = 8, cols = 8;
  float spacing = 0.3f, half_side = 0.05f, height = 0.5f, albedo = 0.8f;
  bool flat = false;
  float radiance(int i) const { return 1.0f + float(i % 7); }
  vec3 centre(int row, int col) const {
    return {(col - 0.5f * (cols - 1)) * spacing, height + (flat ? 0.0f : 0.04f * float(row % 3)),
            (row - 0.5f * (rows - 1)) * spacing};
  }
  SceneDescription scene() const {
    SceneDescription d;
    test::add_mesh(d, test::make_quad({0, 0, 0}, {20, 0, 0}, {0, 0, -20}, test::add_material(d, test::diffuse(vec3(albedo)))));
    for (int row = 0; row < rows; ++row)
      for (int col = 0; col < cols; ++col) {
        const int i = row * cols + col;
        Material m = test::emitter(vec3(radiance(i)));
        m.double_sided = !flat && i % 3 == 1;
        const vec3 tilt = !flat && i % 5 == 4 ? vec3(0, half_side * 0.7f, 0) : vec3(0.0f);
        // make_quad's front is cross(u, v): (+x) x (+z) = -y, down.
        test::add_mesh(d, test::make_quad(centre(row, col), vec3(half_side, 0, 0) + tilt, {0, 0, half_side},
                                          test::add_material(d, m)));
      }
    return d;
  }
};

const vec3 kPoints[] = {{0, 0, 0}, {0.7f, 0, -0.4f}, {2.5f, 0, 1.5f}, {0.2f, 0.45f, 0.1f}, {-0.6f, 0.8f, 0.3f}};

TEST(EmitterTree, TheTrianglesProbabilitiesSumToOneWhereEveryOneCanReach) {
  EmitterGrid grid;
  grid.flat = true;  // all facing down, and every point below them
  const RenderScene rs(grid.scene(), EnvironmentParams{});
  const AreaLights& lights = *rs.area_lights;
  ASSERT_EQ(lights.tree().size(), std::size_t(2 * grid.rows * grid.cols));
  for (const vec3& p : {vec3(0, 0, 0), vec3(0.7f, 0, -0.4f), vec3(2.5f, 0, 1.5f), vec3(-1, 0.3f, 0)})
    for (const vec3& n : {vec3(0, 1, 0), glm::normalize(vec3(1, 1, 0)), vec3(0.0f)}) {
      double sum = 0.0;
      for (std::uint32_t i = 0; i < lights.size(); ++i) {
        const float pmf = lights.tree().pmf(p, n, i);
        EXPECT_GT(pmf, 0.0f);
        sum += pmf;
      }
      EXPECT_NEAR(sum, 1.0, 1e-5);
    }
}

// Sampling a point through the tree and tracing towards it finds the emitter; pdf() there is
// the sample's density: the tree's probability (bit for bit the walk's) x distance^2 / (area cos).
TEST(EmitterTree, PdfIsTheTreesProbabilityTimesThePointsDensity) {
  const EmitterGrid grid;
  const RenderScene rs(grid.scene(), EnvironmentParams{});
  const AreaLights& lights = *rs.area_lights;
  std::mt19937 rng(17);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  int checked = 0;
  for (const vec3& p : kPoints) {
    const AreaLights::ShadingPlace place{p, vec3(0, 1, 0)};
    for (int k = 0; k < 200; ++k) {
      const float pick = k % 2 ? 1.0f : 0.6f;
      const AreaLights::Choice c = lights.choose(unit(rng) * pick, pick, &place);
      if (c.index >= lights.size()) continue;
      EXPECT_EQ(c.pmf, lights.tree().pmf(p, place.n, std::uint32_t(c.index)));
      AreaLightSample s;
      if (!lights.sample(p, 0.0f, c, {unit(rng), unit(rng)}, s)) continue;
      Ray ray{p, s.wi, 0.0f, std::numeric_limits<float>::infinity(), 0.0f};
      HitRecord hit;
      if (!rs.geometry->intersect(ray, hit)) continue;
      const SurfaceHit surface = rs.geometry->surface(ray, hit);
      if (glm::length(surface.p - s.p) > 1e-4f) continue;  // another emitter in front of it
      const float pdf = lights.pdf(hit, surface, s.wi, pick, &place);
      EXPECT_NEAR(pdf, s.pdf, 1e-3f * s.pdf);
      const SceneGeometry::Corners corners = rs.geometry->corners(hit);
      const double area = 0.5 * glm::length(glm::cross(glm::dvec3(corners.p1 - corners.p0), glm::dvec3(corners.p2 - corners.p0)));
      const double expected = pick * c.pmf * glm::dot(glm::dvec3(s.p - p), glm::dvec3(s.p - p)) /
                              (std::fabs(glm::dot(glm::dvec3(surface.ng), glm::dvec3(s.wi))) * area);
      EXPECT_NEAR(pdf, expected, 1e-3 * expected);
      ++checked;
    }
  }
  EXPECT_GT(checked, 250);  // 313: points above the one-sided squares see few
}

TEST(EmitterTree, SamplingChoosesEachTriangleAsOftenAsItsProbability) {
  const EmitterGrid grid;
  const RenderScene rs(grid.scene(), EnvironmentParams{});
  const AreaLights& lights = *rs.area_lights;
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> unit(0.0f, 1.0f);
  for (const vec3& p : kPoints) {
    const AreaLights::ShadingPlace place{p, glm::normalize(vec3(0.2f, 1.0f, -0.1f))};
    const int samples = 200000;
    std::vector<int> counts(lights.size(), 0);
    int none = 0;
    for (int k = 0; k < samples; ++k) {
      const AreaLights::Choice c = lights.choose(unit(rng), 1.0f, &place);
      if (c.index < lights.size()) ++counts[c.index];
      else ++none;
    }
    // Pearson's chi-square over the triangles, the dead ends (no triangle) as one more cell.
    double chi2 = 0.0, none_expected = 1.0;
    int cells = 0;
    for (std::uint32_t i = 0; i < lights.size(); ++i) {
      const double expected = samples * double(lights.tree().pmf(p, place.n, i));
      none_expected -= lights.tree().pmf(p, place.n, i);
      if (expected == 0.0) {
        EXPECT_EQ(counts[i], 0) << "triangle " << i << " has no probability";
        continue;
      }
      chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
      ++cells;
    }
    none_expected *= samples;
    if (none_expected > 1.0) chi2 += (none - none_expected) * (none - none_expected) / none_expected, ++cells;
    else EXPECT_LE(none, 2);
    // The 1 - 1e-6 quantile of chi-square with df degrees of freedom is below df + 7 sqrt(2 df) here.
    const double df = cells - 1;
    EXPECT_LT(chi2, df + 7.0 * std::sqrt(2.0 * df)) << "at " << p.x << "," << p.y << "," << p.z;
    EXPECT_GT(chi2, 0.0);
  }
}

// A white Lambertian floor (albedo a) under the grid of small squares facing down: the radiance
// at x is a * sum_i Le_i F_i(x), F_i the form factor from x (normal +y) to square i by Lambert's
// polygon formula.
double form_factor(const glm::dvec3& x, const glm::dvec3 corners[4]) {
  double sum = 0.0;
  for (int i = 0; i < 4; ++i) {
    const glm::dvec3 r0 = glm::normalize(corners[i] - x), r1 = glm::normalize(corners[(i + 1) % 4] - x);
    const double angle = std::acos(std::clamp(glm::dot(r0, r1), -1.0, 1.0));
    sum += angle * glm::normalize(glm::cross(r0, r1)).y;
  }
  return std::fabs(sum) / (2.0 * M_PI);
}

TEST(EmitterTree, AFloorUnderAGridOfSmallEmittersMatchesTheFormFactorSum) {
  EmitterGrid grid;
  grid.rows = grid.cols = 12;
  grid.flat = true;
  const RenderScene scene(grid.scene(), EnvironmentParams{});
  for (vec3 target : {vec3(0.0f), vec3(0.5f, 0.0f, -0.35f), vec3(2.5f, 0.0f, 1.0f)}) {
    double expected = 0.0;
    for (int row = 0; row < grid.rows; ++row)
      for (int col = 0; col < grid.cols; ++col) {
        const glm::dvec3 c(grid.centre(row, col));
        const double a = grid.half_side;
        const glm::dvec3 corners[4] = {c + glm::dvec3(-a, 0, -a), c + glm::dvec3(a, 0, -a), c + glm::dvec3(a, 0, a),
                                       c + glm::dvec3(-a, 0, a)};
        expected += grid.radiance(row * grid.cols + col) * form_factor(glm::dvec3(target), corners);
      }
    expected *= grid.albedo;
    for (LightTreeUse use : {LightTreeUse::On, LightTreeUse::Off}) {
      RenderSettings st;
      st.width = st.height = 4;
      st.spp = 1024;
      st.max_bounces = 1;
      st.light_tree = use;
      const Camera cam = test::look_at(target + vec3(0.0f, 0.05f, 0.015f), target, 0.01f);
      const RenderResult r = render_frame(scene, make_camera(cam, st.width, st.height, {}), st);
      EXPECT_EQ(r.stats.emitter_tree_triangles, use == LightTreeUse::On ? std::size_t(2 * 144) : 0u);
      EXPECT_NEAR(test::stats_of(r.image).mean, expected, 1e-2 * expected)
          << (use == LightTreeUse::On ? "tree" : "by power") << " at " << target.x << "," << target.z;
    }
  }
}

// Auto's pilot (integrator/emitter_pick.h): one emitter (two triangles, one leaf: the tree's
// choice is the power choice) gains nothing; a floor under a wide grid of small emitters, seen
// from above, gains many times (each point is lit mostly by the few squares near it).
TEST(EmitterTree, AutoChoosesTheTreeWhereThePilotsVarianceFallsEnough) {
  SceneDescription d;
  test::add_mesh(d, test::make_quad({0, 0, 0}, {5, 0, 0}, {0, 0, -5}, test::add_material(d, test::diffuse(vec3(0.5f)))));
  test::add_mesh(d, test::make_quad({0, 1, 0}, {0.2f, 0, 0}, {0, 0, 0.2f}, test::add_material(d, test::emitter(vec3(5.0f)))));
  const RenderScene one(std::move(d), EnvironmentParams{});
  const RenderCamera above_one = one.camera(test::look_at({0, 0.8f, 2.5f}, {0, 0, 0}, 60.0f), 64, 36, {});
  EXPECT_NEAR(emitter_tree_gain(one, above_one), 1.0, 1e-6);
  EXPECT_FALSE(emitter_tree_used(one, above_one, LightTreeUse::Auto));
  EXPECT_FALSE(emitter_tree_used(one, above_one, LightTreeUse::Off));
  EXPECT_TRUE(emitter_tree_used(one, above_one, LightTreeUse::On));

  EmitterGrid grid;
  grid.rows = grid.cols = 32;
  grid.flat = true;
  const RenderScene many(grid.scene(), EnvironmentParams{});
  const RenderCamera below_many = many.camera(test::look_at({0, 0.3f, 5.0f}, {0, 0, 0}, 60.0f), 64, 36, {});
  EXPECT_GT(emitter_tree_gain(many, below_many), 4.0);
  EXPECT_TRUE(emitter_tree_used(many, below_many, LightTreeUse::Auto));
}

}  // namespace
}  // namespace tessera
