// Transaction vectors (model/vectors/scene_dump.hpp, docs/vectors.md): a draw dumped at every
// stage boundary through the chain's taps, read back and re-stepped; the dump against the unit's
// own output (run_raster_unit, which runs without taps); corrupted dumps are caught; the committed
// dump under vectors/scenes/ is what the generator writes today.
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "frontend/scene.hpp"
#include "model/stages/line_setup.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/raster_unit.hpp"
#include "model/vectors/record_vectors.hpp"
#include "model/vectors/scene_dump.hpp"

using namespace fxr;
namespace fs = std::filesystem;

namespace {

fs::path temp_dir(const std::string& tag) {
  return fs::temp_directory_path() / ("fxr_scene_dump_" + tag + "_" + std::to_string(::getpid()));
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void spit(const fs::path& p, const std::string& s) {
  std::ofstream o(p, std::ios::binary);
  o << s;
}

fs::path source_dir() {
  const char* src = std::getenv("FXR_SOURCE_DIR");
  return fs::path(src ? src : ".");
}

// A dump's rows of one file, read through the public reader of the vector format.
struct Rows {
  VecLayout lay;
  std::vector<vec_word> data;
  uint64_t n = 0;
  VecRow row(uint64_t i) const {
    return VecRow(data.begin() + (ptrdiff_t)(i * lay.size()), data.begin() + (ptrdiff_t)((i + 1) * lay.size()));
  }
};

// Reads DIR/stage.side.hex with the field list of record R after `header` 32-bit header fields
// (the last header field of an out file is the 1-bit `last`).
template <class R>
Rows read_rows(const fs::path& dir, const std::string& stage, const std::string& side, const RecordShape& s,
               size_t header) {
  std::vector<VecField> f;
  const VecDir d = side == "in" ? VecDir::In : VecDir::Out;
  // Header widths from docs/vectors.md: 32-bit ids and counts, the out files' last flag 1 bit.
  for (size_t i = 0; i < header; ++i)
    f.push_back({"h" + std::to_string(i), d, (side == "out" && i + 1 == header) ? 1 : kTxnIdBits, false, ""});
  append_record_fields<R>(s, d, f);
  Rows r;
  r.lay = VecLayout(f);
  const fs::path hex = dir / (stage + "." + side + ".hex");
  const std::string text = slurp(hex);
  r.n = (uint64_t)std::count(text.begin(), text.end(), '\n');
  read_vec_hex(hex.string(), r.lay, r.n, r.data);
  return r;
}

template <class T>
struct Tag {
  using type = T;
};

// The record fields (after the header) of row i of a and row k of b are equal.
bool same_record(const Rows& a, uint64_t i, size_t ha, const Rows& b, uint64_t k, size_t hb) {
  const VecRow ra = a.row(i), rb = b.row(k);
  if (ra.size() - ha != rb.size() - hb) return false;
  return std::equal(ra.begin() + (ptrdiff_t)ha, ra.end(), rb.begin() + (ptrdiff_t)hb);
}

}  // namespace

// The default scene's wireframe variant (the bunny included: 69,668 triangles, then 3,298 line
// segments drawn with their own draw state), through the taps into files and back: every stage
// of both paths re-stepped on its own inputs gives its recorded outputs; the last stages'
// outputs are the fragments run_raster_unit produces without taps; the links between stages
// carry the same records on both sides.
TEST(SceneDump, DefaultSceneRoundTripsThroughEveryStage) {
  SceneOptions so;
  so.wireframe = true;
  const Scene sc = default_scene(so);
  ASSERT_GT(sc.lines.size(), 1000u);
  const fs::path dir = temp_dir("default");
  const SceneDump d = dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, dir.string(), sc.name);
  ASSERT_EQ(d.files.size(), 2 * scene_dump_stages().size());
  ASSERT_EQ(scene_dump_stages().size(), 18u);  // 9 triangle stages, 9 line stages (docs/vectors.md)
  for (const auto& f : d.files) EXPECT_GT(f.rows, 0u) << f.hex;

