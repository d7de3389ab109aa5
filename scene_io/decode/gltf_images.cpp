#include "scene_io/decode/gltf_images.h"

#include <algorithm>
#include <cstring>

#include <fmt/format.h>
#include <webp/decode.h>

#include "scene_io/base/gltf_data_uri.h"
#include "scene_io/decode/gltf_jpeg.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

bool is_webp(const unsigned char* b, int size) {
  return size >= 12 && std::memcmp(b, "RIFF", 4) == 0 && std::memcmp(b + 8, "WEBP", 4) == 0;
}

bool is_ktx2(const unsigned char* b, int size) {
  static const unsigned char magic[12] = {0xAB, 'K', 'T', 'X', ' ', '2', '0', 0xBB, '\r', '\n', 0x1A, '\n'};
  return size >= 12 && std::memcmp(b, magic, 12) == 0;
}

// RGBA, as tinygltf decodes PNG and JPEG.
bool decode_webp(tinygltf::Image* image, const unsigned char* bytes, int size) {
  int w = 0, h = 0;
  std::uint8_t* pixels = WebPDecodeRGBA(bytes, static_cast<std::size_t>(size), &w, &h);
  if (!pixels) return false;
  const int channels = 4;
  image->image.assign(pixels, pixels + static_cast<std::size_t>(w) * h * channels);
  WebPFree(pixels);
  image->width = w;
  image->height = h;
  image->component = channels;
  image->bits = 8;
  image->pixel_type = TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE;
  return true;
}

struct ImageFormat {
  const char* media_type;
  const char* name;
};

// The format the validator recognises `bytes` as, by their signature; nullptr for none of these.
const ImageFormat* recognised_format(const unsigned char* b, int size) {
  static const ImageFormat png{"image/png", "PNG"}, jpeg{"image/jpeg", "JPEG"}, webp{"image/webp", "WebP"},
      ktx2{"image/ktx2", "KTX2"};
  static const unsigned char png_signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  if (size >= 8 && std::memcmp(b, png_signature, 8) == 0) return &png;
  if (is_jpeg(b, size)) return &jpeg;
  if (is_webp(b, size)) return &webp;
  if (is_ktx2(b, size)) return &ktx2;
  return nullptr;
}

// Why image `index`'s bytes contradict a media type it declares; empty when they do not.
std::string media_type_mismatch(const tinygltf::Image& image, int index, const unsigned char* bytes, int size,
                                const std::vector<DeclaredMediaTypes>& declared) {
  const ImageFormat* format = recognised_format(bytes, size);
  if (!format || index < 0 || static_cast<std::size_t>(index) >= declared.size()) return "";
  const DeclaredMediaTypes& d = declared[static_cast<std::size_t>(index)];
  // As the validator: mimeType compared exactly, a data URI's media type in any case (RFC 2045).
  const std::pair<const std::string*, const char*> claims[] = {{&d.data_uri, "its data URI declares"},
                                                               {&d.mime_type, "its mimeType is"}};
  if ((format->media_type == std::string("image/webp") && !d.webp_declared) ||
      (format->media_type == std::string("image/ktx2") && !d.ktx2_declared))
    return fmt::format("image {} ({}) is a {} image, but extensionsUsed does not declare {} (glTF requires it for a {} "
                       "image)",
                       index, gltf_image_source(image), format->name,
                       format->name == std::string("WebP") ? "EXT_texture_webp" : "KHR_texture_basisu", format->name);
  for (const auto& [type, what] : claims)
    if (!type->empty() && *type != format->media_type)
      return fmt::format("image {} ({}) is a {} image, but {} '{}' (glTF requires the media type to match the "
                         "image data)",
                         index, gltf_image_source(image), format->name, what, shorten(*type, 40));
  return "";
}

int extension_source(const tinygltf::Texture& tex, const char* name) {
  auto it = tex.extensions.find(name);
  if (it == tex.extensions.end() || !it->second.Has("source") || !it->second.Get("source").IsNumber()) return -1;
  return it->second.Get("source").GetNumberAsInt();
}

}  // namespace

// The one place that picks a decoder.
std::string decode_image(tinygltf::Image* image, int index, const unsigned char* bytes, int size) {
  if (is_jpeg(bytes, size)) return decode_jpeg(image, bytes, size);
  if (is_webp(bytes, size)) return decode_webp(image, bytes, size) ? "" : "it is not a valid WebP image";
  std::string ignored, warn;
  return tinygltf::LoadImageData(image, index, &ignored, &warn, 0, 0, bytes, size, nullptr)
             ? ""
             : "it is not a PNG, JPEG or WebP image";
}

