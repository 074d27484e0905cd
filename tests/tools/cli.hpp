// Runs the fxraster CLI from a test: exit status, stdout and stderr captured in files under
// the test's own scratch folder (build/test_cli/<name>/). Used by the tools-label tests.
#pragma once

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/wait.h>

namespace fxr::test {

inline std::string env_or(const char* name, const std::string& fallback) {
  const char* v = std::getenv(name);
  return v ? v : fallback;
}
inline std::string binary_dir() { return env_or("FXR_BINARY_DIR", "build"); }
inline std::string source_dir() { return env_or("FXR_SOURCE_DIR", "."); }
inline std::string fxraster() { return binary_dir() + "/app/fxraster"; }

inline std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
inline void write_file(const std::string& path, const std::string& text) {
  std::filesystem::create_directories(std::filesystem::path(path).parent_path());
  std::ofstream(path, std::ios::binary) << text;
}

// A clean scratch folder named after the running test.
inline std::string scratch() {
  const auto* t = ::testing::UnitTest::GetInstance()->current_test_info();
  const std::string d = binary_dir() + "/test_cli/" + t->test_suite_name() + "." + t->name();
  std::filesystem::remove_all(d);
  std::filesystem::create_directories(d);
  return d;
}

struct CliResult {
  int exit = -1;     // exit status, or 128 + signal
  std::string out, err;
};

// Runs `fxraster ARGS` (ARGS passed to /bin/sh as written) with stdout / stderr into files in dir.
inline CliResult run_cli(const std::string& dir, const std::string& args) {
  const std::string o = dir + "/stdout.txt", e = dir + "/stderr.txt";
  const std::string cmd = "'" + fxraster() + "' " + args + " > '" + o + "' 2> '" + e + "'";
  const int st = std::system(cmd.c_str());
  CliResult r;
  if (WIFEXITED(st)) r.exit = WEXITSTATUS(st);
  else if (WIFSIGNALED(st)) r.exit = 128 + WTERMSIG(st);
  r.out = read_file(o);
  r.err = read_file(e);
  return r;
}

}  // namespace fxr::test
