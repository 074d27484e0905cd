// Transaction vectors of a whole draw (model/vectors/scene_dump.hpp, docs/vectors.md).
#include "model/vectors/scene_dump.hpp"

#include <array>
#include <filesystem>
#include <fstream>
#include <memory>
#include <optional>
#include <tuple>
#include <type_traits>

#include "model/config/json_input.hpp"
#include "model/config/validate.hpp"
#include "model/unit/backend.hpp"
#include "model/unit/chain.hpp"
#include "model/unit/line_chain.hpp"
#include "model/vectors/record_vectors.hpp"
#include "model/vectors/vectors.hpp"

namespace fxr {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// The stages in chain order: the triangles' chain, then the line path's (drawn after the triangles
// into the same depth buffer, with the line draw state).
using Stages = std::tuple<ConvertStage, ClipStage, RecipStage, ViewportStage, SetupStage, TraverseStage, InterpStage,
                          DepthStage, DivideStage, LineConvertStage, LineClipStage, LineRecipStage, LineViewportStage,
                          LineSetupStage, LineTraverseStage, LineInterpStage, LineDepthStage, LineDivideStage>;
constexpr size_t kNumStages = std::tuple_size_v<Stages>;

template <class S, size_t I = 0>
constexpr size_t stage_index() {
  static_assert(I < kNumStages, "not a stage of the chain");
  if constexpr (std::is_same_v<S, std::tuple_element_t<I, Stages>>) return I;
  else return stage_index<S, I + 1>();
}

template <class F, size_t... I>
void for_each_stage_impl(F&& f, std::index_sequence<I...>) {
  (f(std::integral_constant<size_t, I>{}), ...);
}
// Calls f(std::integral_constant<size_t, I>) for every stage index in chain order.
template <class F>
void for_each_stage(F&& f) {
  for_each_stage_impl(f, std::make_index_sequence<kNumStages>{});
}

// Stages with a per-primitive context (a `ctx` column): the interpolators latch the equations the
// setup stage of their path emitted (ContextOf<S>: that setup stage).
template <class S>
constexpr bool kHasContext = std::is_same_v<S, InterpStage> || std::is_same_v<S, LineInterpStage>;
template <class S>
using ContextOf = std::conditional_t<std::is_same_v<S, LineInterpStage>, LineSetupStage, SetupStage>;
// Stages of the line path: constructed with the line draw state.
template <class S>
constexpr bool kIsLineStage = stage_index<S>() >= stage_index<LineConvertStage>();
// Stages holding the frame's depth buffer.
template <class S>
constexpr bool kIsDepth = std::is_same_v<S, DepthStage> || std::is_same_v<S, LineDepthStage>;

// Header columns. In files: txn, n_out[, ctx]; out files: txn, seq, last.
constexpr size_t kInTxn = 0, kInNOut = 1, kInCtx = 2;
constexpr size_t kOutTxn = 0, kOutSeq = 1, kOutLast = 2, kOutHeader = kTxnOutHeaderFields;
template <class S>
constexpr size_t in_header_size() {
  return kHasContext<S> ? kTxnCtxHeaderFields : kTxnInHeaderFields;
}

template <class S>
VecLayout in_layout(const RecordShape& s) {
  std::vector<VecField> f = {
      {"txn", VecDir::In, kTxnIdBits, false, "transaction id: index of this input in the stage's input stream"},
      {"n_out", VecDir::In, kTxnCountBits, false, "number of records the stage emits for this input (0: none)"}};
  if (kHasContext<S>)
    f.push_back({"ctx", VecDir::In, kTxnIdBits, false,
                 std::string("line (from 0) of ") + ContextOf<S>::kName +
                     ".out holding this input's primitive equations (the latched context)"});
  append_record_fields<typename S::In>(s, VecDir::In, f);
  return VecLayout(f);
}

template <class S>
VecLayout out_layout(const RecordShape& s) {
  std::vector<VecField> f = {
      {"txn", VecDir::Out, kTxnIdBits, false, "id of the input (S.in txn) this output came from"},
      {"seq", VecDir::Out, kTxnCountBits, false, "index of this output among the outputs of its input"},
      {"last", VecDir::Out, 1, false, "1 on the last output of its input"}};
  append_record_fields<typename S::Out>(s, VecDir::Out, f);
  return VecLayout(f);
}

std::string file_name(const std::string& stage, const char* side) { return stage + "." + side + ".hex"; }

// ---- the draw state as JSON (its visit(): one integer per register field) --------------------

struct DrawStateToJson {
  json* j;
  template <class T>
  void operator()(const std::string& name, T& v, int, bool) {
    (*j)[name] = (int64_t)v;
  }
};
struct DrawStateFromJson {
  const json* j;
  std::string where;
  template <class T>
  void operator()(const std::string& name, T& v, int width, bool is_signed) {
    const std::string w = where + ": field '" + name + "'";
    if (!j->is_object() || !j->contains(name)) throw ConfigError(w + " is missing");
    const int64_t lo = is_signed ? -((int64_t)1 << (width - 1)) : 0;
    const int64_t hi = is_signed ? ((int64_t)1 << (width - 1)) - 1 : ((int64_t)1 << width) - 1;
    const int64_t x = json_int(j->at(name), lo, hi, w);
    if constexpr (std::is_same_v<T, bool>) v = x != 0;
    else v = (T)x;
  }
};

json draw_state_to_json(const Config& cfg, const DrawState& st) {
  json j = json::object();
  DrawStateToJson v{&j};
  const_cast<DrawState&>(st).visit(v, RecordShape{cfg, st.num_varyings});
  return j;
}

// ---- writing ---------------------------------------------------------------------------------

struct StageWriter {
  std::string stage, in_record, out_record;
  VecLayout in_lay, out_lay;
  std::unique_ptr<VecWriter> in_w, out_w;
  VecRow in_row, out_row;
  bool in_pending = false, out_pending = false;
  uint64_t next_txn = 0, n_out = 0, outs_total = 0;
  std::string in_where, out_where;

