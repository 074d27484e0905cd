// app/out_folder.hpp — the output folder of `fxraster render` and `fxraster sweep`: a run writes
// into a temporary folder beside --out and renames it to --out only when every file is written; a
// failed run also removes the previous run's files from --out, so no output folder is ever
// mistaken for this run's (docs/reports.md, "Render output"). An existing --out is replaced only
// when it holds nothing but files the command writes (and its cache folder): a mistyped --out
// never deletes a user's files.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace fxr::app {

struct OutFolder {
  std::string command;                           // named in the refusal ("… which render does not write")
  std::function<bool(const std::string&)> owns;  // a file name the command writes
  std::string cache;  // a sub-folder carried from the previous run into the new one (and back when a
                      // run fails): sweep's synthesis cache; "" none
};

// --out as a folder path: "dir/" → "dir".
std::filesystem::path out_path(const std::string& out);

// Contract: refuses (fxr::ConfigError, before anything is written) an `out` that exists and is not
// a folder or holds a file `f` does not own; creates out's parent folder and the temporary folder
// OUT.partial-<pid> beside it (the cache moved in); returns run_into(temporary folder) after
// replacing `out` with it. When run_into throws: the previous run's files are removed from `out`
// (the folder too when that empties it), the cache is put back, the temporary folder removed, and
// the exception goes on.
int write_out_folder(const OutFolder& f, const std::filesystem::path& out,
                     const std::function<int(const std::filesystem::path& tmp)>& run_into);

}  // namespace fxr::app
