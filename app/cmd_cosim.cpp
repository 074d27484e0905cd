// `fxraster cosim SCENE|--default --out DIR [--wave] ...`: a scene through the model and the
// verilated RTL, every stage boundary compared, a report (docs/rtl.md, "fxraster cosim"). The
// work is done by the executable fxraster-cosim (tb/cosim/cosim_main.cpp), built with everything
// else: fxraster generates the packages the RTL is verilated with, so it cannot contain the
// verilated RTL itself. This subcommand runs it with the same arguments (`--help` included) and
// returns its exit status (0 match, 1 mismatch, 2 bad input). The executable is looked up in
// $FXRASTER_COSIM, then next to fxraster's build folder (build/tb/fxraster-cosim).
#include <cstdlib>
#include <filesystem>
#include <iostream>
#include <string>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

#include "command.hpp"

namespace fxr::app {

std::string cosim_binary() {
  if (const char* e = std::getenv("FXRASTER_COSIM")) return e;
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const std::filesystem::path p = self.parent_path().parent_path() / "tb" / "fxraster-cosim";
    if (std::filesystem::exists(p)) return p.string();
  }
  return FXR_COSIM_BINARY;
}

int run_cosim(const std::vector<std::string>& arguments) {
  const std::string bin = cosim_binary();
  if (!std::filesystem::exists(bin)) {
    std::cerr << "fxraster: error: " << bin
              << ": the co-simulation executable is not built (cmake --build build builds it; or set FXRASTER_COSIM)\n";
    return 2;
  }
  std::vector<std::string> args = {bin};
  for (const std::string& a : arguments) args.push_back(a);
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::cout.flush();
  const pid_t pid = fork();
  if (pid < 0) {
    std::cerr << "fxraster: error: fork failed\n";
    return 1;
  }
  if (pid == 0) {
    execv(bin.c_str(), argv.data());
    std::perror(("fxraster: " + bin).c_str());
    _exit(127);
  }
  int status = 0;
  if (waitpid(pid, &status, 0) < 0) return 1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : 1;
}

}  // namespace fxr::app

namespace {

fxr::app::Runner setup(CLI::App& sub) {
  sub.prefix_command();   // every argument goes to fxraster-cosim
  sub.set_help_flag();    // --help too
  return [&sub]() -> int { return fxr::app::run_cosim(sub.remaining()); };
}

fxr::app::Registrar reg("cosim",
                        "a scene through the model and the verilated RTL, stage boundaries compared: report.md / "
                        "report.json, FST and CSV of the first mismatch (exit 0 match, 1 mismatch, 2 bad input)",
                        setup);

}  // namespace