  void flush_out(bool last) {
    if (!out_pending) return;
    out_row[kOutLast] = last;
    out_w->write(out_row);
    out_pending = false;
  }
  void flush_in() {
    if (!in_pending) return;
    in_row[kInNOut] = n_out;
    in_w->write(in_row);
    in_pending = false;
  }
  void check_id(uint64_t v, int bits, const char* what) const {
    if (v >> bits)
      throw ConfigError("scene dump: stage " + stage + ": more than 2^" + std::to_string(bits) + " " + what +
                        " (the transaction header's width)");
  }
};

class DumpTaps {
 public:
  DumpTaps(const Config& cfg, const DrawState& st, const std::string& dir, const std::array<bool, kNumStages>& on)
      : shape_{cfg, st.num_varyings} {
    for_each_stage([&](auto ic) {
      using S = std::tuple_element_t<decltype(ic)::value, Stages>;
      StageWriter& w = w_[decltype(ic)::value];
      w.stage = S::kName;
      w.in_lay = in_layout<S>(shape_);
      w.out_lay = out_layout<S>(shape_);
      if (!on[decltype(ic)::value]) return;  // not written (its outputs are still counted: ctx)
      w.in_w = std::make_unique<VecWriter>(dir + "/" + file_name(w.stage, "in"), w.in_lay);
      w.out_w = std::make_unique<VecWriter>(dir + "/" + file_name(w.stage, "out"), w.out_lay);
      w.in_row.assign(w.in_lay.size(), 0);
      w.out_row.assign(w.out_lay.size(), 0);
      w.in_where = "scene dump: " + file_name(w.stage, "in");
      w.out_where = "scene dump: " + file_name(w.stage, "out");
    });
  }

  template <class S>
  void in(const typename S::In& r) {
    StageWriter& w = w_[stage_index<S>()];
    if (!w.in_w) return;
    w.flush_out(true);
    w.flush_in();
    w.check_id(w.next_txn, kTxnIdBits, "inputs");
    w.in_row[kInTxn] = w.next_txn++;
    if constexpr (kHasContext<S>) w.in_row[kInCtx] = w_[stage_index<ContextOf<S>>()].outs_total - 1;
    pack_record(r, shape_, w.in_row, in_header_size<S>(), w.in_where);
    w.n_out = 0;
    w.in_pending = true;
  }

  template <class S>
  void out(const typename S::Out& r) {
    StageWriter& w = w_[stage_index<S>()];
    ++w.outs_total;
    if (!w.out_w) return;
    w.flush_out(false);
    w.check_id(w.n_out, kTxnCountBits, "outputs of one input");
    w.out_row[kOutTxn] = w.next_txn - 1;
    w.out_row[kOutSeq] = w.n_out++;
    pack_record(r, shape_, w.out_row, kOutHeader, w.out_where);
    w.out_pending = true;
  }

