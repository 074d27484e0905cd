// The scene front end: JSON scene → draw state + float32 clip-space triangles (frontend/scene.hpp).
// Floating point is allowed here: this is the vertex stage, not the raster unit.
#include "frontend/scene.hpp"

#include <algorithm>
#include <cctype>
#include <array>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <unordered_map>

#include <glm/ext/matrix_clip_space.hpp>
#include <glm/ext/matrix_transform.hpp>
#include <glm/mat4x4.hpp>
#include <glm/vec4.hpp>
#include <tiny_obj_loader.h>

#include "model/config/json_input.hpp"

namespace fxr {

namespace {

using nlohmann::json;

// Largest viewport side accepted (memory of the output images; the unit itself takes up to
// 2^(window_int_bits − 1) px).
constexpr int kMaxViewportSide = 16384;

// A JSON value with its JSON-pointer path, for error messages "file: /a/2/b: message".
struct Node {
  const json& j;
  std::string where;  // file name
  std::string path;   // JSON pointer ("" = the document root)

  [[noreturn]] void fail(const std::string& msg) const {
    throw ConfigError(where + ": " + (path.empty() ? "/" : path) + ": " + msg);
  }
  bool has(const char* key) const { return j.is_object() && j.contains(key); }
  Node at(const char* key) const {
    if (!has(key)) Node{j, where, path + "/" + key}.fail("missing field");
    return Node{j.at(key), where, path + "/" + key};
  }
  Node at(size_t i) const { return Node{j.at(i), where, path + "/" + std::to_string(i)}; }
  void expect_object(std::initializer_list<const char*> known) const {
    if (!j.is_object()) fail("expected an object, got " + type_of());
    for (auto it = j.begin(); it != j.end(); ++it) {
      bool ok = false;
      std::string list;
      for (const char* k : known) {
        ok |= it.key() == k;
        list += (list.empty() ? "" : ", ") + std::string(k);
      }
      if (!ok) Node{it.value(), where, path + "/" + cut(it.key(), kMaxExcerptChars)}.fail("unknown field (known: " + list + ")");
    }
  }
  // Bounded: a huge or deep value is summarised (model/config/json_input.hpp).
  std::string type_of() const { return json_typed_excerpt(j); }
  size_t array_size() const {
    if (!j.is_array()) fail("expected an array, got " + type_of());
    return j.size();
  }
  double number() const {
    if (!j.is_number()) fail("expected a number, got " + type_of());
    const double d = j.get<double>();
    if (!std::isfinite(d)) fail("expected a finite number");
    return d;
  }
  int integer(int lo, int hi) const {
    if (!j.is_number_integer()) fail("expected an integer, got " + type_of());
    // Checked: unsigned values beyond int64 are not wrapped (json_int compares them as such).
    try {
      return (int)json_int(j, lo, hi, "");
    } catch (const ConfigError& e) {
      fail(std::string(e.what()).substr(2));  // drop json_int's empty prefix ": "
    }
  }
  bool boolean() const {
    if (!j.is_boolean()) fail("expected true or false, got " + type_of());
    return j.get<bool>();
  }
  std::string string() const {
    if (!j.is_string()) fail("expected a string, got " + type_of());
    return j.get<std::string>();
  }
  // A colour "#rrggbb": '#' and exactly 6 lowercase hex digits (docs/scene-format.md; lowercase as
  // every hex field of the project: bits: patterns, vector files).
  uint32_t color() const {
    const std::string s = string();
    uint32_t c = 0;
    if (parse_hex_color(s, &c)) return c;
    const bool upper = s.size() == 7 && s[0] == '#' &&
                       std::all_of(s.begin() + 1, s.end(), [](char ch) { return std::isxdigit((unsigned char)ch); });
    fail("expected a colour \"#rrggbb\" (6 lowercase hex digits), got " + type_of() +
         (upper ? " (uppercase digits: write them in lowercase)" : ""));
  }
  template <class E>
  E choice(std::initializer_list<std::pair<const char*, E>> names) const {
    const std::string s = string();
    std::string list;
    for (const auto& [n, e] : names) {
      if (s == n) return e;
      list += (list.empty() ? "" : ", ") + std::string(n);
    }
    fail("'" + cut(s, kMaxExcerptChars) + "' is not one of: " + list);
  }
  // Exactly n numbers (or, with n == 0, any count).
  std::vector<double> numbers(size_t n) const {
    if (!j.is_array() || (n && j.size() != n)) {
      if (n) fail("expected " + std::to_string(n) + " numbers, got " + type_of());
      fail("expected an array of numbers, got " + type_of());
    }
    std::vector<double> out;
    for (size_t i = 0; i < j.size(); ++i) out.push_back(at(i).number());
    return out;
  }
};

// Row-major 16 numbers (as a matrix is written on paper) → GLM's column-major dmat4.
glm::dmat4 matrix_from_rows(const std::vector<double>& m) {
  glm::dmat4 r(1.0);
  for (int row = 0; row < 4; ++row)
    for (int col = 0; col < 4; ++col) r[col][row] = m[row * 4 + col];
  return r;
}

glm::dvec3 vec3(const Node& n) {
  const auto v = n.numbers(3);
  return {v[0], v[1], v[2]};
}

// "model": 16 numbers (row-major) or {"translate": [3], "rotate_deg": a, "axis": [3],
// "scale": s | [3]}, composed M = T · R · S.
glm::dmat4 parse_model(const Node& n) {
  if (n.j.is_array()) return matrix_from_rows(n.numbers(16));
  if (!n.j.is_object()) n.fail("expected 16 numbers or an object {translate, rotate_deg, axis, scale}, got " + n.type_of());
  n.expect_object({"translate", "rotate_deg", "axis", "scale"});
  glm::dmat4 m(1.0);
  if (n.has("translate")) m = glm::translate(m, vec3(n.at("translate")));
  if (n.has("rotate_deg")) {
    glm::dvec3 axis(0, 1, 0);
    if (n.has("axis")) axis = vec3(n.at("axis"));
    if (glm::length(axis) == 0.0) n.at("axis").fail("the rotation axis has zero length");
    m = glm::rotate(m, glm::radians(n.at("rotate_deg").number()), glm::normalize(axis));
  } else if (n.has("axis")) {
    n.at("axis").fail("'axis' needs 'rotate_deg'");
  }
  if (n.has("scale")) {
    const Node s = n.at("scale");
    if (s.j.is_number()) m = glm::scale(m, glm::dvec3(s.number()));
    else m = glm::scale(m, vec3(s));
  }
  return m;
}

float parse_f32_at(const Node& n) { return parse_f32(n.j, n.where, n.path); }

std::string dir_of(const std::string& path) {
  const auto p = path.find_last_of('/');
  return p == std::string::npos ? "." : path.substr(0, p);
}

std::string resolve(const std::string& base_dir, const std::string& p) {
  if (p.empty() || p[0] == '/' || base_dir.empty()) return p;
  return base_dir + "/" + p;
}

struct Mesh {
  std::vector<glm::dvec3> pos;
  std::vector<glm::dvec2> uv;           // empty, or one per entry of pos
  std::vector<std::array<uint32_t, 3>> tri;
};

// OBJ indices are checked here before tinyobjloader sees them: it converts them with an
// unchecked atoi (an index of 99999999999999999999 overflows into some valid vertex) and maps a
// texcoord index it cannot use to "none". A face index must be a non-zero integer naming an
// existing element: 1..N (N = the file's count of v / vt / vn lines), or −1..−n (n = the count
// so far). Returns false with *why = "<file>:<line>: ...".
bool check_obj_indices(const std::string& path, std::string* why) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(std::move(l));
  if (in.bad()) {
    *why = "read error";
    return false;
  }
  auto keyword = [](const std::string& l, size_t* rest) {
    size_t a = l.find_first_not_of(" \t");
    if (a == std::string::npos) return std::string();
    size_t b = l.find_first_of(" \t", a);
    if (b == std::string::npos) b = l.size();
    *rest = b;
    return l.substr(a, b - a);
  };
  int64_t total[3] = {0, 0, 0};  // v, vt, vn
  const char* kinds[3] = {"v", "vt", "vn"};
  for (const auto& l : lines) {
    size_t rest = 0;
    const std::string k = keyword(l, &rest);
    for (int t = 0; t < 3; ++t) total[t] += k == kinds[t];
  }
  const char* names[3] = {"vertex", "texcoord", "normal"};
  int64_t so_far[3] = {0, 0, 0};
  for (size_t ln = 0; ln < lines.size(); ++ln) {
    const std::string& l = lines[ln];
    size_t rest = 0;
    const std::string k = keyword(l, &rest);
    for (int t = 0; t < 3; ++t) so_far[t] += k == kinds[t];
    if (k != "f") continue;
    std::istringstream ss(l.substr(rest));
    for (std::string tok; ss >> tok;) {
      if (tok[0] == '#') break;
      size_t start = 0;
      for (int t = 0; t < 3 && start <= tok.size(); ++t) {
        size_t slash = tok.find('/', start);
        if (slash == std::string::npos) slash = tok.size();
        const std::string part = tok.substr(start, slash - start);
        start = slash + 1;
        if (part.empty() && t > 0) continue;  // "1//3": no texcoord
        const std::string where = path + ":" + std::to_string(ln + 1) + ": face " + names[t] + " index '" +
                                  cut(part, kMaxExcerptChars) + "'";
        // Checked integer: optional '-', digits, |value| ≤ the count (no overflow).
        size_t i = part.size() > 0 && part[0] == '-' ? 1 : 0;
        if (i == part.size()) {
          *why = where + ": not an integer";
          return false;
        }
        int64_t mag = 0;
        for (; i < part.size(); ++i) {
          if (part[i] < '0' || part[i] > '9') {
            *why = where + ": not an integer";
            return false;
          }
          mag = mag * 10 + (part[i] - '0');
          if (mag > total[t]) break;  // already beyond every count: stop before it can overflow
        }
        const bool neg = part[0] == '-';
        const int64_t limit = neg ? so_far[t] : total[t];
        if (mag == 0 || mag > limit) {
          *why = where + ": no such " + names[t] + " (the file has " + std::to_string(neg ? so_far[t] : total[t]) +
                 (neg ? " before this line)" : ")");
          return false;
        }
      }
    }
  }
  return true;
}

// Loads an OBJ through tinyobjloader (triangulated). Returns false with *why on failure.
bool load_obj(const std::string& path, Mesh& m, std::string* why) {
  if (!check_obj_indices(path, why)) return false;
  tinyobj::ObjReaderConfig rc;
  rc.triangulate = true;
  rc.vertex_color = false;
  tinyobj::ObjReader r;
  if (!r.ParseFromFile(path, rc)) {
    *why = r.Error().empty() ? "cannot parse" : r.Error();
    while (!why->empty() && why->back() == '\n') why->pop_back();
    return false;
  }
  const auto& a = r.GetAttrib();
  bool any_uv = !a.texcoords.empty();
  // One output vertex per (position, texcoord) index pair used by a face.
  std::map<std::pair<int, int>, uint32_t> remap;
  for (const auto& sh : r.GetShapes()) {
    for (size_t f = 0; f + 2 < sh.mesh.indices.size(); f += 3) {
      std::array<uint32_t, 3> t{};
      for (int k = 0; k < 3; ++k) {
        const auto& idx = sh.mesh.indices[f + k];
        const int ti = any_uv ? idx.texcoord_index : -1;
        auto key = std::make_pair(idx.vertex_index, ti);
        auto it = remap.find(key);
        if (it == remap.end()) {
          if (idx.vertex_index < 0 || 3 * (size_t)idx.vertex_index + 2 >= a.vertices.size()) {
            *why = "face refers to a missing vertex";
            return false;
          }
          it = remap.emplace(key, (uint32_t)m.pos.size()).first;
          m.pos.emplace_back(a.vertices[3 * idx.vertex_index], a.vertices[3 * idx.vertex_index + 1],
                             a.vertices[3 * idx.vertex_index + 2]);
          if (any_uv) {
            if (ti < 0 || 2 * (size_t)ti + 1 >= a.texcoords.size()) {
              any_uv = false;  // faces without texcoords: fall back to texgen for the whole mesh
              m.uv.clear();
            } else {
              m.uv.emplace_back(a.texcoords[2 * ti], a.texcoords[2 * ti + 1]);
            }
          }
        }
        t[k] = it->second;
      }
      m.tri.push_back(t);
    }
  }
  if (!any_uv) m.uv.clear();
  if (m.tri.empty()) {
    *why = "no triangles";
    return false;
  }
  return true;
}

glm::dvec3 permute_axis(const glm::dvec3& q, int axis) {
  if (axis == 0) return {q.y, q.z, q.x};
  if (axis == 1) return {q.z, q.x, q.y};
  return q;
}

const char* texgen_name(TexGen t) {
  switch (t) {
    case TexGen::Auto: return "auto";
    case TexGen::None: return "none";
    case TexGen::Planar: return "planar";
    case TexGen::Spherical: return "spherical";
    case TexGen::Cylindrical: return "cylindrical";
    case TexGen::Cube: return "cube";
  }
  return "?";
}

struct Camera {
  glm::dmat4 view{1.0}, proj{1.0};
};

Camera parse_camera(const Node& n, double aspect) {
  Camera c;
  if (n.has("view") || n.has("projection")) {
    n.expect_object({"view", "projection"});
    c.view = matrix_from_rows(n.at("view").numbers(16));
    c.proj = matrix_from_rows(n.at("projection").numbers(16));
    return c;
  }
  n.expect_object({"eye", "target", "up", "fovy_deg", "near", "far", "aspect"});
  const glm::dvec3 eye = vec3(n.at("eye")), target = vec3(n.at("target"));
  glm::dvec3 up(0, 1, 0);
  if (n.has("up")) up = vec3(n.at("up"));
  if (target == eye) n.at("target").fail("equals 'eye': the view direction is undefined");
  if (glm::length(glm::cross(target - eye, up)) == 0.0) {
    if (n.has("up")) n.at("up").fail("is parallel to the view direction (target − eye)");
    Node{n.j, n.where, n.path + "/up"}.fail("the default up (0, 1, 0) is parallel to the view direction (target − eye): give 'up'");
  }
  const double fovy = n.at("fovy_deg").number();
  if (!(fovy > 0 && fovy < 180)) n.at("fovy_deg").fail("must be in (0, 180)");
  const double zn = n.at("near").number(), zf = n.at("far").number();
  if (!(zn > 0)) n.at("near").fail("must be > 0");
  if (!(zf > zn)) n.at("far").fail("must be > near");
  if (n.has("aspect")) {
    aspect = n.at("aspect").number();
    if (!(aspect > 0)) n.at("aspect").fail("must be > 0");
  }
  c.view = glm::lookAtRH(eye, target, up);
  // 0 ≤ z_c ≤ w_c clip volume (D3D / Vulkan depth convention, docs/references.md#d3d11-clip),
  // as the clipper expects.
  c.proj = glm::perspectiveRH_ZO(glm::radians(fovy), aspect, zn, zf);
  return c;
}

// The vertex stage: clip = PV · M · p in double, then ONE rounding per component to float32.
ClipVertex emit_vertex(const glm::dmat4& pvm, const glm::dvec3& p, const glm::dvec2& uv, int u_var, int v_var) {
  const glm::dvec4 c = pvm * glm::dvec4(p, 1.0);
  ClipVertex v;
  for (int i = 0; i < 4; ++i) v.pos[i] = (float)c[i];  // precision lost: double → float32, RNE
  if (u_var >= 0) v.var[u_var] = (float)uv.x;           // precision lost: double → float32, RNE
  if (v_var >= 0) v.var[v_var] = (float)uv.y;
  return v;
}

void parse_mesh(const Node& o, Scene& sc, const glm::dmat4& pv, const std::string& base_dir,
                const SceneOptions& opt) {
  o.expect_object({"type", "name", "obj", "positions", "texcoords", "indices", "model", "texgen", "texgen_axis",
                   "uv_scale", "uv_offset", "optional", "wireframe"});
  enum class Wire { None, Edges, Silhouette };
  Wire wire = Wire::None;
  if (o.has("wireframe"))
    wire = o.at("wireframe").choice<Wire>({{"none", Wire::None}, {"edges", Wire::Edges}, {"silhouette", Wire::Silhouette}});
  const bool optional = o.has("optional") && o.at("optional").boolean();
  SceneObjectInfo info;
  info.kind = "mesh";
  Mesh m;
  if (o.has("obj")) {
    if (o.has("positions") || o.has("indices") || o.has("texcoords"))
      o.at("obj").fail("give either 'obj' or inline 'positions' / 'indices', not both");
    const Node on = o.at("obj");
    const std::string path = resolve(base_dir, on.string());
    info.what = path;
    if (optional && opt.no_optional) {
      sc.notes.push_back("optional mesh " + path + " skipped (--no-bunny / no_optional)");
      return;
    }
    std::string why;
    if (!std::ifstream(path)) {
      if (optional) {
        sc.notes.push_back("optional mesh " + path + " not found: drawn without it" +
                           (path.find("glmark2") != std::string::npos ? " (install the Debian package glmark2-data)" : ""));
        return;
      }
      on.fail("cannot open OBJ file '" + path + "'");
    }
    if (!load_obj(path, m, &why)) on.fail("cannot load OBJ file '" + path + "': " + why);
  } else {
    info.what = "inline";
    const Node pn = o.at("positions");
    for (size_t i = 0; i < pn.array_size(); ++i) m.pos.push_back(vec3(pn.at(i)));
    if (o.has("texcoords")) {
      const Node tn = o.at("texcoords");
      if (tn.array_size() != m.pos.size())
        tn.fail("expected " + std::to_string(m.pos.size()) + " texcoords (one per position), got " + std::to_string(tn.j.size()));
      for (size_t i = 0; i < tn.j.size(); ++i) {
        const auto v = tn.at(i).numbers(2);
        m.uv.emplace_back(v[0], v[1]);
      }
    }
    const Node in = o.at("indices");
    for (size_t i = 0; i < in.array_size(); ++i) {
      const Node t = in.at(i);
      if (!t.j.is_array() || t.j.size() != 3) t.fail("expected 3 vertex indices, got " + t.type_of());
      std::array<uint32_t, 3> tri{};
      for (int k = 0; k < 3; ++k) tri[k] = (uint32_t)t.at(k).integer(0, (int)m.pos.size() - 1);
      m.tri.push_back(tri);
    }
  }
  glm::dmat4 model(1.0);
  if (o.has("model")) model = parse_model(o.at("model"));
  TexGen tg = TexGen::Auto;
  if (o.has("texgen"))
    tg = o.at("texgen").choice<TexGen>({{"auto", TexGen::Auto}, {"uv", TexGen::Auto}, {"none", TexGen::None},
                                        {"planar", TexGen::Planar}, {"spherical", TexGen::Spherical},
                                        {"cylindrical", TexGen::Cylindrical}, {"cube", TexGen::Cube}});
  if (tg == TexGen::Auto && o.has("texgen") && o.at("texgen").string() == "uv" && m.uv.empty())
    o.at("texgen").fail("'uv' asks for the mesh's own texture coordinates, but it has none");
  if (tg == TexGen::Auto && m.uv.empty()) tg = TexGen::Planar;  // documented default
  int axis = 2;
  if (o.has("texgen_axis")) axis = o.at("texgen_axis").choice<int>({{"x", 0}, {"y", 1}, {"z", 2}});
  glm::dvec2 scale(1, 1), offset(0, 0);
  if (o.has("uv_scale")) {
    const auto v = o.at("uv_scale").numbers(2);
    scale = {v[0], v[1]};
  }
  if (o.has("uv_offset")) {
    const auto v = o.at("uv_offset").numbers(2);
    offset = {v[0], v[1]};
  }
  info.texgen = tg == TexGen::Auto ? "uv" : texgen_name(tg);
  // Bounding box normalisation of object-space positions for texgen.
  glm::dvec3 lo(INFINITY), hi(-INFINITY);
  for (const auto& p : m.pos) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  const glm::dvec3 centre = (lo + hi) * 0.5;
  const glm::dvec3 half = (hi - lo) * 0.5;
  double radius = std::max(half.x, std::max(half.y, half.z));
  if (!(radius > 0)) radius = 1;
  const glm::dmat4 pvm = pv * model;
  const int nv = sc.state.num_varyings;
  const int u_var = sc.u_varying < nv ? sc.u_varying : -1, v_var = sc.v_varying < nv ? sc.v_varying : -1;
  info.first_prim = (uint32_t)sc.tris.size();
  // Wireframe: every edge once (first-seen order and direction), with the vertices of the first
  // triangle that has it. Facing of a triangle for silhouettes: the sign of its window-space
  // area from the double clip coordinates (0 when a w ≤ 0 or the area is 0: never a silhouette
  // side). An edge is a silhouette when its two triangles face opposite ways, or when it has one.
  struct Edge {
    ClipLine line;
    int facing[2] = {0, 0};
    int count = 0;
  };
  std::vector<Edge> edges;
  std::unordered_map<uint64_t, size_t> edge_of;
  for (const auto& t : m.tri) {
    ClipTriangle ct;
    glm::dvec4 c[3];
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3 p = m.pos[t[k]];
      glm::dvec2 uv = tg == TexGen::Auto ? m.uv[t[k]] : texgen(tg, permute_axis((p - centre) / radius, axis));
      uv = uv * scale + offset;
      ct.v[k] = emit_vertex(pvm, p, uv, u_var, v_var);
      c[k] = pvm * glm::dvec4(p, 1.0);
    }
    sc.tris.push_back(ct);
    if (wire == Wire::None) continue;
    int facing = 0;
    if (c[0].w > 0 && c[1].w > 0 && c[2].w > 0) {
      const glm::dvec2 a(c[0].x / c[0].w, c[0].y / c[0].w), b(c[1].x / c[1].w, c[1].y / c[1].w),
          d(c[2].x / c[2].w, c[2].y / c[2].w);
      const double area = (b.x - a.x) * (d.y - a.y) - (d.x - a.x) * (b.y - a.y);
      facing = area > 0 ? 1 : area < 0 ? -1 : 0;
    }
    for (int k = 0; k < 3; ++k) {
      const uint32_t i0 = t[k], i1 = t[(k + 1) % 3];
      const uint64_t key = ((uint64_t)std::min(i0, i1) << 32) | std::max(i0, i1);
      auto it = edge_of.find(key);
      if (it == edge_of.end()) {
        it = edge_of.emplace(key, edges.size()).first;
        Edge e;
        e.line.v[0] = ct.v[k];
        e.line.v[1] = ct.v[(k + 1) % 3];
        edges.push_back(e);
      }
      Edge& e = edges[it->second];
      if (e.count < 2) e.facing[e.count] = facing;
      ++e.count;
    }
  }
  for (const Edge& e : edges) {
    const bool silhouette = e.count == 1 || (e.count == 2 && e.facing[0] * e.facing[1] < 0);
    if (wire == Wire::Edges || silhouette) sc.lines.push_back(e.line);
  }
  if (wire != Wire::None) info.what += wire == Wire::Edges ? " + wireframe edges" : " + silhouette edges";
  info.prim_count = (uint32_t)m.tri.size();
  sc.objects.push_back(info);
}

