// The OSMesa / llvmpipe peer (see reference/peer/peer_osmesa.hpp for the conventions).
#define GL_GLEXT_PROTOTYPES 1
#include "reference/peer/peer_osmesa.hpp"

#include <GL/osmesa.h>
#include <GL/glext.h>

#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <map>
#include <sstream>

namespace fxr::peer {

namespace {

// Colour attachment 0 counts fragments (R32F, additive blending: exact up to 2^24 per pixel).
// Attachments 1… are RGBA32F and carry, in order, float(gl_PrimitiveID + 1) and the varyings.
constexpr int kChannelsPerAttachment = 4;
constexpr int kVaryingsPerAttribute = 4;  // varyings travel as vec4 attributes / interpolants
constexpr int kPayloadChannels = 1 + kMaxVaryings;  // primitive id + varyings
constexpr int kMaxPayloadAttachments =
    (kPayloadChannels + kChannelsPerAttachment - 1) / kChannelsPerAttachment;
constexpr int kMaxVaryingAttributes = (kMaxVaryings + kVaryingsPerAttribute - 1) / kVaryingsPerAttribute;
// The OSMesa colour buffer is unused (everything goes to the FBO) but MakeCurrent needs one.
constexpr int kDummySize = 8;

using PFNCLIPCONTROL = void (*)(GLenum, GLenum);
using PFNQUERYUI64 = void (*)(GLuint, GLenum, GLuint64*);  // not exported by libOSMesa

void check_gl(const char* what) {
  const GLenum e = glGetError();
  if (e != GL_NO_ERROR) {
    std::ostringstream os;
    os << "peer: GL error 0x" << std::hex << e << " after " << what;
    throw PeerError(os.str());
  }
}

GLenum gl_depth_func(DepthFunc f) {
  switch (f) {
    case DepthFunc::Never: return GL_NEVER;
    case DepthFunc::Less: return GL_LESS;
    case DepthFunc::Equal: return GL_EQUAL;
    case DepthFunc::LessEqual: return GL_LEQUAL;
    case DepthFunc::Greater: return GL_GREATER;
    case DepthFunc::NotEqual: return GL_NOTEQUAL;
    case DepthFunc::GreaterEqual: return GL_GEQUAL;
    case DepthFunc::Always: return GL_ALWAYS;
  }
  return GL_LESS;
}

int payload_attachments(int num_varyings) {
  return (1 + num_varyings + kChannelsPerAttachment - 1) / kChannelsPerAttachment;
}
int varying_attributes(int num_varyings) {
  return (num_varyings + kVaryingsPerAttribute - 1) / kVaryingsPerAttribute;
}

// GLSL for `num_varyings` varyings. Vertex shader: position unchanged (y negated when
// mirroring: exact), varyings unchanged. Fragment shader: count 1, then primitive id + 1 and the
// interpolated varyings packed 4 per attachment.
std::string vertex_source(int num_varyings, bool affine, bool mirror) {
  std::ostringstream s;
  s << "#version 330 core\n";
  s << "layout(location = 0) in vec4 a_pos;\n";
  const char* q = affine ? "noperspective" : "smooth";
  for (int i = 0; i < varying_attributes(num_varyings); ++i) {
    s << "layout(location = " << 1 + i << ") in vec4 a_var" << i << ";\n";
    s << q << " out vec4 v_var" << i << ";\n";
  }
  s << "void main() {\n";
  s << (mirror ? "  gl_Position = vec4(a_pos.x, -a_pos.y, a_pos.z, a_pos.w);\n" : "  gl_Position = a_pos;\n");
  for (int i = 0; i < varying_attributes(num_varyings); ++i) s << "  v_var" << i << " = a_var" << i << ";\n";
  s << "}\n";
  return s.str();
}

std::string fragment_source(int num_varyings, bool affine) {
  std::ostringstream s;
  s << "#version 330 core\n";
  const char* q = affine ? "noperspective" : "smooth";
  for (int i = 0; i < varying_attributes(num_varyings); ++i) s << q << " in vec4 v_var" << i << ";\n";
  s << "layout(location = 0) out float o_count;\n";
  const int na = payload_attachments(num_varyings);
  for (int i = 0; i < na; ++i) s << "layout(location = " << 1 + i << ") out vec4 o_pay" << i << ";\n";
  s << "void main() {\n  o_count = 1.0;\n";
  // Channel c of the payload: 0 = primitive id + 1 (exact in float below 2^24), 1 + k = varying k.
  const char* comp = "xyzw";
  for (int i = 0; i < na; ++i) {
    s << "  o_pay" << i << " = vec4(";
    for (int j = 0; j < kChannelsPerAttachment; ++j) {
      const int c = i * kChannelsPerAttachment + j;
      if (j) s << ", ";
      if (c == 0)
        s << "float(gl_PrimitiveID + 1)";
      else if (c - 1 < num_varyings)
        s << "v_var" << (c - 1) / kVaryingsPerAttribute << "." << comp[(c - 1) % kVaryingsPerAttribute];
      else
        s << "0.0";
    }
    s << ");\n";
  }
  s << "}\n";
  return s.str();
}

GLuint compile(GLenum type, const std::string& src) {
  const GLuint sh = glCreateShader(type);
  const char* p = src.c_str();
  glShaderSource(sh, 1, &p, nullptr);
  glCompileShader(sh);
  GLint ok = 0;
  glGetShaderiv(sh, GL_COMPILE_STATUS, &ok);
  if (!ok) {
    char log[4096] = {};
    glGetShaderInfoLog(sh, sizeof log, nullptr, log);
    throw PeerError(std::string("peer: shader compile failed: ") + log + "\n" + src);
  }
  return sh;
}

}  // namespace

uint64_t PeerImage::fragments() const {
  uint64_t n = 0;
  for (uint32_t c : count) n += c;
  return n;
}

struct OsmesaPeer::Impl {
  PeerOptions opt;
  PeerInfo info;
  OSMesaContext ctx = nullptr;
  unsigned char dummy[kDummySize * kDummySize * 4] = {};
  PFNCLIPCONTROL clip_control = nullptr;
  PFNQUERYUI64 query_ui64 = nullptr;

