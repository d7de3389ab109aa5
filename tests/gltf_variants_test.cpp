// KHR_materials_variants: which material each primitive gets with each variant (the loader's
// SceneDescription), the checks on malformed mappings, and `tessera render --variant` /
// `tessera info` as a user meets them. The scene is scenes/material-variants (unlit quads, so a
// pixel on a quad is its material's base colour); every expected value is read from its JSON.
#include <gtest/gtest.h>

#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfIntAttribute.h>
#include <OpenEXR/ImfStringAttribute.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "imageio/image_input.h"
#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

namespace fs = std::filesystem;
using Json = nlohmann::json;

std::string scene_file() { return test::scene_path("material-variants/material-variants.gltf"); }
std::string box() { return test::scene_path("khronos/Box/glTF-Binary/Box.glb"); }
std::string quote(const std::string& s) { return "'" + s + "'"; }

Json scene_json() {
  std::ifstream in(scene_file());
  return Json::parse(in);
}

// What the file says: the variant index named `name`.
int variant_index(const Json& j, const std::string& name) {
  const Json& variants = j["extensions"]["KHR_materials_variants"]["variants"];
  for (std::size_t i = 0; i < variants.size(); ++i)
    if (variants[i]["name"] == name) return static_cast<int>(i);
  ADD_FAILURE() << "the scene has no variant " << name;
  return -1;
}

// What the file says: the material primitive `p` of mesh 0 has with variant `variant` (-1: none).
int expected_material(const Json& j, std::size_t p, int variant) {
  const Json& prim = j["meshes"][0]["primitives"][p];
  for (const Json& mapping : prim["extensions"]["KHR_materials_variants"]["mappings"])
    for (const Json& v : mapping["variants"])
      if (v.get<int>() == variant) return mapping["material"].get<int>();
  return prim["material"].get<int>();
}

glm::vec4 base_color_in_file(const Json& j, int material) {
  const Json& f = j["materials"][material]["pbrMetallicRoughness"]["baseColorFactor"];
  return {f[0].get<float>(), f[1].get<float>(), f[2].get<float>(), f[3].get<float>()};
}

// The base colour the loaded scene gives primitive `p` of its only mesh.
glm::vec4 loaded_base_color(const GltfLoadResult& r, std::size_t p) {
  const TriangleMesh& prim = r.scene.meshes.at(0).primitives.at(p);
  return r.scene.materials.at(prim.material).base_color_factor;
}

GltfLoadResult load_from_json(const Json& j, const std::string& name = "variants.gltf",
                              const GltfLoadParams& params = {}) {
  const std::string text = j.dump();
  return load_gltf_from_memory(std::vector<std::uint8_t>(text.begin(), text.end()), name, ".", params);
}

// The problem (without the file name) a JSON edit of the scene is refused with.
std::string load_error(const Json& j, const GltfLoadParams& params = {}) {
  try {
    load_from_json(j, "variants.gltf", params);
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.file(), "variants.gltf");
    return e.problem();
  }
  return "(loaded)";
}

Json& mappings_of(Json& j, std::size_t p) {
  return j["meshes"][0]["primitives"][p]["extensions"]["KHR_materials_variants"]["mappings"];
}

// ---- the loader ---------------------------------------------------------------------------

TEST(GltfVariants, TheExtensionIsSupported) {
  EXPECT_TRUE(is_supported_gltf_extension("KHR_materials_variants"));
  Json j = scene_json();
  j["extensionsRequired"] = Json::array({"KHR_materials_variants"});
  EXPECT_NO_THROW(load_from_json(j));
}

TEST(GltfVariants, TheFilesVariantsAreListedByIndex) {
  const Json j = scene_json();
  const GltfLoadResult r = load_gltf(scene_file());
  ASSERT_EQ(r.material_variants.size(), j["extensions"]["KHR_materials_variants"]["variants"].size());
  for (std::size_t i = 0; i < r.material_variants.size(); ++i)
    EXPECT_EQ(r.material_variants[i], j["extensions"]["KHR_materials_variants"]["variants"][i]["name"]);
  EXPECT_EQ(r.material_variant, -1);
  EXPECT_TRUE(load_gltf(box()).material_variants.empty());
}

TEST(GltfVariants, WithoutAVariantEveryPrimitiveKeepsItsDefaultMaterial) {
  const Json j = scene_json();
  const GltfLoadResult r = load_gltf(scene_file());
  ASSERT_EQ(r.scene.meshes.size(), 1u);
  ASSERT_EQ(r.scene.meshes[0].primitives.size(), 2u);
  for (std::size_t p = 0; p < 2; ++p) {
    const int material = j["meshes"][0]["primitives"][p]["material"].get<int>();
    EXPECT_EQ(r.scene.meshes[0].primitives[p].material, material);
    EXPECT_EQ(loaded_base_color(r, p), base_color_in_file(j, material)) << "primitive " << p;
  }
}

