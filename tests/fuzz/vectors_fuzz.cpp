// Fuzz harness: the vector reader (manifest + hex lines, model/vectors/vectors.cpp) and the
// recheck against the model. The input is "<manifest JSON>\0<hex text>". read_vectors takes a
// path (it has no in-memory entry point), so both parts are written to a per-process scratch
// folder and read back through the production reader. Invariants: only ConfigError for bad
// input; an accepted file has count rows of the layout's field count.
//
// Speed (docs/testing.md, "Fuzzing"): the scratch folder is on tmpfs (/dev/shm) when there is
// one — on ext4 every rewrite of a file truncates it, and closing a truncated file starts its
// writeback (auto_da_alloc), which made the kernel half of the harness's time; the old files are
// unlinked rather than truncated; and the pair is written and read once, under the name the
// manifest's text mentions (recip.hex, else div.hex). Reading the other name as well only
// reached the hex_file mismatch error after parsing the whole manifest a second time; that error
// is still reached by every manifest that names neither file.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "model/vectors/vectors.hpp"
#include "tests/fuzz/fuzz_common.hpp"

namespace {

std::string scratch_dir() {
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::path base = fs::is_directory("/dev/shm", ec) && access("/dev/shm", W_OK) == 0
                            ? fs::path("/dev/shm")
                            : fs::temp_directory_path();
  const std::string d = (base / ("fxr_vectors_fuzz_" + std::to_string(getpid()))).string();
  fs::create_directories(d);
  // Removed at a normal exit (libFuzzer's end of run; a finding aborts and leaves the files).
  static const struct Cleanup {
    std::string dir;
    ~Cleanup() {
      std::error_code ignored;
      std::filesystem::remove_all(dir, ignored);
    }
  } cleanup{d};
  return d;
}

void write_fresh(const std::string& path, const std::string& text) {
  std::remove(path.c_str());  // unlink, not truncate: no writeback of the old file
  std::ofstream out(path, std::ios::binary);
  out << text;
  if (!out.flush()) fxr::fuzz::finding("cannot write the scratch file " + path);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  using namespace fxr;
  static const std::string dir = scratch_dir();
  const std::string all(reinterpret_cast<const char*>(data), size);
  const size_t split = all.find('\0');
  const std::string manifest = all.substr(0, split), hex = split == std::string::npos ? "" : all.substr(split + 1);
  // The manifest must name its hex file (field hex_file); offer the name its text mentions.
  const std::string unit = manifest.find("recip.hex") != std::string::npos ? "recip" : "div";
  write_fresh(dir + "/" + unit + ".json", manifest);
  write_fresh(dir + "/" + unit + ".hex", hex);
  fuzz::run_expecting_config_errors([&] {
    const VecFile f = read_vectors(dir + "/" + unit + ".hex", nullptr);
    fuzz::check(f.data.size() == f.rows() * f.manifest.layout.size(), "row data does not match the layout");
    fuzz::check(f.rows() == f.manifest.count, "row count differs from the manifest's");
    recheck_vectors(f, nullptr, 0);
  });
  return 0;
}
