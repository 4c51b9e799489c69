// Shared by the libFuzzer targets: an input a reader rejects must be rejected with an InputError
// (a clear message); anything else escaping the reader, or a crash, is a bug the fuzzer reports.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "uavplan/io/input_error.h"

namespace uavplan::fuzz {

template <class F>
int run_reader(F&& read) {
  try {
    read();
  } catch (const InputError& e) {
    // The promise: one line per error, none empty, no control byte from the input inside one.
    const std::string msg = e.what();
    std::size_t begin = 0;
    while (begin <= msg.size()) {
      const std::size_t end = std::min(msg.find('\n', begin), msg.size());
      const std::string line = msg.substr(begin, end - begin);
      const bool control = std::any_of(line.begin(), line.end(),
                                       [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
      if (line.empty() || control) {
        std::fprintf(stderr, "error message line not printable: %s\n", printable(msg).c_str());
        std::abort();
      }
      begin = end + 1;
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "escaped as %s\n", e.what());
    std::abort();
  }
  return 0;
}

}  // namespace uavplan::fuzz
