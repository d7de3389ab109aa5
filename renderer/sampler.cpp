#include "renderer/sampler.h"

#include <algorithm>
#include <stdexcept>

namespace tessera {

const std::vector<std::string>& sampler_names() {
  static const std::vector<std::string> names = {"sobol", "independent"};
  return names;
}

const char* sampler_name(SamplerKind kind) { return sampler_names()[static_cast<int>(kind)].c_str(); }

SamplerKind parse_sampler(const std::string& name) {
  const auto& names = sampler_names();
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) throw std::invalid_argument("unknown sampler '" + name + "'");
  return static_cast<SamplerKind>(it - names.begin());
}

}  // namespace tessera
