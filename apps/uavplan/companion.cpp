#include "companion.h"

#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <string>

#include "commands.h"

namespace uavplan::cli {
namespace {

int g_argc = 0;
char** g_argv = nullptr;

}  // namespace

void remember_command_line(int argc, char** argv) {
  g_argc = argc;
  g_argv = argv;
}

int run_companion(const char* name) {
  std::error_code ec;
  const std::filesystem::path self = std::filesystem::read_symlink("/proc/self/exe", ec);
  const std::string path = (ec ? std::filesystem::path(".") : self.parent_path()) / name;
  std::cout.flush();
  std::cerr.flush();
  std::fflush(nullptr);
  if (g_argv && g_argc > 0) ::execv(path.c_str(), g_argv);  // argv[0] as typed: messages say "uavplan"
  const int err = errno;
  std::cerr << "uavplan: this command is in " << path << ", which cannot be started (" << std::strerror(err)
            << "): build it with `cmake --build build --target " << name << "` (make build builds it)\n";
  return kExitBadInput;
}

}  // namespace uavplan::cli
