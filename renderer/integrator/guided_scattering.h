// How a path vertex uses the path guide (renderer/guiding/path_guide.h): it draws its
// direction from a one-sample mixture of the guide and the BSDF, whose density is the
// mixture's (share x guide + (1 - share) x BSDF) in the throughput and in every MIS weight,
// so the estimate stays unbiased whatever the guide learnt; and, while the guide learns, it
// records what arrived along the directions it took.
#pragma once


#include "renderer/bsdfs/bsdf.h"
#include "renderer/guiding/path_guide.h"
#include "renderer/scene/render_scene.h"

namespace tessera {

// The guide at one vertex: its region there and the share of directions it gives.
struct GuideAt {
  const PathGuide* guide = nullptr;
  int region = -1;  // -1: nothing learnt here yet
  float share = 0.0f;  // 0: the BSDF alone; > 0 where nothing was learnt yet: what the vertex may learn
  bool samples() const { return region >= 0 && share > 0.0f; }
  // The mixture's density of world direction wi, from the BSDF's own.
  float pdf(const vec3& wi, float bsdf_pdf) const {
    return samples() ? share * guide->pdf(region, wi) + (1.0f - share) * bsdf_pdf : bsdf_pdf;
  }
};

// The share of the directions the guide draws at a shading point: half of its diffuse lobes'
// (reflected and transmitted) share. Specular and metal lobes, glossy or sharp, are left to
// the BSDF, whose density follows them closely where the guide's coarse one cannot; a thin
// surface's straight pass (a delta, which a mixture of densities cannot hold) as well.
float guide_share(const ShadingPoint& sp, const GltfBsdf& bsdf);

// The guide at point p of a shading point (null guide: none).
GuideAt guide_at(const PathGuide* guide, const vec3& p, const ShadingPoint& sp, const GltfBsdf& bsdf);

// A direction from the mixture (where g.samples()): the guide when u.z < share (u.z rescaled for the BSDF's lobe
// choice otherwise), bs.pdf the mixture's density, bs.f the whole BSDF. False when no
// direction was drawn (or the guided one carries nothing).
bool sample_guided(const GltfBsdf& bsdf, const Frame& frame, const vec3& wo_local, const GuideAt& g, const vec3& u,
                   BsdfSample& bs);

// A radiance typical of the scene's lights: the guide's fixed-point scale.
float guide_brightness(const RenderScene& scene);

// What one path records for the guide: at each vertex that drew from the mixture, the
// direction, its density and the path's throughput and radiance there; at the end, the
// radiance that arrived along each direction (what the path gathered after the vertex, over
// the throughput), over the density. Light is counted as the image counts it, MIS-weighted:
// the guide learns what light sampling leaves to the path (counting an emitter's light in
// full drew half the directions towards lights that next-event estimation finds anyway).
class GuidePath {
 public:
  void vertex(const vec3& p, const vec3& wi, float pdf, const vec3& throughput, const vec3& radiance) {
    if (count_ < kMost) at_[count_++] = Vertex{p, wi, throughput, radiance, pdf};
  }
  void finish(PathGuide& guide, const vec3& radiance) const;

 private:
  static constexpr int kMost = 16;
  struct Vertex {
    vec3 p, wi, throughput, radiance;
    float pdf;
  };
  Vertex at_[kMost];
  int count_ = 0;
};

}  // namespace tessera
