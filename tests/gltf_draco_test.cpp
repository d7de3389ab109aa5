// KHR_draco_mesh_compression: every attribute the extension maps comes out in its accessor's
// component type and normalisation. A 4x4-vertex grid with known values in each attribute is
// encoded losslessly (no quantisation) with libdraco here, wrapped in a glTF whose accessors
// declare float, normalized UNSIGNED_SHORT/UNSIGNED_BYTE and plain UNSIGNED_BYTE types, and read
// back through the loader.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <set>

#include <draco/compression/decode.h>
#include <draco/compression/encode.h>
#include <draco/mesh/triangle_soup_mesh_builder.h>
#include <fmt/format.h>

#include "scene_io/gltf_loader.h"
#include "scene_io/nodes/gltf_mesh.h"
#include "scene_io/base/load_error.h"
#include "tests/test_support.h"

namespace tessera {
namespace {

constexpr int kSide = 4;  // vertices per grid side

// The values vertex v (0..15) carries, as the encoder is given them.
struct Vertex {
  std::array<float, 3> position, normal;
  std::array<float, 4> tangent;
  std::array<std::uint16_t, 2> uv;  // normalized in the accessor and in Draco
  std::array<std::uint8_t, 4> color;  // normalized
  std::array<std::uint8_t, 4> joints;  // plain integers
  std::array<float, 4> weights;  // float in Draco, normalized UNSIGNED_BYTE in the accessor: k / 255
};

Vertex vertex(int v) {
  const float x = static_cast<float>(v % kSide), y = static_cast<float>(v / kSide);
  Vertex out;
  out.position = {x, y, 0.125f * x * y};
  out.normal = {0.0f, 0.6f, 0.8f};
  out.tangent = {1.0f, 0.0f, 0.0f, v % 2 ? 1.0f : -1.0f};
  out.uv = {static_cast<std::uint16_t>(v * 4000), static_cast<std::uint16_t>(65535 - v * 3000)};
  out.color = {static_cast<std::uint8_t>(v * 15), static_cast<std::uint8_t>(255 - v * 10), static_cast<std::uint8_t>(7 * v), 200};
  out.joints = {static_cast<std::uint8_t>(v % 4), static_cast<std::uint8_t>((v + 1) % 4), 0, 0};
  out.weights = {static_cast<float>(255 - 5 * v) / 255.0f, static_cast<float>(5 * v) / 255.0f, 0.0f, 0.0f};
  return out;
}

std::vector<std::array<int, 3>> grid_faces() {
  std::vector<std::array<int, 3>> faces;
  for (int y = 0; y + 1 < kSide; ++y)
    for (int x = 0; x + 1 < kSide; ++x) {
      const int v = y * kSide + x;
      faces.push_back({v, v + 1, v + kSide + 1});
      faces.push_back({v, v + kSide + 1, v + kSide});
    }
  return faces;
}

struct Encoded {
  std::vector<std::uint8_t> bytes;
  std::map<std::string, int> ids;  // glTF attribute name -> Draco unique id
  std::size_t points = 0;
};

Encoded encode_grid() {
  const auto faces = grid_faces();
  draco::TriangleSoupMeshBuilder b;
  b.Start(static_cast<int>(faces.size()));
  using GA = draco::GeometryAttribute;
  const int pos = b.AddAttribute(GA::POSITION, 3, draco::DT_FLOAT32);
  const int nrm = b.AddAttribute(GA::NORMAL, 3, draco::DT_FLOAT32);
  const int tan = b.AddAttribute(GA::GENERIC, 4, draco::DT_FLOAT32);
  const int uv = b.AddAttribute(GA::TEX_COORD, 2, draco::DT_UINT16, true);
  const int col = b.AddAttribute(GA::COLOR, 4, draco::DT_UINT8, true);
  const int jnt = b.AddAttribute(GA::GENERIC, 4, draco::DT_UINT8);
  const int wgt = b.AddAttribute(GA::GENERIC, 4, draco::DT_FLOAT32);
  for (std::size_t f = 0; f < faces.size(); ++f) {
    const Vertex c[3] = {vertex(faces[f][0]), vertex(faces[f][1]), vertex(faces[f][2])};
    const draco::FaceIndex fi(static_cast<std::uint32_t>(f));
    b.SetAttributeValuesForFace(pos, fi, c[0].position.data(), c[1].position.data(), c[2].position.data());
    b.SetAttributeValuesForFace(nrm, fi, c[0].normal.data(), c[1].normal.data(), c[2].normal.data());
    b.SetAttributeValuesForFace(tan, fi, c[0].tangent.data(), c[1].tangent.data(), c[2].tangent.data());
    b.SetAttributeValuesForFace(uv, fi, c[0].uv.data(), c[1].uv.data(), c[2].uv.data());
    b.SetAttributeValuesForFace(col, fi, c[0].color.data(), c[1].color.data(), c[2].color.data());
    b.SetAttributeValuesForFace(jnt, fi, c[0].joints.data(), c[1].joints.data(), c[2].joints.data());
    b.SetAttributeValuesForFace(wgt, fi, c[0].weights.data(), c[1].weights.data(), c[2].weights.data());
  }
  std::unique_ptr<draco::Mesh> mesh = b.Finalize();
  draco::Encoder encoder;  // no quantisation: every value comes back exactly
  draco::EncoderBuffer out;
  EXPECT_TRUE(encoder.EncodeMeshToBuffer(*mesh, &out).ok());
  Encoded e;
  e.bytes.assign(out.data(), out.data() + out.size());
  const char* names[] = {"POSITION", "NORMAL", "TANGENT", "TEXCOORD_0", "COLOR_0", "JOINTS_0", "WEIGHTS_0"};
  const int atts[] = {pos, nrm, tan, uv, col, jnt, wgt};
  for (int i = 0; i < 7; ++i) e.ids[names[i]] = static_cast<int>(mesh->attribute(atts[i])->unique_id());
  draco::DecoderBuffer in;  // the decoded point count, which the accessors must state
  in.Init(reinterpret_cast<const char*>(e.bytes.data()), e.bytes.size());
  draco::Decoder decoder;
  e.points = decoder.DecodeMeshFromBuffer(&in).value()->num_points();
  return e;
}

// One accessor per attribute, in the types a glTF exporter declares for them.
std::string grid_gltf(const Encoded& e) {
  struct Acc {
    const char* name;
    int component_type;
    const char* type;
    bool normalized;
  };
  const Acc accs[] = {{"POSITION", 5126, "VEC3", false},  {"NORMAL", 5126, "VEC3", false},
                      {"TANGENT", 5126, "VEC4", false},   {"TEXCOORD_0", 5123, "VEC2", true},
                      {"COLOR_0", 5121, "VEC4", true},    {"JOINTS_0", 5121, "VEC4", false},
                      {"WEIGHTS_0", 5121, "VEC4", true}};
  std::string accessors = fmt::format(R"({{"componentType":5125,"count":{},"type":"SCALAR"}})", grid_faces().size() * 3);
  std::array<float, 3> lo = vertex(0).position, hi = lo;  // POSITION's bounds, which glTF requires
  for (int v = 0; v < kSide * kSide; ++v)
    for (int c = 0; c < 3; ++c) lo[c] = std::min(lo[c], vertex(v).position[c]), hi[c] = std::max(hi[c], vertex(v).position[c]);
  const std::string bounds = fmt::format(R"(,"min":[{},{},{}],"max":[{},{},{}])", lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]);
  std::string attributes, mapped;
  for (int i = 0; i < 7; ++i) {
    accessors += fmt::format(R"(,{{"componentType":{},"count":{},"type":"{}"{}{}}})", accs[i].component_type, e.points,
                             accs[i].type, accs[i].normalized ? R"(,"normalized":true)" : "", i == 0 ? bounds : "");
    attributes += fmt::format(R"({}"{}":{})", i ? "," : "", accs[i].name, i + 1);
    mapped += fmt::format(R"({}"{}":{})", i ? "," : "", accs[i].name, e.ids.at(accs[i].name));
  }
  return fmt::format(
      R"({{"asset":{{"version":"2.0"}},"extensionsUsed":["KHR_draco_mesh_compression"],
  "extensionsRequired":["KHR_draco_mesh_compression"],"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
  "meshes":[{{"primitives":[{{"attributes":{{{}}},"indices":0,
    "extensions":{{"KHR_draco_mesh_compression":{{"bufferView":0,"attributes":{{{}}}}}}}}}]}}],
  "accessors":[{}],"bufferViews":[{{"buffer":0,"byteLength":{}}}],
  "buffers":[{{"byteLength":{},"uri":"data:application/octet-stream;base64,{}"}}]}})",
      attributes, mapped, accessors, e.bytes.size(), e.bytes.size(), test::base64(e.bytes));
}

