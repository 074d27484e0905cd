// reference/peer/peer_osmesa.hpp — the external peer: Mesa llvmpipe through OSMesa (GL 4.5 core context,
// GL 3.3 features plus GL_ARB_clip_control).
//
// The peer draws exactly what the raster unit receives — float32 clip-space triangles with
// float32 varyings and a DrawState — and Mesa does everything else itself: clipping, the
// perspective divide, the viewport transform, snapping to 1/256 px (round to nearest),
// the fill rule, perspective-correct interpolation and the depth test. The vertex shader passes
// the clip position through unchanged (y negated when mirroring, an exact float operation).
//
// Conventions (docs/peer.md):
//   - Images are returned in the model's convention: row 0 at the bottom, pixel centres at
//     (x + ½, y + ½), window [0, viewport_x + viewport_w) × [0, viewport_y + viewport_h).
//   - llvmpipe applies its top-left rule with y counting down from row 0 (memory order): in the
//     y-up window coordinates of GL, left and BOTTOM edges are inclusive. With mirror_y (the
//     default) the peer draws the y-mirrored scene (y_c → −y_c, mirrored viewport and scissor,
//     opposite front face) and mirrors the readback back, so its fill rule becomes the model's
//     top-left rule (left and top edges inclusive in y-up coordinates). Mirroring is exact on
//     the 1/256 grid: RNE snapping commutes with y → H − y for an integer H.
//   - Depth: glClipControl(GL_LOWER_LEFT, GL_ZERO_TO_ONE), glDepthRange(0, 1): window z is
//     z_c / w_c, clip volume 0 ≤ z_c ≤ w_c, like the model. Read back as float32 (the depth
//     buffer is GL_DEPTH_COMPONENT32F, cleared to 1).
//   - llvmpipe is only the peer for coverage and sanity: its varyings are off the exact value by
//     up to 1.1e-3 on u, v in 0..16 (docs/references.md#peer-disagreement). Accuracy is judged
//     against exact arithmetic elsewhere.
#pragma once

#include <cstdint>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/unit/io.hpp"

namespace fxr::peer {

// Anything the peer cannot do (no OSMesa context, not llvmpipe, no clip control, a GL error):
// thrown, never swallowed. Tests fail on it unless FXR_NO_PEER is set.
struct PeerError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct PeerOptions {
  // Draw the y-mirrored scene so that llvmpipe's fill rule equals the model's (see above).
  bool mirror_y = true;
  // LP_NUM_THREADS for llvmpipe (0: rasterise in the calling thread, fully single-threaded).
  // llvmpipe reads it when OSMesa creates its screen, i.e. at the first context of the process:
  // later values have no effect. −1 leaves the environment alone.
  int lp_num_threads = 0;
};

// What the peer drew, per pixel, row 0 at the bottom (index y · width + x).
struct PeerImage {
  int width = 0, height = 0, num_varyings = 0;
  std::vector<uint32_t> count;  // fragments written to the pixel (all that passed the depth test)
  std::vector<int32_t> prim;    // index of the triangle written last (−1: none)
  std::vector<float> var;       // varyings of that fragment, num_varyings per pixel
  std::vector<float> depth;     // depth buffer (window z in [0, 1]; 1 where never written)

  size_t index(int x, int y) const { return (size_t)y * (size_t)width + (size_t)x; }
  bool covered(int x, int y) const { return count[index(x, y)] != 0; }
  float varying(int x, int y, int k) const { return var[index(x, y) * (size_t)num_varyings + (size_t)k]; }
  uint64_t fragments() const;  // Σ count
};

// Mesa's identification strings and the limits that matter here.
struct PeerInfo {
  std::string version, renderer;
  int subpixel_bits = 0;
  int max_viewport = 0;
  bool clip_control = false;
};

class OsmesaPeer {
 public:
  // Creates the OSMesa GL core context (GALLIUM_DRIVER forced to llvmpipe). Throws PeerError
  // when no context can be created, the renderer is not llvmpipe or clip control is missing.
  explicit OsmesaPeer(const PeerOptions& opt = {});
  ~OsmesaPeer();
  OsmesaPeer(const OsmesaPeer&) = delete;
  OsmesaPeer& operator=(const OsmesaPeer&) = delete;

  const PeerInfo& info() const;

  // Draws `tris` (GL_TRIANGLES, in order, gl_PrimitiveID = index) with `st` and reads back.
  // Honoured: viewport, scissor, num_varyings (≤ kMaxVaryings), front_ccw, cull, depth_test,
  // depth_func, depth_write, interp (Affine → noperspective). Deterministic.
  PeerImage render(const DrawState& st, const std::vector<ClipTriangle>& tris);

  // Draws `lines` (GL_LINES, width 1, not smoothed: GL's diamond-exit rule, docs/lines.md;
  // gl_PrimitiveID = index) with `st`, as render() does triangles (cull and front face do not
  // apply). docs/references.md#llvmpipe-lines: how llvmpipe implements the rule.
  PeerImage render_lines(const DrawState& st, const std::vector<ClipLine>& lines);

  // The same in three steps, for timing: prepare() uploads the triangles and sets the state
  // (not timed); draw() clears, draws and waits for completion (glFinish); read() reads back.
  void prepare(const DrawState& st, const std::vector<ClipTriangle>& tris);
  void draw();
  PeerImage read();
  // Samples that passed the depth test in one draw() (GL_SAMPLES_PASSED query).
  uint64_t draw_counting_samples();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fxr::peer