void parse_clip(const Node& o, Scene& sc) {
  o.expect_object({"type", "name", "triangles"});
  SceneObjectInfo info;
  info.kind = "clip";
  info.what = "explicit clip-space triangles";
  info.texgen = "given";
  info.first_prim = (uint32_t)sc.tris.size();
  const Node tl = o.at("triangles");
  const int nv = sc.state.num_varyings;
  for (size_t i = 0; i < tl.array_size(); ++i) {
    const Node t = tl.at(i);
    if (!t.j.is_array() || t.j.size() != 3) t.fail("expected 3 vertices, got " + t.type_of());
    ClipTriangle ct;
    for (size_t k = 0; k < 3; ++k) {
      const Node v = t.at(k);
      v.expect_object({"pos", "var"});
      const Node pn = v.at("pos");
      if (!pn.j.is_array() || pn.j.size() != 4) pn.fail("expected 4 numbers (x_c, y_c, z_c, w_c), got " + pn.type_of());
      for (size_t c = 0; c < 4; ++c) ct.v[k].pos[c] = parse_f32_at(pn.at(c));
      if (nv > 0 || v.has("var")) {
        const Node vn = v.at("var");
        if (!vn.j.is_array() || (int)vn.j.size() != nv)
          vn.fail("expected " + std::to_string(nv) + " varyings (varyings.count), got " + vn.type_of());
        for (int c = 0; c < nv; ++c) ct.v[k].var[c] = parse_f32_at(vn.at(c));
      }
    }
    sc.tris.push_back(ct);
  }
  info.prim_count = (uint32_t)sc.tris.size() - info.first_prim;
  sc.objects.push_back(info);
}

