// model/vectors/vectors.hpp — golden vectors: one format for every stage boundary (docs/vectors.md).
//
// A vector file is plain hex that `$readmemh` reads in any simulator: one vector per line, the
// fields of the vector concatenated into ONE hex word (first field in the most significant
// digits), each field zero-padded to a whole number of hex digits, no `0x`, no separators, no
// comments, a newline after every line (the last one included: Verilator 5.006's $readmemh drops
// a last word without one). Beside `NAME.hex` lies the manifest `NAME.json`: the field names,
// widths, bit offsets (Verilog `word[offset +: width]`), formats and directions, the
// configuration sections the unit depends on, the seed, the generator version, the count and the
// kinds of cases (directed / random / exhaustive) with their line ranges.
//
// A stage plugs in with a VectorModel: its fields (inputs, then outputs), a function computing
// the outputs from the inputs with the bit-accurate model, and generators of directed, random and
// exhaustive cases. Everything else (writer, reader / validator, CLI, testbenches) is generic.
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "model/arith/fixed.hpp"
#include "model/arith/fxfloat.hpp"
#include "model/config/config.hpp"
#include "model/unit/stage.hpp"

namespace fxr {

// Manifest "format" and "format_version": bumped when the file layout rules change.
inline constexpr const char* kVectorFormatName = "fxraster-vectors";
inline constexpr int kVectorFormatVersion = 1;
// Manifest "generator_version": bumped whenever a generator (directed list, random draw order,
// exhaustive order) of any unit changes, so old files are recognisably different.
inline constexpr int kVectorGeneratorVersion = 1;
// A field is held in a vec_word (unsigned 128 bits): widths 1..128. Wider record fields (none
// today) would be split into named limbs by the record layout (docs/vectors.md).
using vec_word = u128;
inline constexpr int kVecMaxFieldBits = 128;
// Hex digits per field: one digit carries 4 bits.
inline constexpr int kVecBitsPerDigit = 4;

enum class VecDir : uint8_t { In, Out };

struct VecField {
  std::string name;  // the RTL port without its _i / _o suffix: in_sig, out_exp, ...
  VecDir dir = VecDir::In;
  int width = 1;           // bits, 1..kVecMaxFieldBits
  bool is_signed = false;  // two's complement in `width` bits (the padding digits stay zero)
  std::string format;      // for people: "unsigned significand, 24 bits, msb set (0 for w = 0)"
  // Derived by VecLayout::finalize():
  int digits = 0;  // ceil(width / 4)
  int offset = 0;  // bit offset of the field's lsb in the line word (lsb of the line = 0)
};

// The fields of one unit's vectors, in file order (most significant first): inputs, then outputs.
class VecLayout {
 public:
  VecLayout() = default;
  explicit VecLayout(std::vector<VecField> fields);  // computes digits and offsets; validates

  const std::vector<VecField>& fields() const { return fields_; }
  size_t size() const { return fields_.size(); }
  const VecField& operator[](size_t i) const { return fields_[i]; }
  int digits() const { return digits_; }                           // hex digits per line
  int word_bits() const { return digits_ * kVecBitsPerDigit; }    // $readmemh word width
  int index(const std::string& name) const;                       // -1 when absent
  const std::vector<int>& inputs() const { return in_; }
  const std::vector<int>& outputs() const { return out_; }

