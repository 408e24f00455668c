#include <stiffsoft/scene/scene_text.hpp>

#include <cmath>
#include <optional>
#include <set>
#include <vector>

#include <stiffsoft/libfem/format_number.hpp>
#include <stiffsoft/scene/printable.hpp>
#include <stiffsoft/scene/scene_schema.hpp>

namespace stiffsoft {

namespace {

using Json = nlohmann::ordered_json;

// nlohmann reports the byte offset of a syntax error; people want line and column.
std::string syntax_location(const std::string& text, std::size_t byte) {
  const std::size_t end = std::min(text.size(), byte > 0 ? byte - 1 : 0);
  std::size_t line = 1, column = 1;
  for (std::size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') {
      ++line;
      column = 1;
    } else {
      ++column;
    }
  }
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// The part of nlohmann's message after its own location prefix.
std::string syntax_reason(const std::string& what) {
  const std::size_t column = what.find("column ");
  if (column != std::string::npos) {
    const std::size_t colon = what.find(": ", column);
    if (colon != std::string::npos) return what.substr(colon + 2);
  }
  return what;
}

/// A first pass over the text (nlohmann's SAX interface) that builds nothing and stops at the
/// first problem, knowing the JSON path of every value: the DOM parser reports a number overflow
/// without any position, and keeps one copy of a duplicated key without a word.
class TextChecker : public nlohmann::json_sax<Json> {
 public:
  /// A problem found: where (a JSON path, or for a syntax error the byte it was found at) and what.
  struct Problem {
    bool syntax = false;   ///< a syntax error: `byte` says where
    std::size_t byte = 0;  ///< syntax errors: nlohmann's byte offset
    std::string path;      ///< otherwise: the JSON path
    std::string what;      ///< what is wrong
  };

  /// The first problem, if any.
  const std::optional<Problem>& problem() const { return problem_; }

  bool null() override { return value(); }
  bool boolean(bool) override { return value(); }
  bool number_integer(number_integer_t) override { return value(); }
  bool number_unsigned(number_unsigned_t) override { return value(); }
  bool number_float(number_float_t x, const string_t& text) override {
    value();
    // strtod rounds 1e-400 to 0: refuse rather than read a zero the file does not say.
    if (x == 0.0 && text.find_first_of("123456789") < text.find_first_of("eE"))
      return fail(path(), "the number " + text + " is too small for a double (it would read as 0)");
    return true;
  }
  bool string(string_t&) override { return value(); }
  bool binary(binary_t&) override { return value(); }
  bool start_object(std::size_t) override {
    value();
    frames_.push_back({true});
    return true;
  }
  bool key(string_t& key) override {
    Frame& frame = frames_.back();
    frame.key = key;
    if (!frame.keys.insert(key).second)
      return fail(path(), "the key \"" + key + "\" is given twice in this object; keep one");
    return true;
  }
  bool end_object() override {
    frames_.pop_back();
    return true;
  }
  bool start_array(std::size_t) override {
    value();
    frames_.push_back({false});
    return true;
  }
  bool end_array() override {
    frames_.pop_back();
    return true;
  }
  bool parse_error(std::size_t byte, const std::string& token, const nlohmann::detail::exception& error) override {
    if (error.id == 406)  // number overflow: the value has a path
      return fail(path_of_next_value(), "the number " + token + " is too large for a double (largest: 1.8e308)");
    problem_ = Problem{true, byte, "", "invalid JSON: " + syntax_reason(error.what())};
    return false;
  }

 private:
  struct Frame {
    bool object;
    std::set<std::string> keys = {};  ///< objects: the keys seen
    std::string key = {};             ///< objects: the current key
    std::size_t next = 0;             ///< arrays: index of the next element
    std::size_t current = 0;          ///< arrays: index of the current element
  };

  // A value starts: inside an array it takes the next index.
  bool value() {
    if (!frames_.empty() && !frames_.back().object) frames_.back().current = frames_.back().next++;
    return true;
  }

  bool fail(std::string where, std::string what) {
    problem_ = Problem{false, 0, std::move(where), std::move(what)};
    return false;
  }

  // The path of the value being read: `bodies[3].density`.
  std::string path() const {
    std::string out;
    for (const Frame& frame : frames_) {
      // Appended piece by piece: `"[" + std::string` trips GCC 12's -Wrestrict (a false positive).
      if (frame.object) {
        if (!out.empty()) out += '.';
        out += frame.key;
      } else {
        out += '[';
        out += std::to_string(frame.current);
        out += ']';
      }
    }
    return out;
  }

  // The path of a value that failed before value() saw it (an overflowing number).
  std::string path_of_next_value() {
    value();
    return path();
  }

  std::vector<Frame> frames_;
  std::optional<Problem> problem_;
};

void check_values(const Json& json, const std::string& path, const std::string& file) {
  if (json.is_number_float() && !std::isfinite(json.get<double>()))
    throw SceneError(file, path, "must be a finite number (got " + fem::format_number(json.get<double>()) + ")");
  if (json.is_string() && !is_valid_utf8(json.get_ref<const std::string&>()))
    throw SceneError(file, path, "must be valid UTF-8 text (got \"" + json.get<std::string>() + "\")");
  if (json.is_object()) {
    for (const auto& [key, value] : json.items()) {
      const std::string at = path.empty() ? key : path + "." + key;
      if (!is_valid_utf8(key)) throw SceneError(file, at, "the key must be valid UTF-8 text");
      check_values(value, at, file);
    }
  }
  if (json.is_array())
    for (std::size_t i = 0; i < json.size(); ++i) check_values(json[i], path + "[" + std::to_string(i) + "]", file);
}

}  // namespace

nlohmann::ordered_json parse_scene_text(const std::string& text, const std::string& file_label) {
  TextChecker checker;
  Json::sax_parse(text, &checker);
  if (const auto& problem = checker.problem()) {
    if (problem->syntax)
      throw SceneError(file_label, syntax_location(text, problem->byte), problem->what);
    throw SceneError(file_label, problem->path, problem->what);
  }
  try {
    return Json::parse(text);
  } catch (const nlohmann::json::exception& error) {  // the checker passed it: not expected
    throw SceneError(file_label, "", "invalid JSON: " + std::string(error.what()));
  }
}

void check_json_values(const nlohmann::ordered_json& json, const std::string& file_label) {
  check_values(json, "", file_label);
}

}  // namespace stiffsoft