// {"type": "lines", "lines": [[v0, v1], …]}: explicit clip-space segments, vertices as in "clip".
void parse_lines(const Node& o, Scene& sc) {
  o.expect_object({"type", "name", "lines"});
  SceneObjectInfo info;
  info.kind = "lines";
  info.what = "explicit clip-space segments";
  info.texgen = "given";
  info.first_prim = (uint32_t)sc.lines.size();  // + the triangle count, once all are known
  const Node ll = o.at("lines");
  const int nv = sc.state.num_varyings;
  for (size_t i = 0; i < ll.array_size(); ++i) {
    const Node t = ll.at(i);
    if (!t.j.is_array() || t.j.size() != 2) t.fail("expected 2 vertices, got " + t.type_of());
    ClipLine cl;
    for (size_t k = 0; k < 2; ++k) {
      const Node v = t.at(k);
      v.expect_object({"pos", "var"});
      const Node pn = v.at("pos");
      if (!pn.j.is_array() || pn.j.size() != 4) pn.fail("expected 4 numbers (x_c, y_c, z_c, w_c), got " + pn.type_of());
      for (size_t c = 0; c < 4; ++c) cl.v[k].pos[c] = parse_f32_at(pn.at(c));
      if (nv > 0 || v.has("var")) {
        const Node vn = v.at("var");
        if (!vn.j.is_array() || (int)vn.j.size() != nv)
          vn.fail("expected " + std::to_string(nv) + " varyings (varyings.count), got " + vn.type_of());
        for (int c = 0; c < nv; ++c) cl.v[k].var[c] = parse_f32_at(vn.at(c));
      }
    }
    sc.lines.push_back(cl);
  }
  info.prim_count = (uint32_t)ll.j.size();
  sc.objects.push_back(info);
}

}  // namespace

