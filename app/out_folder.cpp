// app/out_folder.hpp: the output folder of render and sweep, replaced only when a run finishes.
#include "out_folder.hpp"

#include <vector>

#include <unistd.h>

#include "model/config/param.hpp"

namespace fxr::app {

namespace fs = std::filesystem;

fs::path out_path(const std::string& out) {
  fs::path p = fs::path(out).lexically_normal();
  if (!p.has_filename()) p = p.parent_path();  // "dir/" → "dir"
  return p;
}

namespace {

// Throws unless `out` is absent, or a folder holding only what the command writes.
void check_replaceable(const OutFolder& f, const fs::path& out) {
  std::error_code ec;
  if (!fs::exists(out, ec)) return;
  if (!fs::is_directory(out, ec)) throw fxr::ConfigError(out.string() + ": --out exists and is not a folder");
  for (const auto& e : fs::directory_iterator(out, ec)) {
    const std::string n = e.path().filename().string();
    if (!f.owns(n) && !(!f.cache.empty() && n == f.cache && e.is_directory()))
      throw fxr::ConfigError(out.string() + ": refusing to replace this folder: it holds '" +
                             fxr::cut(n, fxr::kMaxExcerptChars) + "', which " + f.command +
                             " does not write (give a new or an empty --out)");
  }
  if (ec) throw fxr::ConfigError(out.string() + ": cannot list the folder: " + ec.message());
}

// Removes a previous run's files from `out` (and the folder when that empties it); the cache stays.
void remove_previous(const OutFolder& f, const fs::path& out) {
  std::error_code ec;
  if (!fs::is_directory(out, ec)) return;
  std::vector<fs::path> old;
  for (const auto& e : fs::directory_iterator(out, ec))
    if (f.owns(e.path().filename().string())) old.push_back(e.path());
  for (const auto& p : old) fs::remove(p, ec);
  fs::remove(out, ec);  // only succeeds when empty
}

}  // namespace

int write_out_folder(const OutFolder& f, const fs::path& out, const std::function<int(const fs::path& tmp)>& run_into) {
  check_replaceable(f, out);  // before anything: a foreign folder is left untouched
  std::error_code ec;
  if (!out.parent_path().empty()) {
    fs::create_directories(out.parent_path(), ec);
    if (ec) throw fxr::ConfigError(out.parent_path().string() + ": cannot create the folder: " + ec.message());
  }
  const fs::path tmp = out.parent_path() / (out.filename().string() + ".partial-" + std::to_string(getpid()));
  fs::remove_all(tmp, ec);
  fs::create_directory(tmp, ec);
  if (ec) throw fxr::ConfigError(tmp.string() + ": cannot create the folder: " + ec.message());
  const bool had_cache = !f.cache.empty() && fs::is_directory(out / f.cache, ec);
  if (had_cache) fs::rename(out / f.cache, tmp / f.cache);
  try {
    const int rc = run_into(tmp);
    remove_previous(f, out);
    fs::rename(tmp, out);  // same parent folder: one rename
    return rc;
  } catch (...) {
    remove_previous(f, out);  // the previous run's files must not pass for this run's
    if (had_cache) {  // the cache goes back where it was (with what this run added to it)
      fs::create_directories(out, ec);
      fs::rename(tmp / f.cache, out / f.cache, ec);
    }
    fs::remove_all(tmp, ec);
    throw;
  }
}

}  // namespace fxr::app
