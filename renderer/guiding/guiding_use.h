// Whether a frame is rendered with path guiding.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace tessera {

enum class GuidingUse : std::uint8_t { Auto, On, Off };
const std::vector<std::string>& guiding_use_names();  // "auto", "on", "off"
GuidingUse parse_guiding_use(const std::string& name);  // throws std::invalid_argument

// Auto does not guide: on every scene measured (docs/materials-and-lights.md#path-guiding:
// a caustic under a glass ball, a candle in thick glass, GlassVaseFlowers, the shared
// CornellBox) guiding took longer to equal noise than BSDF and light sampling alone.
bool guiding_used(GuidingUse use);

}  // namespace tessera
