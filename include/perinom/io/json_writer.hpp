#pragma once
/// @file A tiny JSON value builder for summary files (no external JSON library).
#include <string>
#include <vector>

namespace perinom::io {

/// A JSON value: null, bool, number, string, array or object. Objects keep their
/// members in insertion order, so summaries read in the order they were built.
/// Build-only: numbers are formatted when the value is made (integers exactly,
/// doubles in the shortest form that reads back bit for bit, NaN and Inf as null).
///
///     Json s = Json::object();
///     s["particles"] = n;
///     s["errors"]["l2"] = 1.2e-4;
///     write_json_file("out/summary.json", s);
class Json {
 public:
  Json();  ///< null
  Json(bool value);
  Json(double value);
  Json(int value);
  Json(long value);
  Json(long long value);
  Json(unsigned value);
  Json(unsigned long value);
  Json(unsigned long long value);
  Json(const char* value);  ///< a string; without it a literal would turn into a bool
  Json(std::string value);

  static Json object();  ///< {}
  static Json array();   ///< []

  /// The member `key` of an object, created as null if absent; a null value becomes an object.
  /// @throws std::logic_error if the value is neither null nor an object.
  Json& operator[](const std::string& key);

  /// Appends to an array; a null value becomes an array.
  /// @throws std::logic_error if the value is neither null nor an array.
  void push_back(Json value);

  /// The JSON text. indent >= 0: one member or element per line, indented by `indent`
  /// spaces per level; indent < 0: a single line. No trailing newline.
  std::string dump(int indent = 2) const;

 private:
  enum class Kind { Null, Bool, Number, String, Array, Object };
  const char* kind_name() const;
  void dump_to(std::string& out, int indent, int depth) const;

  Kind kind_ = Kind::Null;
  std::string text_;           ///< a number's JSON text, or a string's (unescaped) value
  bool boolean_ = false;
  std::vector<std::string> keys_;  ///< object member names, parallel to items_
  std::vector<Json> items_;        ///< array elements or object member values
};

/// Writes json.dump() and a newline to path via path + ".tmp" and a rename.
/// @throws perinom::InputError naming the path if it cannot be written.
void write_json_file(const std::string& path, const Json& json);

}  // namespace perinom::io
