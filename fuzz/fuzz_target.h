// Shared by the libFuzzer targets: an input a reader rejects must be rejected with an InputError
// (a clear message); anything else escaping the reader, or a crash, is a bug the fuzzer reports.
#pragma once

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
    const std::string msg = e.what();
    if (msg.find('\n') != std::string::npos) {  // the one-line promise
      std::fprintf(stderr, "error message spans lines: %s\n", msg.c_str());
      std::abort();
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "escaped as %s\n", e.what());
    std::abort();
  }
  return 0;
}

}  // namespace uavplan::fuzz
