// The plain float rasterizer (see reference/float_raster.hpp). float32 everywhere on purpose: this
// is the "what a quick software rasterizer costs" baseline the model's speed is compared to.
#include "reference/float_raster.hpp"

#include <algorithm>
#include <cmath>

namespace fxr::peer {

namespace {

// Outcode bit per clip plane −w ≤ x ≤ w, −w ≤ y ≤ w, 0 ≤ z ≤ w.
unsigned outcode(const float* p) {
  const float x = p[0], y = p[1], z = p[2], w = p[3];
  return (x < -w) | (x > w) << 1 | (y < -w) << 2 | (y > w) << 3 | (z < 0) << 4 | (z > w) << 5;
}

}  // namespace

void float_raster(const DrawState& st, const std::vector<ClipTriangle>& tris, FloatFrame& f) {
  const int W = st.viewport_x + st.viewport_w, H = st.viewport_y + st.viewport_h;
  const int nv = st.num_varyings;
  f.width = W;
  f.height = H;
  f.num_varyings = nv;
  f.depth.assign((size_t)W * H, 1.0f);
  f.var.assign((size_t)W * H * nv, 0.0f);
  f.prim.assign((size_t)W * H, -1);
  f.fragments_generated = f.fragments_passed = f.skipped_w = f.rejected = 0;

  // Pixels drawn: viewport ∩ scissor.
  const int sx0 = st.scissor_w < 0 ? st.viewport_x : std::max(st.viewport_x, st.scissor_x);
  const int sy0 = st.scissor_h < 0 ? st.viewport_y : std::max(st.viewport_y, st.scissor_y);
  const int sx1 = st.scissor_w < 0 ? W : std::min(W, st.scissor_x + st.scissor_w);
  const int sy1 = st.scissor_h < 0 ? H : std::min(H, st.scissor_y + st.scissor_h);
  const float half_w = 0.5f * (float)st.viewport_w, half_h = 0.5f * (float)st.viewport_h;
  const float off_x = (float)st.viewport_x + half_w, off_y = (float)st.viewport_y + half_h;
  const bool affine = st.interp == InterpMode::Affine;

  float X[3], Y[3], Z[3], RW[3];
  float VW[3][kMaxVaryings];
  for (size_t t = 0; t < tris.size(); ++t) {
    const ClipVertex* v = tris[t].v;
    if (outcode(v[0].pos) & outcode(v[1].pos) & outcode(v[2].pos)) {
      ++f.rejected;
      continue;
    }
    if (!(v[0].pos[3] > 0 && v[1].pos[3] > 0 && v[2].pos[3] > 0)) {
      ++f.skipped_w;  // would need the clipper
      continue;
    }
    for (int i = 0; i < 3; ++i) {
      RW[i] = 1.0f / v[i].pos[3];
      X[i] = v[i].pos[0] * RW[i] * half_w + off_x;
      Y[i] = v[i].pos[1] * RW[i] * half_h + off_y;
      Z[i] = v[i].pos[2] * RW[i];
      for (int k = 0; k < nv; ++k) VW[i][k] = affine ? v[i].var[k] : v[i].var[k] * RW[i];
    }
    float area = (X[1] - X[0]) * (Y[2] - Y[0]) - (X[2] - X[0]) * (Y[1] - Y[0]);
    if (!(area != 0) || !std::isfinite(area)) continue;
    const bool front = (area > 0) == st.front_ccw;
    if ((st.cull == CullMode::Back && !front) || (st.cull == CullMode::Front && front)) continue;
    int idx[3] = {0, 1, 2};
    if (area < 0) {  // make it counter-clockwise (y up)
      std::swap(idx[1], idx[2]);
      area = -area;
    }
    // Edge i runs from vertex idx[i+1] to idx[i+2] (opposite vertex idx[i]); E_i > 0 inside.
    float A[3], B[3], AX[3], AY[3];
    bool tl[3];
    for (int i = 0; i < 3; ++i) {
      const int a = idx[(i + 1) % 3], b = idx[(i + 2) % 3];
      const float dx = X[b] - X[a], dy = Y[b] - Y[a];
      A[i] = -dy;
      B[i] = dx;
      AX[i] = X[a];
      AY[i] = Y[a];
      tl[i] = (dy == 0 && dx < 0) || dy < 0;  // top or left edge, y up
    }
    const float inv_area = 1.0f / area;
    const float xmin = std::min({X[0], X[1], X[2]}), xmax = std::max({X[0], X[1], X[2]});
    const float ymin = std::min({Y[0], Y[1], Y[2]}), ymax = std::max({Y[0], Y[1], Y[2]});
    const int bx0 = std::max(sx0, (int)std::floor(xmin)), bx1 = std::min(sx1 - 1, (int)std::ceil(xmax));
    const int by0 = std::max(sy0, (int)std::floor(ymin)), by1 = std::min(sy1 - 1, (int)std::ceil(ymax));
    if (bx0 > bx1 || by0 > by1) continue;
    const float* Zs[3] = {&Z[idx[0]], &Z[idx[1]], &Z[idx[2]]};
    for (int py = by0; py <= by1; ++py) {
      const float cy = (float)py + 0.5f, cx = (float)bx0 + 0.5f;
      float e[3];
      for (int i = 0; i < 3; ++i) e[i] = A[i] * (cx - AX[i]) + B[i] * (cy - AY[i]);
      for (int px = bx0; px <= bx1; ++px, e[0] += A[0], e[1] += A[1], e[2] += A[2]) {
        bool in = true;
        for (int i = 0; i < 3; ++i) in &= e[i] > 0 || (e[i] == 0 && tl[i]);
        if (!in) continue;
        ++f.fragments_generated;
        const float l0 = e[0] * inv_area, l1 = e[1] * inv_area, l2 = e[2] * inv_area;
        const float z = l0 * *Zs[0] + l1 * *Zs[1] + l2 * *Zs[2];
        const size_t o = (size_t)py * W + px;
        if (st.depth_test) {
          if (!depth_compare(st.depth_func, z, f.depth[o])) continue;
          if (st.depth_write) f.depth[o] = z;
        }
        ++f.fragments_passed;
        f.prim[o] = (int32_t)t;
        const float q = affine ? 1.0f : l0 * RW[idx[0]] + l1 * RW[idx[1]] + l2 * RW[idx[2]];
        const float rq = 1.0f / q;
        float* out = f.var.data() + o * nv;  // not &var[…]: var is empty when nv == 0
        for (int k = 0; k < nv; ++k)
          out[k] = (l0 * VW[idx[0]][k] + l1 * VW[idx[1]][k] + l2 * VW[idx[2]][k]) * rq;
      }
    }
  }
}

}  // namespace fxr::peer
