// KHR_materials_iridescence: the Fresnel reflectance of a surface under a thin dielectric
// film, as the extension specifies it after Belcour and Barla (2017, "A Practical Extension
// to Microfacet Theory for the Modeling of Varying Iridescence"). The two interfaces
// (outside to film, film to base) use Schlick's reflectance; the base's index comes from
// its normal-incidence reflectance f0 (for metals too, their extinction taken as 0). The
// Airy sum over the light's round trips in the film is integrated over the visible
// spectrum in Fourier space: its m-th term oscillates with m times the optical path
// difference, and the colour matching functions' Fourier transform (Gaussian fits) turns
// each term into RGB directly; terms beyond m = 2 are below 1e-3 for any film the
// extension describes.
//
// One deviation, measured against the exact Airy reflectance integrated with the colour
// matching functions (thin_film_test.cpp): the extension's sensitivities map an
// equal-energy spectrum to Rec. 709 (1.20, 0.95, 0.91), while the non-oscillating term is
// taken as white; here every term is white balanced (divided by that response), so a film
// whose interference averages out leaves the reflectance uncoloured. The extension's
// formula is off by up to 0.03 absolute in red at normal incidence; this one by 0.005.
#pragma once

#include "renderer/util/math.h"

namespace tessera {

struct ThinFilm {
  float thickness = 0.0f;  // nm; 0 = no film
  float ior = 1.3f;  // the film's index
  float outside_ior = 1.0f;  // the medium above it (the clear coat's 1.5 under a coat)
};

// Reflectance per RGB channel for light meeting the film at cos_theta (to the normal of the
// microfacet), over a base of normal-incidence reflectance base_f0 (in [0, 1]).
vec3 thin_film_reflectance(const ThinFilm& film, float cos_theta, const vec3& base_f0);

}  // namespace tessera
