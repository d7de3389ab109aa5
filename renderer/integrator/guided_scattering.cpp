#include "renderer/integrator/guided_scattering.h"

#include <algorithm>

namespace tessera {

float guide_share(const ShadingPoint& sp, const GltfBsdf& bsdf) {
  constexpr float kHalf = 0.5f;
  if (sp.thin_walled && sp.transmission > 0.0f) return 0.0f;
  const float broad = bsdf.lobe_probability(GltfBsdf::kDiffuse) + bsdf.lobe_probability(GltfBsdf::kDiffuseTransmission);
  return kHalf * broad;
}

GuideAt guide_at(const PathGuide* guide, const vec3& p, const ShadingPoint& sp, const GltfBsdf& bsdf) {
  if (!guide) return {};
  const float share = guide_share(sp, bsdf);
  return share > 0.0f ? GuideAt{guide, guide->region(p), share} : GuideAt{};
}

bool sample_guided(const GltfBsdf& bsdf, const Frame& frame, const vec3& wo_local, const GuideAt& g, const vec3& u,
                   BsdfSample& bs) {
  if (!g.samples()) return bsdf.sample(wo_local, u.z, {u.x, u.y}, bs);
  if (u.z >= g.share) {
    if (!bsdf.sample(wo_local, (u.z - g.share) / (1.0f - g.share), {u.x, u.y}, bs)) return false;
    bs.pdf = g.pdf(frame.to_world(bs.wi), bs.pdf);  // the share excludes straight passes
    return bs.pdf > 0.0f;
  }
  float guide_pdf;
  const vec3 wi = g.guide->sample(g.region, {u.x, u.y}, guide_pdf);
  const vec3 wi_local = frame.to_local(wi);
  float bsdf_pdf;
  bs.f = bsdf.eval(wo_local, wi_local, bsdf_pdf);
  if (bs.f == vec3(0.0f)) return false;
  bs.set_wi(wi_local);
  bs.pdf = g.share * guide_pdf + (1.0f - g.share) * bsdf_pdf;
  bs.transmitted = wi_local.z < 0.0f;
  bs.passthrough = false;
  bs.lobe = GltfBsdf::kGuided;
  return bs.pdf > 0.0f;
}

float guide_brightness(const RenderScene& scene) {
  float b = 0.0f;
  for (const Material& m : scene.description.materials)
    b = std::max(b, luminance(m.emissive_factor) * m.emissive_strength);
  const float size = std::max(glm::length(scene.description.bounds.diagonal()), 1e-6f);
  for (const PunctualLight& l : scene.description.lights) {
    const float power = l.intensity * luminance(l.color);
    // A point or spot light seen from a quarter of the scene away; the sun on a white surface.
    b = std::max(b, l.type == PunctualLight::Type::Directional ? power * kInvPi : power / sqr(0.25f * size));
  }
  // The environment in a few directions (a uniform background: its colour).
  for (int i = 0; i < 64; ++i) {
    const vec3 d = square_to_direction({(i % 8 + 0.5f) / 8.0f, (i / 8 + 0.5f) / 8.0f});
    b = std::max(b, luminance(scene.environment.radiance(d)));
  }
  return std::isfinite(b) && b > 0.0f ? b : 1.0f;
}

void GuidePath::finish(PathGuide& guide, const vec3& radiance) const {
  for (int i = 0; i < count_; ++i) {
    const Vertex& v = at_[i];
    const vec3 arrived = radiance - v.radiance;
    // Per channel over the throughput where it carries light; their mean, over the density.
    float sum = 0.0f;
    int channels = 0;
    for (int c = 0; c < 3; ++c)
      if (v.throughput[c] > 0.0f) sum += arrived[c] / v.throughput[c], ++channels;
    if (channels > 0 && v.pdf > 0.0f) guide.record(v.p, v.wi, sum / static_cast<float>(channels) / v.pdf);
  }
}

}  // namespace tessera
