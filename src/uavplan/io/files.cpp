#include "uavplan/io/files.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

#include "uavplan/io/input_error.h"

namespace uavplan {
namespace fs = std::filesystem;

namespace {

// Input files larger than this are refused before they are read: the largest input the limits
// allow (a 4096 x 4096 terrain written out in YAML) is about 200 MB.
constexpr std::uint64_t kMaxInputBytes = 512ull << 20;

// "No space left on device (ENOSPC)": what the OS said, and its name for scripts and searches.
std::string os_error(int err) {
  std::string s = std::strerror(err);
  if (const char* name = ::strerrorname_np(err)) s += std::string(" (") + name + ")";
  return s;
}

// The process id a temporary's name carries ("NAME.tmp.PID" or "NAME.tmp.PID.N"), or 0.
long temporary_pid(const std::string& name, std::size_t tmp_at) {
  const std::size_t from = tmp_at + 5;
  const std::size_t to = std::min(name.find('.', from), name.size());
  const std::string digits = name.substr(from, to - from);
  if (digits.empty() || digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return 0;
  return std::strtol(digits.c_str(), nullptr, 10);
}

// Temporaries of `target` (empty: of any file) in the folder whose process is gone. Only
// regular files: a link of that name is somebody else's, and is left alone.
void remove_stale_temporaries(const fs::path& dir, const std::string& target_name) {
  const std::string prefix = target_name + ".tmp.";
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(dir, ec)) {
    const std::string name = entry.path().filename().string();
    const auto at = target_name.empty() ? name.rfind(".tmp.")
                                        : (name.rfind(prefix, 0) == 0 ? target_name.size() : std::string::npos);
    if (at == std::string::npos) continue;
    const long pid = temporary_pid(name, at);
    std::error_code st;
    if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH &&
        fs::is_regular_file(fs::symlink_status(entry.path(), st)))
      fs::remove(entry.path(), st);
  }
}

// A fresh temporary beside `target`, created exclusively: never an existing file, never a link.
int open_temporary(const std::string& target, std::string& tmp) {
  static std::atomic<std::uint64_t> counter{0};
  for (int attempt = 0; attempt < 64; ++attempt) {
    tmp = target + ".tmp." + std::to_string(::getpid()) + "." + std::to_string(counter++);
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0644);
    if (fd >= 0) return fd;
    if (errno != EEXIST) throw OutputError("cannot write " + target + ": " + os_error(errno));
  }
  throw OutputError("cannot write " + target + ": no free temporary name beside it");
}

// Writes all of `content` to fd and closes it; on failure removes `tmp` and throws.
void write_all(int fd, std::string_view content, const std::string& tmp, const std::string& target) {
  std::size_t done = 0;
  int err = 0;
  while (done < content.size()) {
    const ssize_t n = ::write(fd, content.data() + done, content.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      err = n < 0 ? errno : EIO;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0 && err == 0) err = errno;
  if (err != 0) {
    ::unlink(tmp.c_str());
    throw OutputError("cannot write " + target + ": " + os_error(err));
  }
}

}  // namespace

std::string read_text_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0)
    throw InputError(path, 0, "", "cannot open: " + std::string(std::strerror(errno)));
  if (S_ISDIR(st.st_mode)) throw InputError(path, 0, "", "is a directory, not a file");
  // A FIFO would block, a device (/dev/zero) would never end.
  if (!S_ISREG(st.st_mode)) throw InputError(path, 0, "", "is not a regular file (a device, FIFO or socket)");
  if (static_cast<std::uint64_t>(st.st_size) > kMaxInputBytes)
    throw InputError(path, 0, "",
                     "is " + std::to_string(st.st_size >> 20) + " MiB; input files are at most " +
                         std::to_string(kMaxInputBytes >> 20) + " MiB");
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) throw InputError(path, 0, "", "cannot open: " + std::string(std::strerror(errno)));
  std::string text;
  text.resize(static_cast<std::size_t>(st.st_size));
  const std::size_t got = std::fread(text.data(), 1, text.size(), f);
  const bool bad = std::ferror(f) != 0;
  std::fclose(f);
  if (bad) throw InputError(path, 0, "", "read error");
  text.resize(got);  // the file shrank while read
  return text;
}

void check_output_dir(const std::string& dir, const std::string& option) {
  if (dir.empty()) throw InputError(option, 0, "", "the output folder's name is empty (give a folder, e.g. out)");
}

StagedFiles::StagedFiles(std::string dir, bool remove_stale) : dir_(std::move(dir)) {
  if (dir_.empty()) dir_ = ".";
  std::error_code ec;
  fs::create_directories(dir_, ec);
  if (ec) throw OutputError("cannot create the folder " + dir_ + ": " + os_error(ec.value()));
  if (remove_stale) remove_stale_temporaries(dir_, "");
}

StagedFiles::~StagedFiles() { discard(); }

void StagedFiles::discard() noexcept {
  for (const auto& [tmp, target] : staged_) ::unlink(tmp.c_str());
  staged_.clear();
}

void StagedFiles::add(const std::string& name, std::string_view content) {
  const std::string target = (fs::path(dir_) / name).string();
  try {
    std::error_code ec;
    if (fs::is_directory(fs::symlink_status(target, ec)))
      throw OutputError("cannot write " + target + ": a folder of that name is in the way");
    std::string tmp;
    const int fd = open_temporary(target, tmp);
    write_all(fd, content, tmp, target);
    staged_.emplace_back(tmp, target);
  } catch (...) {
    discard();
    throw;
  }
}

void StagedFiles::commit() {
  for (std::size_t k = 0; k < staged_.size(); ++k) {
    if (std::rename(staged_[k].first.c_str(), staged_[k].second.c_str()) == 0) continue;
    const int err = errno;
    const std::string target = staged_[k].second;
    staged_.erase(staged_.begin(), staged_.begin() + static_cast<std::ptrdiff_t>(k));
    discard();
    throw OutputError("cannot write " + target + ": " + os_error(err));
  }
  staged_.clear();
}

void write_file_atomic(const std::string& path, const std::string& content) {
  const fs::path target(path);
  std::error_code probe;
  if (fs::is_directory(target, probe))
    throw InputError(path, 0, "", "is a folder: give a file name (" + (target / "NAME").string() + ")");
  const fs::path dir = target.has_parent_path() ? target.parent_path() : fs::path(".");
  StagedFiles files(dir.string(), false);
  remove_stale_temporaries(dir, target.filename().string());
  files.add(target.filename().string(), content);
  files.commit();
}

void remove_temporaries(const std::string& dir) { remove_stale_temporaries(dir, ""); }

void write_file_atomic_in(const std::string& path, const std::string& content) {
  const fs::path target(path);
  StagedFiles files(target.has_parent_path() ? target.parent_path().string() : ".", false);
  files.add(target.filename().string(), content);
  files.commit();
}

std::string content_fingerprint(std::string_view bytes) {
  std::uint64_t h = 14695981039346656037ull;  // FNV-1a, 64 bits
  for (unsigned char c : bytes) {
    h ^= c;
    h *= 1099511628211ull;
  }
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(h));
  return buf;
}

}  // namespace uavplan
