// Checks every text input gets before it is parsed: not empty, no NUL bytes, valid UTF-8 (so
// nothing read can fail to be written back), line endings made "\n" (CR-only and CRLF files read
// like any other). Errors name the file and the line.
#pragma once

#include <nlohmann/json.hpp>
#include <string>
#include <string_view>

namespace uavplan {

std::string checked_text(std::string text, const std::string& file);

// 1-based line of a byte offset.
int line_at(std::string_view text, std::size_t offset);

// A nlohmann JSON error as a message without its "[json.exception...]" prefix, and its line:
// parse errors carry a byte offset, others (a number too large) quote the text, found again.
std::string json_error_text(const std::exception& e, std::string_view text, int& line);
// Throws InputError "FILE:LINE: not valid JSON: ..." for a JSON parse error of `text`.
[[noreturn]] void throw_json_error(const std::exception& e, std::string_view text, const std::string& file);

// Arrays and objects a JSON file may nest (GeoJSON needs 6): deeper trees would overflow the
// stack of whatever copies, compares or prints them recursively.
inline constexpr std::size_t kMaxJsonDepth = 128;

// nlohmann's tree builder that refuses nesting past kMaxJsonDepth (a parse error at its offset).
class DepthLimitedSax : public nlohmann::detail::json_sax_dom_parser<nlohmann::json> {
 public:
  using Base = nlohmann::detail::json_sax_dom_parser<nlohmann::json>;
  explicit DepthLimitedSax(nlohmann::json& tree) : Base(tree, true) {}
  bool start_object(std::size_t n) { return deeper() && Base::start_object(n); }
  bool end_object() {
    --depth_;
    return Base::end_object();
  }
  bool start_array(std::size_t n) { return deeper() && Base::start_array(n); }
  bool end_array() {
    --depth_;
    return Base::end_array();
  }
  bool too_deep() const { return too_deep_; }

 private:
  bool deeper() {
    too_deep_ = ++depth_ > kMaxJsonDepth;
    return !too_deep_;
  }
  std::size_t depth_ = 0;
  bool too_deep_ = false;
};

// Parses a whole JSON file: InputError naming the file and line for bad JSON or nesting deeper
// than kMaxJsonDepth.
nlohmann::json parse_json_file(std::string_view text, const std::string& file);

}  // namespace uavplan