TEST(GltfVariants, EachVariantGivesEachPrimitiveItsMappedMaterialOrItsDefault) {
  const Json j = scene_json();
  for (const std::string name : {"red", "green"}) {
    const int v = variant_index(j, name);
    const GltfLoadResult r = load_gltf(scene_file(), {"", name});
    EXPECT_EQ(r.material_variant, v);
    for (std::size_t p = 0; p < 2; ++p) {
      const int material = expected_material(j, p, v);
      EXPECT_EQ(r.scene.meshes[0].primitives[p].material, material) << name << ", primitive " << p;
      EXPECT_EQ(loaded_base_color(r, p), base_color_in_file(j, material)) << name << ", primitive " << p;
    }
  }
  // The scene covers both cases: the panel is mapped by "red", the trim is not (keeps white).
  const int red = variant_index(j, "red");
  EXPECT_NE(expected_material(j, 0, red), j["meshes"][0]["primitives"][0]["material"].get<int>());
  EXPECT_EQ(expected_material(j, 1, red), j["meshes"][0]["primitives"][1]["material"].get<int>());
}

TEST(GltfVariants, AVariantIsChosenByIndexToo) {
  const Json j = scene_json();
  const GltfLoadResult by_index = load_gltf(scene_file(), {"", "1"});
  const std::string name = j["extensions"]["KHR_materials_variants"]["variants"][1]["name"];
  const GltfLoadResult by_name = load_gltf(scene_file(), {"", name});
  EXPECT_EQ(by_index.material_variant, 1);
  for (std::size_t p = 0; p < 2; ++p) {
    EXPECT_EQ(loaded_base_color(by_index, p), base_color_in_file(j, expected_material(j, p, 1)));
    EXPECT_EQ(by_index.scene.meshes[0].primitives[p].material, by_name.scene.meshes[0].primitives[p].material);
  }
}

TEST(GltfVariants, AnUnknownVariantIsALoadErrorListingTheFilesVariants) {
  const std::string listed = "(it has 2 variants: 0 'red', 1 'green')";
  for (const std::string wanted : {"blue", "2", "-1", "RED"}) {
    try {
      load_gltf(scene_file(), {"", wanted});
      ADD_FAILURE() << wanted << " was accepted";
    } catch (const SceneLoadError& e) {
      EXPECT_EQ(e.file(), scene_file());
      EXPECT_EQ(e.problem(), "has no material variant '" + wanted + "' " + listed);
    }
  }
}

TEST(GltfVariants, AVariantOfAFileWithoutVariantsIsALoadError) {
  try {
    load_gltf(box(), {"", "red"});
    ADD_FAILURE() << "accepted";
  } catch (const SceneLoadError& e) {
    EXPECT_EQ(e.problem(), "has no material variants (KHR_materials_variants), so variant 'red' cannot be chosen");
  }
}

// ---- malformed extension data ------------------------------------------------------------

TEST(GltfVariantsMalformed, AMappedMaterialOutOfRangeNamesMeshPrimitiveAndMapping) {
  Json j = scene_json();
  const std::size_t materials = j["materials"].size();
  mappings_of(j, 1)[0]["material"] = materials;
  EXPECT_EQ(load_error(j), "mesh 0 primitive 1: KHR_materials_variants mapping 0 refers to material " +
                               std::to_string(materials) + ", but the file has " + std::to_string(materials) +
                               " materials");
  // Refused whether or not the bad mapping's variant is chosen.
  EXPECT_EQ(load_error(j, {"", "red"}), load_error(j));
  // An index beyond 32 bits is named as written, not wrapped to a valid one.
  mappings_of(j, 1)[0]["material"] = 4294967296ull;
  EXPECT_EQ(load_error(j), "mesh 0 primitive 1: KHR_materials_variants mapping 0 refers to material 4294967296, but "
                           "the file has " + std::to_string(materials) + " materials");
}

TEST(GltfVariantsMalformed, AVariantIndexOutOfRangeNamesMeshPrimitiveAndMapping) {
  Json j = scene_json();
  const std::size_t variants = j["extensions"]["KHR_materials_variants"]["variants"].size();
  mappings_of(j, 0)[1]["variants"] = Json::array({variants + 3});
  EXPECT_EQ(load_error(j), "mesh 0 primitive 0: KHR_materials_variants mapping 1 refers to variant " +
                               std::to_string(variants + 3) + ", but the file has " + std::to_string(variants) +
                               " variants");
}

TEST(GltfVariantsMalformed, MappingsWithoutTheRootsVariantsAreRefused) {
  Json j = scene_json();
  j["extensions"].erase("KHR_materials_variants");
  EXPECT_EQ(load_error(j), "mesh 0 primitive 0: KHR_materials_variants mapping 0 refers to variant 0, but the file "
                           "has no variants");
}

