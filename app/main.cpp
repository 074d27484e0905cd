// fxraster — the command line of the bit-accurate raster unit model.
#include <algorithm>
#include <cstdio>
#include <exception>
#include <fstream>
#include <iterator>
#include <iostream>
#include <map>
#include <unistd.h>

#include "command.hpp"
#include "model/config/param.hpp"

namespace fxr::app {

std::vector<Command>& registry() {
  static std::vector<Command> r;
  return r;
}

void progress(const std::string& label, uint64_t done, uint64_t total) {
  static const bool tty = isatty(fileno(stderr));
  if (total == 0) return;
  const int pct = (int)(100 * done / total);
  static int last_pct = -1;
  if (tty) {
    std::fprintf(stderr, "\r[%s] %llu/%llu (%d%%)%s", label.c_str(), (unsigned long long)done,
                 (unsigned long long)total, pct, done == total ? "\n" : "");
  } else if (pct / 10 != last_pct / 10 || done == total) {
    std::fprintf(stderr, "[%s] %llu/%llu (%d%%)\n", label.c_str(), (unsigned long long)done,
                 (unsigned long long)total, pct);
  }
  last_pct = done == total ? -1 : pct;
}

void write_file_if_changed(const std::string& path, const std::string& text) {
  {
    std::ifstream in(path, std::ios::binary);
    if (in) {
      const std::string old((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      if (old == text) return;
    }
  }
  std::ofstream out(path, std::ios::binary);
  if (!out) throw fxr::ConfigError(path + ": cannot write");
  out << text;
  if (!out) throw fxr::ConfigError(path + ": write failed");
}

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace fxr::app

int main(int argc, char** argv) {
  using namespace fxr::app;
  CLI::App app{"fxraster " FXR_VERSION
               " — bit-accurate fixed-point model of a GPU raster unit: golden vectors, "
               "co-simulation support and precision / error-budget reports."};
  app.set_version_flag("--version", std::string("fxraster ") + FXR_VERSION);
  app.require_subcommand(1);
  auto& cmds = registry();
  std::sort(cmds.begin(), cmds.end(), [](const Command& a, const Command& b) { return a.name < b.name; });
  std::map<CLI::App*, Runner> runners;
  for (auto& c : cmds) {
    CLI::App* sub = app.add_subcommand(c.name, c.help);
    runners[sub] = c.setup(*sub);
  }
  // CLI11 reports a mistyped subcommand as "A subcommand is required": name it instead.
  if (argc > 1 && argv[1][0] != '-' &&
      std::none_of(cmds.begin(), cmds.end(), [&](const Command& c) { return c.name == argv[1]; })) {
    std::cerr << "fxraster: error: unknown subcommand '" << argv[1] << "' (fxraster --help lists them)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    // --help and --version print and exit 0; every usage error (a missing or unknown option, a
    // value out of range) prints CLI11's message and exits 2, as bad input everywhere else.
    return app.exit(e) == 0 ? 0 : 2;
  }
  try {
    for (auto& [sub, run] : runners)
      if (sub->parsed()) return run();
  } catch (const fxr::ConfigError& e) {
    std::cerr << "fxraster: error: " << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "fxraster: error: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
