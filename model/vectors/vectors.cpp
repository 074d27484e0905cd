// Golden vectors: layout, generation, writer, reader / validator (docs/vectors.md), and the
// vector descriptions of the units (at the end of the file, one section per unit).
#include "model/vectors/vectors.hpp"

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "model/arith/div.hpp"
#include "model/config/json_input.hpp"
#include "model/config/validate.hpp"
#include "model/stages/recip.hpp"
#include "model/stages/setup.hpp"
#include "model/stages/texaddr.hpp"
#include "model/vectors/setup_vectors.hpp"

namespace fxr {

// Largest exhaustive sweep a unit offers (lines): 2^24 lines are about 0.4 GB of hex.
static constexpr uint64_t kMaxExhaustive = 1ull << 24;

// ---- layout ----------------------------------------------------------------------------------

VecLayout::VecLayout(std::vector<VecField> fields) : fields_(std::move(fields)) {
  bool seen_out = false;
  for (size_t i = 0; i < fields_.size(); ++i) {
    auto& f = fields_[i];
    if (f.width < 1 || f.width > kVecMaxFieldBits)
      throw ConfigError("vector layout: field '" + f.name + "': width " + std::to_string(f.width) +
                        " is outside [1, " + std::to_string(kVecMaxFieldBits) + "]");
    if (f.dir == VecDir::Out) seen_out = true;
    if (f.dir == VecDir::In && seen_out)
      throw ConfigError("vector layout: field '" + f.name + "': inputs must precede outputs");
    for (size_t j = 0; j < i; ++j)
      if (fields_[j].name == f.name) throw ConfigError("vector layout: field '" + f.name + "' twice");
    f.digits = (f.width + kVecBitsPerDigit - 1) / kVecBitsPerDigit;
    digits_ += f.digits;
    (f.dir == VecDir::In ? in_ : out_).push_back((int)i);
  }
  // Offsets from the lsb: the last field sits at bit 0.
  int off = 0;
  for (size_t i = fields_.size(); i-- > 0;) {
    fields_[i].offset = off;
    off += fields_[i].digits * kVecBitsPerDigit;
  }
}

int VecLayout::index(const std::string& name) const {
  for (size_t i = 0; i < fields_.size(); ++i)
    if (fields_[i].name == name) return (int)i;
  return -1;
}

vec_word vec_mask(int width) { return width >= kVecMaxFieldBits ? ~(vec_word)0 : (((vec_word)1 << width) - 1); }

i128 vec_unpack_signed(vec_word bits, int width) {
  bits &= vec_mask(width);
  if (width < kVecMaxFieldBits && ((bits >> (width - 1)) & 1)) bits |= ~vec_mask(width);
  return (i128)bits;
}

std::string vec_field_hex(const VecField& f, vec_word bits) {
  static const char* kHex = "0123456789abcdef";
  std::string s((size_t)f.digits, '0');
  for (int d = f.digits - 1; d >= 0; --d) {
    s[(size_t)d] = kHex[bits & 0xf];
    bits >>= kVecBitsPerDigit;
  }
  return s;
}

std::string vec_hex(const VecLayout& l, const VecRow& r) {
  std::string s;
  s.reserve((size_t)l.digits());
  for (size_t i = 0; i < l.size(); ++i) s += vec_field_hex(l[i], r[i]);
  return s;
}

std::string vec_hex(const VecLayout& l, const VecRow& r, VecDir dir) {
  std::string s;
  for (int i : dir == VecDir::In ? l.inputs() : l.outputs()) s += vec_field_hex(l[(size_t)i], r[(size_t)i]);
  return s;
}

VecRow VecFile::row(size_t i) const {
  const size_t n = manifest.layout.size();
  return VecRow(data.begin() + (ptrdiff_t)(i * n), data.begin() + (ptrdiff_t)((i + 1) * n));
}

// ---- units -----------------------------------------------------------------------------------

std::vector<VectorUnitInfo> builtin_vector_units();  // end of this file

static std::vector<VectorUnitInfo>& unit_registry() {
  static std::vector<VectorUnitInfo> r = builtin_vector_units();
  return r;
}

const std::vector<VectorUnitInfo>& vector_units() { return unit_registry(); }

void add_vector_unit(VectorUnitInfo info) {
  auto& r = unit_registry();
  for (auto& u : r)
    if (u.name == info.name) {
      u = std::move(info);
      return;
    }
  r.push_back(std::move(info));
}

const VectorUnitInfo& vector_unit(const std::string& name) {
  std::string known;
  for (const auto& u : vector_units()) {
    if (u.name == name) return u;
    known += (known.empty() ? "" : ", ") + u.name;
  }
  throw ConfigError("unknown vector unit '" + name + "' (known: " + known + ")");
}

std::unique_ptr<VectorModel> make_vector_model(const std::string& unit, const Config& cfg) {
  validate(cfg, "configuration");  // every range and rule (model/config/validate.hpp)
  return vector_unit(unit).make(cfg);
}

// ---- generation ------------------------------------------------------------------------------

std::vector<VecCases> generate_vectors(const VectorModel& m, uint64_t seed, uint64_t count,
                                       bool exhaustive,
                                       const std::function<void(const VecRow&)>& sink) {
  std::vector<VecCases> cases;
  uint64_t line = 0;
  auto emit = [&](VecRow& r) {
    m.compute(r);
    sink(r);
    ++line;
  };
  {
    auto dir = m.directed();
    cases.push_back({"directed", line, dir.size()});
    for (auto& r : dir) emit(r);
  }
  if (exhaustive) {
    const uint64_t n = m.exhaustive_count();
    if (n == 0)
      throw ConfigError("--exhaustive: the input domain of this unit at this configuration is too "
                        "large to enumerate; use --count for random cases");
    cases.push_back({"exhaustive", line, n});
    VecRow r = m.blank();
    for (uint64_t i = 0; i < n; ++i) {
      std::fill(r.begin(), r.end(), 0);
      m.exhaustive(i, r);
      emit(r);
    }
  } else if (count > 0) {
    cases.push_back({"random", line, count});
    std::mt19937_64 rng(seed);
    VecRow r = m.blank();
    for (uint64_t i = 0; i < count; ++i) {
      std::fill(r.begin(), r.end(), 0);
      m.random(rng, r);
      emit(r);
    }
  }
  return cases;
}

// ---- manifest --------------------------------------------------------------------------------

static const char* dir_name(VecDir d) { return d == VecDir::In ? "in" : "out"; }

nlohmann::json manifest_to_json(const VecManifest& m) {
  using nlohmann::json;
  json j;  // nlohmann's json keeps keys sorted: the file is byte-stable
  j["format"] = kVectorFormatName;
  j["format_version"] = kVectorFormatVersion;
  j["generator"] = "fxraster vectors";
  j["generator_version"] = m.generator_version;
  j["unit"] = m.unit;
  j["hex_file"] = m.hex_file;
  j["seed"] = m.seed;
  j["count"] = m.count;
  j["line_hex_digits"] = m.layout.digits();
  j["word_bits"] = m.layout.word_bits();
  j["layout_rule"] =
      "one vector per line: the fields below concatenated msb-first into one hex word, each "
      "zero-padded to ceil(width/4) digits; field value = word[offset +: width]; signed = two's "
      "complement in width bits";
  json fields = json::array();
  for (const auto& f : m.layout.fields())
    fields.push_back({{"name", f.name}, {"dir", dir_name(f.dir)}, {"width", f.width},
                      {"hex_digits", f.digits}, {"offset", f.offset}, {"signed", f.is_signed},
                      {"format", f.format}});
  j["fields"] = fields;
  json cases = json::array();
  for (const auto& c : m.cases)
    cases.push_back({{"kind", c.kind}, {"first_line", c.first + 1}, {"count", c.count}});
  j["cases"] = cases;
  j["config"] = m.config;
  return j;
}

std::string vec_manifest_path(const std::string& hex_path) {
  const size_t slash = hex_path.find_last_of('/');
  const size_t dot = hex_path.find_last_of('.');
  if (dot != std::string::npos && (slash == std::string::npos || dot > slash))
    return hex_path.substr(0, dot) + ".json";
  return hex_path + ".json";
}

static std::string base_name(const std::string& p) {
  const size_t slash = p.find_last_of('/');
  return slash == std::string::npos ? p : p.substr(slash + 1);
}

// ---- writer ----------------------------------------------------------------------------------

struct VecWriter::Impl {
  std::FILE* f = nullptr;
  std::string line;
};

// No stale output (docs/vectors.md): the previous pair (hex + manifest) is removed first, both
// files are written under a ".partial" name and renamed by finish(); a run that fails leaves
// neither, so no pair from an earlier run passes for this run's.
static std::string partial(const std::string& p) { return p + ".partial"; }

VecWriter::VecWriter(const std::string& hex_path, const VecLayout& layout)
    : impl_(new Impl), layout_(layout), path_(hex_path) {
  std::remove(hex_path.c_str());
  std::remove(vec_manifest_path(hex_path).c_str());
  impl_->f = std::fopen(partial(hex_path).c_str(), "wb");
  if (!impl_->f) throw ConfigError(hex_path + ": cannot write");
  impl_->line.reserve((size_t)layout.digits() + 1);
}

VecWriter::~VecWriter() {
  if (impl_ && impl_->f) {  // not finished: an exception is unwinding
    std::fclose(impl_->f);
    std::remove(partial(path_).c_str());
  }
}

void VecWriter::write(const VecRow& row) {
  impl_->line = vec_hex(layout_, row);
  impl_->line += '\n';  // every line ends in a newline, the last one too
  std::fwrite(impl_->line.data(), 1, impl_->line.size(), impl_->f);
  ++count_;
}

void VecWriter::finish(VecManifest m, const nlohmann::json& overrides) {
  const bool bad = std::ferror(impl_->f) != 0;
  if (std::fclose(impl_->f) != 0 || bad) {
    impl_->f = nullptr;
    std::remove(partial(path_).c_str());
    throw ConfigError(path_ + ": write failed");
  }
  impl_->f = nullptr;
  m.count = count_;
  m.hex_file = base_name(path_);
  m.layout = layout_;
  const std::string mp = vec_manifest_path(path_);
  {
    std::ofstream o(partial(mp), std::ios::binary);
    nlohmann::json j = manifest_to_json(m);
    for (auto it = overrides.begin(); it != overrides.end(); ++it) j[it.key()] = it.value();
    o << j.dump(2) << "\n";
    o.close();
    if (!o) {
      std::remove(partial(path_).c_str());
      std::remove(partial(mp).c_str());
      throw ConfigError(mp + ": cannot write");
    }
  }
  // Hex first, manifest last: a reader needs both, and finds the manifest only once both exist.
  if (std::rename(partial(path_).c_str(), path_.c_str()) != 0 || std::rename(partial(mp).c_str(), mp.c_str()) != 0)
    throw ConfigError(path_ + ": cannot rename the finished files into place");
}

VecManifest write_unit_vectors(const std::string& unit, const Config& cfg, uint64_t seed,
                               uint64_t count, bool exhaustive, const std::string& dir) {
  auto m = make_vector_model(unit, cfg);
  if (exhaustive && m->exhaustive_count() == 0)  // before any file is opened
    throw ConfigError("vectors " + unit + " --exhaustive: the input domain at this configuration is too "
                      "large to enumerate (more than " + std::to_string(kMaxExhaustive) +
                      " lines); use --count for random cases");
  VecWriter w(dir + "/" + unit + ".hex", m->layout());
  VecManifest man;
  man.unit = unit;
  man.config = m->config_json();
  man.seed = seed;
  man.cases = generate_vectors(*m, seed, count, exhaustive, [&](const VecRow& r) { w.write(r); });
  w.finish(man);
  man.count = w.count();
  man.hex_file = unit + ".hex";
  man.layout = m->layout();
  return man;
}

VecManifest write_unit_rows(const std::string& unit, const Config& cfg, const std::vector<VecRow>& inputs,
                            const std::string& kind, const std::string& dir, const nlohmann::json& extra) {
  auto m = make_vector_model(unit, cfg);
  VecWriter w(dir + "/" + unit + ".hex", m->layout());
  VecManifest man;
  man.unit = unit;
  man.config = m->config_json();
  VecRow r;
  for (const VecRow& in : inputs) {
    if (in.size() != m->layout().size())
      throw ConfigError("vectors " + unit + ": a row of " + std::to_string(in.size()) + " fields, the layout has " +
                        std::to_string(m->layout().size()));
    r = in;
    m->compute(r);
    w.write(r);
  }
  man.cases = {{kind, 0, w.count()}};
  w.finish(man, extra);
  man.count = w.count();
  man.hex_file = unit + ".hex";
  man.layout = m->layout();
  return man;
}

std::vector<VecRow> texaddr_fragment_rows(const Config& cfg, const std::vector<std::array<FxFloat, 2>>& uv,
                                          uint32_t width, uint32_t height) {
  const TexAddrConfig& c = cfg.tex_addr;
  const uint64_t max_size = 1ull << c.size_bits;
  if (width < 1 || height < 1 || width > max_size || height > max_size)
    throw ConfigError("vectors texaddr: texture size " + std::to_string(width) + " x " + std::to_string(height) +
                      " is outside [1, 2^tex_addr.size_bits]");
  const int emin = -(1 << (c.exp_bits - 1)), emax = (1 << (c.exp_bits - 1)) - 1;
  const size_t nf = make_vector_model("texaddr", cfg)->layout().size();
  std::vector<VecRow> rows;
  rows.reserve(uv.size() * 8);
  for (size_t i = 0; i < uv.size(); ++i)
    for (uint64_t fil = 0; fil < 2; ++fil)  // nearest, bilinear
      for (uint64_t wrap = 0; wrap < 4; ++wrap) {  // the order of tex_addr.wrap
        VecRow r(nf, 0);
        r[0] = fil;
        r[1] = wrap;
        for (int a = 0; a < 2; ++a) {
          const FxFloat& x = uv[i][a];
          if (x.exp < emin || x.exp > emax || x.sig >> c.sig_bits)
            throw ConfigError("vectors texaddr: fragment " + std::to_string(i) + ": coordinate " + (a ? "v" : "u") +
                              " (exponent " + std::to_string(x.exp) +
                              ") does not fit the unit's input fields (tex_addr.exp_bits, sig_bits)");
          r[2 + 3 * (size_t)a] = x.neg;
          r[3 + 3 * (size_t)a] = vec_pack(x.exp, c.exp_bits);
          r[4 + 3 * (size_t)a] = x.sig;
        }
        r[8] = width;
        r[9] = height;
        rows.push_back(std::move(r));
      }
  return rows;
}

// ---- reader / validator ----------------------------------------------------------------------

namespace {

// Manifest fields, read with checked conversions: a value of the wrong type, a fraction, or a
// number beyond the destination's range is an error naming the field (never truncated, never
// wrapped; docs/vectors.md). Quoted values are bounded (json_excerpt).
const nlohmann::json& need_field(const nlohmann::json& j, const char* key, const std::string& where) {
  if (!j.is_object()) throw ConfigError(where + ": expected an object, got " + json_typed_excerpt(j));
  if (!j.contains(key)) throw ConfigError(where + ": field '" + key + "' is missing");
  return j.at(key);
}
std::string need_string(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto& v = need_field(j, key, where);
  if (!v.is_string()) throw ConfigError(where + ": field '" + key + "': expected a string, got " + json_typed_excerpt(v));
  return v.get<std::string>();
}
bool need_bool(const nlohmann::json& j, const char* key, const std::string& where) {
  const auto& v = need_field(j, key, where);
  if (!v.is_boolean()) throw ConfigError(where + ": field '" + key + "': expected true or false, got " + json_typed_excerpt(v));
  return v.get<bool>();
}
int need_int(const nlohmann::json& j, const char* key, const std::string& where) {
  return (int)json_int(need_field(j, key, where), INT32_MIN, INT32_MAX, where + ": field '" + key + "'");
}
uint64_t need_uint(const nlohmann::json& j, const char* key, const std::string& where) {
  return json_uint(need_field(j, key, where), UINT64_MAX, where + ": field '" + key + "'");
}

// First differing key between two JSON objects, as a path ("recip.seed_index_bits").
std::string first_difference(const nlohmann::json& a, const nlohmann::json& b, const std::string& path) {
  if (a.is_object() && b.is_object()) {
    for (auto it = a.begin(); it != a.end(); ++it) {
      const std::string p = path.empty() ? it.key() : path + "." + it.key();
      if (!b.contains(it.key())) return p + " (missing on one side)";
      std::string d = first_difference(it.value(), b.at(it.key()), p);
      if (!d.empty()) return d;
    }
    for (auto it = b.begin(); it != b.end(); ++it)
      if (!a.contains(it.key())) return (path.empty() ? it.key() : path + "." + it.key()) + " (missing on one side)";
    return "";
  }
  return a == b ? "" : cut(path, kMaxExcerptChars) + " (" + json_excerpt(a) + " vs " + json_excerpt(b) + ")";
}

int hex_value(char c) {
  if (c >= '0' && c <= '9') return c - '0';
  if (c >= 'a' && c <= 'f') return c - 'a' + 10;
  return -1;  // uppercase too: the format is lowercase hex (docs/vectors.md)
}

}  // namespace

void read_vec_hex(const std::string& hex_path, const VecLayout& lay, uint64_t count, std::vector<vec_word>& data) {
  std::ifstream in(hex_path, std::ios::binary);
  if (!in) throw ConfigError(hex_path + ": cannot open");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t nf = lay.size();
  // Reserve from the file's size, not from the manifest's count (which may be anything).
  data.reserve(text.size() / ((size_t)lay.digits() + 1) * nf);
  size_t pos = 0;
  uint64_t line = 0;
  while (pos < text.size()) {
    ++line;
    const size_t eol = text.find('\n', pos);
    const std::string where = hex_path + ":" + std::to_string(line);
    if (eol == std::string::npos)
      throw ConfigError(where + ": the last line has no trailing newline (Verilator's $readmemh "
                        "would drop it; the file may be truncated)");
    size_t len = eol - pos;
    if (len > 0 && text[eol - 1] == '\r')
      throw ConfigError(where + ": CR line end (the format uses LF only)");
    if (line > count)
      throw ConfigError(where + ": more lines than the manifest's count " + std::to_string(count));
    if ((int)len != lay.digits()) {
      throw ConfigError(where + ": " + std::to_string(len) + " hex digits, expected " +
                        std::to_string(lay.digits()) + " (" + std::to_string(nf) +
                        " fields; wrong field count or width)");
    }
    size_t col = pos;
    for (size_t fi = 0; fi < nf; ++fi) {
      const auto& f = lay[fi];
      vec_word v = 0;
      for (int d = 0; d < f.digits; ++d, ++col) {
        const int h = hex_value(text[col]);
        if (h < 0) {
          const unsigned char c = (unsigned char)text[col];
          char shown[8];
          std::snprintf(shown, sizeof shown, (c >= 0x20 && c < 0x7f) ? "%c" : "\\x%02x", c);
          throw ConfigError(where + ": field '" + f.name + "' (column " + std::to_string(col - pos + 1) +
                            "): bad hex digit '" + std::string(shown) + "'" +
                            (c >= 'A' && c <= 'F' ? " (uppercase: the format is lowercase hex)" : ""));
        }
        v = (v << kVecBitsPerDigit) | (vec_word)h;
      }
      if (v & ~vec_mask(f.width))
        throw ConfigError(where + ": field '" + f.name + "': value " + vec_field_hex(f, v) +
                          " does not fit its " + std::to_string(f.width) + " bits");
      data.push_back(v);
    }
    pos = eol + 1;
  }
  if (line < count)
    throw ConfigError(hex_path + ": " + std::to_string(line) + " lines, the manifest says " +
                      std::to_string(count) + " (truncated file?)");
}

VecFile read_vectors(const std::string& hex_path, const Config* expect) {
  VecFile vf;
  vf.hex_path = hex_path;
  const std::string mp = vec_manifest_path(hex_path);
  if (!std::ifstream(mp)) throw ConfigError(mp + ": cannot open the manifest of " + hex_path);
  const nlohmann::json j = read_json_file(mp, "manifest");  // bounded, numbers checked
  if (!j.is_object()) throw ConfigError(mp + ": the manifest must be a JSON object");
  if (need_string(j, "format", mp) != kVectorFormatName)
    throw ConfigError(mp + ": field 'format': expected \"" + kVectorFormatName + "\"");
  const int fv = need_int(j, "format_version", mp);
  if (fv != kVectorFormatVersion)
    throw ConfigError(mp + ": field 'format_version': " + std::to_string(fv) +
                      " is not supported (expected " + std::to_string(kVectorFormatVersion) + ")");
  VecManifest& m = vf.manifest;
  m.generator_version = need_int(j, "generator_version", mp);
  if (m.generator_version != kVectorGeneratorVersion)
    throw ConfigError(mp + ": field 'generator_version': " + std::to_string(m.generator_version) +
                      " differs from this generator's " + std::to_string(kVectorGeneratorVersion) +
                      " (regenerate the file with `fxraster vectors`)");
  m.unit = need_string(j, "unit", mp);
  m.hex_file = need_string(j, "hex_file", mp);
  if (m.hex_file != base_name(hex_path))
    throw ConfigError(mp + ": field 'hex_file': \"" + m.hex_file + "\" is not " + base_name(hex_path));
  m.seed = need_uint(j, "seed", mp);
  m.count = need_uint(j, "count", mp);
  if (!j.contains("config") || !j.at("config").is_object())
    throw ConfigError(mp + ": field 'config' is missing or not an object");
  m.config = j.at("config");
  const Config cfg = config_from_json(m.config, mp + ": config");
  auto model = make_vector_model(m.unit, cfg);
  if (model->config_json() != m.config)
    throw ConfigError(mp + ": field 'config': sections other than the unit's, or not in canonical "
                      "form: " + first_difference(m.config, model->config_json(), "config"));
  if (expect) {
    const auto want = make_vector_model(m.unit, *expect)->config_json();
    if (want != m.config)
      throw ConfigError(mp + ": field 'config' does not match the expected configuration: " +
                        first_difference(m.config, want, "config") +
                        " (manifest vs expected; regenerate the vectors or pass the same --config)");
  }
  // Fields: must equal the model's layout at this configuration, field by field.
  const VecLayout& lay = model->layout();
  const auto& jf = j.contains("fields") ? j.at("fields") : nlohmann::json();
  if (!jf.is_array()) throw ConfigError(mp + ": field 'fields' is missing or not an array");
  if (jf.size() != lay.size())
    throw ConfigError(mp + ": field 'fields': " + std::to_string(jf.size()) + " fields, the unit '" +
                      m.unit + "' has " + std::to_string(lay.size()));
  for (size_t i = 0; i < lay.size(); ++i) {
    const std::string w = mp + ": fields[" + std::to_string(i) + "]";
    const auto& f = lay[i];
    const auto name = need_string(jf[i], "name", w);
    if (name != f.name) throw ConfigError(w + ": field 'name': \"" + name + "\", expected \"" + f.name + "\"");
    const std::string wf = mp + ": field '" + f.name + "'";
    if (need_int(jf[i], "width", wf) != f.width)
      throw ConfigError(wf + ": width " + json_excerpt(jf[i].at("width")) + ", the configuration gives " +
                        std::to_string(f.width));
    if (need_int(jf[i], "offset", wf) != f.offset)
      throw ConfigError(wf + ": offset " + json_excerpt(jf[i].at("offset")) + ", the layout gives " +
                        std::to_string(f.offset));
    if (need_string(jf[i], "dir", wf) != dir_name(f.dir))
      throw ConfigError(wf + ": dir " + json_excerpt(jf[i].at("dir")) + ", expected \"" + dir_name(f.dir) + "\"");
    if (need_bool(jf[i], "signed", wf) != f.is_signed)
      throw ConfigError(wf + ": signed " + json_excerpt(jf[i].at("signed")) + " differs from the unit's");
  }
  m.layout = lay;
  if (need_int(j, "line_hex_digits", mp) != lay.digits())
    throw ConfigError(mp + ": field 'line_hex_digits': " + json_excerpt(j.at("line_hex_digits")) +
                      ", the fields add up to " + std::to_string(lay.digits()));
  if (j.contains("cases") && j.at("cases").is_array()) {
    uint64_t next = 1;
    for (const auto& c : j.at("cases")) {
      const uint64_t first_line = need_uint(c, "first_line", mp + ": cases");
      VecCases vc{need_string(c, "kind", mp + ": cases"), first_line - 1, need_uint(c, "count", mp + ": cases")};
      if (first_line != next)
        throw ConfigError(mp + ": field 'cases': kind '" + cut(vc.kind, kMaxExcerptChars) + "' starts at line " +
                          std::to_string(first_line) + ", expected " + std::to_string(next));
      // Checked: the kinds may not cover more lines than 'count' (no uint64 wrap-around).
      if (vc.count > m.count - (next - 1))
        throw ConfigError(mp + ": field 'cases': kind '" + cut(vc.kind, kMaxExcerptChars) + "' count " +
                          std::to_string(vc.count) + " runs past the manifest's count " + std::to_string(m.count));
      next += vc.count;
      m.cases.push_back(vc);
    }
    if (next - 1 != m.count)
      throw ConfigError(mp + ": field 'cases': the kinds cover " + std::to_string(next - 1) +
                        " lines, 'count' says " + std::to_string(m.count));
  } else {
    throw ConfigError(mp + ": field 'cases' is missing or not an array");
  }

  read_vec_hex(hex_path, lay, m.count, vf.data);
  return vf;
}

uint64_t recheck_vectors(const VecFile& f, std::vector<std::string>* first, size_t max_report) {
  const Config cfg = config_from_json(f.manifest.config, f.hex_path);
  auto model = make_vector_model(f.manifest.unit, cfg);
  const VecLayout& lay = f.manifest.layout;
  uint64_t bad = 0;
  VecRow r;
  for (size_t i = 0; i < f.rows(); ++i) {
    const VecRow want = f.row(i);
    r = want;
    for (int o : lay.outputs()) r[(size_t)o] = 0;
    try {
      model->compute(r);
    } catch (const std::invalid_argument& e) {
      // Inputs outside the unit's contract (e.g. a div operand without its msb): name the line.
      throw ConfigError(f.hex_path + ":" + std::to_string(i + 1) + ": input " + vec_hex(lay, want, VecDir::In) +
                        " is outside the unit's input domain: " + cut(e.what(), kMaxExcerptChars));
    }
    if (r != want) {
      ++bad;
      if (first && first->size() < max_report)
        first->push_back(f.hex_path + ":" + std::to_string(i + 1) + ": in=" + vec_hex(lay, want, VecDir::In) +
                         " file=" + vec_hex(lay, want, VecDir::Out) + " model=" + vec_hex(lay, r, VecDir::Out));
    }
  }
  return bad;
}

// ==== the units ===============================================================================
// One section per unit: its fields (named as the RTL ports without _i / _o), the model call,
// and its directed / random / exhaustive cases.

namespace {

// Raw-bit helpers for the generators (platform-independent: no std distributions).
inline uint64_t bit(int i) { return 1ull << i; }
// A significand of `bits` bits with its msb set, the rest from rng.
inline uint64_t random_sig(std::mt19937_64& rng, int bits) { return bit(bits - 1) | (rng() & vec_mask(bits - 1)); }

nlohmann::json unit_config_json(const char* unit, const nlohmann::json& params) {
  return {{"version", kConfigFormatVersion}, {unit, params}};
}

// ---- div: the per-pixel significand divider (model/arith/div.hpp, rtl/fxr_div.sv) -------------------
// Fields: in_num [num_bits], in_den [den_bits] (significands with the msb set, or 0);
// out_sig [quot_bits], out_exp_adj (signed, {−1, 0, +1}), out_dbz. Model: div_sig.

// out_exp_adj ∈ {−1, 0, +1}: two's complement needs 2 bits.
constexpr int kDivExpAdjBits = 2;

class DivVectors : public VectorModel {
 public:
  explicit DivVectors(const Config& c) : c_(c.div) {
    nb_ = c_.num_bits;
    db_ = c_.den_bits;
    qb_ = c_.quot_bits;
    const std::string nb = std::to_string(nb_), db = std::to_string(db_), qb = std::to_string(qb_);
    lay_ = VecLayout({
        {"in_num", VecDir::In, nb_, false, "unsigned numerator significand, " + nb + " bits, msb set (or 0)"},
        {"in_den", VecDir::In, db_, false, "unsigned denominator significand, " + db + " bits, msb set (or 0 = divide by zero)"},
        {"out_sig", VecDir::Out, qb_, false,
         "unsigned quotient significand, " + qb + " bits, msb set, RNE; 0 when num = 0; all ones when den = 0"},
        {"out_exp_adj", VecDir::Out, kDivExpAdjBits, true,
         "signed exponent adjustment: quotient = sig·2^-(" + qb + "-1)·2^exp_adj, exp_adj in {-1, 0, +1}"},
        {"out_dbz", VecDir::Out, 1, false, "1 when den = 0"},
    });
  }
  const VecLayout& layout() const override { return lay_; }
  nlohmann::json config_json() const override {
    nlohmann::json j = unit_config_json("div", to_json_params(c_));
    // quot_bits is derived from raster.varying_out_sig_bits (model/config/validate.hpp): a
    // non-default width is recorded at its source so that the manifest reads back.
    if (c_.quot_bits != RasterConfig{}.varying_out_sig_bits)
      j["raster"] = {{"varying_out_sig_bits", c_.quot_bits}};
    return j;
  }
  void compute(VecRow& r) const override {
    const DivSig q = div_sig(c_, r[0], r[1]);
    r[2] = q.sig;
    r[3] = vec_pack(q.exp_adj, kDivExpAdjBits);
    r[4] = r[1] == 0;
  }
  std::vector<VecRow> directed() const override {
    std::vector<VecRow> v;
    auto add = [&](uint64_t n, uint64_t d) { v.push_back({n, d, 0, 0, 0}); };
    const uint64_t nmin = bit(nb_ - 1), nmax = vec_mask(nb_), dmin = bit(db_ - 1), dmax = vec_mask(db_);
    // Extremes and zeros (den = 0: the RTL raises out_dbz and saturates, as the model).
    for (uint64_t n : {nmin, nmin + 1, nmax - 1, nmax})
      for (uint64_t d : {dmin, dmin + 1, dmax - 1, dmax}) add(n, d);
    for (uint64_t n : {uint64_t(0), nmin, nmax}) add(n, 0);
    for (uint64_t d : {dmin, dmax}) add(0, d);
    // Equal operands and n = d ± 1 ulp of n (d aligned to n's width), across the range.
    const int sh = nb_ - db_;
    auto align = [&](uint64_t d) { return sh >= 0 ? d << sh : d >> -sh; };
    for (uint64_t d : {dmin, dmin + 1, dmin | (dmin >> 1), dmax - 1, dmax}) {
      const uint64_t n = align(d);
      if (n >= nmin && n <= nmax) add(n, d);
      if (n - 1 >= nmin) add(n - 1, d);
      if (n + 1 <= nmax) add(n + 1, d);
    }
    // Round-to-nearest-even ties and near-ties: d = 1.0, n with the bit below the quotient lsb set.
    if (nb_ > qb_) {
      const uint64_t half = bit(nb_ - qb_ - 1);
      for (uint64_t base : {nmin, nmin + 2 * half, (uint64_t)(nmax & ~vec_mask(nb_ - qb_))}) {
        add(base + half, dmin);
        add(base + half - 1, dmin);
        if (half > 1 || base + half + 1 <= nmax) add(std::min(base + half + 1, nmax), dmin);
      }
    }
    // Powers of two in the divisor's fraction (quotients with long carry chains).
    for (int i = 0; i < db_ - 1; ++i) add(nmax, dmin | bit(i));
    return v;
  }
  // Random: 1 case in 32 has den = 0, 1 in 32 num = 0, 1 in 16 has n within ±8 of the aligned d
  // (quotients near 1, the exp_adj boundary); the others are uniform significands.
  void random(std::mt19937_64& rng, VecRow& r) const override {
    const uint64_t sel = rng() & 31;
    r[0] = random_sig(rng, nb_);
    r[1] = random_sig(rng, db_);
    if (sel == 0) r[1] = 0;
    if (sel == 1) r[0] = 0;
    if (sel == 2 || sel == 3) {
      const int sh = nb_ - db_;
      const uint64_t n = sh >= 0 ? r[1] << sh : r[1] >> -sh;
      const int64_t delta = vec_random_in(rng, -8, 8);
      const uint64_t m = (uint64_t)((int64_t)n + delta);
      r[0] = (m >= bit(nb_ - 1) && m <= vec_mask(nb_)) ? m : n;
    }
  }
  // Every pair of significands (msb set) when there are at most kMaxExhaustive.
  uint64_t exhaustive_count() const override {
    const int b = (nb_ - 1) + (db_ - 1);
    return bit(std::min(b, 63)) <= kMaxExhaustive ? bit(b) : 0;
  }
  void exhaustive(uint64_t i, VecRow& r) const override {
    r[0] = bit(nb_ - 1) | (i >> (db_ - 1));
    r[1] = bit(db_ - 1) | (i & vec_mask(db_ - 1));
  }