  // Flushes and writes the manifests; returns the files.
  std::vector<SceneDumpFile> finish(const Config& cfg, const std::string& scene_name) {
    std::vector<SceneDumpFile> files;
    for (auto& w : w_) {
      if (!w.in_w) continue;
      w.flush_out(true);
      w.flush_in();
      for (int side = 0; side < 2; ++side) {
        VecWriter& vw = side ? *w.out_w : *w.in_w;
        const char* sn = side ? "out" : "in";
        VecManifest m;
        m.unit = w.stage;
        m.config = config_to_json(cfg);
        m.cases = {{"scene", 0, vw.count()}};
        json extra = {{"format", kSceneVectorFormatName},
                      {"format_version", kSceneVectorFormatVersion},
                      {"generator", "fxraster vectors scene"},
                      {"stage", w.stage},
                      {"side", sn},
                      {"scene", scene_name},
                      {"num_varyings", shape_.num_varyings},
                      {"transaction_rule",
                       side ? "txn: the S.in transaction this output came from; seq: its index among that "
                              "input's outputs; last: 1 on the final one (docs/vectors.md)"
                            : "txn: index of the input in stream order; n_out: outputs emitted for it (0..n)"
                              "; ctx (interp, line_interp): line of setup.out / line_setup.out with the "
                              "primitive's equations"}};
        const uint64_t rows = vw.count();
        vw.finish(m, extra);
        files.push_back({w.stage, sn, file_name(w.stage, sn), rows, (side ? w.out_lay : w.in_lay).word_bits()});
      }
    }
    return files;
  }

 private:
  RecordShape shape_;
  std::array<StageWriter, kNumStages> w_;
};

// Fragments are counted, not kept: the divide stage's outputs are in divide.out.hex.
class DiscardFragments final : public FragmentSink {
 public:
  void emit(const Fragment&) override {}
};

bool is_dump_file(const std::string& n) {
  if (n == "scene.json") return true;
  for (const auto& s : scene_dump_stages())
    for (const char* side : {"in", "out"})
      for (const char* ext : {".hex", ".json"})
        if (n == s + "." + side + ext) return true;
  return false;
}

}  // namespace

const std::vector<std::string>& scene_dump_stages() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> v;
    for_each_stage([&](auto ic) { v.push_back(std::tuple_element_t<decltype(ic)::value, Stages>::kName); });
    return v;
  }();
  return names;
}

SceneDump dump_scene_vectors(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             const std::string& dir, const std::string& scene_name) {
  return dump_scene_vectors(cfg, st, tris, st, {}, dir, scene_name);
}

SceneDump dump_scene_vectors(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             const DrawState& line_st, const std::vector<ClipLine>& lines, const std::string& dir,
                             const std::string& scene_name) {
  return dump_scene_vectors(cfg, st, tris, line_st, lines, dir, scene_name, {});
}

