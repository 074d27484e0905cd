// Scene front end: parsing, errors naming file and field, hex floats, transforms, texgen.
// Expected values are computed by hand here (or from the C library / IEEE facts), never
// copied from the code under test.
#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "frontend/scene.hpp"

using namespace fxr;

namespace {

// A minimal valid scene with one explicit clip triangle; `extra` is spliced into the root.
std::string clip_scene(const std::string& extra = "", const std::string& v2pos = "[0, 1, 0.5, 1]") {
  return R"({"version": 1, "viewport": {"width": 8, "height": 8}, )" + extra +
         R"( "objects": [{"type": "clip", "triangles": [[
             {"pos": [-1, -1, 0.5, 1], "var": [0, 0]},
             {"pos": [1, -1, 0.5, 1], "var": [1, 0]},
             {"pos": )" + v2pos + R"(, "var": [0, 1]}]]}]})";
}

// Parses `text` and returns the error message ("" when it parsed).
std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "scene.json", "/nonexistent-dir");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_ERROR_HAS(text, needle)                                         \
  do {                                                                         \
    const std::string msg_ = error_of(text);                                   \
    EXPECT_NE(msg_.find(needle), std::string::npos) << "message: " << msg_;    \
    EXPECT_EQ(msg_.rfind("scene.json", 0), 0u) << "message: " << msg_;         \
  } while (0)

}  // namespace

TEST(Scene, MinimalClipSceneParsesWithExactBits) {
  const Scene s = parse_scene(clip_scene(), "scene.json", ".");
  ASSERT_EQ(s.tris.size(), 1u);
  EXPECT_EQ(s.state.viewport_w, 8);
  EXPECT_EQ(s.state.num_varyings, 2);
  EXPECT_EQ(s.tris[0].v[1].pos[0], 1.0f);
  EXPECT_EQ(s.tris[0].v[2].var[1], 1.0f);
}

TEST(Scene, MalformedMissingFieldNamesIt) {
  EXPECT_ERROR_HAS(R"({"version": 1, "objects": []})", "scene.json: /viewport: missing field");
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": 4}, "objects": []})", "/viewport/height: missing field");
  EXPECT_ERROR_HAS(R"({"viewport": {"width": 4, "height": 4}, "objects": []})", "/version: missing field");
}

TEST(Scene, MalformedWrongTypeNamesIt) {
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": "8", "height": 8}, "objects": []})",
                   "scene.json: /viewport/width: expected an integer");
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": 8, "height": 8}, "objects": {}})",
                   "/objects: expected an array");
  EXPECT_ERROR_HAS(clip_scene(R"("state": {"depth_test": 1},)"), "/state/depth_test: expected true or false");
  EXPECT_ERROR_HAS(clip_scene(R"("state": {"cull": "sideways"},)"), "/state/cull: 'sideways' is not one of");
}

TEST(Scene, TruncatedJsonGivesLineAndColumn) {
  const std::string text = "{\"version\": 1,\n  \"viewport\": {\"width\": 8,\n";
  const std::string msg = error_of(text);
  // Truncated after line 2: the error is reported at line 3 (end of input), column 1.
  EXPECT_EQ(msg.rfind("scene.json:3:1: JSON parse error", 0), 0u) << msg;
  EXPECT_NE(error_of("{\"version\": 1,, }").find("scene.json:1:"), std::string::npos);
}

TEST(Scene, WrongVersionIsRejected) {
  EXPECT_ERROR_HAS(R"({"version": 2, "viewport": {"width": 8, "height": 8}, "objects": []})",
                   "scene.json: /version: 2 is not supported");
}

