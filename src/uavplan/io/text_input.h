// Checks every text input gets before it is parsed: not empty, no NUL bytes, valid UTF-8 (so
// nothing read can fail to be written back), line endings made "\n" (CR-only and CRLF files read
// like any other). Errors name the file and the line.
#pragma once

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

}  // namespace uavplan