SceneDump dump_scene_vectors(const Config& cfg, const DrawState& st, const std::vector<ClipTriangle>& tris,
                             const DrawState& line_st, const std::vector<ClipLine>& lines, const std::string& dir_arg,
                             const std::string& scene_name, const std::vector<std::string>& stages) {
  std::array<bool, kNumStages> on{};
  on.fill(stages.empty());
  for (const std::string& n : stages) {
    bool found = false;
    for_each_stage([&](auto ic) {
      if (n != std::tuple_element_t<decltype(ic)::value, Stages>::kName) return;
      if (on[decltype(ic)::value]) throw ConfigError("scene dump: stage '" + n + "' named twice");
      on[decltype(ic)::value] = found = true;
    });
    if (!found) throw ConfigError("scene dump: no stage named '" + n + "' (the stages: convert … divide, line_convert … line_divide)");
  }
  auto need = [&](size_t a, size_t b, const char* why) {
    if (on[a] && !on[b])
      throw ConfigError(std::string("scene dump: stage '") + scene_dump_stages()[a] + "' needs '" +
                        scene_dump_stages()[b] + "' in the dump (" + why + ")");
  };
  need(stage_index<InterpStage>(), stage_index<SetupStage>(), "its ctx column names setup.out lines");
  need(stage_index<LineInterpStage>(), stage_index<LineSetupStage>(), "its ctx column names line_setup.out lines");
  need(stage_index<LineDepthStage>(), stage_index<DepthStage>(), "it is re-stepped on the buffer the triangles left");
  validate(cfg, "configuration");
  if (line_st.num_varyings != st.num_varyings)  // one record shape for every file of the dump
    throw ConfigError("scene dump: the line draw state has " + std::to_string(line_st.num_varyings) +
                      " varyings, the triangles' " + std::to_string(st.num_varyings) + " (they must agree)");
  fs::path dir = fs::path(dir_arg).lexically_normal();
  if (!dir.has_filename()) dir = dir.parent_path();
  std::error_code ec;
  if (fs::exists(dir, ec)) {  // replaced only when it holds a previous dump and nothing else
    if (!fs::is_directory(dir, ec)) throw ConfigError(dir.string() + ": exists and is not a folder");
    for (const auto& e : fs::directory_iterator(dir, ec))
      if (!is_dump_file(e.path().filename().string()))
        throw ConfigError(dir.string() + ": holds '" + e.path().filename().string() +
                          "', which a scene dump does not write; choose an empty or new folder");
  }
  const fs::path tmp = dir.string() + ".partial";
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) throw ConfigError(tmp.string() + ": cannot create the folder: " + ec.message());
  SceneDump out;
  try {
    FrameOutput f;
    DiscardFragments sink;
    DumpTaps taps(cfg, st, tmp.string(), on);
    run_raster_unit_to(cfg, st, tris, line_st, lines, f, &sink, taps);
    out.files = taps.finish(cfg, scene_name);
    out.stats = f.stats;
    json j;
    j["format"] = kSceneVectorFormatName;
    j["format_version"] = kSceneVectorFormatVersion;
    j["generator"] = "fxraster vectors scene";
    j["generator_version"] = kVectorGeneratorVersion;
    j["scene"] = scene_name;
    j["primitives"] = (uint64_t)tris.size();
    j["line_segments"] = (uint64_t)lines.size();
    j["config"] = config_to_json(cfg);
    j["draw_state"] = draw_state_to_json(cfg, st);
    j["line_draw_state"] = draw_state_to_json(cfg, line_st);
    json files = json::array();
    for (const auto& fl : out.files)
      files.push_back({{"stage", fl.stage}, {"side", fl.side}, {"hex_file", fl.hex}, {"count", fl.rows},
                       {"word_bits", fl.word_bits}});
    j["files"] = files;
    json stats = json::object();
    struct StatsToJson {
      json* j;
      void operator()(const char* n, uint64_t v) { (*j)[n] = v; }
    } sv{&stats};
    out.stats.visit(sv);
    json line_stats = json::object();
    StatsToJson lv{&line_stats};
    out.stats.lines.visit(lv);
    stats["lines"] = line_stats;  // the line path's counters (LineStats), also when there are no segments
    j["stats"] = stats;
    std::ofstream o(tmp / "scene.json", std::ios::binary);
    o << j.dump(2) << "\n";
    o.close();
    if (!o) throw ConfigError((tmp / "scene.json").string() + ": cannot write");
  } catch (...) {
    fs::remove_all(tmp, ec);
    throw;
  }
  fs::remove_all(dir, ec);
  fs::rename(tmp, dir, ec);
  if (ec) throw ConfigError(dir.string() + ": cannot rename the finished dump into place: " + ec.message());
  return out;
}

// ---- reading and re-stepping -----------------------------------------------------------------

