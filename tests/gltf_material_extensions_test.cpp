// The KHR_materials_* extensions read from the Khronos sample models, values as their JSON
// states them.
#include <gtest/gtest.h>

#include "scene_io/gltf_loader.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

SceneDescription load(const std::string& name) {
  return load_gltf(test::scene_path("khronos/" + name + "/glTF-Binary/" + name + ".glb")).scene;
}

TEST(GltfMaterialExtensions, TransmissionIorAndVolume) {
  const SceneDescription s = load("TransmissionRoughnessTest");
  const Material& air = s.materials[1];  // "Mat_IOR_1.0"
  EXPECT_EQ(air.name, "Mat_IOR_1.0");
  EXPECT_FLOAT_EQ(air.transmission_factor, 1.0f);
  EXPECT_FLOAT_EQ(air.ior, 1.0f);
  EXPECT_FLOAT_EQ(air.thickness_factor, 0.005f);
  EXPECT_FLOAT_EQ(s.materials[2].ior, 1.33f);
  EXPECT_FLOAT_EQ(s.materials[3].ior, 1.5f);  // no KHR_materials_ior: the default
}

TEST(GltfMaterialExtensions, VolumeAttenuation) {
  const SceneDescription s = load("AttenuationTest");
  const Material& m = s.materials[1];  // "R2_ThicknessFac_1.5"
  EXPECT_EQ(m.name, "R2_ThicknessFac_1.5");
  EXPECT_FLOAT_EQ(m.thickness_factor, 1.5f);
  EXPECT_FLOAT_EQ(m.attenuation_distance, 1.0f);
  EXPECT_EQ(m.attenuation_color, glm::vec3(0.1f, 0.5f, 0.9f));
}

TEST(GltfMaterialExtensions, ClearcoatWithTextures) {
  const SceneDescription s = load("ClearCoatTest");
  EXPECT_FLOAT_EQ(s.materials[1].clearcoat_factor, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[1].clearcoat_roughness_factor, 0.03f);
  EXPECT_FALSE(s.materials[1].clearcoat_texture.present());
  EXPECT_TRUE(s.materials[4].clearcoat_texture.present());  // "Partial_Coated"
  EXPECT_TRUE(s.materials[7].clearcoat_roughness_texture.present());  // "RoughVariations_Coated"
  EXPECT_FLOAT_EQ(s.materials[0].clearcoat_factor, 0.0f);  // no extension: none
}

TEST(GltfMaterialExtensions, ClearcoatNormalTexture) {
  const SceneDescription s = load("ClearCoatTest");
  EXPECT_EQ(s.materials[13].name, "CoatNorm_Coated");
  EXPECT_TRUE(s.materials[13].clearcoat_normal_texture.present());
  EXPECT_FLOAT_EQ(s.materials[13].clearcoat_normal_scale, 1.0f);
  EXPECT_TRUE(s.materials[16].clearcoat_normal_texture.present());  // "SharedNorm_Coated"
  EXPECT_FALSE(s.materials[1].clearcoat_normal_texture.present());
}

TEST(GltfMaterialExtensions, Anisotropy) {
  const SceneDescription strength = load("AnisotropyStrengthTest");
  EXPECT_FLOAT_EQ(strength.materials[0].anisotropy_strength, 0.0f);
  EXPECT_FLOAT_EQ(strength.materials[1].anisotropy_strength, 1.0f / 6.0f);
  const SceneDescription s = load("AnisotropyRotationTest");
  EXPECT_EQ(s.materials[1].name, "Aniso Tan + Rotation");
  EXPECT_FLOAT_EQ(s.materials[1].anisotropy_strength, 0.5f);
  EXPECT_FLOAT_EQ(s.materials[1].anisotropy_rotation, 0.523598775598f);  // 30 degrees
  EXPECT_FALSE(s.materials[1].anisotropy_texture.present());
  EXPECT_TRUE(s.materials[3].anisotropy_texture.present());
  EXPECT_FLOAT_EQ(s.materials[3].anisotropy_rotation, 0.349065850398866f);  // 20 degrees
}

