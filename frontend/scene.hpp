// frontend/scene.hpp — the scene front end (not part of the raster unit; floating point allowed).
//
// A versioned JSON scene (docs/scene-format.md) → what a vertex stage would emit: the draw
// state, float32 clip-space triangles with their varyings, the texture, and metadata.
// Vertex transform: clip = P · V · M · p in double precision (GLM dmat4), then each clip
// component and each varying is rounded to float32 ONCE (round to nearest even, the C++
// double → float conversion). That single rounding is the only precision lost here.
//
// Errors: every problem throws fxr::ConfigError naming the file and the JSON path of the
// field, e.g. "scene.json: /objects/2/model: expected 16 numbers"; JSON syntax errors give
// line and column.
#pragma once

#include <string>
#include <vector>

#include <glm/mat4x4.hpp>
#include <glm/vec2.hpp>
#include <glm/vec3.hpp>
#include <nlohmann/json.hpp>

#include "model/config/config.hpp"
#include "model/unit/io.hpp"
#include "frontend/texture.hpp"

namespace fxr {

// Version of the scene JSON format (field "version").
inline constexpr int kSceneFormatVersion = 1;

// Texture-coordinate generation for meshes without UVs (docs/references.md#seed-002-texgen).
enum class TexGen : uint8_t { Auto, None, Planar, Spherical, Cylindrical, Cube };

// Per-object record kept for reports.
struct SceneObjectInfo {
  std::string kind;   // "mesh", "clip"
  std::string what;   // OBJ path, "inline", ...
  std::string texgen; // texgen used ("uv" when the mesh had its own texture coordinates)
  uint32_t first_prim = 0, prim_count = 0;
};

struct Scene {
  std::string name;
  std::string source;      // file name, or "<default>" for the embedded scene
  Config config;           // defaults, overridden by the scene's "config" object
  DrawState state;
  std::vector<ClipTriangle> tris;
  // Line segments (objects of type "lines", mesh "wireframe" edges), drawn after all triangles
  // with line_state (the draw state with the scene's "line_state" overrides), into the same
  // depth buffer; shaded with line_color. docs/scene-format.md, docs/lines.md.
  std::vector<ClipLine> lines;
  DrawState line_state;
  uint32_t line_color = 0xffffffffu;  // packed RGBA, like background
  Texture texture;
  uint32_t background = 0;           // packed RGBA of the cleared framebuffer
  int u_varying = 0, v_varying = 1;  // which varyings are the texture u, v (−1: none → flat colour)
  std::vector<SceneObjectInfo> objects;
  std::vector<std::string> notes;    // e.g. a missing optional mesh
};

// Options applied on top of a scene file (CLI overrides).
struct SceneOptions {
  int width = 0, height = 0;  // > 0: override the viewport size (the camera aspect follows)
  bool no_optional = false;   // skip objects marked "optional" (e.g. the bunny)
  bool wireframe = false;     // default scene only: the face's edges and the bunny's silhouette as lines
  // Fields of the scene's "state" object replaced (or added) before it is read, with the same
  // names, values and checks (`fxraster vectors scene --state JSON`; errors name the scene and
  // /state/<field>). Must be a JSON object; empty: the scene's own state.
  nlohmann::json state = nlohmann::json::object();
};

// `--config F` of the commands that read a scene: the fields of configuration file F override
// the scene's configuration (unit by unit, field by field). Errors name F and the field.
void apply_config_file(Scene& sc, const std::string& config_path);

// Parses a scene from JSON text; `where` names it in errors (the file name), `base_dir` is
// where relative OBJ / PNG paths are resolved. Throws ConfigError.
Scene parse_scene(const std::string& text, const std::string& where, const std::string& base_dir,
                  const SceneOptions& opt = {});
// Reads and parses a scene file. Throws ConfigError (cannot open, syntax, fields).
Scene load_scene(const std::string& path, const SceneOptions& opt = {});
// The embedded default scene (the checkerboard face at an angle of docs/references.md#seed-000,
// and the Stanford bunny from glmark2-data when installed; a note says so when it is not).
// Its name says what was drawn: "… + bunny (glmark2-data)", or "…, without the bunny (…)" and
// why (frontend/scene_default.cpp).
Scene default_scene(const SceneOptions& opt = {});
// The JSON text of the embedded default scene (its name: the face's part only).
const char* default_scene_json();

// ---- pieces exposed for tests ---------------------------------------------------------------

// Parses a float32 given as a JSON number (rounded once to nearest float32) or a string:
// a C99 hex float ("0x1.8p+1", exact when it fits float32, else an error), a decimal, or
// "nan" / "inf" / "-inf". Throws ConfigError naming `path`.
float parse_f32(const nlohmann::json& j, const std::string& where, const std::string& path);
// The shortest hex-float text that reads back to exactly the same float32 bits
// (e.g. "0x1.8p+1", "-0x1p-149", "nan", "inf").
std::string f32_to_hex(float f);

// Texture-coordinate generation from a point q already normalised to the mesh's bounding box
// (q = (p − box centre) / largest half extent, so each |q_i| ≤ 1) and permuted so that the
// chosen axis is q.z ("texgen_axis": x → (y, z, x), y → (z, x, y), z → (x, y, z)).
// Formulas of docs/references.md#seed-002-texgen:
//   planar:           (u, v) = ((1 + q.x) / 2, (1 + q.y) / 2)   (orthographic along q.z)
//   spherical:        u = (π + atan2(y, x)) / 2π,  v = (π − acos(z / |q|)) / π   (|q| = 0 → v = ½)
//   cylindrical:      u = (π + atan2(y, x)) / 2π,  v = (1 + z) / 2
//   cube:             face by the largest |component|, face coordinates (s, t) ∈ [0, 1] by
//                     the OpenGL table (docs/references.md#seed-002-cube), packed into a
//                     3 × 2 atlas:
//                     column = face % 3, row = face / 3 with faces +x, −x, +y, −y, +z, −z
//                     = 0..5; u = (column + s) / 3, v = (row + t) / 2.
//   Auto / None:      (0, 0)
// Ties between equal |components| in cube: x wins over y, y over z.
glm::dvec2 texgen(TexGen mode, const glm::dvec3& q);

}  // namespace fxr
