// The command-line tool: one small file per subcommand. Exit codes: 0 solved / plan holds,
// 1 not solved / violations, 2 bad input.
#pragma once

#include <CLI/CLI.hpp>
#include <functional>
#include <string>

namespace uavplan::cli {

inline constexpr int kExitOk = 0;
inline constexpr int kExitNotSolved = 1;
inline constexpr int kExitBadInput = 2;

// Each registers its subcommand on the app and sets `run` to the action to take when chosen.
void add_plan_command(CLI::App& app, std::function<int()>& run);
void add_verify_command(CLI::App& app, std::function<int()>& run);
void add_info_command(CLI::App& app, std::function<int()>& run);
void add_bench_command(CLI::App& app, std::function<int()>& run);

// Progress on stderr, only on a terminal and only once a run has taken over a second.
class Progress {
 public:
  Progress();
  ~Progress();
  void update(const std::string& line);

 private:
  double started_s_;
  bool tty_;
  bool shown_ = false;
};

}  // namespace uavplan::cli
