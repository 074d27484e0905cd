// The golden-vector format (docs/vectors.md): layout, writer, reader / validator errors, and that
// the committed vectors under vectors/ are exactly what the generator produces today.
#include <gtest/gtest.h>

#include <climits>
#include <cstdlib>
#include <unistd.h>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "model/vectors/vectors.hpp"

using namespace fxr;
namespace fs = std::filesystem;

namespace {

// A toy unit for the generic layer: s = a + b, a unsigned (raster.subpixel_bits wide, so the
// layout depends on the configuration), b signed 7 bits; outputs s (signed, a + 8 bits) and
// neg (s < 0). The expected values below are computed by hand from the format rules.
constexpr int kToyBBits = 7;
// Characters per line at the default configuration: 9 hex digits + newline.
constexpr size_t kLine = 10;

class ToyAdd : public VectorModel {
 public:
  explicit ToyAdd(const Config& c) : cfg_(c.raster) {
    const int a = cfg_.subpixel_bits;
    lay_ = VecLayout({{"in_a", VecDir::In, a, false, "unsigned"},
                      {"in_b", VecDir::In, kToyBBits, true, "signed"},
                      {"out_s", VecDir::Out, a + kToyBBits + 1, true, "signed a + b"},
                      {"out_neg", VecDir::Out, 1, false, "s < 0"}});
  }
  const VecLayout& layout() const override { return lay_; }
  nlohmann::json config_json() const override {
    return {{"version", kConfigFormatVersion}, {"raster", to_json_params(cfg_)}};
  }
  void compute(VecRow& r) const override {
    const int64_t s = (int64_t)r[0] + vec_unpack_signed(r[1], kToyBBits);
    r[2] = vec_pack(s, lay_[2].width);
    r[3] = s < 0;
  }
  std::vector<VecRow> directed() const override {
    return {{0, 0, 0, 0}, {vec_mask(lay_[0].width), vec_pack(-64, kToyBBits), 0, 0}};
  }
  void random(std::mt19937_64& rng, VecRow& r) const override {
    r[0] = rng() & vec_mask(lay_[0].width);
    r[1] = rng() & vec_mask(kToyBBits);
  }
  uint64_t exhaustive_count() const override { return 1ull << (lay_[0].width + kToyBBits); }
  void exhaustive(uint64_t i, VecRow& r) const override {
    r[0] = i >> kToyBBits;
    r[1] = i & vec_mask(kToyBBits);
  }

 private:
  RasterConfig cfg_;
  VecLayout lay_;
};

struct ToyRegistered {
  ToyRegistered() {
    add_vector_unit({"toy_add", "none", "test unit", [](const Config& c) { return std::make_unique<ToyAdd>(c); }, {}});
  }
};
const ToyRegistered toy_registered;

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
// 0 when equal, else the 1-based number of the first line that differs.
size_t first_different_line(const std::string& a, const std::string& b) {
  if (a == b) return 0;
  size_t line = 1;
  for (size_t i = 0; i < std::min(a.size(), b.size()) && a[i] == b[i]; ++i) line += a[i] == '\n';
  return line;
}
void spit(const std::string& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

class VectorsFile : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("fxr_vectors_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::create_directories(dir_);
    man_ = write_unit_vectors("toy_add", cfg_, 7, 20, false, dir_.string());
    hex_ = (dir_ / "toy_add.hex").string();
    json_ = (dir_ / "toy_add.json").string();
  }
  void TearDown() override { fs::remove_all(dir_); }
  // Asserts that reading fails with a ConfigError whose message contains every piece.
  void expect_error(std::initializer_list<std::string> pieces, const Config* expect = nullptr) {
    try {
      read_vectors(hex_, expect);
      ADD_FAILURE() << "no error";
    } catch (const ConfigError& e) {
      for (const auto& p : pieces) EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    }
  }
  Config cfg_;
  fs::path dir_;
  VecManifest man_;
  std::string hex_, json_;
};

}  // namespace

