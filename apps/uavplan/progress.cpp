#include <unistd.h>

#include <chrono>
#include <iostream>

#include "commands.h"

namespace uavplan::cli {
namespace {
double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace

Progress::Progress() : started_s_(now_s()), tty_(::isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() {
  if (shown_) std::cerr << "\n";
}

void Progress::update(const std::string& line) {
  if (!tty_ || now_s() - started_s_ < 1.0) return;
  std::cerr << "\r\033[K" << line << std::flush;
  shown_ = true;
}

}  // namespace uavplan::cli