namespace {

struct LoadedFile {
  std::string path;
  VecLayout lay;
  uint64_t rows = 0;
  std::vector<vec_word> data;
  vec_word at(uint64_t r, size_t f) const { return data[r * lay.size() + f]; }
  VecRow row(uint64_t r) const {
    const size_t n = lay.size();
    return VecRow(data.begin() + (ptrdiff_t)(r * n), data.begin() + (ptrdiff_t)((r + 1) * n));
  }
};

// Reads one file of the dump and checks its manifest against the layout the records give.
LoadedFile load_file(const std::string& dir, const std::string& stage, const char* side, const VecLayout& lay,
                     const json& config) {
  LoadedFile lf;
  lf.path = dir + "/" + file_name(stage, side);
  lf.lay = lay;
  const std::string mp = vec_manifest_path(lf.path);
  if (!std::ifstream(mp)) throw ConfigError(mp + ": cannot open the manifest of " + lf.path);
  const json j = read_json_file(mp, "manifest");
  auto need = [&](const char* k) -> const json& {
    if (!j.is_object() || !j.contains(k)) throw ConfigError(mp + ": field '" + k + "' is missing");
    return j.at(k);
  };
  if (need("format") != kSceneVectorFormatName)
    throw ConfigError(mp + ": field 'format': expected \"" + std::string(kSceneVectorFormatName) + "\"");
  if (json_int(need("format_version"), INT32_MIN, INT32_MAX, mp + ": field 'format_version'") != kSceneVectorFormatVersion)
    throw ConfigError(mp + ": field 'format_version': " + json_excerpt(need("format_version")) + " is not supported");
  if (need("stage") != stage) throw ConfigError(mp + ": field 'stage': expected \"" + stage + "\"");
  if (need("side") != side) throw ConfigError(mp + ": field 'side': expected \"" + std::string(side) + "\"");
  if (need("config") != config) throw ConfigError(mp + ": field 'config' differs from scene.json's");
  const json& jf = need("fields");
  if (!jf.is_array() || jf.size() != lay.size())
    throw ConfigError(mp + ": field 'fields': the records give " + std::to_string(lay.size()) + " fields");
  for (size_t i = 0; i < lay.size(); ++i) {
    const VecField& f = lay[i];
    const json& e = jf[i];
    const std::string w = mp + ": fields[" + std::to_string(i) + "]";
    if (!e.is_object() || !e.contains("name") || e.at("name") != f.name)
      throw ConfigError(w + ": expected the field '" + f.name + "'");
    if (!e.contains("width") || e.at("width") != f.width || !e.contains("offset") || e.at("offset") != f.offset ||
        !e.contains("signed") || e.at("signed") != f.is_signed)
      throw ConfigError(w + " ('" + f.name + "'): width, offset or signedness differ from the record's (width " +
                        std::to_string(f.width) + ", offset " + std::to_string(f.offset) + ")");
  }
  lf.rows = json_uint(need("count"), UINT64_MAX, mp + ": field 'count'");
  read_vec_hex(lf.path, lay, lf.rows, lf.data);
  return lf;
}

// Transaction headers: in-file txn = line, Σ n_out = out rows, out rows' (txn, seq, last)
// follow the in-file's counts.
void check_headers(const LoadedFile& in, const LoadedFile& out) {
  uint64_t o = 0;
  for (uint64_t i = 0; i < in.rows; ++i) {
    if (in.at(i, kInTxn) != i)
      throw ConfigError(in.path + ":" + std::to_string(i + 1) + ": field 'txn': expected " + std::to_string(i));
    const uint64_t n = (uint64_t)in.at(i, kInNOut);
    for (uint64_t k = 0; k < n; ++k, ++o) {
      const std::string w = out.path + ":" + std::to_string(o + 1);
      if (o >= out.rows) throw ConfigError(w + ": missing (the in file's n_out counts more outputs)");
      if (out.at(o, kOutTxn) != i) throw ConfigError(w + ": field 'txn': expected " + std::to_string(i));
      if (out.at(o, kOutSeq) != k) throw ConfigError(w + ": field 'seq': expected " + std::to_string(k));
      if (out.at(o, kOutLast) != (k + 1 == n)) throw ConfigError(w + ": field 'last': expected " + std::to_string(k + 1 == n));
    }
  }
  if (o != out.rows)
    throw ConfigError(out.path + ": " + std::to_string(out.rows) + " rows, the in file's n_out add up to " +
                      std::to_string(o));
}

std::string field_diff(const VecLayout& lay, const VecRow& a, const VecRow& b) {
  for (size_t f = 0; f < lay.size(); ++f)
    if (a[f] != b[f])
      return "field '" + lay[f].name + "': file " + vec_field_hex(lay[f], a[f]) + ", model " + vec_field_hex(lay[f], b[f]);
  return "";
}

}  // namespace

