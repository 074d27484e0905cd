// model/config/json_input.hpp — reading untrusted JSON (configurations, scenes, vector manifests).
//
// Every JSON file fxraster reads goes through parse_json_input: syntax errors name file:line:column,
// nesting deeper than kMaxJsonDepth and numbers beyond a double's range are errors naming the
// file and the JSON path (docs/number-formats.md, "Reading input"). Values quoted in error
// messages go through json_excerpt, which is bounded (kMaxExcerptChars) however large or deep
// the value is; numbers are converted with the checked json_int / json_uint, never truncated
// or wrapped.
#pragma once

#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "model/config/param.hpp"

namespace fxr {

// Deepest nesting of arrays / objects accepted. fxraster's own files nest at most 5 levels; 64
// leaves room and keeps every recursive walk (dump, copy, compare) far from the stack limit.
inline constexpr int kMaxJsonDepth = 64;
// kMaxExcerptChars (model/config/param.hpp): longest quotation of an input value in a message.
// Longest input text quoted verbatim (file names and strings inside messages are cut too).
inline constexpr size_t kMaxQuotedChars = 200;

// Parses `text` (the contents of `where`). Throws ConfigError:
//   "<where>:<line>:<col>: JSON parse error ..."                 syntax (line / column 1-based)
//   "<where>: <path>: JSON nesting deeper than 64 levels"        depth
//   "<where>: <path>: number '1e400' is outside the range of a double"
nlohmann::json parse_json_input(const std::string& text, const std::string& where);
// Reads and parses a file; `what` names it in the error ("configuration file", "manifest").
nlohmann::json read_json_file(const std::string& path, const std::string& what);

// Bounded description of a value for error messages: scalars as JSON (strings quoted), cut to
// kMaxExcerptChars with "…"; arrays and objects as their type and size plus a cut excerpt.
// (declared in param.hpp) std::string json_excerpt(const nlohmann::json& j);
// cut(s, n): s cut to at most n bytes with "…" appended when cut (declared in param.hpp).

// Checked conversions. `what` is the message prefix naming file and field ("f.json: field 'x'").
// j must be an integer JSON number (not 1.0, not 1e3, not a string) within [lo, hi].
int64_t json_int(const nlohmann::json& j, int64_t lo, int64_t hi, const std::string& what);
uint64_t json_uint(const nlohmann::json& j, uint64_t hi, const std::string& what);

}  // namespace fxr
