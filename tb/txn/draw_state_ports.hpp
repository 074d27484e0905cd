// tb/txn/draw_state_ports.hpp — the draw state (fxr::DrawState, the register block) on a DUT's
// per-field draw-state ports (rtl/fxr_setup.sv, rtl/fxr_raster_backend.sv), and read back from a
// transaction dump's scene.json ("draw_state", written by model/vectors/scene_dump.cpp).
#pragma once

#include <string>
#include <type_traits>

#include "model/config/param.hpp"
#include "model/unit/io.hpp"
#include "model/vectors/scene_dump.hpp"

namespace fxr::tb {

// A signed field of `bits` bits as the port's two's-complement bit pattern.
inline uint32_t state_bits(int v, int bits) { return (uint32_t)v & (uint32_t)((1ull << bits) - 1); }

// Ports present on every DUT with setup's draw state; the depth ones when the DUT has them.
template <class D, class = void>
struct HasDepthState : std::false_type {};
template <class D>
struct HasDepthState<D, std::void_t<decltype(std::declval<D&>().depth_func_i)>> : std::true_type {};

template <class Dut>
void drive_draw_state(Dut& d, const DrawState& st, int window_int_bits) {
  const int b = window_int_bits;
  d.viewport_x_i = state_bits(st.viewport_x, b);
  d.viewport_y_i = state_bits(st.viewport_y, b);
  d.viewport_w_i = state_bits(st.viewport_w, b + 1);
  d.viewport_h_i = state_bits(st.viewport_h, b + 1);
  d.scissor_x_i = state_bits(st.scissor_x, b);
  d.scissor_y_i = state_bits(st.scissor_y, b);
  d.scissor_w_i = state_bits(st.scissor_w, b + 1);
  d.scissor_h_i = state_bits(st.scissor_h, b + 1);
  d.cull_i = (uint8_t)st.cull;
  d.front_ccw_i = st.front_ccw;
  d.interp_i = (uint8_t)st.interp;
  if constexpr (HasDepthState<Dut>::value) {
    d.depth_func_i = (uint8_t)st.depth_func;
    d.depth_test_i = st.depth_test;
    d.depth_write_i = st.depth_write;
  }
}

// The draw state of a dump (scene.json "draw_state"): the model's reader (checked conversions,
// ConfigError naming the file and field).
inline DrawState read_dump_draw_state(const std::string& dir) { return load_scene_draw_state(dir); }

}  // namespace fxr::tb
