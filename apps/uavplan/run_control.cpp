// What every long-running command shares: interrupts (SIGINT, SIGTERM) that stop planning
// cleanly, thread and memory limits.
#include <sys/prctl.h>
#include <unistd.h>

#include <atomic>
#include <cmath>
#include <csignal>
#include <cstdlib>
#include <ctime>
#include <fstream>
#include <iterator>
#include <sstream>
#include <string>

#include "commands.h"
#include "uavplan/experiments/batch.h"

namespace uavplan::cli {
namespace {

std::atomic<bool> g_interrupted{false};

extern "C" void on_interrupt(int sig) {
  // The first one asks planning to stop (it ends with a message, exit 130, nothing half
  // written); a second one ends the process at once.
  if (g_interrupted.exchange(true)) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

// When this process started, on the planners' clock: the kernel's start time of the process
// (/proc/self/stat, field 22, clock ticks after boot) against CLOCK_BOOTTIME. Loading the
// program's shared libraries comes before main and takes a noticeable part of a short limit on a
// busy machine; where the start cannot be read, now.
StopCondition::Clock::time_point process_start() {
  const auto now = StopCondition::Clock::now();
  std::ifstream file("/proc/self/stat");
  const std::string stat((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  // Field 2, the command's name, is in parentheses and may hold spaces: count from its ')'.
  const std::size_t close = stat.rfind(')');
  if (close == std::string::npos) return now;
  std::istringstream fields(stat.substr(close + 1));
  std::string skipped;
  for (int field = 3; field < 22; ++field) fields >> skipped;
  unsigned long long start_ticks = 0;
  timespec boot{};
  const long ticks_per_s = ::sysconf(_SC_CLK_TCK);
  if (!(fields >> start_ticks) || ticks_per_s <= 0 || ::clock_gettime(CLOCK_BOOTTIME, &boot) != 0) return now;
  const double age_s = static_cast<double>(boot.tv_sec) + 1e-9 * static_cast<double>(boot.tv_nsec) -
                       static_cast<double>(start_ticks) / static_cast<double>(ticks_per_s);
  constexpr double kOldest_s = 60.0;  // a start older than that is a clock we misread
  if (!(age_s > 0.0 && age_s < kOldest_s)) return now;
  return now - std::chrono::duration_cast<StopCondition::Clock::duration>(std::chrono::duration<double>(age_s));
}

}  // namespace

CLI::Validator positive_number() {
  return CLI::Validator(
      [](std::string& v) {
        double x = 0.0;
        return CLI::detail::lexical_cast(v, x) && x > 0.0 && std::isfinite(x)
                   ? std::string()
                   : "must be a positive number, got '" + v + "'";
      },
      "POSITIVE");
}

CLI::Validator non_negative_integer() {
  return CLI::Validator(
      [](std::string& v) {
        // Digits only, and within 64 bits: "1e23" or "-1" would otherwise be read as some other
        // number without a word.
        const bool digits = !v.empty() && v.size() <= 20 && v.find_first_not_of("0123456789") == std::string::npos;
        const bool fits = digits && (v.size() < 20 || v <= "18446744073709551615");
        return fits ? std::string() : "must be a whole number from 0 to 18446744073709551615, got '" + v + "'";
      },
      "NONNEGATIVE");
}

void install_interrupt_handlers() {
  struct sigaction sa {};
  sa.sa_handler = on_interrupt;
  sigemptyset(&sa.sa_mask);
  sigaction(SIGINT, &sa, nullptr);
  sigaction(SIGTERM, &sa, nullptr);
}

bool interrupted() { return g_interrupted.load(); }

void die_with_batch() {
  const char* parent = std::getenv(kParentPidVariable);
  if (!parent) return;
  ::prctl(PR_SET_PDEATHSIG, SIGKILL);
  // The batch may have died before the line above: then this process has another parent now.
  if (std::to_string(::getppid()) != parent) std::_Exit(kExitInterrupted);
}

const std::atomic<bool>* interrupt_flag() { return &g_interrupted; }

StopCondition run_stop(const RunArgs& a) {
  StopCondition stop = StopCondition::cancel_flag(&g_interrupted);
  if (a.time_limit_s > 0.0) stop = stop | StopCondition::time_limit(a.time_limit_s, process_start());
  return stop.with_threads(a.threads).with_memory_cap(a.max_memory_bytes);
}

void add_run_options(CLI::App& cmd, RunArgs& a) {
  cmd.add_option("--time-limit", a.time_limit_s, "Stop after this many seconds of wall time (the whole command)")
      ->check(positive_number());
  cmd.add_option("--threads", a.threads,
                 "Threads the planners may use (default 0: every core); plans are the same for any count")
      ->check(non_negative_integer());
  cmd.add_option("--max-memory", a.max_memory_bytes,
                 "Memory a planner's grids may take, e.g. 512M or 8G (default half the machine's RAM; 0: no cap)")
      ->check(CLI::Validator(
          [](std::string& v) {
            return v.find('-') == std::string::npos ? std::string()
                                                    : "must be a size such as 512M or 8G, got '" + v + "'";
          },
          "SIZE"))
      ->transform(CLI::AsSizeValue(false));
}

}  // namespace uavplan::cli
