// app/command.hpp — subcommand registry of the `fxraster` CLI.
//
// Each app/cmd_<name>.cpp defines one subcommand and registers it with a static
//   static fxr::app::Registrar reg("name", "one-line help", setup_fn);
// where setup_fn(CLI::App& sub) adds options and returns the function to run (exit code).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

namespace fxr::app {

using Runner = std::function<int()>;
using Setup = std::function<Runner(CLI::App&)>;

struct Command {
  std::string name, help;
  Setup setup;
};

std::vector<Command>& registry();

struct Registrar {
  Registrar(std::string name, std::string help, Setup setup) {
    registry().push_back({std::move(name), std::move(help), std::move(setup)});
  }
};

// Prints "[label] done/total (pct%)" on one line of stderr, rewritten in place; silent when
// stderr is not a terminal except for every 10 %.
void progress(const std::string& label, uint64_t done, uint64_t total);

// The co-simulation executable (tb/cosim/cosim_main.cpp; app/cmd_cosim.cpp): its path
// ($FXRASTER_COSIM, else build/tb/fxraster-cosim), and a run of it with `arguments` (its exit
// status: 0 match, 1 mismatch, 2 bad input or not built).
std::string cosim_binary();

// Writes `text` to `path` only when the file's content differs (throws fxr::ConfigError naming the
// path when it cannot write). The build's generated packages go through it: an unchanged package
// keeps its time stamp, so a new fxraster binary does not re-verilate every RTL model.
void write_file_if_changed(const std::string& path, const std::string& text);
int run_cosim(const std::vector<std::string>& arguments);

// `s` as one word of a /bin/sh command line: in single quotes, each ' written '\''.
std::string quote(const std::string& s);

}  // namespace fxr::app