namespace {

// scene.json of a dump: its JSON, configuration and draw state.
struct SceneManifest {
  json j;
  Config cfg;
  DrawState st, line_st;
};
SceneManifest read_scene_manifest(const std::string& dir) {
  const std::string sp = dir + "/scene.json";
  if (!std::ifstream(sp)) throw ConfigError(sp + ": cannot open (not a scene dump folder?)");
  const json j = read_json_file(sp, "scene dump manifest");
  if (!j.is_object() || !j.contains("format") || j.at("format") != kSceneVectorFormatName)
    throw ConfigError(sp + ": field 'format': expected \"" + std::string(kSceneVectorFormatName) + "\"");
  if (!j.contains("format_version") ||
      json_int(j.at("format_version"), INT32_MIN, INT32_MAX, sp + ": field 'format_version'") != kSceneVectorFormatVersion)
    throw ConfigError(sp + ": field 'format_version' is missing or not supported");
  if (!j.contains("config")) throw ConfigError(sp + ": field 'config' is missing");
  const Config cfg = config_from_json(j.at("config"), sp + ": config");
  auto read_state = [&](const char* key) {
    DrawState st;
    DrawStateFromJson v{j.contains(key) ? &j.at(key) : nullptr, sp + ": " + key};
    if (!v.j) throw ConfigError(sp + ": field '" + key + "' is missing");
    st.visit(v, RecordShape{cfg, 0});
    return st;
  };
  const DrawState st = read_state("draw_state"), line_st = read_state("line_draw_state");
  if (line_st.num_varyings != st.num_varyings)
    throw ConfigError(sp + ": field 'line_draw_state': num_varyings differs from draw_state's");
  return {j, cfg, st, line_st};
}

}  // namespace

namespace {
// The stages listed in scene.json "files" (both sides), as a mask in chain order.
std::array<bool, kNumStages> stages_present(const json& j, const std::string& dir) {
  std::array<bool, kNumStages> on{};
  const std::string sp = dir + "/scene.json";
  if (!j.contains("files") || !j.at("files").is_array()) throw ConfigError(sp + ": field 'files' is missing");
  for (const json& f : j.at("files")) {
    if (!f.is_object() || !f.contains("stage") || !f.at("stage").is_string())
      throw ConfigError(sp + ": field 'files': an entry without 'stage'");
    bool found = false;
    for_each_stage([&](auto ic) {
      if (f.at("stage") == std::tuple_element_t<decltype(ic)::value, Stages>::kName) on[decltype(ic)::value] = found = true;
    });
    if (!found) throw ConfigError(sp + ": field 'files': no stage named " + json_excerpt(f.at("stage")));
  }
  return on;
}
}  // namespace

std::vector<std::string> scene_dump_stages_present(const std::string& dir) {
  const SceneManifest m = read_scene_manifest(dir);
  const std::array<bool, kNumStages> on = stages_present(m.j, dir);
  std::vector<std::string> v;
  for (size_t i = 0; i < kNumStages; ++i)
    if (on[i]) v.push_back(scene_dump_stages()[i]);
  return v;
}

DrawState load_scene_draw_state(const std::string& dir, bool lines) {
  const SceneManifest m = read_scene_manifest(dir);
  return lines ? m.line_st : m.st;
}

SceneStageVectors load_scene_stage(const std::string& dir, const std::string& stage) {
  const SceneManifest m = read_scene_manifest(dir);
  const RecordShape shape{m.cfg, m.st.num_varyings};
  std::optional<SceneStageVectors> r;
  const std::array<bool, kNumStages> on = stages_present(m.j, dir);
  for_each_stage([&](auto ic) {
    using S = std::tuple_element_t<decltype(ic)::value, Stages>;
    if (stage != S::kName) return;
    if (!on[decltype(ic)::value])
      throw ConfigError(dir + "/scene.json: the dump does not hold stage '" + stage + "' (written with a stage list)");
    LoadedFile in = load_file(dir, stage, "in", in_layout<S>(shape), m.j.at("config"));
    LoadedFile out = load_file(dir, stage, "out", out_layout<S>(shape), m.j.at("config"));
    check_headers(in, out);
    r.emplace(SceneStageVectors{stage, m.cfg, m.st.num_varyings, {}, {}});
    r->in = SceneStageFile{in.path, in.lay, in_header_size<S>(), in.rows, std::move(in.data)};
    r->out = SceneStageFile{out.path, out.lay, kOutHeader, out.rows, std::move(out.data)};
  });
  if (!r) throw ConfigError(dir + ": no stage named '" + stage + "' (the stages: convert … divide, line_convert … line_divide)");
  return std::move(*r);
}

