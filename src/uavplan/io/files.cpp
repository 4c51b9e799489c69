#include "uavplan/io/files.h"

#include <signal.h>
#include <unistd.h>

#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "uavplan/io/input_error.h"

namespace uavplan {

std::string read_text_file(const std::string& path) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) throw InputError(path, 0, "", "is a directory, not a file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "", std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "", "read error");
  return ss.str();
}

namespace {

// Temporary files of this target left by a run that was killed (its process is gone).
// Temporaries of `target` (empty: of any file) in its folder whose process is gone.
void remove_stale_temporaries(const std::filesystem::path& dir, const std::string& target_name) {
  namespace fs = std::filesystem;
  const std::string prefix = target_name + ".tmp.";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const auto at = target_name.empty() ? name.rfind(".tmp.") : (name.rfind(prefix, 0) == 0 ? target_name.size() : std::string::npos);
    if (at == std::string::npos) continue;
    const std::string pid_text = name.substr(at + 5);
    if (pid_text.empty() || pid_text.find_first_not_of("0123456789") != std::string::npos) continue;
    const long pid = std::strtol(pid_text.c_str(), nullptr, 10);
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH) fs::remove(entry.path(), ec);
  }
}

}  // namespace

void write_file_atomic(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  std::error_code probe;
  if (fs::is_directory(target, probe))
    throw InputError(path, 0, "", "is a folder: give a file name (" + (target / "NAME").string() + ")");
  if (target.has_parent_path()) fs::create_directories(target.parent_path());
  remove_stale_temporaries(target.has_parent_path() ? target.parent_path() : fs::path("."), target.filename().string());
  write_file_atomic_in(path, content);
}

void remove_temporaries(const std::string& dir) { remove_stale_temporaries(dir, ""); }

void write_file_atomic_in(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  const fs::path target(path);
  const fs::path tmp = target.string() + ".tmp." + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    if (!out) throw std::runtime_error("cannot write " + tmp.string() + ": " + std::strerror(errno));
    out << content;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error("cannot write " + tmp.string());
    }
  }
  std::error_code ec;
  fs::rename(tmp, target, ec);
  if (ec) {
    const std::string why = ec.message();
    fs::remove(tmp, ec);
    throw std::runtime_error("cannot move " + tmp.string() + " to " + path + ": " + why);
  }
}

}  // namespace uavplan
