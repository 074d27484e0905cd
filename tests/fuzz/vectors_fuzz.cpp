// Fuzz harness: the vector reader (manifest + hex lines, model/vectors/vectors.cpp) and the
// recheck against the model. The input is "<manifest JSON>\0<hex text>"; both are written to a
// per-process scratch folder because read_vectors takes a path. Invariants: only ConfigError for
// bad input; an accepted file has count rows of the layout's field count.
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "model/vectors/vectors.hpp"
#include "tests/fuzz/fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fxr;
  static const std::string dir = [] {
    const std::string d = std::filesystem::temp_directory_path().string() + "/fxr_vectors_fuzz_" + std::to_string(getpid());
    std::filesystem::create_directories(d);
    return d;
  }();
  const std::string all(reinterpret_cast<const char*>(data), size);
  const size_t split = all.find('\0');
  const std::string manifest = all.substr(0, split), hex = split == std::string::npos ? "" : all.substr(split + 1);
  // The manifest names its hex file; the harness always offers both candidate names.
  for (const char* unit : {"div", "recip"}) {
    std::ofstream(dir + "/" + unit + ".json", std::ios::binary) << manifest;
    std::ofstream(dir + "/" + unit + ".hex", std::ios::binary) << hex;
  }
  for (const char* unit : {"div", "recip"}) {
    fuzz::run_expecting_config_errors([&] {
      const VecFile f = read_vectors(dir + "/" + unit + ".hex", nullptr);
      fuzz::check(f.data.size() == f.rows() * f.manifest.layout.size(), "row data does not match the layout");
      fuzz::check(f.rows() == f.manifest.count, "row count differs from the manifest's");
      recheck_vectors(f, nullptr, 0);
    });
  }
  return 0;
}