  const RestepReport r = restep_scene_vectors(dir.string());
  ASSERT_EQ(r.stages.size(), scene_dump_stages().size());
  EXPECT_EQ(r.mismatches(), 0u) << (r.first.empty() ? "" : r.first[0]);

  // The unit without taps: same statistics, same fragments (the triangles' from divide.out, then
  // the segments' from line_divide.out).
  const FrameOutput fo = run_raster_unit(sc.config, sc.state, sc.tris, sc.line_state, sc.lines);
  EXPECT_EQ(d.stats.prims_in, fo.stats.prims_in);
  EXPECT_EQ(d.stats.prims_drawn, fo.stats.prims_drawn);
  EXPECT_EQ(d.stats.fragments_generated, fo.stats.fragments_generated);
  EXPECT_EQ(d.stats.fragments_depth_pass, fo.stats.fragments_depth_pass);
  EXPECT_EQ(d.stats.lines.in, sc.lines.size());
  EXPECT_EQ(d.stats.lines.drawn, fo.stats.lines.drawn);
  EXPECT_EQ(d.stats.lines.fragments_generated, fo.stats.lines.fragments_generated);
  const RecordShape shape{sc.config, sc.state.num_varyings};
  const Rows tfrag = read_rows<Fragment>(dir, "divide", "out", shape, kTxnOutHeaderFields);
  const Rows lfrag = read_rows<Fragment>(dir, "line_divide", "out", shape, kTxnOutHeaderFields);
  ASSERT_GT(lfrag.n, 1000u);
  ASSERT_EQ(tfrag.n + lfrag.n, fo.fragments.size());
  for (uint64_t i = 0; i < tfrag.n + lfrag.n; ++i) {
    Fragment f{};
    unpack_record(f, shape, i < tfrag.n ? tfrag.row(i) : lfrag.row(i - tfrag.n), kTxnOutHeaderFields);
    const Fragment& g = fo.fragments[i];
    bool same = f.x == g.x && f.y == g.y && f.depth == g.depth && f.prim == g.prim;
    for (int k = 0; k < sc.state.num_varyings; ++k)
      same = same && f.var[k].sig == g.var[k].sig && f.var[k].exp == g.var[k].exp && f.var[k].neg == g.var[k].neg;
    ASSERT_TRUE(same) << "fragment " << i;
  }

  // Links: S.out records = next stage's S'.in records where the chain forwards every output
  // (every link when no primitive is rejected for range, as in the default scene).
  ASSERT_EQ(fo.stats.prims_rejected_range, 0u);
  ASSERT_EQ(fo.stats.lines.rejected_range, 0u);
  auto link = [&](auto out_tag, auto in_tag, const std::string& a, const std::string& b, size_t in_header) {
    using RO = typename decltype(out_tag)::type;
    using RI = typename decltype(in_tag)::type;
    const Rows o = read_rows<RO>(dir, a, "out", shape, kTxnOutHeaderFields);
    const Rows i = read_rows<RI>(dir, b, "in", shape, in_header);
    ASSERT_EQ(o.n, i.n) << a << " -> " << b;
    for (uint64_t k = 0; k < o.n; ++k) ASSERT_TRUE(same_record(o, k, kTxnOutHeaderFields, i, k, in_header)) << a << " -> " << b << " row " << k;
  };
  link(Tag<ExactTriangle>{}, Tag<ExactTriangle>{}, "convert", "clip", kTxnInHeaderFields);
  link(Tag<ClippedTriangle>{}, Tag<ClippedTriangle>{}, "clip", "recip", kTxnInHeaderFields);
  link(Tag<RecipTriangle>{}, Tag<RecipTriangle>{}, "recip", "viewport", kTxnInHeaderFields);
  link(Tag<SetupTriangle>{}, Tag<SetupTriangle>{}, "viewport", "setup", kTxnInHeaderFields);
  link(Tag<TriangleEquations>{}, Tag<TriangleEquations>{}, "setup", "traverse", kTxnInHeaderFields);
  link(Tag<Span>{}, Tag<Span>{}, "traverse", "interp", kTxnCtxHeaderFields);
  link(Tag<PlaneSample>{}, Tag<PlaneSample>{}, "interp", "depth", kTxnInHeaderFields);
  link(Tag<PlaneSample>{}, Tag<PlaneSample>{}, "depth", "divide", kTxnInHeaderFields);
  link(Tag<ExactLine>{}, Tag<ExactLine>{}, "line_convert", "line_clip", kTxnInHeaderFields);
  link(Tag<ClippedLine>{}, Tag<ClippedLine>{}, "line_clip", "line_recip", kTxnInHeaderFields);
  link(Tag<RecipLine>{}, Tag<RecipLine>{}, "line_recip", "line_viewport", kTxnInHeaderFields);
  link(Tag<SetupLine>{}, Tag<SetupLine>{}, "line_viewport", "line_setup", kTxnInHeaderFields);
  link(Tag<LineEquations>{}, Tag<LineEquations>{}, "line_setup", "line", kTxnInHeaderFields);
  link(Tag<LineFragment>{}, Tag<LineFragment>{}, "line", "line_interp", kTxnCtxHeaderFields);
  link(Tag<PlaneSample>{}, Tag<PlaneSample>{}, "line_interp", "line_depth", kTxnInHeaderFields);
  link(Tag<PlaneSample>{}, Tag<PlaneSample>{}, "line_depth", "line_divide", kTxnInHeaderFields);
  fs::remove_all(dir);
}

