// glTF images and which one a texture shows: PNG (tinygltf's stb_image), JPEG (libjpeg-turbo,
// gltf_jpeg.h), WebP (EXT_texture_webp, libwebp), and KTX2 (KHR_texture_basisu), which Debian
// has no decoder for: its image is left empty and the texture's fallback source is used instead.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene_io/gltf_defects.h"

namespace tessera {

// The mimeType of an image tessera cannot decode: left empty, refused when a texture shows it.
inline constexpr const char* kUndecodableImage = "tessera/undecodable";

// The media types an image declares, each empty when not given: its `mimeType`, and the
// media type of its data URI. glTF requires each to match the image's bytes (the validator's
// IMAGE_MIME_TYPE_INVALID and INVALID_URI errors).
struct DeclaredMediaTypes {
  std::string mime_type;
  std::string data_uri;
  // A WebP image needs EXT_texture_webp in extensionsUsed, a KTX2 image KHR_texture_basisu.
  bool webp_declared = false, ktx2_declared = false;
};

// By image index, from the JSON as the file gives it (before gltf_prepare.cpp rewrites it).
std::vector<DeclaredMediaTypes> declared_media_types(const nlohmann::json& gltf);

// What the image callback saw: the encoded bytes of the images to decode (by index, decoded
// afterwards and in parallel by decode_pending_images), and the images that could not be, or
// whose bytes contradict what they declare (`declared`, filled before tinygltf reads the file).
struct ImageLoadContext {
  struct Pending {
    int index;
    std::vector<unsigned char> bytes;
  };
  std::vector<DeclaredMediaTypes> declared;
  std::vector<Pending> pending;
  std::vector<std::pair<int, std::string>> defective;
};

// tinygltf's LoadImageDataFunction; `user` is an ImageLoadContext. It keeps the bytes for
// decode_pending_images: tinygltf calls it image after image, and decoding a model's
// textures one by one was most of its load time (DamagedHelmet: five 2048^2 images). An image
// of a recognised format (PNG, JPEG, WebP, KTX2) other than it declares goes to ctx.defective.
bool load_gltf_image(tinygltf::Image* image, int index, std::string* err, std::string* warn, int width, int height,
                     const unsigned char* bytes, int size, void* user);

// Decodes the images load_gltf_image kept, each by the decoder its bytes' signature picks
// (JPEG: libjpeg-turbo; WebP: libwebp; else tinygltf's stb_image, for PNG), in parallel
// (TBB), largest first; each one it cannot decode goes to ctx.defective, in index order.
void decode_pending_images(tinygltf::Model& model, ImageLoadContext& ctx);

// "textures/a.png", "bufferView 3" or "data URI": where an image's bytes are, for messages.
std::string gltf_image_source(const tinygltf::Image& image);

// Decodes a base64 data URI of media type image/webp (which tinygltf leaves undecoded) into
// `image`. False when the URI is not one or does not hold a WebP image.
bool decode_webp_data_uri(tinygltf::Image& image);

// True for a KTX2 image, which load_gltf_image leaves undecoded, and for one it could not decode.
bool is_ktx2_image(const tinygltf::Image& image);

// The image texture `index` shows: EXT_texture_webp's source, else `source` (for
// KHR_texture_basisu, its fallback). -1 when it has none. Throws SceneLoadError for a
// texture that has only a KTX2 image, and the defect of an image it shows.
int texture_image(const tinygltf::Model& model, const std::string& file, int index, const GltfDefects& defects);

}  // namespace tessera
