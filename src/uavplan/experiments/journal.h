// A batch's journal: DIR/journal/rank-R.jsonl, one line per finished run (journal_line,
// results.h), appended in one write(2) after the run's plan file is in place, so a SIGKILL loses
// at most the runs under way and a line cut short is dropped on resume (its run done again).
// Under MPI every rank appends to its own file.
#pragma once

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "uavplan/experiments/results.h"
#include "uavplan/experiments/sweep.h"

namespace uavplan {

// DIR/journal.
std::string journal_dir(const std::string& out_dir);

// Every parsable line of every rank's file, the files in name order.
std::vector<RunRecord> read_journals(const std::string& out_dir);

// Every parsable line of a text of journal lines (what the ranks gathered).
std::vector<RunRecord> parse_journal_lines(const std::string& lines);

// The runs the journal holds, one record per run number, each checked against the sweep's run
// of that number; nullopt with `error` set when one is of another sweep or its scenario changed.
// The runs not among `previous` (a resumed batch's) that rank `rank` of `ranks` runs: every
// ranks-th of them in run order, so the ranks share the work and each run is done once.
std::vector<RunSpec> pending_runs(const std::vector<RunSpec>& runs, const std::vector<RunRecord>& previous, int rank,
                                  int ranks);

std::optional<std::vector<RunRecord>> resumed_runs(const std::string& out_dir, const std::vector<RunSpec>& runs,
                                                   std::string& error);

// Rank 0 before the ranks resume: the records kept, as the one file rank-0.jsonl (the other
// files removed).
void merge_journal(const std::string& out_dir, const std::vector<RunRecord>& kept);

// One rank's file, appended to (opened with O_APPEND | O_NOFOLLOW, never through a link).
class JournalWriter {
 public:
  // Throws std::runtime_error naming the file when it cannot be opened.
  JournalWriter(const std::string& out_dir, int rank);
  ~JournalWriter();
  JournalWriter(const JournalWriter&) = delete;
  JournalWriter& operator=(const JournalWriter&) = delete;
  // One line in one write(2); throws std::runtime_error when it cannot.
  void append(const RunRecord& record);

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace uavplan