 private:
  DivConfig c_;
  int nb_, db_, qb_;
  VecLayout lay_;
};

// ---- recip: the reciprocal unit 1/w (model/stages/recip.hpp, rtl/fxr_recip.sv) ----------------------
// Fields: in_neg, in_exp [exp_bits] (signed exponent of the leading one), in_sig [in_sig_bits]
// (msb set, or 0 for w = 0); out_neg, out_exp [exp_bits], out_sig [out_sig_bits] (msb set),
// out_dbz (w = 0), out_ovf (exponent overflow). Model: RecipUnit (= fxr::recip).

class RecipVectors : public VectorModel {
 public:
  explicit RecipVectors(const Config& c) : c_(c.recip), unit_(c.recip) {
    n_ = c_.in_sig_bits;
    o_ = c_.out_sig_bits;
    eb_ = c_.exp_bits;
    emin_ = recip_exp_min(c_);
    emax_ = recip_exp_max(c_);
    const std::string n = std::to_string(n_), o = std::to_string(o_), e = std::to_string(eb_);
    const std::string range = "[" + std::to_string(emin_) + ", " + std::to_string(emax_) + "]";
    lay_ = VecLayout({
        {"in_neg", VecDir::In, 1, false, "sign of w (1 = negative)"},
        {"in_exp", VecDir::In, eb_, true, "signed exponent of the leading one of w, " + e + " bits, " + range},
        {"in_sig", VecDir::In, n_, false,
         "unsigned significand of w, " + n + " bits, msb set: w = (-1)^neg * sig * 2^(exp-(" + n + "-1)); 0 for w = 0"},
        {"out_neg", VecDir::Out, 1, false, "sign of 1/w (= in_neg)"},
        {"out_exp", VecDir::Out, eb_, true, "signed exponent of the leading one of 1/w, " + e + " bits"},
        {"out_sig", VecDir::Out, o_, false,
         "unsigned significand of 1/w, " + o + " bits, msb set, round to nearest (fxr::recip)"},
        {"out_dbz", VecDir::Out, 1, false, "w = 0 (result: largest magnitude)"},
        {"out_ovf", VecDir::Out, 1, false, "exponent overflow: 1/|w| >= 2^(exp_max+1) (result: largest magnitude)"},
    });
  }
  const VecLayout& layout() const override { return lay_; }
  nlohmann::json config_json() const override { return unit_config_json("recip", to_json_params(c_)); }
  void compute(VecRow& r) const override {
    FxFloat w;
    w.neg = r[0] != 0;
    w.sig = r[2];
    w.exp = (int)vec_unpack_signed(r[1], eb_) - (n_ - 1);
    const RecipResult q = unit_(w);
    r[3] = q.value.neg;
    r[4] = vec_pack(q.value.exp + (o_ - 1), eb_);  // lead exponent, always in [emin, emax]
    r[5] = q.value.sig;
    r[6] = q.div_by_zero;
    r[7] = q.exp_overflow;
  }
  std::vector<VecRow> directed() const override {
    std::vector<VecRow> v;
    auto add = [&](bool neg, int exp, uint64_t sig) { v.push_back({neg, vec_pack(exp, eb_), sig, 0, 0, 0, 0, 0}); };
    const uint64_t one = bit(n_ - 1), max = vec_mask(n_);
    // w = ±0 (divide by zero), with a few exponents (the exponent of a zero is ignored).
    for (int e : {0, emin_, emax_}) add(false, e, 0);
    add(true, 0, 0);
    // Powers of two, just above and just below, at the exponent extremes (w = 2^emin overflows).
    for (int e : {0, 1, -1, emin_, emin_ + 1, emax_, emax_ - 1})
      for (uint64_t m : {one, one + 1, max, max - 1}) add(false, e, m);
    for (uint64_t m : {one, one + 1, max}) add(true, 0, m);
    add(true, emin_, one);
    add(true, emax_, max);
    // Every seed-table segment boundary: first significand of each segment and the one before.
    const int s = c_.seed_index_bits;
    for (uint64_t i = 1; i < bit(s); ++i) {
      const uint64_t m = one + (i << (n_ - 1 - s));
      add(false, 0, m - 1);
      add(false, 0, m);
    }
    return v;
  }
  // Random: 1 case in 64 is w = 0, 1 in 64 has exp = emin, 1 in 64 exp = emax, 1 in 64 an exact
  // power of two; the others: random sign, exponent uniform in [emin, emax], uniform significand.
  void random(std::mt19937_64& rng, VecRow& r) const override {
    const uint64_t sel = rng() & 63;
    r[0] = rng() & 1;
    int e = (int)vec_random_in(rng, emin_, emax_);
    r[2] = random_sig(rng, n_);
    if (sel == 0) r[2] = 0;
    if (sel == 1) e = emin_;
    if (sel == 2) e = emax_;
    if (sel == 3) r[2] = bit(n_ - 1);
    r[1] = vec_pack(e, eb_);
  }
  // Every significand at exponent 0 (the significand datapath sees nothing else: the exponent
  // path is a negation), when there are at most kMaxExhaustive.
  uint64_t exhaustive_count() const override { return bit(n_ - 1) <= kMaxExhaustive ? bit(n_ - 1) : 0; }
  void exhaustive(uint64_t i, VecRow& r) const override {
    r[0] = 0;
    r[1] = 0;
    r[2] = bit(n_ - 1) | i;
  }

