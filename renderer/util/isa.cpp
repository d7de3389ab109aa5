#include "renderer/util/isa.h"

namespace tessera {

std::string_view compiled_isa() { return TESSERA_ISA; }

}  // namespace tessera
