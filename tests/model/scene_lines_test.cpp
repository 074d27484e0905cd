// Scene front end: "lines" objects, mesh "wireframe" and "line_state" (docs/scene-format.md).
// Expected values are written from the format's definition (exact float32 inputs, edge counts of
// simple solids by hand), not from the parser.
#include <gtest/gtest.h>

#include <string>

#include "frontend/scene.hpp"

using namespace fxr;

namespace {

std::string error_of(const std::string& text) {
  try {
    parse_scene(text, "scene.json", "/nonexistent-dir");
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

const char* const kTwoObjects = R"({"version": 1, "viewport": {"width": 8, "height": 8},
  "objects": [
    {"type": "lines", "lines": [[{"pos": [-1, -1, 0.5, 1], "var": [0, 0]}, {"pos": ["0x1.8p-1", 1, 0.25, 2], "var": [1, "0x1p-3"]}]]},
    {"type": "clip", "triangles": [[{"pos": [-1, -1, 0.5, 1], "var": [0, 0]}, {"pos": [1, -1, 0.5, 1], "var": [1, 0]},
                                    {"pos": [0, 1, 0.5, 1], "var": [0, 1]}]]}]})";

// A cube (12 triangles, consistent winding) seen by `camera`, with the given wireframe mode.
std::string cube(const std::string& mode) {
  return R"({"version": 1, "viewport": {"width": 64, "height": 48},
    "camera": {"eye": [2.2, 1.6, 3.0], "target": [0, 0, 0], "up": [0, 1, 0], "fovy_deg": 45, "near": 0.5, "far": 20},
    "objects": [{"type": "mesh", "wireframe": ")" + mode + R"(",
      "positions": [[-1,-1,-1],[1,-1,-1],[1,1,-1],[-1,1,-1],[-1,-1,1],[1,-1,1],[1,1,1],[-1,1,1]],
      "indices": [[0,2,1],[0,3,2],[4,5,6],[4,6,7],[0,1,5],[0,5,4],[3,7,6],[3,6,2],[0,4,7],[0,7,3],[1,2,6],[1,6,5]]}]})";
}

}  // namespace

TEST(SceneLines, LinesObjectParsesExactlyAndIsNumberedAfterTheTriangles) {
  const Scene s = parse_scene(kTwoObjects, "scene.json", ".");
  ASSERT_EQ(s.lines.size(), 1u);
  ASSERT_EQ(s.tris.size(), 1u);
  EXPECT_EQ(s.lines[0].v[1].pos[0], 0.75f);
  EXPECT_EQ(s.lines[0].v[1].pos[3], 2.0f);
  EXPECT_EQ(s.lines[0].v[1].var[1], 0.125f);
  ASSERT_EQ(s.objects.size(), 2u);
  EXPECT_EQ(s.objects[0].kind, "lines");
  EXPECT_EQ(s.objects[0].first_prim, 1u);  // after the one triangle
  EXPECT_EQ(s.objects[0].prim_count, 1u);
  // line_state defaults to the draw state, white.
  EXPECT_EQ(s.line_state.depth_func, s.state.depth_func);
  EXPECT_EQ(s.line_state.num_varyings, 2);
  EXPECT_EQ(s.line_color, 0xffffffffu);
}

