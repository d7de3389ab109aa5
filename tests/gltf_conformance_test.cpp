// Files the Khronos glTF-Validator (2.0.0-dev.3.10) calls valid load, with the warnings the
// policy in docs/reliability.md gives: tests/data/conformance/ holds them, each checked with
// tools/gltf-validate.js (0 errors; the warnings it reports are named per test). Their used
// counterparts, which the policy refuses, are in tests/data/malformed/.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "scene_io/gltf_loader.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

GltfLoadResult load(const std::string& name) { return load_gltf(test::data_path("conformance/" + name)); }

std::uint64_t triangles(const SceneDescription& s) {
  std::uint64_t n = 0;
  for (const Instance& inst : s.instances)
    for (const TriangleMesh& p : s.meshes.at(inst.mesh).primitives) n += p.triangle_count();
  return n;
}

TEST(GltfConformance, UnusedBufferWithoutUriInGltf) {
  const GltfLoadResult r = load("unused_buffer_without_uri.gltf");  // validator: no warning
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.warnings, std::vector<std::string>{});
}

TEST(GltfConformance, GlbBufferOtherThanTheFirstWithoutUri) {
  const GltfLoadResult r = load("glb_placeholder_buffer.glb");  // buffer 1: 1024 bytes, no uri
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.scene.bounds.hi, glm::vec3(1, 1, 0));
  EXPECT_EQ(r.warnings, std::vector<std::string>{});
}

TEST(GltfConformance, GlbTrailingByteIsIgnoredWithAWarning) {
  const GltfLoadResult r = load("glb_trailing_byte.glb");  // validator: warning GLB_EXTRA_DATA
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.warnings, std::vector<std::string>{"1 byte after the end its binary glTF header gives are ignored"});
}

TEST(GltfConformance, IndicesWithoutBufferViewAreZerosBarSparseOnes) {
  const GltfLoadResult r = load("indices_without_bufferview.gltf");
  const Mesh& mesh = r.scene.meshes.at(0);
  ASSERT_EQ(mesh.primitives.size(), 2u);
  EXPECT_EQ(mesh.primitives[0].indices, (MeshArray<std::uint32_t>{0, 0, 0}));  // all zeros
  EXPECT_EQ(mesh.primitives[1].indices, (MeshArray<std::uint32_t>{0, 1, 2}));  // sparse 1, 2 at 1, 2
}

TEST(GltfConformance, UnusedObjectsOfEveryKindLoadInvalidOnesWithAWarning) {
  // Validator: warnings VALUE_NOT_IN_LIST (accessor 1 type VEC5), IMAGE_UNRECOGNIZED_FORMAT.
  const GltfLoadResult r = load("unused_objects.gltf");
  EXPECT_EQ(triangles(r.scene), 1u);  // scene 0 places mesh 0 once; scene 1, mesh 1 unused
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            "ignored, as the scene does not use it: image 0 (bufferView 2) could not be decoded: "
                            "it is not a PNG, JPEG or WebP image",
                            "ignored, as the scene does not use it: accessor 1 has unknown type 'VEC5'"}));
}

TEST(GltfConformance, InvalidObjectsTheSceneDoesNotUseAreWarnings) {
  // Validator: errors INVALID_INDEX (material 0's baseColorTexture index -1), TYPE_MISMATCH
  // (mesh 1's primitives is an object) and ACCESSOR_INVALID_FLOAT (accessor 1 holds a NaN).
  // Used, each refuses the file (tests/data/malformed/texture_index_negative.gltf,
  // primitives_not_array.gltf; GltfLoader.NonFinitePositionsAreRejected).
  const GltfLoadResult r = load("unused_invalid_objects.gltf");
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            "ignored, as the scene does not use it: material 0 has baseColorTexture index -1, which "
                            "names no texture",
                            "ignored, as the scene does not use it: mesh 1 has a \"primitives\" that is not an array; "
                            "glTF requires an array of at least one primitive",
                            "ignored, as the scene does not use it: accessor 1 (unused) holds NaN at element 0"}));
}

// One file, seven scenes: scene 0 uses nothing broken; each other scene uses one broken object.
// Validator (2.0.0-dev.3.10): 11 errors, among them UNRESOLVED_REFERENCE (material 1's texture),
// ARRAY_LENGTH_NOT_IN_LIST (material 2's emissiveFactor, reached only through a
// KHR_materials_variants mapping), UNDEFINED_PROPERTY (skin 0's joints, camera 0's yfov, light
// 0's spot, animation 0's sampler input and output, accessor 1's componentType, bufferView 1's
// byteLength). tinygltf refused all but the first for the whole file.
const char* kChosenScene = "unused_by_the_chosen_scene.gltf";

