#include <unistd.h>

#include <chrono>
#include <iostream>

#include "commands.h"
#include "uavplan/io/input_error.h"

namespace uavplan::cli {
namespace {
double now_s() { return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count(); }
}  // namespace

Progress::Progress() : started_s_(now_s()), tty_(::isatty(STDERR_FILENO) == 1) {}

Progress::~Progress() {
  if (shown_) std::cerr << "\n";
}

void Progress::update(const std::string& line) {
  if (!tty_ || now_s() - started_s_ < 1.0) return;
  // Straight to the terminal: the \r and clear-line are ours (the filter of terminal.cpp would
  // escape them); the line itself is escaped here.
  std::cerr.flush();
  const std::string text = "\r\033[K" + printable(line);
  if (::write(STDERR_FILENO, text.data(), text.size()) < 0) tty_ = false;
  shown_ = true;
}

}  // namespace uavplan::cli