  std::map<int, GLuint> programs;  // key: num_varyings · 2 + affine
  GLuint vao = 0, vbo = 0, fbo = 0, depth_rb = 0, query = 0;
  GLuint color_rb[1 + kMaxPayloadAttachments] = {};
  int fb_w = 0, fb_h = 0;

  // Prepared draw.
  DrawState st;
  GLsizei vertex_count = 0;
  GLenum mode = GL_TRIANGLES;
  int attachments = 0;  // 1 + payload attachments in use

  void make_current() {
    if (!OSMesaMakeCurrent(ctx, dummy, GL_UNSIGNED_BYTE, kDummySize, kDummySize))
      throw PeerError("peer: OSMesaMakeCurrent failed");
  }

  GLuint program(int nv, bool affine) {
    const int key = nv * 2 + (affine ? 1 : 0);
    auto it = programs.find(key);
    if (it != programs.end()) return it->second;
    const GLuint vs = compile(GL_VERTEX_SHADER, vertex_source(nv, affine, opt.mirror_y));
    const GLuint fs = compile(GL_FRAGMENT_SHADER, fragment_source(nv, affine));
    const GLuint p = glCreateProgram();
    glAttachShader(p, vs);
    glAttachShader(p, fs);
    glLinkProgram(p);
    GLint ok = 0;
    glGetProgramiv(p, GL_LINK_STATUS, &ok);
    if (!ok) {
      char log[4096] = {};
      glGetProgramInfoLog(p, sizeof log, nullptr, log);
      throw PeerError(std::string("peer: program link failed: ") + log);
    }
    glDeleteShader(vs);
    glDeleteShader(fs);
    programs[key] = p;
    return p;
  }

  void ensure_framebuffer(int w, int h) {
    if (w == fb_w && h == fb_h) return;
    if (w <= 0 || h <= 0 || w > info.max_viewport || h > info.max_viewport) {
      std::ostringstream os;
      os << "peer: framebuffer " << w << "x" << h << " outside 1.." << info.max_viewport;
      throw PeerError(os.str());
    }
    if (!fbo) {
      glGenFramebuffers(1, &fbo);
      glGenRenderbuffers(1 + kMaxPayloadAttachments, color_rb);
      glGenRenderbuffers(1, &depth_rb);
    }
    glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    for (int i = 0; i < 1 + kMaxPayloadAttachments; ++i) {
      glBindRenderbuffer(GL_RENDERBUFFER, color_rb[i]);
      glRenderbufferStorage(GL_RENDERBUFFER, i == 0 ? GL_R32F : GL_RGBA32F, w, h);
      glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0 + i, GL_RENDERBUFFER, color_rb[i]);
    }
    glBindRenderbuffer(GL_RENDERBUFFER, depth_rb);
    glRenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT32F, w, h);
    glFramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depth_rb);
    const GLenum status = glCheckFramebufferStatus(GL_FRAMEBUFFER);
    if (status != GL_FRAMEBUFFER_COMPLETE) {
      std::ostringstream os;
      os << "peer: framebuffer incomplete (0x" << std::hex << status << ")";
      throw PeerError(os.str());
    }
    check_gl("framebuffer allocation");
    fb_w = w;
    fb_h = h;
  }

  // Window rows in the peer's framebuffer: identity, or y → fb_h − y when mirroring.
  int mirror_rect_y(int y, int h) const { return opt.mirror_y ? fb_h - y - h : y; }
};