TEST(GltfVariantsMalformed, AVariantMappedTwiceInAPrimitiveIsRefused) {
  Json j = scene_json();
  mappings_of(j, 0)[1]["variants"] = Json::array({0});  // mapping 0 already maps variant 0 ("red")
  EXPECT_EQ(load_error(j), "mesh 0 primitive 0: KHR_materials_variants mappings 0 and 1 both list variant 0; a "
                           "primitive may map each variant once");
  j = scene_json();
  mappings_of(j, 0)[0]["variants"] = Json::array({0, 0});
  EXPECT_EQ(load_error(j), "mesh 0 primitive 0: KHR_materials_variants mapping 0 lists variant 0 twice");
}

TEST(GltfVariantsMalformed, MappingsThatAreNotMaterialAndVariantIndicesAreRefused) {
  Json j = scene_json();
  mappings_of(j, 0)[0]["material"] = -1;
  EXPECT_EQ(load_error(j), "mesh 0 primitive 0: KHR_materials_variants mapping 0 has material -1, which is not an index");
  j = scene_json();
  mappings_of(j, 0)[0].erase("material");
  EXPECT_EQ(load_error(j), "mesh 0 primitive 0: KHR_materials_variants mapping 0 has no material");
  j = scene_json();
  mappings_of(j, 0)[0]["variants"] = Json::array();
  EXPECT_EQ(load_error(j), "mesh 0 primitive 0: KHR_materials_variants mapping 0 has no \"variants\" array of "
                           "variant indices");
  j = scene_json();
  mappings_of(j, 1)[0]["variants"] = Json::array({"green"});
  EXPECT_EQ(load_error(j), "mesh 0 primitive 1: KHR_materials_variants mapping 0 lists variant \"green\", which is "
                           "not an index");
  j = scene_json();
  mappings_of(j, 1) = Json::object();
  EXPECT_EQ(load_error(j), "mesh 0 primitive 1: KHR_materials_variants has no \"mappings\" array of "
                           "{\"material\": ..., \"variants\": [...]} objects");
}

TEST(GltfVariantsMalformed, RootVariantsWithoutNamesAreRefused) {
  Json j = scene_json();
  j["extensions"]["KHR_materials_variants"]["variants"][1].erase("name");
  EXPECT_EQ(load_error(j), "its KHR_materials_variants extension has variant 1 without a name (each variant is "
                           "{\"name\": ...})");
  j = scene_json();
  j["extensions"]["KHR_materials_variants"]["variants"][0]["name"] = 7;
  EXPECT_EQ(load_error(j), "its KHR_materials_variants extension has variant 0 without a name (each variant is "
                           "{\"name\": ...})");
  j = scene_json();
  j["extensions"]["KHR_materials_variants"]["variants"] = Json::array();
  EXPECT_EQ(load_error(j), "its KHR_materials_variants extension has no \"variants\" array of {\"name\": ...} "
                           "objects");
}

// ---- the command line ----------------------------------------------------------------------

test::CommandResult tessera(const std::string& args) {
  return test::run_command("timeout 120 " + quote(test::tessera_exe()) + " " + args);
}

const std::string kRender = " --width 24 --spp 4 -q";

glm::vec3 pixel(const FrameImage& image, double fx, double fy) {
  const int x = static_cast<int>(fx * image.width), y = static_cast<int>(fy * image.height);
  const std::size_t i = 3 * (static_cast<std::size_t>(y) * image.width + x);
  return {image.rgb[i], image.rgb[i + 1], image.rgb[i + 2]};
}

std::string variant_attribute(const std::string& path) {
  Imf::InputFile file(path.c_str());
  const auto* a = file.header().findTypedAttribute<Imf::StringAttribute>("materialVariant");
  return a ? a->value() : "(none)";
}

void expect_color(const glm::vec3& got, const glm::vec4& want, const std::string& what) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], want[c], 1e-4f) << what << ", channel " << c;
}

