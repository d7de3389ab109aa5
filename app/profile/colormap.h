// Viridis (van der Walt and Smith, matplotlib) from OpenImageIO's ImageBufAlgo::color_map:
// perceptually uniform, readable in grey and by most colour-blind readers, dark for cheap
// and bright for expensive.
#pragma once

#include <vector>

#include "app/profile/chart.h"

namespace tessera {

// Each t in [0, 1] (clamped) to its sRGB colour.
std::vector<Colour> viridis(const std::vector<double>& t);

// n colours evenly spaced from t = 0 to t = 1: the stops of a colour bar.
std::vector<Colour> viridis_ramp(int n);

// Okabe-Ito colours for categories (a plot's series, a render's ranks): distinguishable by
// colour-blind readers. kCategoryColours of them; the index wraps round.
constexpr int kCategoryColours = 6;
Colour category_colour(std::size_t index);

}  // namespace tessera
