#include "renderer/sampling/sampler.h"

#include "renderer/util/named_enum.h"

namespace tessera {

const std::vector<std::string>& sampler_names() {
  static const std::vector<std::string> names = {"sobol", "independent"};
  return names;
}

const char* sampler_name(SamplerKind kind) { return enum_name(sampler_names(), kind); }

SamplerKind parse_sampler(const std::string& name) { return parse_enum<SamplerKind>(sampler_names(), name, "sampler"); }

}  // namespace tessera