 private:
  RecipConfig c_;
  RecipUnit unit_;
  int n_, o_, eb_, emin_, emax_;
  VecLayout lay_;
};

// ---- texaddr: the texture address unit (model/stages/texaddr.hpp, rtl/fxr_texaddr.sv) ---------------
// Fields: filter [1] (0 nearest, 1 bilinear), wrap [2] (repeat, mirrored_repeat, clamp_to_edge,
// clamp_to_border: the order of tex_addr.wrap), then per coordinate c ∈ {u, v}: c_neg, c_exp
// [exp_bits] (signed exponent of the significand's lsb), c_sig [sig_bits] (msb set, or 0);
// width, height [size_bits + 1] in [1, 2^size_bits]. Outputs per axis a ∈ {s (u, width), t (v,
// height)}: a_i0, a_i1 [size_bits], a_b0, a_b1 (border flags), a_w [weight_frac_bits].
// Filter and wrap are inputs (texture state), the configuration's choices the defaults of
// `fxraster render`. Model: fxr::texaddr with the row's filter and wrap.

constexpr int kTexFilterBits = 1;  // TexFilter: 2 choices
constexpr int kTexWrapBits = 2;    // TexWrap: 4 choices

class TexaddrVectors : public VectorModel {
 public:
  explicit TexaddrVectors(const Config& c) : c_(c.tex_addr) {
    n_ = c_.sig_bits;
    eb_ = c_.exp_bits;
    zb_ = c_.size_bits;
    fb_ = c_.weight_frac_bits;
    emin_ = -(1 << (eb_ - 1));
    emax_ = (1 << (eb_ - 1)) - 1;
    const std::string n = std::to_string(n_), e = std::to_string(eb_), z = std::to_string(zb_);
    std::vector<VecField> f = {
        {"filter", VecDir::In, kTexFilterBits, false, "0 nearest, 1 bilinear"},
        {"wrap", VecDir::In, kTexWrapBits, false, "0 repeat, 1 mirrored_repeat, 2 clamp_to_edge, 3 clamp_to_border"}};
    for (const char* a : {"u", "v"}) {
      const std::string p = a;
      f.push_back({p + "_neg", VecDir::In, 1, false, "sign of " + p});
      f.push_back({p + "_exp", VecDir::In, eb_, true, "signed exponent of the lsb of " + p + "_sig, " + e + " bits"});
      f.push_back({p + "_sig", VecDir::In, n_, false,
                   "unsigned significand, " + n + " bits, msb set (0 for zero): " + p + " = (-1)^neg * sig * 2^exp"});
    }
    f.push_back({"width", VecDir::In, zb_ + 1, false, "texture width in [1, 2^" + z + "]"});
    f.push_back({"height", VecDir::In, zb_ + 1, false, "texture height in [1, 2^" + z + "]"});
    for (const char* a : {"s", "t"}) {
      const std::string p = a;
      f.push_back({p + "_i0", VecDir::Out, zb_, false, "texel index (nearest: the texel; bilinear: floor(c*size - 1/2)), wrapped"});
      f.push_back({p + "_i1", VecDir::Out, zb_, false, "second texel index (i0 + 1 wrapped; nearest: = i0)"});
      f.push_back({p + "_b0", VecDir::Out, 1, false, "clamp_to_border: i0 outside the texture"});
      f.push_back({p + "_b1", VecDir::Out, 1, false, "clamp_to_border: i1 outside the texture"});
      f.push_back({p + "_w", VecDir::Out, fb_, false,
                   "weight of i1, " + std::to_string(fb_) + " fraction bits, RNE (nearest: 0)"});
    }
    lay_ = VecLayout(f);
  }
  const VecLayout& layout() const override { return lay_; }
  nlohmann::json config_json() const override {
    nlohmann::json j = unit_config_json("tex_addr", to_json_params(c_));
    // sig_bits is derived from raster.varying_out_sig_bits (model/config/validate.hpp): a
    // non-default width is recorded at its source so that the manifest reads back.
    if (c_.sig_bits != RasterConfig{}.varying_out_sig_bits) j["raster"] = {{"varying_out_sig_bits", c_.sig_bits}};
    return j;
  }
  void compute(VecRow& r) const override {
    TexAddrConfig c = c_;
    c.filter = (TexFilter)r[0];
    c.wrap = (TexWrap)r[1];
    TexAddrIn in;
    in.u = coord(r, 2);
    in.v = coord(r, 5);
    in.width = (uint32_t)r[8];
    in.height = (uint32_t)r[9];
    const TexAddrOut o = texaddr(c, in);
    size_t k = 10;
    for (const TexAxis& a : {o.s, o.t}) {
      r[k++] = a.i0;
      r[k++] = a.i1;
      r[k++] = a.border0;
      r[k++] = a.border1;
      r[k++] = a.weight;
    }
  }
  std::vector<VecRow> directed() const override {
    std::vector<VecRow> v;
    const uint64_t one = bit(n_ - 1), max = vec_mask(n_);
    const int l = -(n_ - 1);  // exponent of the lsb for a value in [1, 2)
    struct U {
      bool neg;
      int exp;
      uint64_t sig;
    };
    // 0, −0, ±1, ±½, just below 1, just below 0, ±2.25, tiny and huge magnitudes.
    const std::vector<U> us = {{false, 0, 0},       {true, 0, 0},          {false, l, one},     {true, l, one},
                               {false, l - 1, one}, {true, l - 1, one},    {false, l - 1, max}, {true, l - 30, max},
                               {false, l + 1, one + (one >> 3)}, {true, l + 1, one + (one >> 3)},
                               {false, emin_, max}, {true, emin_, one},    {false, emax_, max}, {true, emax_, one + 1},
                               {false, 0, one + 1}, {true, 1, max}};
    const uint64_t zmax = bit(zb_);
    const std::vector<uint64_t> sizes = {1, 2, 3, zmax, zmax - 1 > 0 ? zmax - 1 : 1};
    for (uint64_t fil = 0; fil < 2; ++fil)
      for (uint64_t w = 0; w < 4; ++w)
        for (size_t i = 0; i < us.size(); ++i)
          for (uint64_t sz : sizes) {
            const U& a = us[i];
            const U& b = us[(i + 5) % us.size()];
            VecRow r = blank();
            r[0] = fil;
            r[1] = w;
            set_coord(r, 2, a.neg, a.exp, a.sig);
            set_coord(r, 5, b.neg, b.exp, b.sig);
            r[8] = sz;
            r[9] = sizes[(sz + i) % sizes.size()];
            v.push_back(r);
          }
    return v;
  }
  // Random: filter and wrap uniform; per coordinate 1 in 32 zero, 1 in 32 an exponent uniform over
  // the whole field, the others a leading one in [2^−12, 2^4); sizes: 1 in 4 a power of two,
  // 1 in 4 at most 8, else uniform in [1, 2^size_bits].
  void random(std::mt19937_64& rng, VecRow& r) const override {
    r[0] = rng() & 1;
    r[1] = rng() & 3;
    for (size_t k : {2, 5}) {
      const uint64_t sel = rng() & 31;
      const bool neg = rng() & 1;
      int e = (int)vec_random_in(rng, -12, 3) - (n_ - 1);
      uint64_t sig = random_sig(rng, n_);
      if (sel == 0) sig = 0;
      if (sel == 1) e = (int)vec_random_in(rng, emin_, emax_);
      set_coord(r, k, neg, std::max(emin_, std::min(emax_, e)), sig);
    }
    for (size_t k : {8, 9}) {
      const uint64_t sel = rng() & 3;
      if (sel == 0) r[k] = bit((int)vec_random_in(rng, 0, zb_));
      else if (sel == 1) r[k] = (uint64_t)vec_random_in(rng, 1, std::min<int64_t>(8, (int64_t)bit(zb_)));
      else r[k] = (uint64_t)vec_random_in(rng, 1, (int64_t)bit(zb_));
    }
  }

