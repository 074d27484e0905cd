// The texel report (analysis/texel_errors.hpp).
#include "analysis/texel_errors.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "analysis/render_images.hpp"
#include "model/stages/texaddr.hpp"
#include "model/stages/texfilter.hpp"
#include "reference/reference.hpp"
#include "reference/texture_ref.hpp"

namespace fxr {

using json = nlohmann::json;

namespace {

const char* const kFilterNames[] = {"nearest", "bilinear"};
const char* const kWrapNames[] = {"repeat", "mirrored_repeat", "clamp_to_edge", "clamp_to_border"};

bool same_texels(const TexAxis& a, const TexAxis& b) {
  return a.i0 == b.i0 && a.i1 == b.i1 && a.border0 == b.border0 && a.border1 == b.border1;
}

// Largest channel difference between an RGBA8 colour and an unrounded blend, in 8-bit levels.
double colour_error(uint32_t c, const std::array<double, 4>& ref) {
  double e = 0;
  for (int k = 0; k < kTexChannels; ++k)
    e = std::max(e, std::abs((double)((c >> (kTexChannelBits * k)) & ((1u << kTexChannelBits) - 1)) - ref[k]));
  return e;
}

// The exponent field of the RTL (tex_addr.exp_bits, signed) holds exp.
bool exp_fits(const FxFloat& x, int exp_bits) {
  return x.sig == 0 || (x.exp >= -(1 << (exp_bits - 1)) && x.exp < (1 << (exp_bits - 1)));
}

// One fragment at the exact levels (own, ideal): the unit's address of the model's codes against
// the exact address of the rational coordinates (u, v).
void exact_level(const TexAddrConfig& c, const Image& im, uint32_t border, const TexAddrOut& unit, uint32_t colour,
                 const mpq_class& u, const mpq_class& v, TexelLevel* l) {
  ++l->checked;
  // The correctly rounded address of (u, v) and the unwrapped i0 its weight is relative to.
  mpz_class i0s, i0t;
  const TexAxis rs = exact_tex_axis_rounded(c, u, im.width, &i0s);
  const TexAxis rt = exact_tex_axis_rounded(c, v, im.height, &i0t);
  const RefTexAxis xs = exact_ref_axis(c.filter, c.wrap, u, im.width), xt = exact_ref_axis(c.filter, c.wrap, v, im.height);
  l->colour.add(colour_error(colour, blend_ref(im, border, xs, xt)));
  if (!same_texels(unit.s, rs) || !same_texels(unit.t, rt)) return;
  ++l->same_texels;
  if (c.filter != TexFilter::Bilinear) return;
  // |i0·2^F + weight − (u·W − ½)·2^F|: the unit's position along the axis against the exact one.
  const mpz_class one_f = mpz_class(1) << c.weight_frac_bits;
  auto werr = [&](const mpz_class& i0, uint32_t w, const mpq_class& x, uint32_t size) {
    const mpq_class t = (x * mpq_class(size) - mpq_class(1, 2)) * mpq_class(one_f);
    return std::abs(mpq_class(mpq_class(i0 * one_f + w) - t).get_d());
  };
  l->weight_lsb.add(werr(i0s, unit.s.weight, u, im.width));
  l->weight_lsb.add(werr(i0t, unit.t.weight, v, im.height));
}

}  // namespace

json TexelLevel::to_json() const {
  return {{"checked", checked}, {"same_texels", same_texels},
          {"same_texels_fraction", checked ? (double)same_texels / (double)checked : 0.0},
          {"weight_error_lsb", weight_lsb.to_json()}, {"colour_error_levels", colour.to_json()}};
}

json TexelErrors::to_json() const {
  json j = {{"textured", textured}};
  if (!textured) return j;
  j["wrap"] = wrap;
  j["weight_frac_bits"] = weight_frac_bits;
  j["coordinates_exp_outside_field"] = coords_exp_outside;
  for (const auto& f : filters)
    j["filters"][f.filter] = {{"vs_exact_own_coordinates", f.own.to_json()}, {"vs_exact_ideal", f.ideal.to_json()},
                              {"vs_double_reference", f.ref.to_json()}};
  return j;
}

TexelErrors texel_errors(const Scene& sc, const FrameOutput& fo, const SpotChecks& spot) {
  TexelErrors r;
  r.textured = sc.u_varying >= 0 && sc.v_varying >= 0;
  if (!r.textured) return r;
  const Image& im = sc.texture.image;
  const uint32_t border = sc.texture.border;
  r.wrap = kWrapNames[(int)sc.config.tex_addr.wrap];
  r.weight_frac_bits = sc.config.tex_addr.weight_frac_bits;
  const int nv = sc.state.num_varyings;
  // Triangle fragments only: line fragments (primitives after the triangles) are drawn in a flat
  // colour, not textured (analysis/render_images.cpp).
  auto textured_fragment = [&](const Fragment& f) { return f.prim < sc.tris.size(); };
  for (const Fragment& f : fo.fragments)
    if (textured_fragment(f))
      for (int k : {sc.u_varying, sc.v_varying}) r.coords_exp_outside += !exp_fits(f.var[k], sc.config.tex_addr.exp_bits);

  // The double reference at every fragment (double; computed once for both filters).
  std::vector<RefSample> refs(fo.fragments.size());
  for (size_t i = 0; i < fo.fragments.size(); ++i) {
    const Fragment& f = fo.fragments[i];
    if (textured_fragment(f)) refs[i] = reference_at_pixel(sc.state, sc.tris[f.prim], nv, f.x + 0.5, f.y + 0.5);
  }
  for (TexFilter filter : {TexFilter::Nearest, TexFilter::Bilinear}) {
    Scene s2 = sc;  // the filter under test; everything else as configured
    s2.config.tex_addr.filter = filter;
    const TexAddrConfig& c = s2.config.tex_addr;
    TexelFilterErrors fe;
    fe.filter = kFilterNames[(int)filter];
    auto unit_at = [&](const Fragment& f, TexAddrOut* a) {
      TexAddrIn in;
      in.u = f.var[sc.u_varying];
      in.v = f.var[sc.v_varying];
      in.width = (uint32_t)im.width;
      in.height = (uint32_t)im.height;
      *a = texaddr(c, in);
      return shade_fragment(s2, in.u, in.v);
    };
    for (size_t i = 0; i < fo.fragments.size(); ++i) {
      const Fragment& f = fo.fragments[i];
      if (!textured_fragment(f)) continue;
      TexAddrOut a;
      const uint32_t colour = unit_at(f, &a);
      exact_level(c, im, border, a, colour, to_mpq(f.var[sc.u_varying]), to_mpq(f.var[sc.v_varying]), &fe.own);
      if (!refs[i].valid) continue;
      ++fe.ref.checked;
      const double ru = refs[i].var[sc.u_varying], rv = refs[i].var[sc.v_varying];
      // Same texels: against the correctly rounded address of the double u, v (as for the exact
      // levels: a weight that rounds to 2^F carries into i0 + 1).
      double xs = 0, xt = 0, i0s = 0, i0t = 0;
      const TexAxis qs = ref_tex_axis_rounded(c, ru, im.width, &xs, &i0s);
      const TexAxis qt = ref_tex_axis_rounded(c, rv, im.height, &xt, &i0t);
      if (same_texels(a.s, qs) && same_texels(a.t, qt)) {
        ++fe.ref.same_texels;
        if (filter == TexFilter::Bilinear) {
          const double one_f = std::ldexp(1.0, c.weight_frac_bits);
          fe.ref.weight_lsb.add(std::abs(i0s * one_f + a.s.weight - xs * one_f));
          fe.ref.weight_lsb.add(std::abs(i0t * one_f + a.t.weight - xt * one_f));
        }
      }
      fe.ref.colour.add(colour_error(colour, blend_ref(im, border, ref_tex_axis(filter, c.wrap, ru, im.width),
                                                       ref_tex_axis(filter, c.wrap, rv, im.height))));
    }
    for (const auto& p : spot.ideal_uv) {
      const Fragment& f = fo.fragments[p.fragment];
      TexAddrOut a;
      const uint32_t colour = unit_at(f, &a);
      exact_level(c, im, border, a, colour, p.u, p.v, &fe.ideal);
    }
    r.filters.push_back(std::move(fe));
  }
  return r;
}

}  // namespace fxr
