// References of texture addressing and filtering (reference/texture_ref.hpp).
#include "reference/texture_ref.hpp"

#include <cmath>

#include "model/stages/texfilter.hpp"

namespace fxr {

namespace {

mpz_class floor_q(const mpq_class& q) {
  mpz_class r;
  mpz_fdiv_q(r.get_mpz_t(), q.get_num_mpz_t(), q.get_den_mpz_t());
  return r;
}

// Double wrap of an integer-valued index i (any magnitude; fmod is exact).
void ref_wrap(TexWrap wrap, double i, uint32_t size, uint32_t* idx, bool* border) {
  const double w = size;
  *border = false;
  switch (wrap) {
    case TexWrap::Repeat: {
      double r = std::fmod(i, w);
      if (r < 0) r += w;
      *idx = (uint32_t)r;
      return;
    }
    case TexWrap::MirroredRepeat: {
      double r = std::fmod(i, 2 * w);
      if (r < 0) r += 2 * w;
      *idx = (uint32_t)(r < w ? r : 2 * w - 1 - r);
      return;
    }
    case TexWrap::ClampToBorder: *border = i < 0 || i >= w; [[fallthrough]];
    case TexWrap::ClampToEdge: *idx = (uint32_t)(i < 0 ? 0 : (i >= w ? w - 1 : i)); return;
  }
}

}  // namespace

ExactTexAxis exact_tex_axis(TexFilter filter, const mpq_class& u, uint32_t size) {
  ExactTexAxis a;
  mpq_class x = u * mpq_class(size);
  if (filter == TexFilter::Bilinear) x -= mpq_class(1, 2);
  a.i0 = floor_q(x);
  a.frac = filter == TexFilter::Bilinear ? mpq_class(x - mpq_class(a.i0)) : mpq_class(0);
  return a;
}

void exact_wrap(TexWrap wrap, const mpz_class& i, uint32_t size, uint32_t* idx, bool* border) {
  const mpz_class w(size);
  *border = false;
  mpz_class r;
  switch (wrap) {
    case TexWrap::Repeat: mpz_fdiv_r(r.get_mpz_t(), i.get_mpz_t(), w.get_mpz_t()); break;
    case TexWrap::MirroredRepeat: {
      const mpz_class w2 = 2 * w;
      mpz_fdiv_r(r.get_mpz_t(), i.get_mpz_t(), w2.get_mpz_t());
      if (r >= w) r = w2 - 1 - r;
      break;
    }
    case TexWrap::ClampToEdge:
    case TexWrap::ClampToBorder:
      if (wrap == TexWrap::ClampToBorder) *border = i < 0 || i >= w;
      r = i < 0 ? mpz_class(0) : (i >= w ? mpz_class(w - 1) : i);
      break;
  }
  *idx = (uint32_t)r.get_ui();
}

TexAxis exact_tex_axis_rounded(const TexAddrConfig& c, const mpq_class& u, uint32_t size, mpz_class* i0_unwrapped) {
  ExactTexAxis e = exact_tex_axis(c.filter, u, size);
  TexAxis a;
  if (c.filter == TexFilter::Bilinear) {
    const mpz_class one_f = mpz_class(1) << c.weight_frac_bits;
    const mpq_class scaled = e.frac * mpq_class(one_f);  // ∈ [0, 2^F)
    mpz_class wt = floor_q(scaled);
    const mpq_class rest = scaled - mpq_class(wt);
    if (rest > mpq_class(1, 2) || (rest == mpq_class(1, 2) && mpz_odd_p(wt.get_mpz_t()))) wt += 1;
    if (wt == one_f) {  // rounded up to 1: the blend of i0 + 1 with weight 0
      wt = 0;
      e.i0 += 1;
    }
    a.weight = (uint32_t)wt.get_ui();
    exact_wrap(c.wrap, e.i0, size, &a.i0, &a.border0);
    exact_wrap(c.wrap, mpz_class(e.i0 + 1), size, &a.i1, &a.border1);
  } else {
    exact_wrap(c.wrap, e.i0, size, &a.i0, &a.border0);
    a.i1 = a.i0;
    a.border1 = a.border0;
  }
  if (i0_unwrapped) *i0_unwrapped = e.i0;
  return a;
}

RefTexAxis exact_ref_axis(TexFilter filter, TexWrap wrap, const mpq_class& u, uint32_t size) {
  const ExactTexAxis e = exact_tex_axis(filter, u, size);
  RefTexAxis a;
  exact_wrap(wrap, e.i0, size, &a.i0, &a.border0);
  if (filter == TexFilter::Bilinear) {
    exact_wrap(wrap, mpz_class(e.i0 + 1), size, &a.i1, &a.border1);
    a.weight = e.frac.get_d();
  } else {
    a.i1 = a.i0;
    a.border1 = a.border0;
  }
  return a;
}

RefTexAxis ref_tex_axis(TexFilter filter, TexWrap wrap, double u, uint32_t size) {
  RefTexAxis a;
  double x = u * size;
  if (!std::isfinite(x)) return a;  // NaN, ±Inf, or a product beyond double
  if (filter == TexFilter::Bilinear) x -= 0.5;
  const double i0 = std::floor(x);
  ref_wrap(wrap, i0, size, &a.i0, &a.border0);
  if (filter == TexFilter::Bilinear) {
    ref_wrap(wrap, i0 + 1, size, &a.i1, &a.border1);
    a.weight = x - i0;
  } else {
    a.i1 = a.i0;
    a.border1 = a.border0;
  }
  return a;
}

TexAxis ref_tex_axis_rounded(const TexAddrConfig& c, double u, uint32_t size, double* x_out, double* i0_out) {
  TexAxis a;
  const bool bil = c.filter == TexFilter::Bilinear;
  double x = u * size - (bil ? 0.5 : 0.0);
  if (!std::isfinite(x)) x = 0;  // NaN, ±Inf, or a product beyond double: as ref_tex_axis (texel 0)
  double i0 = std::floor(x);
  if (bil) {
    const double one_f = std::ldexp(1.0, c.weight_frac_bits);
    double w = std::nearbyint((x - i0) * one_f);  // the default rounding mode: to nearest, ties to even
    if (w == one_f) {  // rounded up to 1: the blend of i0 + 1 with weight 0
      w = 0;
      i0 += 1;
    }
    a.weight = (uint32_t)w;
  }
  ref_wrap(c.wrap, i0, size, &a.i0, &a.border0);
  if (bil) {
    ref_wrap(c.wrap, i0 + 1, size, &a.i1, &a.border1);
  } else {
    a.i1 = a.i0;
    a.border1 = a.border0;
  }
  if (x_out) *x_out = x;
  if (i0_out) *i0_out = i0;
  return a;
}

std::array<double, 4> blend_ref(const Image& tex, uint32_t border, const RefTexAxis& s, const RefTexAxis& t) {
  const double ws[2] = {1 - s.weight, s.weight}, wt[2] = {1 - t.weight, t.weight};
  const uint32_t si[2] = {s.i0, s.i1}, ti[2] = {t.i0, t.i1};
  const bool sb[2] = {s.border0, s.border1}, tb[2] = {t.border0, t.border1};
  std::array<double, 4> c{};
  for (int j = 0; j < 2; ++j)
    for (int i = 0; i < 2; ++i) {
      const uint32_t texel = sb[i] || tb[j] ? border : tex.at((int)si[i], (int)ti[j]);
      for (int k = 0; k < kTexChannels; ++k)
        c[k] += ws[i] * wt[j] * (double)((texel >> (kTexChannelBits * k)) & ((1u << kTexChannelBits) - 1));
    }
  return c;
}

uint32_t pack_blend(const std::array<double, 4>& c) {
  uint32_t out = 0;
  const double top = (1u << kTexChannelBits) - 1;
  for (int k = 0; k < kTexChannels; ++k)
    out |= (uint32_t)std::lround(std::fmin(std::fmax(c[k], 0.0), top)) << (kTexChannelBits * k);
  return out;
}

}  // namespace fxr
