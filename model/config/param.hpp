// model/config/param.hpp — the one mechanism through which every configuration parameter is named.
//
// A unit's configuration struct lists its parameters exactly once, in a member template
//
//     template <class V> void visit(V& v) {
//       v.integer("seed_index_bits", seed_index_bits, 2, 14, "log2 of the seed table entries");
//       v.choice("algorithm", algorithm, {"recip_mul", "radix2"}, "divider algorithm");
//     }
//
// and every consumer is a visitor: JSON load (with errors naming the field) and save, the
// SystemVerilog parameter package for the RTL, the Markdown table in docs/, and the vector
// manifests. No parameter is written down twice.
#pragma once

#include <cstdint>
#include <initializer_list>
#include <ostream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace fxr {

// Error in a configuration or input file; what() names the file, line / path and field.
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Bounded quotations of input in messages (model/config/json_input.cpp).
inline constexpr size_t kMaxExcerptChars = 80;
std::string json_excerpt(const nlohmann::json& j);        // value only: 2, "x", array of 3 elements, …
std::string json_typed_excerpt(const nlohmann::json& j);  // with the type: number 2, string "x", …
std::string cut(const std::string& s, size_t n);

// "seed_index_bits" -> "SeedIndexBits" (the RTL's UpperCamelCase parameter name).
std::string camel_case(const std::string& snake);

// --- visitors -------------------------------------------------------------------------------

// Writes every parameter into a JSON object.
struct JsonWriter {
  nlohmann::json& out;
  void integer(const char* name, int& value, int, int, const char*) { out[name] = value; }
  template <class E>
  void choice(const char* name, E& value, std::initializer_list<const char*> names, const char*) {
    out[name] = *(names.begin() + static_cast<int>(value));
  }
};

// Reads parameters from a JSON object. Unknown keys, wrong types and out-of-range values
// throw ConfigError naming `where` (file and JSON path) and the field.
struct JsonReader {
  const nlohmann::json& in;
  std::string where;
  std::vector<std::string> seen;

  void integer(const char* name, int& value, int lo, int hi, const char*);
  template <class E>
  void choice(const char* name, E& value, std::initializer_list<const char*> names, const char*) {
    seen.emplace_back(name);
    if (!in.contains(name)) return;
    const auto& j = in.at(name);
    if (!j.is_string())
      throw ConfigError(where + ": field '" + name + "': expected a string, got " + json_typed_excerpt(j));
    int i = 0;
    std::string allowed;
    for (const char* n : names) {
      if (j.get<std::string>() == n) {
        value = static_cast<E>(i);
        return;
      }
      allowed += (i ? ", " : "") + std::string(n);
      ++i;
    }
    throw ConfigError(where + ": field '" + name + "': '" + cut(j.get<std::string>(), kMaxExcerptChars) +
                      "' is not one of: " + allowed);
  }
  // After visiting: any key not visited is an error (a misspelt parameter must not be ignored).
  void reject_unknown() const;
};

// One row per parameter, for docs tables, manifests and the SV package.
struct ParamRow {
  std::string name;   // snake_case, as in JSON
  int value = 0;      // integer value (index for choices)
  std::string text;   // value as written in JSON (the choice name for choices)
  int lo = 0, hi = 0; // allowed range (choices: 0 .. count−1)
  std::string doc;
  std::vector<std::string> choices;  // empty for integers
};

struct RowCollector {
  std::vector<ParamRow>& rows;
  void integer(const char* name, int& value, int lo, int hi, const char* doc) {
    rows.push_back({name, value, std::to_string(value), lo, hi, doc, {}});
  }
  template <class E>
  void choice(const char* name, E& value, std::initializer_list<const char*> names, const char* doc) {
    ParamRow r{name, static_cast<int>(value), *(names.begin() + static_cast<int>(value)), 0,
               static_cast<int>(names.size()) - 1, doc, {}};
    for (const char* n : names) r.choices.emplace_back(n);
    rows.push_back(r);
  }
};