// A corrupted record field is a mismatch naming the file and line; corrupted transaction headers,
// a truncated file and a manifest whose layout differs from the records' are errors.
TEST(SceneDump, CorruptionIsCaughtAndNamed) {
  const Scene sc = load_scene((source_dir() / "scenes" / "transactions.json").string());
  const fs::path dir = temp_dir("corrupt");
  dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, dir.string(), sc.name);
  ASSERT_EQ(restep_scene_vectors(dir.string()).mismatches(), 0u);

  // setup.out line 2, the last digit (the last record field): a different plane value.
  const fs::path so = dir / "setup.out.hex";
  const std::string good = slurp(so);
  std::string bad = good;
  const size_t eol1 = bad.find('\n'), eol2 = bad.find('\n', eol1 + 1);
  bad[eol2 - 1] = bad[eol2 - 1] == '0' ? '1' : '0';
  spit(so, bad);
  RestepReport r = restep_scene_vectors(dir.string());
  // setup's line-2 input gives its recorded output no longer; the interpolators read their
  // context from setup.out, so the spans of that triangle differ too; no other stage does.
  for (const auto& st : r.stages) {
    if (st.stage == "setup") EXPECT_EQ(st.mismatches, 1u);
    else if (st.stage == "interp") EXPECT_GT(st.mismatches, 0u);
    else EXPECT_EQ(st.mismatches, 0u) << st.stage;
  }
  ASSERT_FALSE(r.first.empty());
  EXPECT_NE(r.first[0].find("setup.out.hex:2"), std::string::npos) << r.first[0];
  spit(so, good);

  // traverse.in line 1: n_out (digits 9..16) changed → the transaction counts disagree.
  const fs::path ti = dir / "traverse.in.hex";
  const std::string tgood = slurp(ti);
  std::string tbad = tgood;
  tbad[15] = tbad[15] == '0' ? '1' : '0';
  spit(ti, tbad);
  EXPECT_THROW(restep_scene_vectors(dir.string()), ConfigError);
  // Truncated: the last line removed.
  spit(ti, tgood.substr(0, tgood.rfind('\n', tgood.size() - 2) + 1));
  EXPECT_THROW(restep_scene_vectors(dir.string()), ConfigError);
  spit(ti, tgood);
  ASSERT_EQ(restep_scene_vectors(dir.string()).mismatches(), 0u);

  // A manifest whose field width differs from the record's.
  const fs::path im = dir / "interp.out.json";
  const std::string mgood = slurp(im);
  std::string mbad = mgood;
  const size_t w = mbad.find("\"width\": ");
  ASSERT_NE(w, std::string::npos);
  mbad.insert(w + 9, "1");
  spit(im, mbad);
  try {
    restep_scene_vectors(dir.string());
    ADD_FAILURE() << "a wrong width was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("interp.out.json"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Flips bit `bit` (counted from the word's least significant bit, as the manifests' offsets) of the
// hex word on line `line` (from 1) of `hex`.
void flip_bit(const fs::path& hex, uint64_t line, int bit) {
  std::string t = slurp(hex);
  size_t at = 0;
  for (uint64_t l = 1; l < line; ++l) at = t.find('\n', at) + 1;
  const size_t eol = t.find('\n', at);
  char& c = t[eol - 1 - (size_t)(bit / 4)];
  const int v = std::stoi(std::string(1, c), nullptr, 16) ^ (1 << (bit % 4));
  c = "0123456789abcdef"[v];
  spit(hex, t);
}

// Field `name` of a stage file's layout (the record's visit()).
VecField field_of(const fs::path& dir, const std::string& stage, bool out, const std::string& name) {
  const SceneStageVectors v = load_scene_stage(dir.string(), stage);
  const VecLayout& lay = out ? v.out.lay : v.in.lay;
  for (size_t f = 0; f < lay.size(); ++f)
    if (lay[f].name == name) return lay[f];
  ADD_FAILURE() << stage << " has no field " << name;
  return {};
}
int field_offset(const fs::path& dir, const std::string& stage, bool out, const std::string& name) {
  return field_of(dir, stage, out, name).offset;
}

// The line stages of the committed scene (9 segments: drawn, behind the triangles, clipped, off-screen,
// culled, NaN, a point, steep, an infinite varying): a moved pixel in line.out, a changed value in
// line_setup.out and a line_interp context pointing nowhere are caught and named, and nothing else.
TEST(SceneDump, CorruptedLineRowsAreCaughtAndNamed) {
  const Scene sc = load_scene((source_dir() / "scenes" / "transactions.json").string());
  ASSERT_GE(sc.lines.size(), 8u);
  const fs::path dir = temp_dir("corrupt_lines");
  const SceneDump d = dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, dir.string(), sc.name);
  EXPECT_GT(d.stats.lines.drawn, 3u);
  EXPECT_GT(d.stats.lines.culled_outside + d.stats.lines.rejected_nan + d.stats.lines.culled_no_pixels, 2u);
  ASSERT_EQ(restep_scene_vectors(dir.string()).mismatches(), 0u);

  auto expect_only = [&](const RestepReport& r, const std::string& stage, const std::string& also) {
    for (const auto& st : r.stages) {
      if (st.stage == stage) EXPECT_EQ(st.mismatches, 1u) << stage;
      else if (st.stage == also) EXPECT_GT(st.mismatches, 0u) << also;
      else EXPECT_EQ(st.mismatches, 0u) << st.stage;
    }
  };
  // line.out line 3: the pixel's x moved by one.
  const fs::path lo = dir / "line.out.hex";
  const std::string lgood = slurp(lo);
  flip_bit(lo, 3, field_offset(dir, "line", true, "x"));
  RestepReport r = restep_scene_vectors(dir.string());
  expect_only(r, "line", "");
  ASSERT_FALSE(r.first.empty());
  EXPECT_NE(r.first[0].find("line.out.hex:3: field 'x'"), std::string::npos) << r.first[0];
  spit(lo, lgood);

  // line_setup.out line 2: the second endpoint's depth value (its second most significant bit);
  // line_interp reads its context there.
  const fs::path so = dir / "line_setup.out.hex";
  const std::string sgood = slurp(so);
  const VecField zq1 = field_of(dir, "line_setup", true, "zq1");
  flip_bit(so, 2, zq1.offset + zq1.width - 2);
  r = restep_scene_vectors(dir.string());
  expect_only(r, "line_setup", "line_interp");
  ASSERT_FALSE(r.first.empty());
  EXPECT_NE(r.first[0].find("line_setup.out.hex:2: field 'zq1'"), std::string::npos) << r.first[0];
  spit(so, sgood);

  // line_depth.in line 1: a different depth code (the test on the triangles' buffer decides anew,
  // or the sample passes on with the changed code).
  const fs::path di = dir / "line_depth.in.hex";
  const std::string dgood = slurp(di);
  flip_bit(di, 1, field_offset(dir, "line_depth", false, "depth") + 4);
  r = restep_scene_vectors(dir.string());
  // (≥ 1: a written code can change the test of a later segment's sample at the same pixel.)
  for (const auto& st : r.stages)
    if (st.stage == "line_depth") EXPECT_GE(st.mismatches, 1u);
    else EXPECT_EQ(st.mismatches, 0u) << st.stage;
  spit(di, dgood);

  // line_interp.in line 1: ctx far beyond line_setup.out.
  const fs::path ii = dir / "line_interp.in.hex";
  const std::string igood = slurp(ii);
  flip_bit(ii, 1, field_offset(dir, "line_interp", false, "ctx") + 20);
  try {
    restep_scene_vectors(dir.string());
    ADD_FAILURE() << "a context beyond line_setup.out was accepted";
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("line_interp.in.hex:1: field 'ctx': no such line in line_setup.out"),
              std::string::npos)
        << e.what();
  }
  spit(ii, igood);
  EXPECT_EQ(restep_scene_vectors(dir.string()).mismatches(), 0u);
  fs::remove_all(dir);
}