TEST(GltfVariantsCli, RenderWithEachVariantShowsItsMaterials) {
  const Json j = scene_json();
  const std::string dir = test::make_temp_dir("variants-cli");
  // The centre sees the panel (primitive 0), 80% down the trim (primitive 1): see the generator.
  for (const std::string choice : {"", "red", "1"}) {
    const std::string out = dir + "/v" + choice + ".exr";
    const auto r = tessera("render " + quote(scene_file()) + kRender + " -o " + quote(out) +
                           (choice.empty() ? "" : " --variant " + choice));
    ASSERT_EQ(r.exit_code, 0) << r.err;
    const int v = choice.empty() ? -1 : choice == "1" ? 1 : variant_index(j, choice);
    const FrameImage image = read_frame_exr(out);
    expect_color(pixel(image, 0.5, 0.5), base_color_in_file(j, expected_material(j, 0, v)), "centre, " + choice);
    expect_color(pixel(image, 0.5, 0.8), base_color_in_file(j, expected_material(j, 1, v)), "trim, " + choice);
    EXPECT_EQ(variant_attribute(out),
              v < 0 ? "(none)" : j["extensions"]["KHR_materials_variants"]["variants"][v]["name"].get<std::string>());
  }
  // The red variant's centre really is red, the green one's green (not white, not each other).
  const glm::vec3 red = pixel(read_frame_exr(dir + "/vred.exr"), 0.5, 0.5);
  const glm::vec3 green = pixel(read_frame_exr(dir + "/v1.exr"), 0.5, 0.5);
  EXPECT_GT(red.r, 4.0f * red.g);
  EXPECT_GT(green.g, 4.0f * green.r);
}

TEST(GltfVariantsCli, AnUnknownVariantExits2ListingTheVariants) {
  const std::string dir = test::make_temp_dir("variants-cli-unknown");
  for (const std::string wanted : {"blue", "2"}) {
    const auto r = tessera("render " + quote(scene_file()) + kRender + " -o " + quote(dir + "/out.exr") +
                           " --variant " + wanted);
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err, "tessera: error: " + scene_file() + ": has no material variant '" + wanted +
                         "' (it has 2 variants: 0 'red', 1 'green')\n");
    EXPECT_FALSE(fs::exists(dir + "/out.exr"));
  }
}

TEST(GltfVariantsCli, AVariantOfAFileWithoutVariantsExits2) {
  const std::string dir = test::make_temp_dir("variants-cli-none");
  const auto r = tessera("render " + quote(box()) + kRender + " -o " + quote(dir + "/out.exr") + " --variant red");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + box() +
                       ": has no material variants (KHR_materials_variants), so variant 'red' cannot be chosen\n");
}

TEST(GltfVariantsCli, AMalformedMappingExits2NamingThePrimitive) {
  Json j = scene_json();
  mappings_of(j, 0)[0]["material"] = 9;
  const std::string path = test::make_temp_dir("variants-cli-malformed") + "/bad.gltf";
  std::ofstream(path) << j.dump(1);
  const auto r = tessera("info " + quote(path));
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: " + path + ": mesh 0 primitive 0: KHR_materials_variants mapping 0 refers to "
                       "material 9, but the file has " + std::to_string(j["materials"].size()) + " materials\n");
}

TEST(GltfVariantsCli, InfoListsTheVariants) {
  const Json j = scene_json();
  const auto r = tessera("info " + quote(scene_file()));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const Json& variants = j["extensions"]["KHR_materials_variants"]["variants"];
  std::string expected = "variants    " + std::to_string(variants.size()) + " (render --variant NAME or INDEX)\n";
  for (std::size_t i = 0; i < variants.size(); ++i)
    expected += "  " + std::to_string(i) + ": '" + variants[i]["name"].get<std::string>() + "'\n";
  EXPECT_NE(r.out.find(expected), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("KHR_materials_variants (supported)"), std::string::npos) << r.out;
  const auto plain = tessera("info " + quote(box()));
  EXPECT_EQ(plain.out.find("\nvariants "), std::string::npos) << plain.out;
}

TEST(GltfVariantsCli, RenderHelpNamesTheOption) {
  const auto r = tessera("render --help");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out.find("--variant"), std::string::npos);
  EXPECT_NE(r.out.find("KHR_materials_variants"), std::string::npos);
}

TEST(GltfVariantsCli, ResumeWithAnotherVariantIsRefused) {
  const std::string dir = test::make_temp_dir("variants-cli-resume");
  const std::string part = dir + "/part.exr";
  const std::string settings = " --width 24 --spp 400 --seed 3 -q";
  auto r = tessera("render " + quote(scene_file()) + settings + " --variant red --time-limit 0.001 -o " + quote(part));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  {
    Imf::InputFile file(part.c_str());
    ASSERT_EQ(file.header().typedAttribute<Imf::IntAttribute>("partial").value(), 1) << "not partial: nothing to test";
  }
  const std::string resume = "render " + quote(scene_file()) + settings + " --resume " + quote(part) + " -o " +
                             quote(dir + "/out.exr");
  r = tessera(resume + " --variant green");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(r.err, "tessera: error: --resume " + part +
                       ": variant differs: the file has 0 'red', this render 1 'green'; resume with the options it "
                       "was started with\n");
  r = tessera(resume + " --variant 0 --time-limit 0.001");  // the same variant by index
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(variant_attribute(dir + "/out.exr"), "red");
  r = tessera(resume);  // left out: the file's
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(variant_attribute(dir + "/out.exr"), "red");
}

}  // namespace
}  // namespace tessera
