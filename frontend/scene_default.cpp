// The embedded default scene (README command 1): the example of docs/references.md#seed-000 —
// a checkerboard on one face of a cube seen at an angle, two triangles whose affine
// interpolation visibly breaks along the shared diagonal — and a real mesh, the Stanford bunny
// of glmark2-data, with a texgen checker (optional: left out with a note when the package is
// not installed).
#include "frontend/scene.hpp"

namespace fxr {

const char* default_scene_json() {
  return R"json({
  "version": 1,
  "name": "default: checkerboard face at an angle (seed 000) + bunny (glmark2-data)",
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

}  // namespace fxr
