#include "uavplan/experiments/journal.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <set>
#include <stdexcept>

#include "uavplan/io/files.h"

namespace uavplan {

namespace fs = std::filesystem;

std::string journal_dir(const std::string& out_dir) { return (fs::path(out_dir) / "journal").string(); }

std::vector<RunRecord> read_journals(const std::string& out_dir) {
  std::vector<RunRecord> done;
  std::error_code ec;
  if (!fs::is_directory(journal_dir(out_dir), ec)) return done;
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(journal_dir(out_dir))) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const fs::path& f : files) {
    std::ifstream in(f);
    std::string line;
    while (std::getline(in, line))
      if (auto r = parse_journal_line(line)) done.push_back(std::move(*r));
  }
  return done;
}

std::vector<RunRecord> parse_journal_lines(const std::string& lines) {
  std::vector<RunRecord> out;
  std::size_t from = 0;
  while (from < lines.size()) {
    const std::size_t nl = lines.find('\n', from);
    if (auto r = parse_journal_line(lines.substr(from, nl - from))) out.push_back(std::move(*r));
    from = nl == std::string::npos ? lines.size() : nl + 1;
  }
  return out;
}

std::vector<RunSpec> pending_runs(const std::vector<RunSpec>& runs, const std::vector<RunRecord>& previous, int rank,
                                  int ranks) {
  std::set<std::size_t> done_before;
  for (const RunRecord& r : previous) done_before.insert(r.spec.index);
  std::vector<RunSpec> pending;
  std::size_t k = 0;
  for (const RunSpec& r : runs)
    if (!done_before.count(r.index) && (k++ % std::size_t(std::max(ranks, 1))) == std::size_t(rank))
      pending.push_back(r);
  return pending;
}

std::optional<std::vector<RunRecord>> resumed_runs(const std::string& out_dir, const std::vector<RunSpec>& runs,
                                                   std::string& error) {
  std::vector<RunRecord> kept;
  std::set<std::size_t> seen;
  for (RunRecord& r : read_journals(out_dir)) {
    if (r.spec.index >= runs.size() || !same_run(r.spec, runs[r.spec.index])) {
      error = out_dir + " holds run " + std::to_string(r.spec.index) +
              " of another sweep, or its scenario file changed since (scenario, its content, planner, seed or "
              "parameters differ); use a new folder";
      return std::nullopt;
    }
    if (seen.insert(r.spec.index).second) kept.push_back(std::move(r));
  }
  return kept;
}

void merge_journal(const std::string& out_dir, const std::vector<RunRecord>& kept) {
  std::string merged;
  for (const RunRecord& r : kept) merged += journal_line(r) + "\n";
  fs::create_directories(journal_dir(out_dir));
  const fs::path mine = fs::path(journal_dir(out_dir)) / "rank-0.jsonl";
  write_file_atomic(mine.string(), merged);
  for (const auto& e : fs::directory_iterator(journal_dir(out_dir)))
    if (e.path() != mine) fs::remove(e.path());
}

JournalWriter::JournalWriter(const std::string& out_dir, int rank)
    : path_((fs::path(journal_dir(out_dir)) / ("rank-" + std::to_string(rank) + ".jsonl")).string()) {
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC | O_NOFOLLOW, 0644);
  if (fd_ < 0) throw std::runtime_error("cannot write " + path_);
}

JournalWriter::~JournalWriter() {
  if (fd_ >= 0) ::close(fd_);
}

void JournalWriter::append(const RunRecord& record) {
  const std::string line = journal_line(record) + "\n";
  if (::write(fd_, line.data(), line.size()) != static_cast<ssize_t>(line.size()))
    throw std::runtime_error("cannot append to " + path_);
}

}  // namespace uavplan
