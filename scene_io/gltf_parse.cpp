#include "scene_io/gltf_parse.h"

#include <fstream>
#include <iterator>
#include <limits>

#include <fmt/format.h>

#include "scene_io/decode/gltf_container.h"
#include "scene_io/validation/gltf_diagnose.h"
#include "scene_io/decode/gltf_draco.h"
#include "scene_io/decode/gltf_images.h"
#include "scene_io/decode/gltf_meshopt.h"
#include "scene_io/decode/gltf_prepare.h"
#include "scene_io/materials/gltf_variants.h"
#include "scene_io/base/load_error.h"

namespace tessera {
namespace {

bool file_exists(const std::string& path, void*) { return unreadable_reason(path).empty(); }

std::string expand_file_path(const std::string& path, void*) { return path; }  // no ~ or $VAR

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  if (!unreadable_reason(path).empty()) {  // a directory, a device, a pipe: never read
    if (err) *err += path + ": cannot be read\n";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (in) out->assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
  if (in && !in.bad()) return true;
  if (err) *err += path + ": cannot be read\n";
  return false;
}

bool write_whole_file(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "tessera never writes glTF files\n";
  return false;
}

// Why image `i`, whose bytes tinygltf did not hand to the store, cannot be read; empty when it
// can (a WebP data URI, kept here, or a KTX2 image whose texture has a fallback).
std::string unreadable_image(const tinygltf::Image& image, int i, const std::string& base_dir, GltfImageStore& store) {
  if (store.kept(i) || keep_webp_data_uri(image, i, store)) return "";
  if (image.uri.rfind("data:image/webp;", 0) == 0)
    return fmt::format("image {} (data URI) could not be decoded: it is not a valid WebP image", i);
  if (image.uri.empty() || image.bufferView >= 0 || is_ktx2_image(image)) return "";
  if (image.uri.rfind("data:", 0) == 0)  // a media type tinygltf does not decode
    return fmt::format("image {} has a data URI of media type '{}'; tessera reads PNG, JPEG and WebP images", i,
                       image.uri.substr(5, image.uri.find_first_of(";,") - 5));
  if (is_remote_uri(image.uri))
    return fmt::format("image {}: tessera reads local files only: {}", i, gltf_image_source(image));
  std::string why = unreadable_reason(resolve_gltf_uri(base_dir, image.uri));
  if (why.empty()) why = "it is empty";
  return fmt::format("image {} refers to {}, which cannot be opened: {}", i, gltf_image_source(image), why);
}

// tinygltf only warns about an external image it cannot open: a defect of the image.
void check_external_images(tinygltf::Model& model, const std::string& base_dir, GltfDefects& defects,
                           GltfImageStore& store) {
  for (std::size_t i = 0; i < model.images.size(); ++i)
    if (const std::string why = unreadable_image(model.images[i], static_cast<int>(i), base_dir, store); !why.empty()) {
      defects.add(fmt::format("image {}", i), why);
      model.images[i].mimeType = kUndecodableImage;
    }
}

// The placeholders gltf_prepare.cpp put in: buffers without data are empty again, and
// indices accessors without a bufferView are the primitives' indices.
void restore_placeholders(tinygltf::Model& model, const GltfDefects& defects) {
  for (std::size_t i = 0; i < model.buffers.size(); ++i)
    if (defects.problems.count(fmt::format("buffer {}", i))) model.buffers[i].data.clear();
  for (tinygltf::Mesh& mesh : model.meshes)
    for (tinygltf::Primitive& prim : mesh.primitives)
      if (auto it = prim.extensions.find(kIndicesWithoutView); it != prim.extensions.end()) {
        prim.indices = it->second.Get("accessor").GetNumberAsInt();
        prim.extensions.erase(it);
      }
}

}  // namespace

tinygltf::Model parse_gltf(const std::vector<std::uint8_t>& bytes, const std::string& name,
                           const std::string& base_dir, GltfDefects& defects, GltfImageStore& images) {
  GltfContainer container = check_gltf_container(bytes, name);
  if (container.trailing_bytes > 0)
    defects.notes.push_back(fmt::format("{} after the end its binary glTF header gives are ignored",
                                        count_of(container.trailing_bytes, "byte")));
  if (bytes.size() > std::numeric_limits<unsigned>::max())
    throw SceneLoadError(name, "is larger than 4 GiB, more than tinygltf can read");
  // Compressed files: tinygltf reads a rewritten JSON (gltf_prepare.h), in a rebuilt .glb.
  ImageLoadContext ctx;
  ctx.store = &images;
  const std::optional<std::string> prepared = prepare_gltf_json(
      container.json, name, {container.binary, container.bin_chunk_size, base_dir}, defects, ctx.declared);
  std::vector<std::uint8_t> rebuilt;
  if (prepared) {
    rebuilt = container.binary ? replace_glb_json(bytes, *prepared)
                               : std::vector<std::uint8_t>(prepared->begin(), prepared->end());
    container = check_gltf_container(rebuilt, name);
  }
  const std::vector<std::uint8_t>& input = prepared ? rebuilt : bytes;
  tinygltf::TinyGLTF parser;
  parser.SetFsCallbacks({&file_exists, &expand_file_path, &read_whole_file, &write_whole_file, &ctx});
  parser.SetImageLoader(&load_gltf_image, &ctx);
  // tinygltf's own reading of extension objects drops empty arrays and objects and cuts
  // integers to int, so KHR_materials_variants (scene_io/materials/gltf_variants.cpp) reads the JSON
  // text of each `extensions` object instead, which tinygltf keeps only when asked to.
  if (container.json.find(kMaterialsVariants) != std::string_view::npos)
    parser.SetStoreOriginalJSONForExtrasAndExtensions(true);
  tinygltf::Model model;
  std::string err, warn;
  const auto size = static_cast<unsigned>(input.size());
  const bool ok =
      container.binary
          ? parser.LoadBinaryFromMemory(&model, &err, &warn, input.data(), size, base_dir)
          : parser.LoadASCIIFromString(&model, &err, &warn,
                                       reinterpret_cast<const char*>(input.data()), size, base_dir);
  if (!ok) {
    if (err.rfind("[json.exception.", 0) != 0)
      if (auto problem = diagnose_gltf_json({container.json, container.binary,
                                             container.bin_chunk_size, base_dir}))
        throw SceneLoadError(name, *problem);
    throw SceneLoadError(name, reword_tinygltf_error(err, container.json));
  }
  if (model.asset.version.rfind("2.", 0) != 0)
    throw SceneLoadError(name, fmt::format("is glTF version '{}'; tessera reads version 2.x",
                                           model.asset.version));
  decode_unrecognised_images(model, ctx);
  for (const auto& [index, problem] : ctx.defective) {
    defects.add(fmt::format("image {}", index), problem);
    model.images[static_cast<std::size_t>(index)].mimeType = kUndecodableImage;
  }
  check_external_images(model, base_dir, defects, images);
  restore_placeholders(model, defects);
  decode_meshopt_views(model, name);  // first: a Draco stream may sit in a meshopt view
  decode_draco_primitives(model, name);
  return model;
}

}  // namespace tessera