TEST(VectorsLayout, FieldsArePaddedToWholeDigitsMsbFirst) {
  Config cfg;
  cfg.raster.subpixel_bits = 5;  // in_a: 5 bits -> 2 digits; in_b 7 -> 2; out_s 13 -> 4; out_neg 1 -> 1
  ToyAdd t(cfg);
  const auto& l = t.layout();
  EXPECT_EQ(l.digits(), 9);
  EXPECT_EQ(l.word_bits(), 36);
  EXPECT_EQ(l[3].offset, 0);
  EXPECT_EQ(l[2].offset, 4);
  EXPECT_EQ(l[1].offset, 20);
  EXPECT_EQ(l[0].offset, 28);
  // a = 0x1f, b = −3 (0x7d in 7 bits), s = 28 (0x1c), neg 0.
  VecRow r{0x1f, vec_pack(-3, kToyBBits), 0, 0};
  t.compute(r);
  EXPECT_EQ(vec_hex(l, r), "1f7d001c0");
  EXPECT_EQ(vec_hex(l, r, VecDir::In), "1f7d");
  EXPECT_EQ(vec_hex(l, r, VecDir::Out), "001c0");
}

TEST(VectorsLayout, SignedFieldsRoundTripThroughTheirWidth) {
  for (int w : {1, 2, 7, 33, 63, 64}) {
    const int64_t lo = w == 64 ? INT64_MIN : -(int64_t(1) << (w - 1));
    const int64_t hi = w == 64 ? INT64_MAX : (int64_t(1) << (w - 1)) - 1;
    for (int64_t v : {int64_t(0), int64_t(-1), lo, hi}) EXPECT_EQ(vec_unpack_signed(vec_pack(v, w), w), v) << w;
  }
  EXPECT_EQ(vec_unpack_signed(0x40, 7), -64);
  EXPECT_EQ(vec_unpack_signed(0x3f, 7), 63);
  // Fields wider than 64 bits (plane sums of the transaction vectors), up to kVecMaxFieldBits.
  for (int w : {65, 100, 125, kVecMaxFieldBits}) {
    const i128 hi = (i128)(((u128)1 << (w - 1)) - 1), lo = -hi - 1;
    for (i128 v : {(i128)0, (i128)-1, lo, hi, (i128)INT64_MIN - 1}) {
      const bool same = vec_unpack_signed(vec_pack(v, w), w) == v;
      EXPECT_TRUE(same) << w;
    }
  }
  // Hex of a wide field: ceil(w / 4) digits, two's complement: −1 in 125 bits is 1 followed by 31 f.
  const VecField f{"wide", VecDir::In, 125, true, ""};
  const VecLayout l({f});
  EXPECT_EQ(vec_field_hex(l[0], vec_pack(-1, 125)), "1" + std::string(31, 'f'));
}

TEST(VectorsLayout, OutputsMustFollowInputs) {
  EXPECT_THROW(VecLayout({{"o", VecDir::Out, 3, false, ""}, {"i", VecDir::In, 3, false, ""}}), ConfigError);
  EXPECT_THROW(VecLayout({{"i", VecDir::In, kVecMaxFieldBits + 1, false, ""}}), ConfigError);
  EXPECT_THROW(VecLayout({{"i", VecDir::In, 0, false, ""}}), ConfigError);
}

TEST(VectorsGenerate, SameSeedSameFileOtherSeedOtherFile) {
  Config cfg;
  ToyAdd t(cfg);
  auto collect = [&](uint64_t seed) {
    std::string s;
    generate_vectors(t, seed, 100, false, [&](const VecRow& r) { s += vec_hex(t.layout(), r) + "\n"; });
    return s;
  };
  EXPECT_EQ(collect(3), collect(3));
  EXPECT_NE(collect(3), collect(4));
}