RestepReport restep_scene_vectors(const std::string& dir, size_t max_report) {
  const SceneManifest m = read_scene_manifest(dir);
  const json& j = m.j;
  const Config& cfg = m.cfg;
  const RecordShape shape{cfg, m.st.num_varyings};
  RestepReport rep;
  FrameOutput frame;
  frame_begin(cfg, m.st, frame);  // the depth stages' buffer, cleared (the triangles', then the lines')
  std::optional<LoadedFile> setup_out, line_setup_out;  // the interpolators' contexts
  const std::array<bool, kNumStages> on = stages_present(j, dir);

  for_each_stage([&](auto ic) {
    using S = std::tuple_element_t<decltype(ic)::value, Stages>;
    if (!on[decltype(ic)::value]) return;  // not in this dump (dump_scene_vectors' stage list)
    const std::string name = S::kName;
    const DrawState& st = kIsLineStage<S> ? m.line_st : m.st;
    const LoadedFile in = load_file(dir, name, "in", in_layout<S>(shape), j.at("config"));
    LoadedFile out = load_file(dir, name, "out", out_layout<S>(shape), j.at("config"));
    check_headers(in, out);
    RestepStage rs{name, in.rows, out.rows, 0};

    std::optional<S> stage;
    if constexpr (kIsDepth<S>)
      stage.emplace(cfg, st, DepthBufferView{frame.depth.data(), frame.width, st.viewport_x, st.viewport_y});
    else stage.emplace(cfg, st);

    typename S::In rec{};
    VecRow row, got(out.lay.size());
    std::vector<VecRow> outs;
    uint64_t o = 0;
    [[maybe_unused]] std::conditional_t<kHasContext<S>, typename ContextOf<S>::Out, char> ctx{};
    [[maybe_unused]] const std::optional<LoadedFile>& ctx_file = std::is_same_v<ContextOf<S>, LineSetupStage> ? line_setup_out : setup_out;
    uint64_t ctx_id = UINT64_MAX;
    const std::string where = "restep " + name;
    for (uint64_t i = 0; i < in.rows; ++i) {
      row = in.row(i);
      rec = typename S::In{};
      unpack_record(rec, shape, row, in_header_size<S>());
      outs.clear();
      auto emit = [&](const typename S::Out& r) {
        std::fill(got.begin(), got.end(), 0);
        got[kOutTxn] = i;
        got[kOutSeq] = outs.size();
        pack_record(r, shape, got, kOutHeader, where);
        outs.push_back(got);
      };
      if constexpr (kHasContext<S>) {
        const uint64_t c = (uint64_t)row[kInCtx];
        if (!ctx_file || c >= ctx_file->rows)
          throw ConfigError(in.path + ":" + std::to_string(i + 1) + ": field 'ctx': no such line in " +
                            ContextOf<S>::kName + ".out");
        if (c != ctx_id) {
          ctx = typename ContextOf<S>::Out{};
          unpack_record(ctx, shape, ctx_file->row(c), kOutHeader);
          ctx_id = c;
        }
        stage->step(ctx, rec, emit);
      } else {
        stage->step(rec, emit);
      }
      if (!outs.empty()) outs.back()[kOutLast] = 1;
      const uint64_t n_file = (uint64_t)row[kInNOut];
      bool bad = outs.size() != n_file;
      std::string why = bad ? "emits " + std::to_string(outs.size()) + " records, the file has " + std::to_string(n_file) : "";
      for (size_t k = 0; k < outs.size() && k < n_file && !bad; ++k) {
        const VecRow want = out.row(o + k);
        if (want != outs[k]) {
          bad = true;
          why = out.path + ":" + std::to_string(o + k + 1) + ": " + field_diff(out.lay, want, outs[k]);
        }
      }
      if (bad) {
        ++rs.mismatches;
        if (rep.first.size() < max_report) rep.first.push_back(in.path + ":" + std::to_string(i + 1) + ": " + why);
      }
      o += n_file;
    }
    rep.stages.push_back(rs);
    if constexpr (std::is_same_v<S, SetupStage>) setup_out = std::move(out);
    if constexpr (std::is_same_v<S, InterpStage>) setup_out.reset();
    if constexpr (std::is_same_v<S, LineSetupStage>) line_setup_out = std::move(out);
    if constexpr (std::is_same_v<S, LineInterpStage>) line_setup_out.reset();
  });
  return rep;
}

}  // namespace fxr