GltfLoadResult load_scene(const std::string& scene, const std::string& animation = "") {
  GltfLoadParams params{scene};
  params.animation = animation;
  return load_gltf(test::data_path(std::string("conformance/") + kChosenScene), params);
}

TEST(GltfConformance, BrokenObjectsTheChosenSceneDoesNotUseAreWarnings) {
  const GltfLoadResult r = load_scene("");
  EXPECT_EQ(r.scene.scene_name, "good");
  EXPECT_EQ(triangles(r.scene), 1u);
  const std::string ignored = "ignored, as the scene does not use it: ";
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            ignored + "material 1 baseColorTexture refers to texture 9, but the file has no textures",
                            ignored + "accessor 1 has no valid componentType",
                            ignored + "animation 0 sampler 0 has no valid input and output accessors (glTF requires "
                                      "both)",
                            ignored + "bufferView 1 has no valid byteLength",
                            ignored + "camera 0 has no yfov number",
                            ignored + "light 0 is a spot light but has no \"spot\" object",
                            ignored + "material 2 has an emissiveFactor that is not 3 numbers",
                            ignored + "skin 0 has no joints (glTF requires a \"joints\" array of at least one node)"}));
}

TEST(GltfConformance, TheSameObjectsRefuseTheFileWhenTheChosenSceneUsesThem) {
  const std::pair<std::string, std::string> cases[] = {
      {"material", "material 1 baseColorTexture refers to texture 9, but the file has no textures"},
      {"skin", "skin 0 has no joints (glTF requires a \"joints\" array of at least one node)"},
      {"camera", "camera 0 has no yfov number"},
      {"light", "light 0 is a spot light but has no \"spot\" object"},
      {"animation", "animation 0 sampler 0 has no valid input and output accessors (glTF requires both)"},
      // Whichever variant is chosen (none here): every mapped material can be.
      {"variant", "material 2 has an emissiveFactor that is not 3 numbers"}};
  for (const auto& [scene, problem] : cases) {
    try {
      load_scene(scene);
      ADD_FAILURE() << "scene " << scene << " loaded";
    } catch (const SceneLoadError& e) {
      EXPECT_EQ(e.problem(), problem) << "scene " << scene;
    }
  }
}

TEST(GltfConformance, AnAnimationThatDoesNotPlayIsNotUsed) {
  const GltfLoadResult r = load_scene("animation", "none");  // its channel targets node 5, in the scene
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_NE(std::find(r.warnings.begin(), r.warnings.end(),
                      "ignored, as the scene does not use it: animation 0 sampler 0 has no valid input and output "
                      "accessors (glTF requires both)"),
            r.warnings.end());
}

TEST(GltfConformance, PercentEncodedDataUrisAreDecoded) {
  // RFC 2397: buffer 0 holds the triangle percent-encoded ("%00%00...%80%3F"), buffer 1 the same
  // in base64 whose first three characters are escaped ("%41%41%41AAA..."). Validator: valid.
  const GltfLoadResult r = load("percent_encoded_data_uris.gltf");
  const Mesh& mesh = r.scene.meshes.at(0);
  ASSERT_EQ(mesh.primitives.size(), 2u);
  const MeshArray<glm::vec3> triangle = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(mesh.primitives[0].positions, triangle);
  EXPECT_EQ(mesh.primitives[1].positions, triangle);
  EXPECT_EQ(r.warnings, std::vector<std::string>{});
}