std::vector<float> floats_of(const Vertex& v, const std::string& name) {
  auto f = [](const auto& a, float scale) {
    std::vector<float> out;
    for (auto x : a) out.push_back(static_cast<float>(x) / scale);
    return out;
  };
  if (name == "POSITION") return f(v.position, 1);
  if (name == "NORMAL") return f(v.normal, 1);
  if (name == "TANGENT") return f(v.tangent, 1);
  if (name == "TEXCOORD_0") return f(v.uv, 65535);
  if (name == "COLOR_0") return f(v.color, 255);
  if (name == "JOINTS_0") return f(v.joints, 1);
  return f(v.weights, 1);
}

TEST(GltfDraco, EveryMappedAttributeComesOutInItsAccessorsType) {
  const Encoded e = encode_grid();
  ASSERT_GE(e.points, 16u);
  const std::string json = grid_gltf(e);
  const GltfDocument doc = read_gltf_from_memory(std::vector<std::uint8_t>(json.begin(), json.end()), "grid.gltf", "/nonexistent");
  const AccessorReader reader{doc.model, doc.path};
  const auto& attributes = doc.model.meshes[0].primitives[0].attributes;
  const std::vector<float> positions = reader.floats(attributes.at("POSITION"), 3, "POSITION");
  std::vector<int> original(e.points);  // decoded point -> grid vertex, by its exact position
  for (std::size_t i = 0; i < e.points; ++i) {
    original[i] = -1;
    for (int v = 0; v < kSide * kSide; ++v)
      if (std::equal(positions.begin() + 3 * i, positions.begin() + 3 * i + 3, vertex(v).position.begin())) original[i] = v;
    ASSERT_GE(original[i], 0) << "point " << i;
  }
  for (const char* name : {"NORMAL", "TANGENT", "TEXCOORD_0", "COLOR_0", "JOINTS_0", "WEIGHTS_0"}) {
    const tinygltf::Accessor& acc = doc.model.accessors[attributes.at(name)];
    const int n = name == std::string("NORMAL") ? 3 : name == std::string("TEXCOORD_0") ? 2 : 4;
    EXPECT_EQ(doc.model.bufferViews[acc.bufferView].byteLength, e.points * n * gltf_component_size(acc.componentType)) << name;
    const std::vector<float> got = reader.floats(attributes.at(name), n, name);
    for (std::size_t i = 0; i < e.points; ++i) {
      const std::vector<float> want = floats_of(vertex(original[i]), name);
      for (int c = 0; c < n; ++c) EXPECT_FLOAT_EQ(got[i * n + c], want[c]) << name << " of point " << i << " [" << c << "]";
    }
  }
  // The triangles, as grid vertices with their winding, are the grid's.
  std::vector<std::string> warnings;
  const TriangleMesh mesh = *convert_primitive(reader, doc.model.meshes[0].primitives[0], "grid", warnings);
  auto canonical = [](std::array<int, 3> t) {
    std::rotate(t.begin(), std::min_element(t.begin(), t.end()), t.end());
    return t;
  };
  std::set<std::array<int, 3>> want, got;
  for (const auto& f : grid_faces()) want.insert(canonical(f));
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3)
    got.insert(canonical({original[mesh.indices[t]], original[mesh.indices[t + 1]], original[mesh.indices[t + 2]]}));
  EXPECT_EQ(mesh.indices.size(), grid_faces().size() * 3);
  EXPECT_EQ(got, want);
}

// An accessor whose count differs from the stream's point count is refused, naming both.
TEST(GltfDraco, AccessorCountOtherThanTheStreamsIsRefused) {
  Encoded e = encode_grid();
  e.points += 1;
  const std::string json = grid_gltf(e);
  try {
    read_gltf_from_memory(std::vector<std::uint8_t>(json.begin(), json.end()), "grid.gltf", "/nonexistent");
    ADD_FAILURE() << "loaded";
  } catch (const SceneLoadError& err) {
    EXPECT_NE(err.problem().find("mesh 0 primitive 0 (KHR_draco_mesh_compression) decodes"), std::string::npos)
        << err.problem();
  }
}

}  // namespace
}  // namespace tessera