 private:
  FxFloat coord(const VecRow& r, size_t k) const {
    FxFloat x;
    x.neg = r[k] != 0;
    x.exp = (int)vec_unpack_signed(r[k + 1], eb_);
    x.sig = r[k + 2];
    return x;
  }
  void set_coord(VecRow& r, size_t k, bool neg, int exp, uint64_t sig) const {
    r[k] = neg;
    r[k + 1] = vec_pack(std::max(emin_, std::min(emax_, exp)), eb_);
    r[k + 2] = sig;
  }
  TexAddrConfig c_;
  int n_, eb_, zb_, fb_, emin_, emax_;
  VecLayout lay_;
};

}  // namespace

std::vector<VectorUnitInfo> builtin_vector_units() {
  return {
      {"recip", "fxr_recip", "reciprocal unit 1/w (fxr::recip)",
       [](const Config& c) { return std::make_unique<RecipVectors>(c); },
       [](const Config& c) { return recip_cost(c.recip); }},
      {"div", "fxr_div", "per-pixel significand divider (div_sig)",
       [](const Config& c) { return std::make_unique<DivVectors>(c); },
       [](const Config& c) { return div_cost(c.div); }},
      {"texaddr", "fxr_texaddr", "texture address unit (fxr::texaddr): texel indices, border flags, bilinear weights",
       [](const Config& c) { return std::make_unique<TexaddrVectors>(c); },
       [](const Config& c) { return texaddr_cost(c.tex_addr); }},
      {"setup", "fxr_setup_fields", "triangle setup (SetupStage): edges, top-left bias, 2A, culling, bounding box, planes",
       [](const Config& c) { return make_setup_vectors(c); }, [](const Config& c) { return SetupStage::cost(c); }},
  };
}

}  // namespace fxr