// Objects nothing in the chosen scene reaches are read as a whole, and what would refuse a used
// one is a warning. Validator: 7 errors (UNDEFINED_PROPERTY buffer 1's byteLength, INVALID_URI
// buffer 2's ";;base64", CAMERA_ZFAR_LEQUAL_ZNEAR, KHR_LIGHTS_PUNCTUAL_LIGHT_SPOT_ANGLES,
// UNRESOLVED_REFERENCE texture 0's source and mesh 1's material, MESH_PRIMITIVE_TOO_FEW_TEXCOORDS).
TEST(GltfConformance, UnusedObjectsAreReadAsAWholeAndWarnedAbout) {
  const std::string path = test::data_path("conformance/unused_objects_read_as_a_whole.gltf");
  const GltfLoadResult r = load_gltf(path);
  EXPECT_EQ(triangles(r.scene), 1u);
  const std::string ignored = "ignored, as the scene does not use it: ";
  const std::vector<std::string> problems = {
      "texture 0 refers to image 3, but the file has no images",
      "mesh 1 primitive 0 refers to material 5, but the file has 1 material",
      "buffer 1 has no valid byteLength",
      "buffer 2 has a data URI whose header has a parameter '' that is not attribute=value",
      "camera 0 has zfar 1 not beyond its znear 2",
      "light 0 has spot cone angles 0.5 (inner) and 0.25 (outer); glTF requires 0 <= inner < outer <= pi/2"};
  std::vector<std::string> expected;
  for (const std::string& p : problems) expected.push_back(ignored + p);
  EXPECT_EQ(r.warnings, expected);
  // Each scene but the first uses one of them: refused with the same line.
  const char* scenes[] = {"texture", "mesh", "buffer", "data URI", "camera", "light"};
  for (std::size_t i = 0; i < problems.size(); ++i) {
    try {
      load_gltf(path, GltfLoadParams{scenes[i]});
      ADD_FAILURE() << "scene " << scenes[i] << " loaded";
    } catch (const SceneLoadError& e) {
      EXPECT_EQ(e.problem(), problems[i]) << "scene " << scenes[i];
    }
  }
}

// An image's media type must match its bytes (glTF 2.0, images; tools/gltf-validate.js: errors
// INVALID_URI "The declared mediatype does not match the embedded content" for image 0,
// IMAGE_MIME_TYPE_INVALID for images 1 and 2, UNSATISFIED_DEPENDENCY "'mimeType' must be defined"
// for image 3). None is shown: warnings. Image 4, whose types agree, is the one the material shows.
// Shown, each refuses the file (tests/data/malformed/image_*mime_type*.gltf,
// image_data_uri_media_type_mismatch.gltf).
TEST(GltfConformance, ImagesWhoseBytesContradictTheirMediaTypeAreWarningsWhenUnused) {
  const GltfLoadResult r = load("unused_images_of_another_media_type.gltf");
  const std::string ignored = "ignored, as the scene does not use it: image ";
  const std::string rule = " (glTF requires the media type to match the image data)";
  EXPECT_EQ(r.warnings, (std::vector<std::string>{
                            ignored + "0 (data URI) is a PNG image, but its data URI declares 'image/gif'" + rule,
                            ignored + "1 (data URI) is a PNG image, but its mimeType is 'image/jpeg'" + rule,
                            ignored + "2 (bufferView 2) is a PNG image, but its mimeType is 'image/jpeg'" + rule,
                            ignored + "3 is in bufferView 2 but has no mimeType (glTF requires one for an image "
                                      "in a bufferView)"}));
  const int shown = r.scene.materials.at(0).base_color_texture.image;
  ASSERT_GE(shown, 0);
  EXPECT_EQ(r.scene.images.at(shown).width, 1);  // the 1x1 red PNG, decoded
}

