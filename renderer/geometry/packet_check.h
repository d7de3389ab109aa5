// Whether this CPU's Embree traces camera-ray packets exactly as it traces single rays.
//
// SceneGeometry::intersect_packet promises each ray the hit intersect() gives it, bit for bit,
// so that an image does not depend on which samples share a packet (adaptive sampling, waves
// and --resume group them differently). That holds where Embree's 16-wide packet kernels and
// its single-ray kernel compute alike: on an AMD Zen 5 they did; on an Intel Xeon with
// AVX-512, hits on an instance that moves while the shutter is open differed in the last bits
// of u, v and the normal (12 of tests/packet_intersect_test.cpp's), and with Embree held to
// AVX2 (no 16-wide kernels: its fallback traces the packet) hits differed too. So packets are
// used only where a test scene says they agree.
#pragma once

#include <embree3/rtcore.h>

#include "renderer/geometry/scene_geometry.h"

namespace tessera {

// False without Embree's native 16-wide kernels; else whether every camera-ray packet of a
// test scene found the single rays' hits: a finely tessellated sphere baked into world space
// and instanced, still; for a scene where something moves, also instanced moving and
// deforming. Decided once per process, with the first device asked (about 10 ms).
bool packets_match_single_rays(RTCDevice device, bool scene_moves);

// How many of the n <= kPacketSize rays get another hit from g.intersect_packet than from
// g.intersect (found, t, u, v, triangle, instance or normal, bit for bit); `hits` counts the
// rays intersect() finds a hit for.
int packet_differences(const SceneGeometry& g, const Ray* rays, int n, int* hits = nullptr);

}  // namespace tessera
