// Scenes for the peer comparison and the benchmark (double-precision front end, GLM).
#include "reference/peer/peer_scenes.hpp"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace fxr::peer {

namespace {

// Texture coordinates span [0, kUvRange] (the llvmpipe accuracy figure of
// docs/references.md#peer-disagreement is for u, v in 0..16).
constexpr double kUvRange = 16.0;

DrawState state(int size, int num_varyings) {
  DrawState st;
  st.viewport_w = st.viewport_h = size;
  st.num_varyings = num_varyings;
  st.depth_test = true;
  st.depth_func = DepthFunc::Less;
  return st;
}

// Clip-space vertex from a double position and the matrix; varyings u, v when asked.
ClipVertex clip_vertex(const glm::dmat4& mvp, const glm::dvec3& p, double u, double v, int nv) {
  const glm::dvec4 c = mvp * glm::dvec4(p, 1.0);
  ClipVertex out;
  for (int i = 0; i < 4; ++i) out.pos[i] = (float)c[i];  // the only rounding: double → float32 (RNE)
  if (nv > 0) out.var[0] = (float)u;
  if (nv > 1) out.var[1] = (float)v;
  return out;
}

// A UV sphere with about the bunny's triangle count (stacks × slices × 2).
void sphere_mesh(std::vector<glm::dvec3>& pos, std::vector<unsigned>& idx) {
  const int stacks = 186, slices = 187;  // 2 · 186 · 187 = 69,564 triangles
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= slices; ++j) {
      const double th = M_PI * i / stacks, ph = 2 * M_PI * j / slices;
      pos.emplace_back(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
    }
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const unsigned a = i * (slices + 1) + j, b = a + slices + 1;
      idx.insert(idx.end(), {a, b, a + 1, a + 1, b, b + 1});
    }
}

}  // namespace

PeerScene bunny_scene(int size, int num_varyings, const std::string& path) {
  PeerScene s;
  s.name = "bunny";
  s.st = state(size, num_varyings);
  std::vector<glm::dvec3> pos;
  std::vector<unsigned> idx;
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> mats;
  std::string warn, err;
  if (tinyobj::LoadObj(&attrib, &shapes, &mats, &warn, &err, path.c_str(), nullptr, true) && !shapes.empty()) {
    for (size_t i = 0; i + 2 < attrib.vertices.size(); i += 3)
      pos.emplace_back(attrib.vertices[i], attrib.vertices[i + 1], attrib.vertices[i + 2]);
    for (const auto& sh : shapes)
      for (const auto& ix : sh.mesh.indices) idx.push_back((unsigned)ix.vertex_index);
  } else {
    s.name = "sphere_instead_of_bunny";
    s.note = "bunny not found at " + path + " (Debian package glmark2-data): using a generated sphere";
    sphere_mesh(pos, idx);
  }
  glm::dvec3 lo(1e300), hi(-1e300);
  for (const auto& p : pos) lo = glm::min(lo, p), hi = glm::max(hi, p);
  const glm::dvec3 centre = 0.5 * (lo + hi);
  const double radius = 0.5 * glm::length(hi - lo);
  // Fixed camera: looking down −z at the centre from a distance that frames the bounding sphere.
  const double fov = glm::radians(40.0);
  const double dist = radius / std::sin(fov / 2);
  const glm::dmat4 view = glm::lookAtRH(centre + glm::dvec3(0, 0, dist), centre, glm::dvec3(0, 1, 0));
  const glm::dmat4 proj = glm::perspectiveRH_ZO(fov, 1.0, dist - 1.5 * radius, dist + 1.5 * radius);
  const glm::dmat4 mvp = proj * view;
  const double ext = std::max(hi.x - lo.x, hi.y - lo.y);
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    ClipTriangle tri;
    for (int k = 0; k < 3; ++k) {
      const glm::dvec3& p = pos[idx[t + k]];
      tri.v[k] = clip_vertex(mvp, p, kUvRange * (p.x - lo.x) / ext, kUvRange * (p.y - lo.y) / ext, num_varyings);
    }
    s.tris.push_back(tri);
  }
  return s;
}

PeerScene grazing_plane_scene(int size, int num_varyings) {
  PeerScene s;
  s.name = "grazing_plane";
  s.st = state(size, num_varyings);
  // Plane y = 0, x ∈ [−40, 40], z ∈ [−2, −200]; eye at height 1 looking at the horizon.
  const double x0 = -40, x1 = 40, zn = -2, zf = -200;
  const glm::dmat4 view = glm::lookAtRH(glm::dvec3(0, 1, 0), glm::dvec3(0, 0.6, -10), glm::dvec3(0, 1, 0));
  const glm::dmat4 proj = glm::perspectiveRH_ZO(glm::radians(60.0), 1.0, 0.5, 400.0);
  const glm::dmat4 mvp = proj * view;
  const glm::dvec3 c[4] = {{x0, 0, zn}, {x1, 0, zn}, {x1, 0, zf}, {x0, 0, zf}};
  const double uv[4][2] = {{0, 0}, {kUvRange, 0}, {kUvRange, kUvRange}, {0, kUvRange}};
  const int tri_idx[2][3] = {{0, 1, 2}, {0, 2, 3}};
  for (const auto& ti : tri_idx) {
    ClipTriangle t;
    for (int k = 0; k < 3; ++k) t.v[k] = clip_vertex(mvp, c[ti[k]], uv[ti[k]][0], uv[ti[k]][1], num_varyings);
    s.tris.push_back(t);
  }
  return s;
}

}  // namespace fxr::peer
