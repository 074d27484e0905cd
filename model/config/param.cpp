#include "model/config/param.hpp"

#include "model/config/json_input.hpp"

#include <algorithm>
#include <cctype>

namespace fxr {

std::string camel_case(const std::string& snake) {
  std::string out;
  bool up = true;
  for (char c : snake) {
    if (c == '_') {
      up = true;
      continue;
    }
    out += up ? (char)std::toupper((unsigned char)c) : c;
    up = false;
  }
  return out;
}

void JsonReader::integer(const char* name, int& value, int lo, int hi, const char*) {
  seen.emplace_back(name);
  if (!in.contains(name)) return;
  // Checked: a non-integer, a fraction or a value beyond [lo, hi] (however large) is an error.
  value = (int)json_int(in.at(name), lo, hi, where + ": field '" + name + "'");
}

void JsonReader::reject_unknown() const {
  for (auto it = in.begin(); it != in.end(); ++it) {
    if (std::find(seen.begin(), seen.end(), it.key()) == seen.end()) {
      std::string known;
      for (const auto& s : seen) known += (known.empty() ? "" : ", ") + s;
      throw ConfigError(where + ": unknown field '" + cut(it.key(), kMaxExcerptChars) + "' (known: " + known + ")");
    }
  }
}

// "RecipMul" → "recip_mul" (for the SystemVerilog enum type name).
static std::string snake_case(const std::string& camel) {
  std::string r;
  for (char c : camel) {
    if (c >= 'A' && c <= 'Z') {
      if (!r.empty()) r += '_';
      r += (char)(c - 'A' + 'a');
    } else {
      r += c;
    }
  }
  return r;
}

void emit_sv_params(std::ostream& os, const std::string& prefix, const std::vector<ParamRow>& rows) {
  for (const auto& r : rows) {
    const std::string name = prefix + camel_case(r.name);
    if (r.choices.empty()) {
      os << "  localparam int " << name << " = " << r.value << ";  // " << r.doc << "\n";
      continue;
    }
    // A choice: its names as a typedef enum (<Prefix><Param><Choice>), the parameter as an int
    // holding one of them (Icarus 11 cannot have enum-typed parameters; the RTL compares with
    // the enumerators, never with bare integers).
    const std::string type = snake_case(name) + "_e";
    os << "  typedef enum int {";
    for (size_t i = 0; i < r.choices.size(); ++i)
      os << (i ? ", " : " ") << name << camel_case(r.choices[i]) << " = " << i;
    os << " } " << type << ";\n";
    os << "  localparam int " << name << " = " << name << camel_case(r.choices[(size_t)r.value]) << ";  // "
       << r.doc << " (" << type << ")\n";
  }
}

void emit_md_params(std::ostream& os, const std::vector<ParamRow>& rows) {
  os << "| parameter | default | range | meaning |\n|---|---|---|---|\n";
  for (const auto& r : rows) {
    os << "| `" << r.name << "` | " << r.text << " | ";
    if (r.choices.empty()) {
      os << r.lo << " … " << r.hi;
    } else {
      for (size_t i = 0; i < r.choices.size(); ++i) os << (i ? ", " : "") << r.choices[i];
    }
    os << " | " << r.doc << " |\n";
  }
}

}  // namespace fxr