// tessera's own scenes for the newest extensions (scenes/material-extensions/).
SceneDescription load_own(const std::string& name) {
  return load_gltf(test::scene_path("material-extensions/" + name + ".gltf")).scene;
}

TEST(GltfMaterialExtensions, Iridescence) {
  const SceneDescription s = load_own("iridescence");
  const Material& plain = s.materials[2];  // "dark dielectric, film 400 nm"
  EXPECT_EQ(plain.name, "dark dielectric, film 400 nm");
  EXPECT_FLOAT_EQ(plain.iridescence_factor, 1.0f);
  EXPECT_FLOAT_EQ(plain.iridescence_ior, 1.8f);
  EXPECT_FLOAT_EQ(plain.iridescence_thickness_min, 100.0f);  // the default
  EXPECT_FLOAT_EQ(plain.iridescence_thickness_max, 400.0f);
  EXPECT_FALSE(plain.iridescence_thickness_texture.present());
  const Material& ramp = s.materials[18];  // thickness from the texture's G
  EXPECT_FLOAT_EQ(ramp.iridescence_thickness_max, 1000.0f);
  EXPECT_TRUE(ramp.iridescence_texture.present());
  EXPECT_TRUE(ramp.iridescence_thickness_texture.present());
  EXPECT_FLOAT_EQ(s.materials[19].iridescence_factor, 0.0f);  // the floor: none
}

TEST(GltfMaterialExtensions, Dispersion) {
  const SceneDescription s = load_own("dispersion");
  EXPECT_FLOAT_EQ(s.materials[0].dispersion, 0.0f);
  EXPECT_FLOAT_EQ(s.materials[1].dispersion, 1.0f);
  EXPECT_FLOAT_EQ(s.materials[2].dispersion, 3.0f);
  EXPECT_FLOAT_EQ(s.materials[2].ior, 1.7f);
  EXPECT_GT(s.materials[2].thickness_factor, 0.0f);  // a volume: dispersion needs one
}

TEST(GltfMaterialExtensions, RenderedExtensionsAreSupported) {
  for (const char* name : {"KHR_materials_transmission", "KHR_materials_ior", "KHR_materials_volume",
                           "KHR_materials_specular", "KHR_materials_clearcoat", "KHR_materials_sheen",
                           "KHR_materials_unlit", "KHR_materials_anisotropy", "KHR_materials_iridescence",
                           "KHR_materials_dispersion", "KHR_materials_diffuse_transmission"})
    EXPECT_TRUE(is_supported_gltf_extension(name)) << name;
  EXPECT_FALSE(is_supported_gltf_extension("KHR_materials_pbrSpecularGlossiness"));
}

// Every Khronos sample model loads without a warning about the extensions it uses: tessera
// renders all of them.
TEST(GltfMaterialExtensions, SampleModelsUseOnlySupportedExtensions) {
  for (const char* name : {"AttenuationTest", "ClearCoatTest", "EmissiveStrengthTest", "TransmissionRoughnessTest",
                           "DamagedHelmet", "MetalRoughSpheresNoTextures", "AnisotropyStrengthTest",
                           "AnisotropyRotationTest"}) {
    const GltfLoadResult r = load_gltf(test::scene_path(std::string("khronos/") + name + "/glTF-Binary/" + name + ".glb"));
    for (const std::string& w : r.warnings) EXPECT_EQ(w.find("not supported"), std::string::npos) << name << ": " << w;
    for (const std::string& ext : r.scene.extensions_used) EXPECT_TRUE(is_supported_gltf_extension(ext)) << name << ": " << ext;
  }
  const GltfLoadResult t = load_gltf(test::scene_path("khronos/TextureTransformTest/glTF/TextureTransformTest.gltf"));
  EXPECT_TRUE(t.warnings.empty()) << t.warnings.front();
}

}  // namespace
}  // namespace tessera