std::vector<DeclaredMediaTypes> declared_media_types(const nlohmann::json& gltf) {
  std::vector<DeclaredMediaTypes> out;
  const auto images = gltf.find("images");
  if (images == gltf.end() || !images->is_array()) return out;
  const auto used = gltf.find("extensionsUsed");
  auto declared = [&](const char* name) {
    return used != gltf.end() && used->is_array() && std::find(used->begin(), used->end(), name) != used->end();
  };
  for (const nlohmann::json& image : *images) {
    DeclaredMediaTypes d{"", "", declared("EXT_texture_webp"), declared("KHR_texture_basisu")};
    if (image.is_object() && image.contains("mimeType") && image["mimeType"].is_string())
      d.mime_type = image["mimeType"].get<std::string>();
    if (image.is_object() && image.contains("uri") && image["uri"].is_string())
      d.data_uri = data_uri_media_type(image["uri"].get_ref<const std::string&>());
    out.push_back(std::move(d));
  }
  return out;
}

bool load_gltf_image(tinygltf::Image* image, const int index, std::string* err, std::string* warn, int width,
                     int height, const unsigned char* bytes, int size, void* user) {
  auto* ctx = static_cast<ImageLoadContext*>(user);
  if (std::string problem = media_type_mismatch(*image, index, bytes, size, ctx->declared); !problem.empty()) {
    ctx->defective.emplace_back(index, std::move(problem));  // refused when a texture shows it
    image->mimeType = kUndecodableImage;
    return true;
  }
  if (is_ktx2(bytes, size)) {  // no decoder: textures use their fallback (texture_image)
    image->mimeType = "image/ktx2";
    return true;
  }
  if (!recognised_format(bytes, size)) ctx->unrecognised.push_back(index);
  ctx->store->keep(index, std::vector<unsigned char>(bytes, bytes + size));
  (void)err, (void)warn, (void)width, (void)height;
  return true;
}

void decode_unrecognised_images(const tinygltf::Model& model, ImageLoadContext& ctx) {
  ctx.store->decode(model, ctx.unrecognised);
  for (int index : ctx.unrecognised)
    if (std::string problem = ctx.store->decoded(index).problem; !problem.empty())
      ctx.defective.emplace_back(index, std::move(problem));
}

std::string gltf_image_source(const tinygltf::Image& image) {
  if (image.uri.rfind("data:", 0) == 0) return "data URI";
  if (!image.uri.empty()) return shorten(image.uri);
  if (image.bufferView >= 0) return fmt::format("bufferView {}", image.bufferView);
  return "data URI";
}

bool keep_webp_data_uri(const tinygltf::Image& image, int index, GltfImageStore& store) {
  static const std::string prefix = "data:image/webp;base64,";
  if (image.uri.rfind(prefix, 0) != 0) return false;
  // tinygltf decodes base64 data URIs only of the media types it knows.
  std::vector<unsigned char> bytes;
  std::string mime;
  const std::string known = "data:application/octet-stream;base64," + image.uri.substr(prefix.size());
  if (!tinygltf::DecodeDataURI(&bytes, mime, known, 0, false) || bytes.size() > INT32_MAX ||
      !is_webp(bytes.data(), static_cast<int>(bytes.size())))
    return false;
  store.keep(index, std::move(bytes));
  return true;
}

bool is_ktx2_image(const tinygltf::Image& image) {
  return image.image.empty() && (image.mimeType == "image/ktx2" || image.mimeType == kUndecodableImage);
}

int texture_image(const tinygltf::Model& model, const std::string& file, int index, const GltfDefects& defects,
                  const GltfImageStore& store) {
  const tinygltf::Texture& tex = model.textures[index];
  int source = extension_source(tex, "EXT_texture_webp");
  const int images = static_cast<int>(model.images.size());
  // A WebP source tessera cannot read falls back to `source`, as the extension intends.
  auto unreadable = [&](int image) {
    if (is_ktx2_image(model.images[image])) return true;
    store.decode(model, {image});
    return !store.decoded(image).problem.empty();
  };
  if (source < 0 || (source < images && tex.source >= 0 && unreadable(source))) source = tex.source;
  if (source >= static_cast<int>(model.images.size()))
    throw SceneLoadError(file, fmt::format("texture {} refers to image {}, but the file has {}", index, source,
                                           count_of(model.images.size(), "image")));
  if (source >= 0) defects.check_used(fmt::format("image {}", source), file);
  const bool basisu = tex.extensions.count("KHR_texture_basisu") > 0;
  if ((source < 0 && basisu) || (source >= 0 && is_ktx2_image(model.images[source])))
    throw SceneLoadError(file, fmt::format("texture {} has only a KTX2 image (KHR_texture_basisu), which tessera "
                                           "cannot decode; it needs a PNG, JPEG or WebP fallback source",
                                           index));
  return source;
}

}  // namespace tessera
