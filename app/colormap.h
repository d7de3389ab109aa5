// Viridis (van der Walt and Smith, matplotlib): perceptually uniform, readable in grey and
// by most colour-blind readers, dark for cheap and bright for expensive.
#pragma once

#include "app/canvas.h"

namespace tessera {

// t in [0, 1] (clamped) to 8-bit sRGB.
Rgb8 viridis(double t);

}  // namespace tessera
