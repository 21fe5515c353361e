// A tiny strict JSON parser: just enough to read a vismap map. Numbers keep
// their source text so that the checker can insist on exact integers.
#pragma once
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace vismap_check {

struct JsonMember;

struct Json {
  enum class Type { Null, Bool, Number, String, Array, Object };
  Type type = Type::Null;
  bool boolean = false;
  std::string text;                                   // string value, or number as written
  std::vector<Json> items;                            // Array
  std::vector<JsonMember> members;                    // Object, in file order

  const Json* get(std::string_view key) const;        // nullptr if absent or not an object
  bool is(Type t) const { return type == t; }
};

struct JsonMember {
  std::string key;
  Json value;
};

struct JsonError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// Whole text must be one value (surrounding whitespace allowed). Duplicate keys
// are an error: a map with two "regions" would be ambiguous.
Json parse_json(std::string_view text);

const char* type_name(Json::Type t);

}  // namespace vismap_check