OsmesaPeer::OsmesaPeer(const PeerOptions& opt) : impl_(new Impl) {
  Impl& m = *impl_;
  m.opt = opt;
  // The peer is llvmpipe, never softpipe (not watertight: docs/references.md#peer-fill-rule).
  // Both variables are read when OSMesa creates its gallium screen, at the first context of the
  // process.
  setenv("GALLIUM_DRIVER", "llvmpipe", 1);
  if (opt.lp_num_threads >= 0) setenv("LP_NUM_THREADS", std::to_string(opt.lp_num_threads).c_str(), 1);
  const int attribs[] = {OSMESA_FORMAT, OSMESA_RGBA,
                         OSMESA_DEPTH_BITS, 0,
                         OSMESA_STENCIL_BITS, 0,
                         OSMESA_ACCUM_BITS, 0,
                         OSMESA_PROFILE, OSMESA_CORE_PROFILE,
                         OSMESA_CONTEXT_MAJOR_VERSION, 3,
                         OSMESA_CONTEXT_MINOR_VERSION, 3,
                         0};
  m.ctx = OSMesaCreateContextAttribs(attribs, nullptr);
  if (!m.ctx) throw PeerError("peer: OSMesaCreateContextAttribs failed (no GL 3.3 core context from OSMesa)");
  m.make_current();
  m.info.version = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  m.info.renderer = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  if (m.info.renderer.find("llvmpipe") == std::string::npos)
    throw PeerError("peer: renderer is '" + m.info.renderer + "', not llvmpipe");
  glGetIntegerv(GL_SUBPIXEL_BITS, &m.info.subpixel_bits);
  GLint vp[2] = {0, 0};
  glGetIntegerv(GL_MAX_VIEWPORT_DIMS, vp);
  GLint rb = 0;
  glGetIntegerv(GL_MAX_RENDERBUFFER_SIZE, &rb);
  m.info.max_viewport = std::min(std::min(vp[0], vp[1]), rb);
  GLint next = 0;
  glGetIntegerv(GL_NUM_EXTENSIONS, &next);
  for (GLint i = 0; i < next; ++i)
    if (!std::strcmp(reinterpret_cast<const char*>(glGetStringi(GL_EXTENSIONS, i)), "GL_ARB_clip_control"))
      m.info.clip_control = true;
  m.clip_control = reinterpret_cast<PFNCLIPCONTROL>(OSMesaGetProcAddress("glClipControl"));
  m.query_ui64 = reinterpret_cast<PFNQUERYUI64>(OSMesaGetProcAddress("glGetQueryObjectui64v"));
  if (!m.query_ui64) throw PeerError("peer: glGetQueryObjectui64v missing");
  if (!m.info.clip_control || !m.clip_control)
    throw PeerError("peer: GL_ARB_clip_control missing: cannot use the 0..1 depth convention exactly");
  GLint max_draw = 0;
  glGetIntegerv(GL_MAX_DRAW_BUFFERS, &max_draw);
  if (max_draw < 1 + kMaxPayloadAttachments) throw PeerError("peer: too few draw buffers");
  static_assert(kMaxVaryingAttributes + 1 <= 16, "GL 3.3 guarantees 16 vertex attributes");

  m.clip_control(GL_LOWER_LEFT, GL_ZERO_TO_ONE);
  glDepthRange(0.0, 1.0);
  glGenVertexArrays(1, &m.vao);
  glGenBuffers(1, &m.vbo);
  glGenQueries(1, &m.query);
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  check_gl("context set-up");
}

OsmesaPeer::~OsmesaPeer() {
  if (impl_ && impl_->ctx) OSMesaDestroyContext(impl_->ctx);
}

const PeerInfo& OsmesaPeer::info() const { return impl_->info; }

