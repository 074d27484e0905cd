// Reading untrusted JSON (contracts in model/config/json_input.hpp).
#include "model/config/json_input.hpp"

#include <fstream>
#include <sstream>
#include <vector>

namespace fxr {

namespace {

using nlohmann::json;

// Longest JSON key quoted in a path (a path has at most kMaxJsonDepth components).
constexpr size_t kMaxKeyChars = 40;
// Longest parser message kept (nlohmann quotes the last token read, which may be huge).
constexpr size_t kMaxParserMessageChars = 300;

// 1-based line and column of byte offset `byte` in text.
void line_col(const std::string& text, size_t byte, size_t* line, size_t* col) {
  size_t l = 1, start = 0;
  for (size_t i = 0; i < byte && i < text.size(); ++i)
    if (text[i] == '\n') {
      ++l;
      start = i + 1;
    }
  *line = l;
  *col = byte - start + 1;
}

// Where the parser is: one level per open array / object.
struct Level {
  bool array = false;
  size_t index = 0;  // arrays: index of the element being parsed
  std::string key;   // objects: key of the member being parsed
};

std::string path_of(const std::vector<Level>& levels) {
  std::string p;
  for (const Level& l : levels) {
    if (l.array) p += "/" + std::to_string(l.index);
    else if (!l.key.empty()) p += "/" + cut(l.key, kMaxKeyChars);
  }
  return p.empty() ? "/" : p;
}

// The quoted token of nlohmann's "number overflow parsing '<token>'" message.
std::string quoted_token(const std::string& msg) {
  const size_t a = msg.find('\''), b = msg.rfind('\'');
  return a != std::string::npos && b > a ? msg.substr(a + 1, b - a - 1) : "";
}

}  // namespace

std::string cut(const std::string& s, size_t n) { return s.size() <= n ? s : s.substr(0, n) + "…"; }

json parse_json_input(const std::string& text, const std::string& where) {
  std::vector<Level> levels;
  auto next_element = [&]() {
    if (!levels.empty() && levels.back().array) ++levels.back().index;
  };
  const json::parser_callback_t cb = [&](int, json::parse_event_t ev, json& parsed) -> bool {
    switch (ev) {
      case json::parse_event_t::object_start:
      case json::parse_event_t::array_start:
        if (levels.size() >= (size_t)kMaxJsonDepth)
          throw ConfigError(where + ": " + path_of(levels) + ": JSON nesting deeper than " +
                            std::to_string(kMaxJsonDepth) + " levels");
        levels.push_back({ev == json::parse_event_t::array_start, 0, ""});
        break;
      case json::parse_event_t::key:
        levels.back().key = parsed.get<std::string>();
        break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        levels.pop_back();
        next_element();
        break;
      case json::parse_event_t::value:
        next_element();
        break;
    }
    return true;
  };
  try {
    return json::parse(text, cb);
  } catch (const json::parse_error& e) {
    size_t line = 0, col = 0;
    line_col(text, e.byte > 0 ? e.byte - 1 : 0, &line, &col);
    std::string msg = e.what();
    const auto p = msg.find("parse error");
    if (p != std::string::npos) msg = msg.substr(p);
    throw ConfigError(where + ":" + std::to_string(line) + ":" + std::to_string(col) + ": JSON " +
                      cut(msg, kMaxParserMessageChars));
  } catch (const json::out_of_range& e) {
    // 406: a number literal beyond the range of a double (e.g. 1e400).
    throw ConfigError(where + ": " + path_of(levels) + ": number '" + cut(quoted_token(e.what()), kMaxExcerptChars) +
                      "' is outside the range of a double");
  }
}

json read_json_file(const std::string& path, const std::string& what) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw ConfigError(path + ": cannot open the " + what);
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw ConfigError(path + ": cannot read the " + what);
  return parse_json_input(ss.str(), path);
}

std::string json_excerpt(const json& j) {
  // dump() recurses, but the depth of every parsed value is bounded by kMaxJsonDepth; its
  // length is not, so large containers are summarised before dumping.
  if (j.is_array() || j.is_object()) {
    const std::string kind = j.is_array() ? "array" : "object";
    if (j.empty()) return kind + " " + j.dump();
    std::string first;
    if (j.is_array()) first = json_excerpt(j.front());
    else first = "\"" + cut(j.begin().key(), kMaxKeyChars) + "\": " + json_excerpt(j.begin().value());
    return cut(kind + " of " + std::to_string(j.size()) + (j.size() == 1 ? " element" : " elements") + ", first " +
                   first,
               kMaxExcerptChars);
  }
  return cut(j.dump(), kMaxExcerptChars);
}

std::string json_typed_excerpt(const json& j) {
  if (j.is_array() || j.is_object()) return json_excerpt(j);  // the summary names the type
  return std::string(j.type_name()) + " " + json_excerpt(j);
}

int64_t json_int(const json& j, int64_t lo, int64_t hi, const std::string& what) {
  const std::string range = "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!j.is_number_integer()) throw ConfigError(what + ": expected an integer in " + range + ", got " + json_typed_excerpt(j));
  if (j.is_number_unsigned()) {
    const uint64_t u = j.get<uint64_t>();
    if (hi < 0 || u > (uint64_t)hi || (lo > 0 && u < (uint64_t)lo))
      throw ConfigError(what + ": " + std::to_string(u) + " is outside " + range);
    return (int64_t)u;
  }
  const int64_t v = j.get<int64_t>();
  if (v < lo || v > hi) throw ConfigError(what + ": " + std::to_string(v) + " is outside " + range);
  return v;
}

uint64_t json_uint(const json& j, uint64_t hi, const std::string& what) {
  const std::string range = "[0, " + std::to_string(hi) + "]";
  if (!j.is_number_integer()) throw ConfigError(what + ": expected an integer in " + range + ", got " + json_typed_excerpt(j));
  if (!j.is_number_unsigned()) throw ConfigError(what + ": " + std::to_string(j.get<int64_t>()) + " is outside " + range);
  const uint64_t u = j.get<uint64_t>();
  if (u > hi) throw ConfigError(what + ": " + std::to_string(u) + " is outside " + range);
  return u;
}

}  // namespace fxr