template <class Cfg>
std::vector<ParamRow> param_rows(const Cfg& cfg) {
  std::vector<ParamRow> rows;
  RowCollector c{rows};
  const_cast<Cfg&>(cfg).visit(c);  // visit does not modify through RowCollector
  return rows;
}

template <class Cfg>
nlohmann::json to_json_params(const Cfg& cfg) {
  nlohmann::json j = nlohmann::json::object();
  JsonWriter w{j};
  const_cast<Cfg&>(cfg).visit(w);
  return j;
}

// Overrides fields of cfg from JSON object j; throws ConfigError naming `where` and the field.
template <class Cfg>
void from_json_params(const nlohmann::json& j, Cfg& cfg, const std::string& where) {
  if (!j.is_object()) throw ConfigError(where + ": expected a JSON object, got " + json_typed_excerpt(j));
  JsonReader r{j, where, {}};
  cfg.visit(r);
  r.reject_unknown();
}

// ---- equality and hashing from visit() ------------------------------------------------------
// Every unit configuration compares and hashes through its visit(): a parameter added to visit()
// is compared and hashed without touching these (no field list written a second time).

// Upper bound on the parameters of one unit (static storage for the collector below).
inline constexpr int kMaxUnitParams = 32;

// Collects every parameter's value in visit() order (choices as their index); no allocation.
struct ValueCollector {
  int values[kMaxUnitParams] = {};
  int n = 0;
  void put(int v) {
    if (n == kMaxUnitParams) throw std::logic_error("ValueCollector: more than kMaxUnitParams parameters");
    values[n++] = v;
  }
  void integer(const char*, int& value, int, int, const char*) { put(value); }
  template <class E>
  void choice(const char*, E& value, std::initializer_list<const char*>, const char*) {
    put(static_cast<int>(value));
  }
};

template <class Cfg>
ValueCollector param_values(const Cfg& cfg) {
  ValueCollector c;
  const_cast<Cfg&>(cfg).visit(c);  // visit does not modify through ValueCollector
  return c;
}

// True when every parameter listed by visit() is equal.
template <class Cfg>
bool params_equal(const Cfg& a, const Cfg& b) {
  const ValueCollector va = param_values(a), vb = param_values(b);
  if (va.n != vb.n) return false;
  for (int i = 0; i < va.n; ++i)
    if (va.values[i] != vb.values[i]) return false;
  return true;
}

// FNV-1a (64-bit) over the parameter values in visit() order: deterministic on every platform.
inline uint64_t fnv1a_ints(uint64_t h, const int* v, int n) {
  constexpr uint64_t kFnvPrime = 0x100000001b3ull;
  constexpr int kByteBits = 8;
  constexpr uint32_t kByteMask = 0xffu;
  for (int i = 0; i < n; ++i) {
    const uint32_t u = static_cast<uint32_t>(v[i]);
    for (int byte = 0; byte < (int)sizeof(u); ++byte) {
      h ^= (u >> (kByteBits * byte)) & kByteMask;
      h *= kFnvPrime;
    }
  }
  return h;
}
inline constexpr uint64_t kFnvOffsetBasis = 0xcbf29ce484222325ull;

template <class Cfg>
uint64_t params_hash(const Cfg& cfg) {
  const ValueCollector v = param_values(cfg);
  return fnv1a_ints(kFnvOffsetBasis, v.values, v.n);
}

// Hash functor for unordered containers keyed by a unit configuration.
struct ParamsHash {
  template <class Cfg>
  size_t operator()(const Cfg& c) const {
    return static_cast<size_t>(params_hash(c));
  }
};

// SystemVerilog localparams `localparam int <Prefix><CamelName> = <value>;` with the doc as
// a comment (choices are emitted as their index, with the names in the comment).
void emit_sv_params(std::ostream& os, const std::string& prefix, const std::vector<ParamRow>& rows);

// Markdown table: | parameter | value | range | meaning |
void emit_md_params(std::ostream& os, const std::vector<ParamRow>& rows);

}  // namespace fxr