// The writer checks every value against the width its record's visit() declares.
struct ToyRecord {
  int32_t s = 0;
  uint32_t u = 0;
  template <class V>
  void visit(V& v, const RecordShape&) {
    v("s", s, 4, true);
    v("u", u, 4, false);
  }
};

TEST(SceneDump, ValuesBeyondTheirDeclaredWidthAreRefused) {
  const Config cfg;
  const RecordShape shape{cfg, 0};
  VecRow row(2, 0);
  const std::string where = "toy";
  for (int32_t s : {-8, -1, 0, 7}) {
    ToyRecord t{s, 15};
    EXPECT_NO_THROW(pack_record(t, shape, row, 0, where)) << s;
    ToyRecord back;
    unpack_record(back, shape, row, 0);
    EXPECT_EQ(back.s, s);
    EXPECT_EQ(back.u, 15u);
  }
  EXPECT_THROW(pack_record(ToyRecord{8, 0}, shape, row, 0, where), ConfigError);
  EXPECT_THROW(pack_record(ToyRecord{-9, 0}, shape, row, 0, where), ConfigError);
  EXPECT_THROW(pack_record(ToyRecord{0, 16}, shape, row, 0, where), ConfigError);
}

// The committed dump is what the generator writes today (regenerate with the command printed).
TEST(SceneDumpCommitted, RegeneratingGivesIdenticalFiles) {
  const fs::path committed = source_dir() / "vectors" / "scenes" / "transactions";
  ASSERT_TRUE(fs::is_directory(committed)) << committed;
  const Scene sc = load_scene((source_dir() / "scenes" / "transactions.json").string());
  ASSERT_FALSE(sc.lines.empty());
  const fs::path dir = temp_dir("regen");
  const SceneDump d = dump_scene_vectors(sc.config, sc.state, sc.tris, sc.line_state, sc.lines, dir.string(), sc.name);
  std::vector<std::string> names = {"scene.json"};
  for (const auto& f : d.files) {
    names.push_back(f.hex);
    names.push_back(fs::path(f.hex).replace_extension(".json").string());
  }
  for (const auto& n : names)
    EXPECT_EQ(slurp(dir / n), slurp(committed / n))
        << n << " is stale; regenerate with: build/app/fxraster vectors scene scenes/transactions.json --out "
           "vectors/scenes/transactions";
  fs::remove_all(dir);
}
