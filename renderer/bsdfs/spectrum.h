// Wavelengths in an RGB renderer: the CIE 1931 colour matching functions, their linear
// sRGB (Rec. 709) response, and sampling one wavelength for a path whose light is split by
// dispersion (KHR_materials_dispersion).
//
// A dispersive path carries one wavelength from its first dispersive surface on. Its
// throughput is multiplied by w(lambda) / p(lambda), where w is the RGB response to light of
// that wavelength, normalised so that an equal-energy spectrum integrates to white (1, 1, 1):
// averaged over wavelengths, a path that is not bent differently by wavelength keeps its
// colour exactly, and a white furnace stays 1. w is the Rec. 709 primaries' response to
// the colour matching functions with its negative lobes cut off (a spectral colour lies
// outside the sRGB gamut; the cut keeps every sample non-negative, as a denoiser and the
// adaptive sampler need) and each channel rescaled to integrate to 1. p is proportional to
// w's channel sum, so every weight's channels sum to 3.
#pragma once

#include "renderer/util/math.h"

namespace tessera {

constexpr float kLambdaMin = 360.0f, kLambdaMax = 830.0f;  // nm, the CIE tables' range

// CIE 1931 2-degree colour matching functions (x-bar, y-bar, z-bar) at `lambda` nm: the
// multi-lobe piecewise Gaussian fit of Wyman, Sloan and Shirley (JCGT 2013), within about 1%
// of the tables.
vec3 cie_xyz(float lambda);

// CIE XYZ to linear sRGB (Rec. 709 primaries, D65 white).
vec3 xyz_to_linear_srgb(const vec3& xyz);

struct WavelengthSample {
  float lambda = 0.0f;  // nm
  vec3 weight{0.0f};  // w(lambda) / p(lambda)
};

// A wavelength for u in [0, 1), from a table of p at 1 nm steps (piecewise constant).
WavelengthSample sample_wavelength(float u);
// p(lambda) per nm, and w(lambda): what sample_wavelength uses.
float wavelength_pdf(float lambda);
vec3 wavelength_response(float lambda);

// KHR_materials_dispersion: the index at `lambda` nm of a material with index `ior` at the
// d line (587.6 nm) and dispersion = 20 / Abbe number, from the two-term Cauchy fit the
// extension specifies: n = max(ior + (ior - 1) / V (523655 / lambda^2 - 1.5168), 1).
inline float dispersive_ior(float ior, float dispersion, float lambda) {
  const float inv_abbe = dispersion / 20.0f;
  return fmax_inline(ior + (ior - 1.0f) * inv_abbe * (523655.0f / (lambda * lambda) - 1.5168f), 1.0f);
}

}  // namespace tessera
