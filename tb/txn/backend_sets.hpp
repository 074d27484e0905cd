// The committed back-end stage vectors (docs/vectors.md, "Committed back-end vectors"):
// vectors/scenes/backend_directed/ (the geometric cases) and vectors/scenes/backend_state/<depth
// function>/ (one draw state per folder), which every back-end stage's transaction test runs.
#pragma once

#include <algorithm>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace fxr::tb {

// (folder, short name for run names), the directed set first, then the draw-state sets by name.
inline std::vector<std::pair<std::string, std::string>> committed_backend_dumps() {
  const std::string root = std::string(FXR_SOURCE_DIR) + "/vectors/scenes";
  std::vector<std::pair<std::string, std::string>> v = {{root + "/backend_directed", "directed"}};
  std::vector<std::string> st;
  for (const auto& e : std::filesystem::directory_iterator(root + "/backend_state"))
    if (e.is_directory()) st.push_back(e.path().filename().string());
  std::sort(st.begin(), st.end());
  for (const auto& s : st) v.push_back({root + "/backend_state/" + s, "state_" + s});
  return v;
}

}  // namespace fxr::tb
