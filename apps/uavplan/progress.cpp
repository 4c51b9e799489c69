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

Progress::~Progress() { finish(); }

void Progress::finish() {
  if (beat_.joinable()) {
    beat_.request_stop();
    beat_cv_.notify_all();
    beat_.join();
  }
  const std::lock_guard<std::mutex> lock(mutex_);
  if (shown_) std::cerr << "\n";
  shown_ = false;
  tty_ = false;  // nothing more after the results
}

void Progress::update(const std::string& line) {
  const std::lock_guard<std::mutex> lock(mutex_);
  last_ = line;
  show(line);
}

void Progress::start_heartbeat() {
  if (!tty_) return;
  beat_ = std::jthread([this](const std::stop_token& stop) {
    std::unique_lock<std::mutex> lock(mutex_);
    while (!stop.stop_requested()) {
      beat_cv_.wait_for(lock, stop, std::chrono::milliseconds(500), [] { return false; });
      if (!stop.stop_requested() && !last_.empty())
        show(last_ + " (" + std::to_string(static_cast<int>(now_s() - started_s_)) + " s)");
    }
  });
}

// With the mutex held.
void Progress::show(const std::string& line) {
  if (!tty_ || now_s() - started_s_ < 1.0) return;
  // Straight to the terminal: the \r and clear-line are ours (the filter of terminal.cpp would
  // escape them); the line itself is escaped here.
  std::cerr.flush();
  const std::string text = "\r\033[K" + printable(line);
  if (::write(STDERR_FILENO, text.data(), text.size()) < 0) tty_ = false;
  shown_ = true;
}

}  // namespace uavplan::cli