 private:
  std::vector<VecField> fields_;
  std::vector<int> in_, out_;
  int digits_ = 0;
};

// One vector: the raw bits of every field, in layout order (signed fields as two's complement
// masked to their width).
using VecRow = std::vector<vec_word>;

// Field bits <-> integers. Contract: pack keeps the low `width` bits of v (caller ensures v
// fits); unpack sign-extends bit width−1. 1 ≤ width ≤ kVecMaxFieldBits.
vec_word vec_mask(int width);
inline vec_word vec_pack(i128 v, int width) { return (vec_word)v & vec_mask(width); }
i128 vec_unpack_signed(vec_word bits, int width);

// Integer in [lo, hi] from one raw mt19937_64 word (hi − lo < 2^32; the modulo bias is < 2^−32):
// the generators' only range draw, identical on every platform (no std distributions).
inline int64_t vec_random_in(std::mt19937_64& rng, int64_t lo, int64_t hi) {
  return lo + (int64_t)((rng() >> 32) % (uint64_t)(hi - lo + 1));
}

// Hex of a row: every field (the file line), or only the inputs / outputs concatenated the same
// way (used by mismatch reports: "in=... got=... exp=...").
std::string vec_hex(const VecLayout& l, const VecRow& r);
std::string vec_hex(const VecLayout& l, const VecRow& r, VecDir dir);
// Hex of one field, ceil(width/4) digits.
std::string vec_field_hex(const VecField& f, vec_word bits);

// A unit's vectors at one configuration.
class VectorModel {
 public:
  virtual ~VectorModel() = default;
  virtual const VecLayout& layout() const = 0;
  // The configuration JSON restricted to the sections the unit depends on (a valid --config file).
  virtual nlohmann::json config_json() const = 0;
  // Fills the output fields of `row` from its input fields with the bit-accurate model.
  virtual void compute(VecRow& row) const = 0;
  // Directed corner cases (inputs only; order fixed).
  virtual std::vector<VecRow> directed() const = 0;
  // One random case (inputs only). Must use only raw rng() words and bit operations (never
  // std::*_distribution, whose output differs between standard libraries): files must be
  // identical on every platform.
  virtual void random(std::mt19937_64& rng, VecRow& row) const = 0;
  // Exhaustive sweep of the input domain (or of the part that matters, documented per unit);
  // 0 when the domain is too large to enumerate.
  virtual uint64_t exhaustive_count() const { return 0; }
  virtual void exhaustive(uint64_t i, VecRow& row) const {}
  // A new row of the right size, all zero.
  VecRow blank() const { return VecRow(layout().size(), 0); }
};

struct VectorUnitInfo {
  std::string name;        // CLI name, vectors/<name>/, tb/<name>_test.cpp
  std::string rtl_module;  // rtl/<rtl_module>.sv
  std::string doc;
  std::function<std::unique_ptr<VectorModel>(const Config&)> make;
  // The unit's cost at a configuration (latency and initiation interval drive the testbenches'
  // timing checks); empty for units without hardware.
  std::function<StageCost(const Config&)> cost;
};

// Every unit that has vectors, in a fixed order.
const std::vector<VectorUnitInfo>& vector_units();
// Adds a unit at run time (tests of the generic layer use a toy unit); replaces one of that name.
void add_vector_unit(VectorUnitInfo info);
// Throws ConfigError for an unknown unit (the message lists the known ones).
const VectorUnitInfo& vector_unit(const std::string& name);
std::unique_ptr<VectorModel> make_vector_model(const std::string& unit, const Config& cfg);

// Kinds of cases, as line ranges of a file.
struct VecCases {
  std::string kind;  // "directed", "random", "exhaustive"
  uint64_t first = 0, count = 0;
};

// Contract: calls sink(row, kind) for every vector, in file order: the directed cases, then
// either `count` random cases drawn from mt19937_64(seed) or (exhaustive) the whole sweep.
// Outputs are computed by the model. Deterministic: the same arguments give the same rows on
// every platform. Throws ConfigError when exhaustive is asked of a unit without a sweep.
std::vector<VecCases> generate_vectors(const VectorModel& m, uint64_t seed, uint64_t count,
                                       bool exhaustive,
                                       const std::function<void(const VecRow&)>& sink);

// The manifest of a vector file (everything but the rows).
struct VecManifest {
  std::string unit;
  std::string hex_file;  // file name of the hex beside the manifest
  VecLayout layout;
  nlohmann::json config;  // as VectorModel::config_json()
  uint64_t seed = 0;
  uint64_t count = 0;
  int generator_version = kVectorGeneratorVersion;
  std::vector<VecCases> cases;
};
nlohmann::json manifest_to_json(const VecManifest& m);

// Path of the manifest beside a hex file: "dir/recip.hex" -> "dir/recip.json".
std::string vec_manifest_path(const std::string& hex_path);

// Streaming writer: rows go straight to the file (exhaustive sweeps need not fit in memory).
class VecWriter {
 public:
  VecWriter(const std::string& hex_path, const VecLayout& layout);  // throws on open failure
  ~VecWriter();
  void write(const VecRow& row);
  // Writes the manifest (count and hex_file are filled in) and closes both files. `overrides`:
  // top-level manifest keys replaced or added (the transaction vectors' own format and keys).
  void finish(VecManifest manifest, const nlohmann::json& overrides = nlohmann::json::object());
  uint64_t count() const { return count_; }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  VecLayout layout_;
  std::string path_;
  uint64_t count_ = 0;
};

// Generates the unit's vectors into DIR/<unit>.hex + DIR/<unit>.json; returns the manifest.
VecManifest write_unit_vectors(const std::string& unit, const Config& cfg, uint64_t seed,
                               uint64_t count, bool exhaustive, const std::string& dir);

// Writes the given input rows (outputs recomputed by the unit's model) into DIR/<unit>.hex +
// DIR/<unit>.json, one case range of kind `kind`; `extra`: top-level manifest keys added.
VecManifest write_unit_rows(const std::string& unit, const Config& cfg, const std::vector<VecRow>& inputs,
                            const std::string& kind, const std::string& dir,
                            const nlohmann::json& extra = nlohmann::json::object());

// Input rows of the texaddr unit for fragments' texture coordinates (u, v: the divider's FxFloat
// outputs) on a width × height texture: every fragment under each filter (nearest, bilinear) and
// wrap mode (repeat, mirrored_repeat, clamp_to_edge, clamp_to_border): 8 consecutive rows per
// fragment, filter-major, in fragment order (so every prefix of 8k rows holds every mode). ConfigError when a coordinate or the size does not
// fit the unit's input fields.
std::vector<VecRow> texaddr_fragment_rows(const Config& cfg, const std::vector<std::array<FxFloat, 2>>& uv,
                                          uint32_t width, uint32_t height);

// A vector file in memory, rows stored flat (row i, field f at data[i·nfields + f]).
struct VecFile {
  VecManifest manifest;
  std::vector<vec_word> data;
  std::string hex_path;
  size_t rows() const { return manifest.layout.size() ? data.size() / manifest.layout.size() : 0; }
  VecRow row(size_t i) const;
  vec_word at(size_t i, size_t f) const { return data[i * manifest.layout.size() + f]; }
};

// Reads and validates a hex file and its manifest. Errors (ConfigError) name the file, the line
// and the field: manifest missing / not JSON / wrong format or version / unknown unit / layout
// different from the one the model gives for the manifest's configuration; hex line with the wrong
// number of digits (wrong field count or width), bad hex digit, a value wider than its field,
// CR line ends, missing final newline, fewer or more lines than the manifest's count (truncated).
// With `expect`, the manifest's configuration must equal expect's sections for the unit
// (manifest/config mismatch: the error names the first differing parameter).
VecFile read_vectors(const std::string& hex_path, const Config* expect = nullptr);

// Reads the hex lines of a vector file laid out as `lay` into `data` (row-major, appended): the
// line checks of read_vectors (digit count, lowercase hex digits, values within their widths,
// LF line ends, final newline, exactly `count` lines), errors naming file:line and field.
void read_vec_hex(const std::string& hex_path, const VecLayout& lay, uint64_t count, std::vector<vec_word>& data);

// Recomputes every output with the model at the manifest's configuration; returns the number of
// rows whose outputs differ and fills `first` with up to `max_report` lines describing them.
uint64_t recheck_vectors(const VecFile& f, std::vector<std::string>* first = nullptr,
                         size_t max_report = 20);

}  // namespace fxr