void OsmesaPeer::prepare(const DrawState& st, const std::vector<ClipTriangle>& tris) {
  Impl& m = *impl_;
  if (st.num_varyings < 0 || st.num_varyings > kMaxVaryings)
    throw PeerError("peer: num_varyings " + std::to_string(st.num_varyings) + " outside 0.." +
                    std::to_string(kMaxVaryings));
  if (st.viewport_x < 0 || st.viewport_y < 0)
    throw PeerError("peer: negative viewport origin is not supported");
  m.make_current();
  m.st = st;
  m.ensure_framebuffer(st.viewport_x + st.viewport_w, st.viewport_y + st.viewport_h);
  m.attachments = 1 + payload_attachments(st.num_varyings);

  glBindFramebuffer(GL_FRAMEBUFFER, m.fbo);
  GLenum bufs[1 + kMaxPayloadAttachments];
  for (int i = 0; i < m.attachments; ++i) bufs[i] = GL_COLOR_ATTACHMENT0 + i;
  glDrawBuffers(m.attachments, bufs);

  glUseProgram(m.program(st.num_varyings, st.interp == InterpMode::Affine));
  glBindVertexArray(m.vao);
  glBindBuffer(GL_ARRAY_BUFFER, m.vbo);
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(tris.size() * sizeof(ClipTriangle)), tris.data(), GL_STATIC_DRAW);
  static_assert(sizeof(ClipTriangle) == 3 * sizeof(ClipVertex), "vertices are tightly packed");
  glVertexAttribPointer(0, 4, GL_FLOAT, GL_FALSE, sizeof(ClipVertex), (const void*)offsetof(ClipVertex, pos));
  glEnableVertexAttribArray(0);
  for (int i = 0; i < kMaxVaryingAttributes; ++i) {
    if (i < varying_attributes(st.num_varyings)) {
      // The last vec4 may reach past num_varyings; it stays inside ClipVertex::var (unused lanes).
      glVertexAttribPointer(1 + i, 4, GL_FLOAT, GL_FALSE, sizeof(ClipVertex),
                            (const void*)(offsetof(ClipVertex, var) + sizeof(float) * kVaryingsPerAttribute * i));
      glEnableVertexAttribArray(1 + i);
    } else {
      glDisableVertexAttribArray(1 + i);
    }
  }
  m.vertex_count = (GLsizei)(tris.size() * 3);
  m.mode = GL_TRIANGLES;

  glViewport(st.viewport_x, m.mirror_rect_y(st.viewport_y, st.viewport_h), st.viewport_w, st.viewport_h);
  const int sw = st.scissor_w < 0 ? st.viewport_w : st.scissor_w;
  const int sh = st.scissor_h < 0 ? st.viewport_h : st.scissor_h;
  const int sx = st.scissor_w < 0 ? st.viewport_x : st.scissor_x;
  const int sy = st.scissor_h < 0 ? st.viewport_y : st.scissor_y;
  glEnable(GL_SCISSOR_TEST);
  glScissor(sx, m.mirror_rect_y(sy, sh), sw, sh);

  // Mirroring reverses the winding of every triangle.
  const bool front_ccw = st.front_ccw != m.opt.mirror_y;
  glFrontFace(front_ccw ? GL_CCW : GL_CW);
  if (st.cull == CullMode::None) {
    glDisable(GL_CULL_FACE);
  } else {
    glEnable(GL_CULL_FACE);
    glCullFace(st.cull == CullMode::Back ? GL_BACK : GL_FRONT);
  }
  if (st.depth_test) {
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(gl_depth_func(st.depth_func));
    glDepthMask(st.depth_write ? GL_TRUE : GL_FALSE);
  } else {
    glDisable(GL_DEPTH_TEST);
  }
  glDisable(GL_MULTISAMPLE);
  glDisable(GL_DITHER);
  // Count by additive blending on attachment 0 only; payload attachments take the last write.
  for (int i = 0; i < m.attachments; ++i) {
    if (i == 0) {
      glEnablei(GL_BLEND, 0);
      glBlendFunci(0, GL_ONE, GL_ONE);
      glBlendEquationi(0, GL_FUNC_ADD);
    } else {
      glDisablei(GL_BLEND, i);
    }
  }
  check_gl("prepare");
}