TEST(VectorsGenerate, ExhaustiveCoversEveryInputOnce) {
  Config cfg;
  cfg.raster.subpixel_bits = 3;
  ToyAdd t(cfg);
  std::vector<int> seen(1 << (3 + kToyBBits), 0);
  const size_t n_directed = t.directed().size();
  size_t line = 0;
  const auto cases = generate_vectors(t, 0, 0, true, [&](const VecRow& r) {
    const int64_t s = (int64_t)r[0] + vec_unpack_signed(r[1], kToyBBits);
    EXPECT_EQ(vec_unpack_signed(r[2], 3 + kToyBBits + 1), s);  // exact sum, independent of compute()
    if (line++ >= n_directed) seen[(size_t)((r[0] << kToyBBits) | r[1])]++;
  });
  ASSERT_EQ(cases.size(), 2u);
  EXPECT_EQ(cases[1].kind, "exhaustive");
  EXPECT_EQ(cases[1].count, seen.size());
  for (size_t i = 0; i < seen.size(); ++i) EXPECT_EQ(seen[i], 1) << i;
}

TEST_F(VectorsFile, WrittenFileReadsBackWithItsManifest) {
  const VecFile f = read_vectors(hex_);
  EXPECT_EQ(f.rows(), 22u);  // 2 directed + 20 random
  EXPECT_EQ(f.manifest.unit, "toy_add");
  EXPECT_EQ(f.manifest.seed, 7u);
  ASSERT_EQ(f.manifest.cases.size(), 2u);
  EXPECT_EQ(f.manifest.cases[1].first, 2u);
  EXPECT_EQ(recheck_vectors(f), 0u);
  const std::string text = slurp(hex_);
  EXPECT_EQ(text.back(), '\n');
  // Default subpixel_bits 8: a 2 digits, b 2, s (16 bits) 4, neg 1. Line 2: a = ff, b = −64.
  EXPECT_EQ(text.substr(kLine, kLine), "ff4000bf0\n");
}

TEST_F(VectorsFile, TruncatedFileIsAnError) {
  std::string t = slurp(hex_);
  t.resize(t.size() - kLine);  // drop the last line whole
  spit(hex_, t);
  expect_error({"toy_add.hex", "21 lines", "22", "truncated"});
}

TEST_F(VectorsFile, MissingFinalNewlineIsAnError) {
  std::string t = slurp(hex_);
  t.pop_back();
  spit(hex_, t);
  expect_error({"toy_add.hex:22", "trailing newline"});
}

TEST_F(VectorsFile, WrongDigitCountNamesTheLine) {
  std::string t = slurp(hex_);
  t.insert(kLine * 4, "0");  // line 5 one digit longer
  spit(hex_, t);
  expect_error({"toy_add.hex:5", "10 hex digits, expected 9"});
}

TEST_F(VectorsFile, BadHexNamesLineAndField) {
  std::string t = slurp(hex_);
  t[kLine * 2 + 3] = 'g';  // line 3, second digit of in_b
  spit(hex_, t);
  expect_error({"toy_add.hex:3", "field 'in_b'", "bad hex digit 'g'"});
}

TEST_F(VectorsFile, ValueWiderThanItsFieldIsAnError) {
  std::string t = slurp(hex_);
  t[kLine * 3 + 8] = '2';  // line 4: out_neg (1 bit) = 2
  spit(hex_, t);
  expect_error({"toy_add.hex:4", "field 'out_neg'", "does not fit its 1 bits"});
}

TEST_F(VectorsFile, CrLineEndsAreAnError) {
  std::string t = slurp(hex_);
  t.insert(kLine - 1, "\r");
  spit(hex_, t);
  expect_error({"toy_add.hex:1", "CR"});
}

TEST_F(VectorsFile, UnsupportedVersionIsAnError) {
  auto j = nlohmann::json::parse(slurp(json_));
  j["format_version"] = kVectorFormatVersion + 1;
  spit(json_, j.dump());
  expect_error({"toy_add.json", "format_version", "not supported"});
}

