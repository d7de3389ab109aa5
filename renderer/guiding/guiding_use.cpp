#include "renderer/guiding/guiding_use.h"

#include "renderer/util/named_enum.h"

namespace tessera {

const std::vector<std::string>& guiding_use_names() {
  static const std::vector<std::string> names{"auto", "on", "off"};
  return names;
}

GuidingUse parse_guiding_use(const std::string& name) {
  return parse_enum<GuidingUse>(guiding_use_names(), name, "guiding use");
}

bool guiding_used(GuidingUse use) { return use == GuidingUse::On; }

}  // namespace tessera