TEST(SceneLines, BadLinesNameTheField) {
  const std::string bad3 = R"([[{"pos": [-1, -1, 0.5, 1], "var": [0, 0]}, {"pos": [0, 1, 0.25, 2], "var": [1, 0]}, {"pos": [0, 1, 0.25, 2], "var": [1, 0]}]])";
  const std::string text = R"({"version": 1, "viewport": {"width": 8, "height": 8}, "objects": [{"type": "lines", "lines": )" + bad3 + "}]}";
  EXPECT_NE(error_of(text).find("scene.json: /objects/0/lines/0: expected 2 vertices"), std::string::npos) << error_of(text);
  const std::string nv = R"({"version": 1, "viewport": {"width": 8, "height": 8}, "objects": [{"type": "lines", "lines": [[{"pos": [0, 0, 0, 1], "var": [0]}, {"pos": [0, 0, 0, 1], "var": [0, 0]}]]}]})";
  EXPECT_NE(error_of(nv).find("/objects/0/lines/0/0/var: expected 2 varyings"), std::string::npos) << error_of(nv);
  const std::string ls = R"({"version": 1, "viewport": {"width": 8, "height": 8}, "line_state": {"colour": "#ffffff"}, "objects": []})";
  EXPECT_NE(error_of(ls).find("/line_state/colour: unknown field"), std::string::npos) << error_of(ls);
  const std::string lc = R"({"version": 1, "viewport": {"width": 8, "height": 8}, "line_state": {"color": "red"}, "objects": []})";
  EXPECT_NE(error_of(lc).find("/line_state/color: expected a colour"), std::string::npos) << error_of(lc);
  const std::string wf = R"({"version": 1, "viewport": {"width": 8, "height": 8}, "objects": [{"type": "mesh", "wireframe": "all", "positions": [[0,0,0],[1,0,0],[0,1,0]], "indices": [[0,1,2]]}]})";
  EXPECT_NE(error_of(wf).find("/objects/0/wireframe"), std::string::npos) << error_of(wf);
}

TEST(SceneLines, LineStateOverridesDepthAndColour) {
  const Scene s = parse_scene(R"({"version": 1, "viewport": {"width": 8, "height": 8},
      "state": {"depth_func": "less", "interp": "affine"},
      "line_state": {"depth_func": "always", "depth_write": false, "color": "#102030"}, "objects": []})",
                              "scene.json", ".");
  EXPECT_EQ(s.line_state.depth_func, DepthFunc::Always);
  EXPECT_FALSE(s.line_state.depth_write);
  EXPECT_EQ(s.line_state.interp, InterpMode::Affine);  // not a line_state field: from state
  EXPECT_EQ(s.state.depth_func, DepthFunc::Less);
  EXPECT_NE(s.line_color, 0xffffffffu);
}

// A cube has 12 edges and 6 face diagonals: 18 unique edges of its 12 triangles. Seen from a
// corner direction (three faces visible) its outline is a hexagon: 6 silhouette edges, and no
// diagonal (both triangles of a face face the same way).
TEST(SceneLines, CubeWireframeEdgesAndSilhouette) {
  const Scene e = parse_scene(cube("edges"), "scene.json", ".");
  EXPECT_EQ(e.tris.size(), 12u);
  EXPECT_EQ(e.lines.size(), 18u);
  const Scene s = parse_scene(cube("silhouette"), "scene.json", ".");
  EXPECT_EQ(s.lines.size(), 6u);
  const Scene n = parse_scene(cube("none"), "scene.json", ".");
  EXPECT_EQ(n.lines.size(), 0u);
  // Every line endpoint is exactly a vertex the triangles emitted (same transform, same rounding).
  for (const ClipLine& l : e.lines)
    for (const ClipVertex& v : l.v) {
      bool found = false;
      for (const ClipTriangle& t : e.tris)
        for (const ClipVertex& w : t.v)
          found |= v.pos[0] == w.pos[0] && v.pos[1] == w.pos[1] && v.pos[2] == w.pos[2] && v.pos[3] == w.pos[3] &&
                   v.var[0] == w.var[0] && v.var[1] == w.var[1];
      EXPECT_TRUE(found);
    }
}

TEST(SceneLines, DefaultSceneWireframeVariant) {
  SceneOptions o;
  o.no_optional = true;  // the face only: its 4 edges and the diagonal
  const Scene plain = default_scene(o);
  EXPECT_TRUE(plain.lines.empty());
  o.wireframe = true;
  const Scene w = default_scene(o);
  EXPECT_EQ(w.lines.size(), 5u);
  EXPECT_EQ(w.tris.size(), plain.tris.size());
  EXPECT_EQ(w.line_state.depth_func, DepthFunc::Always);
  EXPECT_FALSE(w.line_state.depth_write);
}