void OsmesaPeer::draw() {
  Impl& m = *impl_;
  m.make_current();
  static const GLfloat zero[4] = {0, 0, 0, 0};
  // Clears ignore the scissor box only when it is disabled.
  glDisable(GL_SCISSOR_TEST);
  for (int i = 0; i < m.attachments; ++i) glClearBufferfv(GL_COLOR, i, zero);
  glDepthMask(GL_TRUE);
  glClearDepth(1.0);
  glClear(GL_DEPTH_BUFFER_BIT);
  glDepthMask(m.st.depth_write ? GL_TRUE : GL_FALSE);
  glEnable(GL_SCISSOR_TEST);
  if (m.vertex_count) glDrawArrays(m.mode, 0, m.vertex_count);
  glFinish();
  check_gl("draw");
}

uint64_t OsmesaPeer::draw_counting_samples() {
  Impl& m = *impl_;
  m.make_current();
  glBeginQuery(GL_SAMPLES_PASSED, m.query);
  draw();
  glEndQuery(GL_SAMPLES_PASSED);
  GLuint64 n = 0;
  m.query_ui64(m.query, GL_QUERY_RESULT, &n);
  check_gl("sample query");
  return n;
}

PeerImage OsmesaPeer::read() {
  Impl& m = *impl_;
  m.make_current();
  PeerImage img;
  img.width = m.fb_w;
  img.height = m.fb_h;
  img.num_varyings = m.st.num_varyings;
  const size_t n = (size_t)m.fb_w * (size_t)m.fb_h;
  std::vector<float> count(n);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, m.fbo);
  glReadBuffer(GL_COLOR_ATTACHMENT0);
  glReadPixels(0, 0, m.fb_w, m.fb_h, GL_RED, GL_FLOAT, count.data());
  const int npay = m.attachments - 1;
  std::vector<float> pay(n * (size_t)npay * kChannelsPerAttachment);
  std::vector<float> tmp(n * kChannelsPerAttachment);
  for (int a = 0; a < npay; ++a) {
    glReadBuffer(GL_COLOR_ATTACHMENT1 + a);
    glReadPixels(0, 0, m.fb_w, m.fb_h, GL_RGBA, GL_FLOAT, tmp.data());
    for (size_t p = 0; p < n; ++p)
      for (int c = 0; c < kChannelsPerAttachment; ++c)
        pay[(p * npay + a) * kChannelsPerAttachment + c] = tmp[p * kChannelsPerAttachment + c];
  }
  std::vector<float> depth(n);
  glReadPixels(0, 0, m.fb_w, m.fb_h, GL_DEPTH_COMPONENT, GL_FLOAT, depth.data());
  check_gl("readback");

  img.count.resize(n);
  img.prim.resize(n);
  img.var.resize(n * (size_t)img.num_varyings);
  img.depth.resize(n);
  const size_t stride = (size_t)npay * kChannelsPerAttachment;
  for (int y = 0; y < m.fb_h; ++y) {
    const int gy = m.opt.mirror_y ? m.fb_h - 1 - y : y;  // peer row of model row y
    for (int x = 0; x < m.fb_w; ++x) {
      const size_t o = img.index(x, y), g = (size_t)gy * (size_t)m.fb_w + (size_t)x;
      img.count[o] = (uint32_t)count[g];  // exact: small integers in float
      img.prim[o] = (int32_t)pay[g * stride] - 1;
      for (int k = 0; k < img.num_varyings; ++k) img.var[o * img.num_varyings + k] = pay[g * stride + 1 + k];
      img.depth[o] = depth[g];
    }
  }
  return img;
}

PeerImage OsmesaPeer::render_lines(const DrawState& st, const std::vector<ClipLine>& lines) {
  DrawState s2 = st;
  s2.cull = CullMode::None;
  prepare(s2, {});
  Impl& m = *impl_;
  static_assert(sizeof(ClipLine) == 2 * sizeof(ClipVertex), "vertices are tightly packed");
  glBindBuffer(GL_ARRAY_BUFFER, m.vbo);  // the attribute pointers of prepare() stay valid
  glBufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(lines.size() * sizeof(ClipLine)), lines.data(), GL_STATIC_DRAW);
  m.vertex_count = (GLsizei)(lines.size() * 2);
  m.mode = GL_LINES;
  glDisable(GL_LINE_SMOOTH);
  glLineWidth(1.0f);
  check_gl("prepare lines");
  draw();
  return read();
}

PeerImage OsmesaPeer::render(const DrawState& st, const std::vector<ClipTriangle>& tris) {
  prepare(st, tris);
  draw();
  return read();
}

}  // namespace fxr::peer