// Rules the validator checks and tinygltf does not (scene_io/validation/gltf_rules.*), broken in objects
// the scene does not use, and in the file as a whole. tools/gltf-validate.js: 32 errors, one per
// warning below (NON_REQUIRED_EXTENSION, ASSET_MIN_VERSION_GREATER_THAN_VERSION, EMPTY_ENTITY
// twice, ACCESSOR_NORMALIZED_INVALID, ANIMATION_DUPLICATE_TARGETS, MESH_PRIMITIVE_ACCESSOR_UNALIGNED,
// BUFFER_VIEW_TARGET_OVERRIDE, ANIMATION_SAMPLER_INPUT_ACCESSOR_TOO_FEW_ELEMENTS, ...,
// IMAGE_NON_ENABLED_MIME_TYPE).
// Used, each refuses the file (tests/data/malformed/: position_without_bounds.gltf,
// joints_without_weights.gltf, morph_target_without_base_attribute.gltf, node_matrix_not_trs.gltf,
// emissive_strength_negative.gltf, extension_not_declared.gltf,
// vertex_accessors_share_view_without_stride.gltf; skin_joint_not_in_scene.gltf).
TEST(GltfConformance, UnusedObjectsBreakingTheValidatorsRulesAreWarnings) {
  const GltfLoadResult r = load("unused_objects_breaking_validator_rules.gltf");
  EXPECT_EQ(triangles(r.scene), 1u);
  const std::string ignored = "ignored, as the scene does not use it: ", empty = " (glTF requires at least one element "
                                                                                 "where an array is given)";
  EXPECT_EQ(r.warnings,
            (std::vector<std::string>{
                ignored + "material 0 occlusionTexture refers to texture 5, but the file has 1 texture",
                ignored + "material 1: KHR_materials_emissive_strength.emissiveStrength must not be negative",
                ignored + "material 2: KHR_materials_specular.specularFactor must be between 0 and 1",
                "its \"samplers\" array is empty" + empty,
                "node 4 has an empty \"children\" array" + empty,
                "its asset minVersion 2.1 is greater than its version 2.0",
                "its extensionsUsed lists KHR_mesh_quantization, which glTF requires in extensionsRequired too",
                ignored + "accessor 1 is normalized, but its componentType 5126 is not a byte or short type; only "
                          "those can be",
                ignored + "animation 0 channels 0 and 1 both animate node 5's translation",
                ignored + "animation 1 channel 0 animates the weights of node 5, which has no mesh with morph targets",
                ignored + "animation 2 sampler 0 input accessor 14 has no min and max (glTF requires both)",
                ignored + "animation 3 sampler 0 is CUBICSPLINE with 1 keyframe; glTF requires at least 2",
                ignored + "bufferView 1 has a byteStride but holds indices (target 34963); only vertex data has one",
                ignored + "camera 0 has both a \"perspective\" and an \"orthographic\" object; glTF allows only the "
                          "one its type names",
                ignored + "image 0 (bufferView 15) is a WebP image, but extensionsUsed does not declare "
                          "EXT_texture_webp (glTF requires it for a WebP image)",
                ignored + "material 3 has extension KHR_materials_emissive_strength in its pbrMetallicRoughness, "
                          "where glTF does not define it",
                ignored + "mesh 1 primitive 0 POSITION accessor 2 has no min and max (glTF requires both)",
                ignored + "mesh 10 primitive 0 morph target 0 POSITION accessor 9 has 2 elements, but the "
                          "primitive's POSITION has 3",
                ignored + "mesh 11 uses bufferView 9 for both vertex attributes and indices (primitive 0); glTF "
                          "requires separate views",
                ignored + "mesh 2 primitive 0 has 1 JOINTS_n and 0 WEIGHTS_n attributes; glTF requires as many of "
                          "each",
                ignored + "mesh 3 primitive 0 morph target 0 has NORMAL, which the primitive's attributes lack",
                ignored + "mesh 4 primitives 0 and 1 have 1 and 0 morph targets; glTF requires the same number",
                ignored + "mesh 5 has 2 weights but 1 morph target",
                ignored + "mesh 6 primitive 0 _ID accessor 4 has componentType UNSIGNED_INT (5125), which glTF "
                          "allows only for indices",
                ignored + "mesh 7 primitive 0 COLOR_0 accessor 5 has byteOffset 2 in its bufferView, not a multiple "
                          "of 4 (glTF requires one for vertex data)",
                ignored + "mesh 8 reads accessors 6 and 7 from bufferView 6, which has no byteStride (glTF requires "
                          "one when vertex accessors share a view)",
                ignored + "mesh 9 primitive 0 indices accessor 8 is in bufferView 7, which has a byteStride (glTF "
                          "forbids one for indices)",
                ignored + "node 1 has a matrix whose last row is not 0, 0, 0, 1, so not a translation, rotation and "
                          "scale (glTF requires one)",
                ignored + "node 2 has a skin but no mesh",
                ignored + "node 3 has morph weights but no mesh",
                ignored + "skin 0's joints 4 and 5 have no common root (glTF requires one)",
                ignored + "texture 0 has extension EXT_example_undeclared, which extensionsUsed does not declare "
                          "(glTF requires it there)"}));
}

// Keyframe times whose accessor has no bufferView are zeros, which the validator accepts (0
// errors) although they do not increase; the node they move shows a mesh, so the animation is
// used. It loads, its two keys at 0.
TEST(GltfConformance, KeyframeTimesWithoutABufferViewLoad) {
  const GltfLoadResult r = load("keyframe_times_without_bufferview.gltf");
  EXPECT_EQ(triangles(r.scene), 1u);
  EXPECT_EQ(r.warnings, std::vector<std::string>{});
  EXPECT_EQ(r.animations.at(0).channels.at(0).times, (std::vector<float>{0, 0}));
}

TEST(GltfConformance, InfoListsTheWarnings) {
  const std::string path = test::data_path("conformance/unused_invalid_objects.gltf");
  const test::CommandResult r = test::run_command(test::tessera_exe() + " info '" + path + "'");
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.err.find("tessera: warning: " + path + ": ignored, as the scene does not use it: mesh 1 has"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace tessera