TEST(Scene, UnknownFieldIsRejected) {
  EXPECT_ERROR_HAS(clip_scene(R"("colour": "#000000",)"), "scene.json: /colour: unknown field");
  EXPECT_ERROR_HAS(clip_scene(R"("camera": {"eye": [0,0,1], "target": [0,0,0], "fovy_deg": 45, "near": 1, "far": 2, "zoom": 2},)"),
                   "/camera/zoom: unknown field");
}

TEST(Scene, BadHexFloatNamesTheComponent) {
  EXPECT_ERROR_HAS(clip_scene("", R"([0, "0x1.8q+1", 0.5, 1])"), "scene.json: /objects/0/triangles/0/2/pos/1: bad number");
  // 1 + 2^-24 needs 25 significand bits: not a float32.
  EXPECT_ERROR_HAS(clip_scene("", R"([0, "0x1.000001p+0", 0.5, 1])"), "/objects/0/triangles/0/2/pos/1: hex float");
  EXPECT_ERROR_HAS(clip_scene("", R"([0, 1, 0.5])"), "/objects/0/triangles/0/2/pos: expected 4 numbers");
  EXPECT_ERROR_HAS(clip_scene("", R"([0, "bits:7fc0", 0.5, 1])"), "/objects/0/triangles/0/2/pos/1: bad bit pattern");
}

// Colours are "#rrggbb" with lowercase digits (docs/scene-format.md): uppercase is an error
// naming the file and the field, with the reason; every colour field.
TEST(Scene, UppercaseColourIsAnErrorNamingTheField) {
  EXPECT_ERROR_HAS(clip_scene(R"("background": "#10A0ff",)"),
                   "scene.json: /background: expected a colour \"#rrggbb\" (6 lowercase hex digits), got");
  EXPECT_ERROR_HAS(clip_scene(R"("background": "#10A0ff",)"), "(uppercase digits: write them in lowercase)");
  EXPECT_ERROR_HAS(clip_scene(R"("texture": {"kind": "checker", "colors": ["#ffffff", "#ABCDEF"]},)"),
                   "scene.json: /texture/colors/1: expected a colour");
  EXPECT_ERROR_HAS(clip_scene(R"("line_state": {"color": "#FFFFFF"},)"), "scene.json: /line_state/color: expected a colour");
  EXPECT_ERROR_HAS(clip_scene(R"("background": "#10a0f",)"), "/background: expected a colour");
  EXPECT_EQ(error_of(clip_scene(R"("background": "#10a0f",)")).find("uppercase"), std::string::npos);
  EXPECT_EQ(error_of(clip_scene(R"("background": "#10a0ff", "texture": {"kind": "checker", "colors": ["#ffffff", "#abcdef"]},)")), "");
}

TEST(Scene, WrongVaryingCountNamesIt) {
  EXPECT_ERROR_HAS(clip_scene(R"("varyings": {"count": 3},)"), "/objects/0/triangles/0/0/var: expected 3 varyings");
}

TEST(Scene, MissingObjFileNamesFieldAndPath) {
  const std::string text = R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "objects": [{"type": "mesh", "obj": "no_such_mesh.obj"}]})";
  EXPECT_ERROR_HAS(text, "scene.json: /objects/0/obj: cannot open OBJ file '/nonexistent-dir/no_such_mesh.obj'");
  // Marked optional: a note instead of an error, and no triangles.
  const std::string opt = R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "objects": [{"type": "mesh", "obj": "no_such_mesh.obj", "optional": true}]})";
  const Scene s = parse_scene(opt, "scene.json", ".");
  EXPECT_TRUE(s.tris.empty());
  ASSERT_EQ(s.notes.size(), 1u);
  EXPECT_NE(s.notes[0].find("not found"), std::string::npos);
}

TEST(Scene, ModelMatrixNeeds16Numbers) {
  const std::string text = R"({"version": 1, "viewport": {"width": 8, "height": 8}, "objects": [
      {"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]]},
      {"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]]},
      {"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]],
       "model": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0]}]})";
  EXPECT_ERROR_HAS(text, "scene.json: /objects/2/model: expected 16 numbers");
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": 8, "height": 8}, "objects": [
      {"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,3]]}]})",
                   "/objects/0/indices/0/2: 3 is outside [0, 2]");
}

TEST(Scene, ConfigOverridesGoThroughConfigFromJson) {
  const Scene s = parse_scene(clip_scene(R"("config": {"raster": {"subpixel_bits": 4}},)"), "scene.json", ".");
  EXPECT_EQ(s.config.raster.subpixel_bits, 4);
  EXPECT_ERROR_HAS(clip_scene(R"("config": {"raster": {"subpixel_bits": 99}},)"), "/config: raster: field 'subpixel_bits'");
  EXPECT_ERROR_HAS(clip_scene(R"("config": {"rastr": {}},)"), "unknown field 'rastr'");
}

TEST(Scene, HexFloatKnownValues) {
  const nlohmann::json j = {"0x1.8p+1", "-0x1p-149", "0x1.fffffep+127", "0x1p-126", "bits:7fc00001", "-0", "0.1"};
  EXPECT_EQ(f32_bits(parse_f32(j[0], "f", "/0")), 0x40400000u);  // 3.0
  EXPECT_EQ(f32_bits(parse_f32(j[1], "f", "/1")), 0x80000001u);  // −(smallest denormal)
  EXPECT_EQ(f32_bits(parse_f32(j[2], "f", "/2")), 0x7f7fffffu);  // FLT_MAX
  EXPECT_EQ(f32_bits(parse_f32(j[3], "f", "/3")), 0x00800000u);  // FLT_MIN
  EXPECT_EQ(f32_bits(parse_f32(j[4], "f", "/4")), 0x7fc00001u);  // NaN payload kept
  EXPECT_EQ(f32_bits(parse_f32(j[5], "f", "/5")), 0x80000000u);  // −0 kept
  EXPECT_EQ(f32_bits(parse_f32(j[6], "f", "/6")), 0x3dcccccdu);  // 0.1 rounded to nearest once
  EXPECT_EQ(f32_to_hex(3.0f), "0x1.8p+1");
  EXPECT_EQ(f32_to_hex(f32_from_bits(0x80000001u)), "-0x1p-149");
}

TEST(Scene, HexFloatRoundTripIsExactForAllClasses) {
  std::mt19937_64 rng(20261121);
  std::vector<uint32_t> bits = {0x00000000u, 0x80000000u, 0x00000001u, 0x007fffffu, 0x00800000u,
                                0x7f7fffffu, 0xff7fffffu, 0x3f800000u, 0x3f800001u, 0x7f800000u, 0xff800000u};
  for (int i = 0; i < 20000; ++i) bits.push_back((uint32_t)rng());
  for (uint32_t b : bits) {
    const float f = f32_from_bits(b);
    if (std::isnan(f)) continue;  // NaN text does not carry the payload (use "bits:")
    const float g = parse_f32(nlohmann::json(f32_to_hex(f)), "f", "/x");
    ASSERT_EQ(f32_bits(g), b) << f32_to_hex(f);
  }
}

TEST(Scene, CameraLookAtPerspectiveMatchesHandComputation) {
  // Eye on +z at distance 5 looking at the origin, fovy 90° (cot = 1), aspect 1, near 1, far 10.
  // RH, depth 0..1: z_c = f/(n−f)·z_e − f·n/(f−n), w_c = −z_e. The origin has z_e = −5:
  // z_c = 50/9 − 10/9 = 40/9, w_c = 5. Point (1, 0, 0): x_c = 1.
  const std::string text = R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "camera": {"eye": [0, 0, 5], "target": [0, 0, 0], "up": [0, 1, 0], "fovy_deg": 90, "near": 1, "far": 10},
      "objects": [{"type": "mesh", "positions": [[0,0,0],[1,0,0],[0,2,0]], "indices": [[0,1,2]]}]})";
  const Scene s = parse_scene(text, "scene.json", ".");
  ASSERT_EQ(s.tris.size(), 1u);
  const ClipVertex& a = s.tris[0].v[0];
  EXPECT_EQ(a.pos[0], 0.0f);
  EXPECT_EQ(a.pos[1], 0.0f);
  EXPECT_EQ(a.pos[2], (float)(40.0 / 9.0));
  EXPECT_EQ(a.pos[3], 5.0f);
  EXPECT_EQ(s.tris[0].v[1].pos[0], 1.0f);
  EXPECT_EQ(s.tris[0].v[2].pos[1], 2.0f);
}

TEST(Scene, ExplicitMatricesAreRowMajor) {
  // Projection that copies x, y, z and puts w = 2 + x (row 3 = [1 0 0 2]); model translates x by 1.
  const std::string text = R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "camera": {"view": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1], "projection": [1,0,0,0, 0,1,0,0, 0,0,1,0, 1,0,0,2]},
      "objects": [{"type": "mesh", "positions": [[0,0,0.25],[1,0,0],[0,1,0]], "indices": [[0,1,2]],
                   "model": [1,0,0,1, 0,1,0,0, 0,0,1,0, 0,0,0,1]}]})";
  const Scene s = parse_scene(text, "scene.json", ".");
  const ClipVertex& a = s.tris[0].v[0];  // object (0, 0, 0.25) → world (1, 0, 0.25) → w = 3
  EXPECT_EQ(a.pos[0], 1.0f);
  EXPECT_EQ(a.pos[2], 0.25f);
  EXPECT_EQ(a.pos[3], 3.0f);
}

TEST(Texgen, PlanarSphericalCylindricalMatchHandValues) {
  const double pi = 3.14159265358979323846;
  auto near = [](glm::dvec2 a, double u, double v) {
    EXPECT_NEAR(a.x, u, 1e-15);
    EXPECT_NEAR(a.y, v, 1e-15);
  };
  near(texgen(TexGen::Planar, {0.5, -0.5, 0.3}), 0.75, 0.25);
  // Spherical: +y direction: longitude atan2(1, 0) = π/2 → u = 3/4; on the equator v = 1/2.
  near(texgen(TexGen::Spherical, {0, 1, 0}), 0.75, 0.5);
  near(texgen(TexGen::Spherical, {0, 0, 2}), 0.5, 1.0);     // north pole: acos(1) = 0 → v = 1
  near(texgen(TexGen::Spherical, {0, 0, -1}), 0.5, 0.0);    // south pole
  near(texgen(TexGen::Spherical, {1, 0, 1}), 0.5, 0.75);    // 45° above the equator: v = (π − π/4)/π
  // Cylindrical: (1, 0, −0.5): u = (π + 0)/2π = 1/2, v = (1 − 0.5)/2.
  near(texgen(TexGen::Cylindrical, {1, 0, -0.5}), 0.5, 0.25);
  near(texgen(TexGen::Cylindrical, {0, -1, 1}), (pi - pi / 2) / (2 * pi), 1.0);
}

TEST(Texgen, CubeFollowsTheOpenGLFaceTable) {
  // OpenGL face table (docs/references.md#seed-002-cube):
  // +z: (sc, tc) = (+x, −y); −x: (+z, −y); +y: (+x, +z).
  // s = (1 + sc/|ma|)/2; atlas: face f at column f % 3, row f / 3 (+x, −x, +y, −y, +z, −z).
  {
    const double s = (1 + 0.2 / 0.9) / 2, t = (1 + 0.3 / 0.9) / 2;  // +z face = 4: column 1, row 1
    const glm::dvec2 uv = texgen(TexGen::Cube, {0.2, -0.3, 0.9});
    EXPECT_NEAR(uv.x, (1 + s) / 3, 1e-15);
    EXPECT_NEAR(uv.y, (1 + t) / 2, 1e-15);
  }
  {
    const double s = (1 + 0.4 / 0.8) / 2, t = (1 - 0.1 / 0.8) / 2;  // −x face = 1: column 1, row 0
    const glm::dvec2 uv = texgen(TexGen::Cube, {-0.8, 0.1, 0.4});
    EXPECT_NEAR(uv.x, (1 + s) / 3, 1e-15);
    EXPECT_NEAR(uv.y, t / 2, 1e-15);
  }
  {
    const double s = (1 + 0.5 / 1.0) / 2, t = (1 + 0.25) / 2;  // +y face = 2: column 2, row 0
    const glm::dvec2 uv = texgen(TexGen::Cube, {0.5, 1.0, 0.25});
    EXPECT_NEAR(uv.x, (2 + s) / 3, 1e-15);
    EXPECT_NEAR(uv.y, t / 2, 1e-15);
  }
}

TEST(Texgen, SceneAppliesPlanarTexgenOnTheBoundingBox) {
  // Box x ∈ [0, 4], y ∈ [0, 2]: centre (2, 1), largest half extent 2. Vertex (4, 2) → q = (1, 0.5)
  // → planar (1, 0.75); then uv_scale 2 and offset 0.5 → (2.5, 2).
  const std::string text = R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "objects": [{"type": "mesh", "positions": [[0,0,0],[4,0,0],[4,2,0]], "indices": [[0,1,2]],
                   "texgen": "planar", "uv_scale": [2, 2], "uv_offset": [0.5, 0.5]}]})";
  const Scene s = parse_scene(text, "scene.json", ".");
  EXPECT_EQ(s.tris[0].v[2].var[0], 2.5f);
  EXPECT_EQ(s.tris[0].v[2].var[1], 2.0f);
  EXPECT_EQ(s.tris[0].v[0].var[0], 0.5f);  // (0, 0) → q = (−1, −0.5) → (0, 0.25) → (0.5, 1)
  EXPECT_EQ(s.tris[0].v[0].var[1], 1.0f);
}

TEST(Scene, DefaultSceneHasTheCheckerFaceAndTheBunnyWhenInstalled) {
  const Scene s = default_scene();
  const bool bunny = std::ifstream("/usr/share/glmark2/models/bunny.obj").good();
  ASSERT_GE(s.objects.size(), 1u);
  EXPECT_EQ(s.objects[0].prim_count, 2u);
  EXPECT_EQ(s.tris.size(), bunny ? 2u + 69666u : 2u);
  EXPECT_EQ(s.notes.empty(), bunny);
  SceneOptions o;
  o.no_optional = true;
  o.width = 64;
  const Scene t = default_scene(o);
  EXPECT_EQ(t.tris.size(), 2u);
  EXPECT_EQ(t.state.viewport_w, 64);
  // Every clip-space vertex of the default scene lies inside the clip volume's depth range.
  for (const auto& tri : s.tris)
    for (const auto& v : tri.v) {
      ASSERT_GT(v.pos[3], 0.0f);
      ASSERT_GE(v.pos[2], 0.0f);
      ASSERT_LE(v.pos[2], v.pos[3]);
    }
}

TEST(Scene, ExampleScenesUnderScenesParse) {
  const char* dir = std::getenv("FXR_SOURCE_DIR");
  if (!dir) GTEST_SKIP() << "FXR_SOURCE_DIR not set";
  for (const char* f : {"checker_quad.json", "bunny.json", "clip_triangles.json", "near_plane.json", "guard_band.json"}) {
    const std::string p = std::string(dir) + "/scenes/" + f;
    EXPECT_NO_THROW(load_scene(p)) << p;
  }
}

TEST(Scene, TextureFilterWrapAndBorderSetTheTextureAddressUnit) {
  const Scene d = parse_scene(R"({"version": 1, "viewport": {"width": 8, "height": 8}, "background": "#102030",
      "objects": []})", "scene.json", "");
  EXPECT_EQ(d.config.tex_addr.filter, TexFilter::Nearest);  // the configuration's defaults
  EXPECT_EQ(d.config.tex_addr.wrap, TexWrap::Repeat);
  EXPECT_EQ(d.texture.border, pack_rgba(0x10, 0x20, 0x30));  // border: the background colour
  const Scene s = parse_scene(R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "texture": {"kind": "checker", "filter": "bilinear", "wrap": "mirrored_repeat", "border": "#ff0000"},
      "objects": []})", "scene.json", "");
  EXPECT_EQ(s.config.tex_addr.filter, TexFilter::Bilinear);
  EXPECT_EQ(s.config.tex_addr.wrap, TexWrap::MirroredRepeat);
  EXPECT_EQ(s.texture.border, pack_rgba(255, 0, 0));
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "texture": {"kind": "checker", "filter": "trilinear"}, "objects": []})", "scene.json: /texture/filter: ");
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "texture": {"kind": "checker", "wrap": "tile"}, "objects": []})", "scene.json: /texture/wrap: ");
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "texture": {"kind": "checker", "border": "red"}, "objects": []})", "scene.json: /texture/border: ");
}

TEST(Scene, PngTextureLoadsRelativeToTheSceneAndMissingOneNamesTheField) {
  const std::string dir = ::testing::TempDir();
  Image img(4, 2, pack_rgba(9, 8, 7));
  img.at(3, 1) = pack_rgba(200, 100, 50);
  write_png(dir + "/fxr_scene_tex.png", img);
  const std::string text = R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "texture": {"kind": "png", "path": "fxr_scene_tex.png", "wrap": "clamp"}, "objects": []})";
  const Scene s = parse_scene(text, "scene.json", dir);
  EXPECT_EQ(s.texture.image.width, 4);
  EXPECT_EQ(s.texture.image.at(3, 1), pack_rgba(200, 100, 50));
  EXPECT_EQ(s.config.tex_addr.wrap, TexWrap::ClampToEdge);  // "clamp": the seed's clamp
  std::remove((dir + "/fxr_scene_tex.png").c_str());
  EXPECT_ERROR_HAS(R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "texture": {"kind": "png", "path": "none.png"}, "objects": []})", "scene.json: /texture/path: ");
}
