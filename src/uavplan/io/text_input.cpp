#include "uavplan/io/text_input.h"

#include <algorithm>
#include <nlohmann/json.hpp>

#include "uavplan/io/input_error.h"

namespace uavplan {

int line_at(std::string_view text, std::size_t offset) {
  const auto upto = text.substr(0, std::min(offset, text.size()));
  return 1 + static_cast<int>(std::count(upto.begin(), upto.end(), '\n'));
}

std::string json_error_text(const std::exception& e, std::string_view text, int& line) {
  std::string what = e.what();
  if (const auto p = what.find("] "); p != std::string::npos) what = what.substr(p + 2);
  line = 0;
  if (const auto* pe = dynamic_cast<const nlohmann::json::parse_error*>(&e)) {
    line = line_at(text, pe->byte);
  } else if (const auto q = what.find('\''); q != std::string::npos) {
    if (const auto q2 = what.find('\'', q + 1); q2 != std::string::npos)
      if (const auto at = text.find(what.substr(q + 1, q2 - q - 1)); at != std::string::npos) line = line_at(text, at);
  }
  return what;
}

std::string checked_text(std::string text, const std::string& file) {
  if (text.find_first_not_of(" \t\r\n") == std::string::npos) throw InputError(file, 0, "", "file is empty");
  if (text.find('\0') != std::string::npos) throw InputError(file, 0, "", "not a text file (contains NUL bytes)");
  std::string out;
  out.reserve(text.size());
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\r') {
      out.push_back(text[i]);
    } else if (i + 1 >= text.size() || text[i + 1] != '\n') {
      out.push_back('\n');  // CR alone ends a line too
    }
  }
  std::size_t bad = 0;
  if (!valid_utf8(out, &bad)) throw InputError(file, line_at(out, bad), "", "not valid UTF-8 text");
  return out;
}

void throw_json_error(const std::exception& e, std::string_view text, const std::string& file) {
  int line = 0;
  const std::string what = json_error_text(e, text, line);
  throw InputError(file, line, "", "not valid JSON: " + what);
}

}  // namespace uavplan

namespace uavplan {

nlohmann::json parse_json_file(std::string_view text, const std::string& file) {
  nlohmann::json tree;
  bool too_deep = false;
  try {
    DepthLimitedSax sax(tree);
    nlohmann::json::sax_parse(text, &sax);
    too_deep = sax.too_deep();
  } catch (const nlohmann::json::exception& e) {
    throw_json_error(e, text, file);
  }
  if (too_deep)
    throw InputError(file, 0, "",
                     "arrays and objects nest more than " + std::to_string(kMaxJsonDepth) + " deep; not read");
  return tree;
}

}  // namespace uavplan
