// Shared by the libFuzzer harnesses (tests/fuzz/*_fuzz.cpp, docs/testing.md "Fuzzing").
// A harness defines LLVMFuzzerTestOneInput; an expected rejection of bad input is a ConfigError
// (exit status 2 in the CLI). Anything else — another exception, a crash, a sanitizer report, a
// broken invariant — is a finding: the harness aborts with a message.
#pragma once

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "model/config/param.hpp"

namespace fxr::fuzz {

[[noreturn]] inline void finding(const std::string& what) {
  std::fprintf(stderr, "FUZZ FINDING: %s\n", what.c_str());
  std::abort();
}

inline void check(bool ok, const std::string& what) {
  if (!ok) finding(what);
}

// Runs f; a ConfigError is the documented answer to bad input, any other exception a finding.
template <class F>
bool run_expecting_config_errors(F&& f) {
  try {
    f();
    return true;
  } catch (const ConfigError& e) {
    // Bounded messages (issue 9): no input makes an error longer than about 1 kB.
    check(std::string(e.what()).size() <= 4096, "error message longer than 4 kB");
    return false;
  } catch (const std::exception& e) {
    finding(std::string("unexpected exception: ") + e.what());
  }
}

}  // namespace fxr::fuzz
