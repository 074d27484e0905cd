// The embedded default scene (README command 1): the example of docs/references.md#seed-000 —
// a checkerboard on one face of a cube seen at an angle, two triangles whose affine
// interpolation visibly breaks along the shared diagonal — and a real mesh, the Stanford bunny
// of glmark2-data, with a texgen checker (optional: left out with --no-bunny, or with a note when
// the package is not installed). The scene's name says which of the two was drawn.
#include <string>

#include "frontend/scene.hpp"

namespace fxr {

namespace {

// The JSON's "objects": the face, then the optional bunny.
constexpr int kFaceObject = 0, kBunnyObject = 1;

}  // namespace

// The "name" is the face's part; default_scene() appends what else was drawn.
const char* default_scene_json() {
  return R"json({
  "version": 1,
  "name": "default: checkerboard face at an angle (seed 000)",
  "viewport": {"width": 512, "height": 384},
  "state": {"cull": "none", "depth_func": "less", "interp": "perspective"},
  "background": "#181820",
  "camera": {"eye": [0.0, 0.9, 3.4], "target": [0.0, 0.0, 0.0], "up": [0, 1, 0],
             "fovy_deg": 45, "near": 0.5, "far": 20},
  "texture": {"kind": "checker", "size": 64, "squares": 8,
              "colors": ["#f0d040", "#2040a0"], "wrap": "repeat"},
  "varyings": {"count": 2, "u": 0, "v": 1},
  "objects": [
    {"type": "mesh", "name": "cube +z face, seen at an angle",
     "positions": [[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]],
     "texcoords": [[0, 0], [1, 0], [1, 1], [0, 1]],
     "indices": [[0, 1, 2], [0, 2, 3]],
     "model": {"translate": [-0.95, 0.05, -0.4], "rotate_deg": 62, "axis": [0, 1, 0], "scale": 0.95}},
    {"type": "mesh", "name": "Stanford bunny", "optional": true,
     "obj": "/usr/share/glmark2/models/bunny.obj",
     "model": {"translate": [1.05, -0.05, 0.0], "rotate_deg": 20, "axis": [0, 1, 0], "scale": 0.8},
     "texgen": "cylindrical", "texgen_axis": "y", "uv_scale": [4, 4]}
  ]
}
)json";
}

Scene default_scene(const SceneOptions& opt) {
  nlohmann::json j = nlohmann::json::parse(default_scene_json());
  // The wireframe variant (docs/scene-format.md): the face's edges and the bunny's silhouette.
  if (opt.wireframe) {
    j["objects"][kFaceObject]["wireframe"] = "edges";
    j["objects"][kBunnyObject]["wireframe"] = "silhouette";
    j["line_state"] = {{"depth_func", "always"}, {"depth_write", false}, {"color", "#ff3030"}};
  }
  const std::string source = opt.wireframe ? "<default scene --wireframe>" : "<default scene>";
  Scene s = parse_scene(j.dump(), source, "", opt);
  s.source = source;
  // The bunny is drawn when the parser kept its object (info.what: the OBJ path, then what
  // the wireframe added); left out by --no-bunny or because the file is missing.
  const std::string bunny_obj = j["objects"][kBunnyObject]["obj"].get<std::string>();
  bool bunny = false;
  for (const SceneObjectInfo& info : s.objects) bunny = bunny || info.what.rfind(bunny_obj, 0) == 0;
  s.name += bunny ? " + bunny (glmark2-data)"
                  : opt.no_optional ? ", without the bunny (--no-bunny)"
                                    : ", without the bunny (" + bunny_obj + " not found: glmark2-data not installed)";
  if (opt.wireframe) s.name += bunny ? ", wireframe (face edges, bunny silhouette)" : ", wireframe (face edges)";
  return s;
}

}  // namespace fxr
