// tb/txn/draw_state_ports.hpp — the draw state (fxr::DrawState, the register block) on a DUT's
// per-field draw-state ports (rtl/fxr_setup.sv, rtl/fxr_raster_backend.sv), and read back from a
// transaction dump's scene.json ("draw_state", written by model/vectors/scene_dump.cpp).
#pragma once

#include <fstream>
#include <string>
#include <type_traits>

#include <nlohmann/json.hpp>

#include "model/config/param.hpp"
#include "model/unit/io.hpp"

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

// The draw state of a dump (scene.json "draw_state"; ConfigError naming the file when absent).
inline DrawState read_dump_draw_state(const std::string& dir) {
  const std::string path = dir + "/scene.json";
  std::ifstream f(path);
  if (!f) throw ConfigError(path + ": cannot open");
  const nlohmann::json all = nlohmann::json::parse(f);
  if (!all.contains("draw_state")) throw ConfigError(path + ": field 'draw_state' is missing");
  const nlohmann::json& j = all.at("draw_state");
  auto get = [&](const char* n) {
    if (!j.contains(n)) throw ConfigError(path + ": field 'draw_state." + std::string(n) + "' is missing");
    return j.at(n).get<int>();
  };
  DrawState st;
  st.viewport_x = get("viewport_x");
  st.viewport_y = get("viewport_y");
  st.viewport_w = get("viewport_w");
  st.viewport_h = get("viewport_h");
  st.scissor_x = get("scissor_x");
  st.scissor_y = get("scissor_y");
  st.scissor_w = get("scissor_w");
  st.scissor_h = get("scissor_h");
  st.num_varyings = get("num_varyings");
  st.front_ccw = get("front_ccw") != 0;
  st.cull = (CullMode)get("cull");
  st.depth_func = (DepthFunc)get("depth_func");
  st.depth_test = get("depth_test") != 0;
  st.depth_write = get("depth_write") != 0;
  st.interp = (InterpMode)get("interp");
  return st;
}

}  // namespace fxr::tb