TEST_F(VectorsFile, ManifestFieldWidthDifferentFromTheConfigurationIsAnError) {
  auto j = nlohmann::json::parse(slurp(json_));
  j["fields"][0]["width"] = 9;
  spit(json_, j.dump());
  expect_error({"toy_add.json", "field 'in_a'", "width 9", "gives 8"});
}

TEST_F(VectorsFile, ManifestConfigurationDifferentFromTheExpectedIsAnError) {
  Config other;
  other.raster.subpixel_bits = 4;
  expect_error({"toy_add.json", "does not match", "raster.subpixel_bits"}, &other);
  EXPECT_NO_THROW(read_vectors(hex_, &cfg_));
}

TEST_F(VectorsFile, WrongCountInManifestIsAnError) {
  auto j = nlohmann::json::parse(slurp(json_));
  j["count"] = 21;
  spit(json_, j.dump());
  expect_error({"toy_add.json", "cases"});
}

TEST_F(VectorsFile, AbsurdCountInManifestIsAnErrorNotACrash) {
  auto j = nlohmann::json::parse(slurp(json_));
  j["count"] = uint64_t(1) << 62;
  j["cases"][1]["count"] = (uint64_t(1) << 62) - 2;
  spit(json_, j.dump());
  expect_error({"toy_add.hex", "22 lines", "truncated"});
}

TEST_F(VectorsFile, StaleOutputIsFoundByRecomputation) {
  std::string t = slurp(hex_);
  t[kLine * 6 + 7] = t[kLine * 6 + 7] == '0' ? '1' : '0';  // line 7: lowest digit of out_s
  spit(hex_, t);
  const VecFile f = read_vectors(hex_);
  std::vector<std::string> lines;
  EXPECT_EQ(recheck_vectors(f, &lines), 1u);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_NE(lines[0].find("toy_add.hex:7"), std::string::npos) << lines[0];
}

TEST(VectorsUnits, UnknownUnitIsAnErrorListingTheKnownOnes) {
  try {
    vector_unit("nope");
    ADD_FAILURE();
  } catch (const ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("toy_add"), std::string::npos);
  }
}

// The committed sets under vectors/<unit>/ must be exactly what the generator writes today for
// the default configuration: regenerate with the manifest's seed and counts and compare bytes.
TEST(VectorsCommitted, RegeneratingGivesIdenticalFiles) {
  const char* src = std::getenv("FXR_SOURCE_DIR");
  const fs::path root = fs::path(src ? src : ".") / "vectors";
  ASSERT_TRUE(fs::is_directory(root)) << root;
  int checked = 0;
  for (const auto& u : vector_units()) {
    const fs::path hex = root / u.name / (u.name + ".hex");
    if (!fs::exists(hex)) continue;
    ++checked;
    const VecFile f = read_vectors(hex.string(), nullptr);
    uint64_t random = 0;
    bool exhaustive = false;
    for (const auto& c : f.manifest.cases) {
      if (c.kind == "random") random = c.count;
      if (c.kind == "exhaustive") exhaustive = true;
    }
    const fs::path tmp = fs::temp_directory_path() / ("fxr_vectors_regen_" + std::to_string(::getpid()));
    fs::create_directories(tmp);
    write_unit_vectors(u.name, Config{}, f.manifest.seed, random, exhaustive, tmp.string());
    const std::string how = "regenerate with: build/app/fxraster vectors " + u.name + " --seed " +
                            std::to_string(f.manifest.seed) + (exhaustive ? " --exhaustive" : " --count " + std::to_string(random)) +
                            " --out vectors/" + u.name;
    EXPECT_EQ(first_different_line(slurp((tmp / (u.name + ".hex")).string()), slurp(hex.string())), 0u)
        << u.name << ".hex is stale; " << how;
    EXPECT_EQ(first_different_line(slurp((tmp / (u.name + ".json")).string()),
                                   slurp(fs::path(hex).replace_extension(".json").string())), 0u)
        << u.name << ".json is stale; " << how;
    fs::remove_all(tmp);
  }
  EXPECT_GE(checked, 1);
}