// ---- float32 text ---------------------------------------------------------------------------

namespace {
// Magnitudes at or above 2^128 − 2^103 (float32's largest finite value plus half an ulp) round to
// infinity in float32: an overflow, not a number the scene can mean (docs/scene-format.md).
const double kF32OverflowThreshold = std::ldexp(1.0, 128) - std::ldexp(1.0, 103);
// "bits:" + this many lowercase hex digits is a raw float32 bit pattern.
constexpr size_t kF32HexDigits = 8;
constexpr size_t kBitsPrefixChars = 5;  // "bits:"
constexpr int kHexRadix = 16;
}  // namespace

float parse_f32(const json& j, const std::string& where, const std::string& path) {
  const Node n{j, where, path};
  if (j.is_number()) {
    const double d = j.get<double>();  // finite: parse_json_input rejects numbers beyond a double
    if (std::fabs(d) >= kF32OverflowThreshold)
      n.fail(cut(j.dump(), kMaxExcerptChars) + " overflows float32 (largest 3.4028235e38; write \"inf\" for infinity)");
    return (float)d;  // double → float32, RNE (see docs: hex for exact bits)
  }
  if (!j.is_string()) n.fail("expected a number or a hex-float string, got " + n.type_of());
  std::string s = j.get<std::string>();
  if (s == "nan") return f32_from_bits(0x7fc00000u);
  if (s == "-nan") return f32_from_bits(0xffc00000u);
  if (s == "inf" || s == "+inf") return f32_from_bits(0x7f800000u);
  if (s == "-inf") return f32_from_bits(0xff800000u);
  if (s.rfind("bits:", 0) == 0) {
    // Raw IEEE-754 bit pattern, e.g. "bits:7fc00001" (NaN payloads, exact denormals): exactly 8
    // lowercase hex digits, nothing else (no sign, no space, no 0x; strtoul would accept those).
    const std::string h = s.substr(kBitsPrefixChars);
    bool ok = h.size() == kF32HexDigits;
    for (char c : h) ok = ok && ((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f'));
    if (!ok) n.fail("bad bit pattern '" + cut(s, kMaxExcerptChars) + "' (expected bits:xxxxxxxx, 8 lowercase hex digits)");
    return f32_from_bits((uint32_t)std::strtoul(h.c_str(), nullptr, kHexRadix));
  }
  if (s.empty()) n.fail("empty number string");
  const std::string shown = cut(s, kMaxExcerptChars);
  // Only a plain decimal or hex-float literal; strtold alone would also take "infinity", "nan(…)",
  // leading spaces and a leading '+'.
  for (char c : s)
    if (!((c >= '0' && c <= '9') || (c >= 'a' && c <= 'f') || c == 'x' || c == 'p' || c == 'X' || c == 'P' ||
          (c >= 'A' && c <= 'F') || c == '.' || c == '-' || c == '+'))
      n.fail("bad number '" + shown + "' (expected e.g. \"0x1.8p+1\" or \"1.5\", or \"inf\", \"nan\", \"bits:7fc00000\")");
  char* end = nullptr;
  errno = 0;
  const long double ld = std::strtold(s.c_str(), &end);
  if (end == s.c_str() || *end) n.fail("bad number '" + shown + "' (expected e.g. \"0x1.8p+1\" or \"1.5\")");
  const bool hex = s.find("0x") != std::string::npos || s.find("0X") != std::string::npos;
  const float f = std::strtof(s.c_str(), nullptr);
  // Overflow (also beyond long double, e.g. "1e5000"): only "inf" / "-inf" mean infinity.
  if (!std::isfinite(f)) n.fail("'" + shown + "' overflows float32 (write \"inf\" for infinity)");
  if (hex && (long double)f != ld)
    n.fail("hex float '" + shown + "' is not exactly representable in float32 (nearest: " + f32_to_hex(f) + ")");
  return f;  // decimals: rounded once to the nearest float32 (strtof)
}

std::string f32_to_hex(float f) {
  if (std::isnan(f)) return std::signbit(f) ? "-nan" : "nan";
  if (std::isinf(f)) return f < 0 ? "-inf" : "inf";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%a", (double)f);  // exact: every float32 is a double
  return buf;
}

// ---- texgen ---------------------------------------------------------------------------------

glm::dvec2 texgen(TexGen mode, const glm::dvec3& q) {
  const double pi = M_PI;
  switch (mode) {
    case TexGen::Auto:
    case TexGen::None: return {0, 0};
    case TexGen::Planar: return {(1 + q.x) / 2, (1 + q.y) / 2};
    case TexGen::Spherical: {
      const double r = glm::length(q);
      const double u = (pi + std::atan2(q.y, q.x)) / (2 * pi);
      const double v = r > 0 ? (pi - std::acos(std::clamp(q.z / r, -1.0, 1.0))) / pi : 0.5;
      return {u, v};
    }
    case TexGen::Cylindrical: return {(pi + std::atan2(q.y, q.x)) / (2 * pi), (1 + q.z) / 2};
    case TexGen::Cube: {
      const double ax = std::abs(q.x), ay = std::abs(q.y), az = std::abs(q.z);
      int face;
      double sc, tc, ma;
      if (ax >= ay && ax >= az) {
        ma = ax;
        face = q.x >= 0 ? 0 : 1;
        sc = q.x >= 0 ? -q.z : q.z;
        tc = -q.y;
      } else if (ay >= az) {
        ma = ay;
        face = q.y >= 0 ? 2 : 3;
        sc = q.x;
        tc = q.y >= 0 ? q.z : -q.z;
      } else {
        ma = az;
        face = q.z >= 0 ? 4 : 5;
        sc = q.z >= 0 ? q.x : -q.x;
        tc = -q.y;
      }
      const double s = ma > 0 ? (1 + sc / ma) / 2 : 0.5, t = ma > 0 ? (1 + tc / ma) / 2 : 0.5;
      return {((face % 3) + s) / 3, ((face / 3) + t) / 2};
    }
  }
  return {0, 0};
}

// ---- the scene ------------------------------------------------------------------------------

Scene parse_scene(const std::string& text, const std::string& where, const std::string& base_dir,
                  const SceneOptions& opt) {
  // Syntax errors with line:column, nesting bounded, numbers beyond a double named by path.
  json doc = parse_json_input(text, where);
  if (!opt.state.is_object()) throw ConfigError(where + ": the state override is not a JSON object");
  if (!opt.state.empty() && doc.is_object()) {  // SceneOptions::state: the fields replaced, then read as the scene's
    if (!doc.contains("state")) doc["state"] = json::object();
    if (doc["state"].is_object()) doc["state"].update(opt.state);
  }
  const Node root{doc, where, ""};
  root.expect_object({"version", "name", "viewport", "config", "state", "line_state", "background", "camera",
                      "texture", "varyings", "objects"});
  const Node ver = root.at("version");
  if (!ver.j.is_number_integer()) ver.fail("expected an integer, got " + ver.type_of());
  if (ver.j != kSceneFormatVersion)  // compared as JSON numbers: no narrowing
    ver.fail(json_excerpt(ver.j) + " is not supported (this fxraster reads scene format version " +
             std::to_string(kSceneFormatVersion) + ")");

  Scene sc;
  sc.source = where;
  sc.name = root.has("name") ? root.at("name").string() : where;

  // Viewport.
  const Node vp = root.at("viewport");
  vp.expect_object({"x", "y", "width", "height"});
  sc.state.viewport_w = opt.width > 0 ? opt.width : vp.at("width").integer(1, kMaxViewportSide);
  sc.state.viewport_h = opt.height > 0 ? opt.height : vp.at("height").integer(1, kMaxViewportSide);
  if (opt.width > kMaxViewportSide || opt.height > kMaxViewportSide)
    throw ConfigError(where + ": viewport override larger than " + std::to_string(kMaxViewportSide));
  if (vp.has("x")) sc.state.viewport_x = vp.at("x").integer(-kMaxViewportSide, kMaxViewportSide);
  if (vp.has("y")) sc.state.viewport_y = vp.at("y").integer(-kMaxViewportSide, kMaxViewportSide);

  // Configuration overrides: passed to config_from_json ("version" may be left out).
  if (root.has("config")) {
    const Node c = root.at("config");
    if (!c.j.is_object()) c.fail("expected an object, got " + c.type_of());
    json cj = c.j;
    if (!cj.contains("version")) cj["version"] = kConfigFormatVersion;
    sc.config = config_from_json(cj, where + ": /config");
  }

  // Draw state.
  if (root.has("state")) {
    const Node s = root.at("state");
    s.expect_object({"cull", "front_face", "depth_func", "depth_test", "depth_write", "interp", "scissor"});
    if (s.has("cull"))
      sc.state.cull = s.at("cull").choice<CullMode>({{"none", CullMode::None}, {"back", CullMode::Back}, {"front", CullMode::Front}});
    if (s.has("front_face")) sc.state.front_ccw = s.at("front_face").choice<bool>({{"ccw", true}, {"cw", false}});
    if (s.has("depth_func"))
      sc.state.depth_func = s.at("depth_func").choice<DepthFunc>(
          {{"never", DepthFunc::Never}, {"less", DepthFunc::Less}, {"equal", DepthFunc::Equal},
           {"lequal", DepthFunc::LessEqual}, {"greater", DepthFunc::Greater}, {"notequal", DepthFunc::NotEqual},
           {"gequal", DepthFunc::GreaterEqual}, {"always", DepthFunc::Always}});
    if (s.has("depth_test")) sc.state.depth_test = s.at("depth_test").boolean();
    if (s.has("depth_write")) sc.state.depth_write = s.at("depth_write").boolean();
    if (s.has("interp"))
      sc.state.interp = s.at("interp").choice<InterpMode>({{"perspective", InterpMode::Perspective}, {"affine", InterpMode::Affine}});
    if (s.has("scissor")) {
      const Node sn = s.at("scissor");
      if (!sn.j.is_array() || sn.j.size() != 4) sn.fail("expected 4 integers [x, y, width, height], got " + sn.type_of());
      sc.state.scissor_x = sn.at(size_t{0}).integer(-kMaxViewportSide, kMaxViewportSide);
      sc.state.scissor_y = sn.at(size_t{1}).integer(-kMaxViewportSide, kMaxViewportSide);
      sc.state.scissor_w = sn.at(size_t{2}).integer(0, kMaxViewportSide);
      sc.state.scissor_h = sn.at(size_t{3}).integer(0, kMaxViewportSide);
    }
  }

  if (root.has("background")) {
    const Node b = root.at("background");
    sc.background = b.color();
  } else {
    sc.background = pack_rgba(24, 24, 32);
  }

  // Varyings: how many, and which are the texture u, v.
  sc.state.num_varyings = 2;
  if (root.has("varyings")) {
    const Node v = root.at("varyings");
    v.expect_object({"count", "u", "v"});
    if (v.has("count")) sc.state.num_varyings = v.at("count").integer(0, kMaxVaryings);
    if (v.has("u")) sc.u_varying = v.at("u").integer(-1, kMaxVaryings - 1);
    if (v.has("v")) sc.v_varying = v.at("v").integer(-1, kMaxVaryings - 1);
    // u / v default to varyings 0 and 1: name the field that is actually given.
    auto check_uv = [&](const char* key, int index) {
      if (index < sc.state.num_varyings) return;
      const std::string count = std::to_string(sc.state.num_varyings);
      if (v.has(key)) v.at(key).fail("names varying " + std::to_string(index) + " but count is " + count);
      Node{v.j, v.where, v.path + "/count"}.fail(count + " leaves no varying for the texture coordinate '" + key +
                                                  "' (default varying " + std::to_string(index) + "): give \"" +
                                                  key + "\": -1 for no texture coordinate, or a larger count");
    };
    check_uv("u", sc.u_varying);
    check_uv("v", sc.v_varying);
  }
  if (sc.state.num_varyings < 2 && !root.has("varyings")) sc.u_varying = sc.v_varying = -1;

  // Texture. Its filter and wrap mode are texture state the texture address unit is fed: given
  // here, they set the configuration's tex_addr.filter / tex_addr.wrap (docs/scene-format.md).
  uint32_t border = sc.background;
  if (root.has("texture")) {
    const Node t = root.at("texture");
    t.expect_object({"kind", "size", "squares", "colors", "path", "wrap", "filter", "border"});
    if (t.has("wrap"))
      sc.config.tex_addr.wrap = t.at("wrap").choice<TexWrap>(
          {{"repeat", TexWrap::Repeat}, {"mirrored_repeat", TexWrap::MirroredRepeat},
           {"clamp_to_edge", TexWrap::ClampToEdge}, {"clamp_to_border", TexWrap::ClampToBorder},
           {"clamp", TexWrap::ClampToEdge}});  // "clamp": the seed's clamp, the name before issue 15
    if (t.has("filter"))
      sc.config.tex_addr.filter =
          t.at("filter").choice<TexFilter>({{"nearest", TexFilter::Nearest}, {"bilinear", TexFilter::Bilinear}});
    if (t.has("border")) border = t.at("border").color();
    const std::string kind = t.at("kind").string();
    if (kind == "checker") {
      const int size = t.has("size") ? t.at("size").integer(1, 4096) : 64;
      const int squares = t.has("squares") ? t.at("squares").integer(1, 4096) : 8;
      if (size % squares) t.at("squares").fail("must divide size " + std::to_string(size));
      uint32_t a = pack_rgba(240, 208, 64), b = pack_rgba(32, 64, 160);
      if (t.has("colors")) {
        const Node c = t.at("colors");
        if (!c.j.is_array() || c.j.size() != 2) c.fail("expected 2 colours [\"#rrggbb\", \"#rrggbb\"], got " + c.type_of());
        a = c.at(size_t{0}).color();
        b = c.at(size_t{1}).color();
      }
      sc.texture = make_checker(size, squares, a, b);
    } else if (kind == "png") {
      const Node p = t.at("path");
      try {
        sc.texture = load_png_texture(resolve(base_dir, p.string()));
      } catch (const ConfigError& e) {
        p.fail(e.what());
      }
      // The texture address unit takes sizes up to 2^tex_addr.size_bits.
      const int64_t most = int64_t{1} << sc.config.tex_addr.size_bits;
      if (sc.texture.image.width > most || sc.texture.image.height > most)
        p.fail("the texture is " + std::to_string(sc.texture.image.width) + "x" +
               std::to_string(sc.texture.image.height) + ", larger than the texture address unit's 2^tex_addr.size_bits = " +
               std::to_string(most) + " texels per side");
    } else {
      t.at("kind").fail("'" + kind + "' is not one of: checker, png");
    }
  } else {
    sc.texture = make_checker(64, 8, pack_rgba(240, 208, 64), pack_rgba(32, 64, 160));
  }
  sc.texture.border = border;

  // Line draw state: the draw state with the depth fields overridden, and the lines' colour.
  sc.line_state = sc.state;
  if (root.has("line_state")) {
    const Node s = root.at("line_state");
    s.expect_object({"depth_func", "depth_test", "depth_write", "color"});
    if (s.has("depth_func"))
      sc.line_state.depth_func = s.at("depth_func").choice<DepthFunc>(
          {{"never", DepthFunc::Never}, {"less", DepthFunc::Less}, {"equal", DepthFunc::Equal},
           {"lequal", DepthFunc::LessEqual}, {"greater", DepthFunc::Greater}, {"notequal", DepthFunc::NotEqual},
           {"gequal", DepthFunc::GreaterEqual}, {"always", DepthFunc::Always}});
    if (s.has("depth_test")) sc.line_state.depth_test = s.at("depth_test").boolean();
    if (s.has("depth_write")) sc.line_state.depth_write = s.at("depth_write").boolean();
    if (s.has("color")) {
      const Node c = s.at("color");
      sc.line_color = c.color();
    }
  }

  // Camera (only meshes use it).
  Camera cam;
  if (root.has("camera"))
    cam = parse_camera(root.at("camera"), (double)sc.state.viewport_w / sc.state.viewport_h);
  const glm::dmat4 pv = cam.proj * cam.view;

  // Objects.
  const Node objs = root.at("objects");
  for (size_t i = 0; i < objs.array_size(); ++i) {
    const Node o = objs.at(i);
    if (!o.j.is_object()) o.fail("expected an object, got " + o.type_of());
    const std::string type = o.at("type").string();
    if (type == "mesh") parse_mesh(o, sc, pv, base_dir, opt);
    else if (type == "clip") parse_clip(o, sc);
    else if (type == "lines") parse_lines(o, sc);
    else o.at("type").fail("'" + type + "' is not one of: mesh, clip, lines");
  }
  for (SceneObjectInfo& info : sc.objects)  // lines are numbered after every triangle
    if (info.kind == "lines") info.first_prim += (uint32_t)sc.tris.size();
  return sc;
}

Scene load_scene(const std::string& path, const SceneOptions& opt) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open the scene file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_scene(ss.str(), path, dir_of(path), opt);
}

}  // namespace fxr

namespace fxr {

void apply_config_file(Scene& sc, const std::string& config_path) {
  const nlohmann::json cj = read_json_file(config_path, "configuration file");  // bounded, numbers checked
  config_fields_from_json(cj, config_path);  // types and ranges of the file on its own (fields named)
  nlohmann::json merged = config_to_json(sc.config);
  merged.merge_patch(cj);
  sc.config = config_from_json(merged, config_path);
}

}  // namespace fxr
