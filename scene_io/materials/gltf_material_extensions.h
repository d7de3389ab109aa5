// The KHR_materials_* extensions tessera renders: transmission, ior, volume, specular,
// clearcoat, sheen, unlit (emissive_strength is read with the core material).
#pragma once

#include <functional>
#include <string>

#include <tiny_gltf.h>

#include "renderer/description/scene.h"

namespace tessera {

// Resolves a textureInfo (index, texCoord, its extensions) of slot `slot` to a TextureRef.
using TextureResolver =
    std::function<TextureRef(int index, int texcoord, const tinygltf::ExtensionMap& extensions, const std::string& slot)>;

// Reads the extensions of `src` into `mat`. Throws SceneLoadError (through `fail`) on
// values the specification forbids.
void read_material_extensions(const tinygltf::Material& src, const TextureResolver& texture,
                              const std::function<void(const std::string&)>& fail, Material& mat);

}  // namespace tessera
