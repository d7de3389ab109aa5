// glTF images and which one a texture shows: PNG (tinygltf's stb_image), JPEG (libjpeg-turbo,
// gltf_jpeg.h), WebP (EXT_texture_webp, libwebp), and KTX2 (KHR_texture_basisu), which Debian
// has no decoder for: its image is left empty and the texture's fallback source is used instead.
#pragma once

#include <string>
#include <vector>

#include <nlohmann/json.hpp>
#include <tiny_gltf.h>

#include "scene_io/base/gltf_defects.h"
#include "scene_io/decode/gltf_image_store.h"

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

// What the image callback saw: the images to decode, kept encoded in `store` (decoded when a
// scene shows them); the images it could not keep, or whose bytes contradict what they declare
// (`declared`, filled before tinygltf reads the file); and the images of no format glTF
// names, which only decoding can tell from garbage (decode_unrecognised_images).
struct ImageLoadContext {
  std::vector<DeclaredMediaTypes> declared;
  GltfImageStore* store = nullptr;
  std::vector<std::pair<int, std::string>> defective;
  std::vector<int> unrecognised;
};

// tinygltf's LoadImageDataFunction; `user` is an ImageLoadContext. It keeps the bytes in the
// store: tinygltf calls it image after image, and decoding there, one by one, was most of a
// model's load time (DamagedHelmet: five 2048^2 images). An image of a recognised format (PNG,
// JPEG, WebP, KTX2) other than it declares goes to ctx.defective.
bool load_gltf_image(tinygltf::Image* image, int index, std::string* err, std::string* warn, int width, int height,
                     const unsigned char* bytes, int size, void* user);

// Decodes the images of no recognised signature now (stb_image reads BMP, GIF and others, and
// tells them from bytes that are no image): those that fail go to ctx.defective, so that one
// the scene does not use is a warning, as before decoding became lazy.
void decode_unrecognised_images(const tinygltf::Model& model, ImageLoadContext& ctx);

// Decodes `bytes` by the decoder their signature picks (JPEG: libjpeg-turbo; WebP: libwebp;
// else tinygltf's stb_image, for PNG) into `image`. "" when decoded, else the problem.
std::string decode_image(tinygltf::Image* image, int index, const unsigned char* bytes, int size);

// "textures/a.png", "bufferView 3" or "data URI": where an image's bytes are, for messages.
std::string gltf_image_source(const tinygltf::Image& image);

// Keeps the bytes of image `index`'s base64 data URI of media type image/webp (which tinygltf
// leaves undecoded) in `store`. False when the URI is not one or does not hold WebP bytes.
bool keep_webp_data_uri(const tinygltf::Image& image, int index, GltfImageStore& store);

// True for a KTX2 image, which load_gltf_image leaves undecoded, and for one parsing marked
// undecodable (bytes that contradict their media type, or of no format and no decoder).
bool is_ktx2_image(const tinygltf::Image& image);

// The image texture `index` shows: EXT_texture_webp's source, else `source` (for
// KHR_texture_basisu, its fallback, and for a WebP image that cannot be decoded, which is
// decoded now to know). -1 when it has none. Throws SceneLoadError for a texture that has only
// a KTX2 image, and the defect of an image it shows.
int texture_image(const tinygltf::Model& model, const std::string& file, int index, const GltfDefects& defects,
                  const GltfImageStore& store);

}  // namespace tessera
