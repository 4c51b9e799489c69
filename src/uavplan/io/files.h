// File access for the io layer: whole-file reads and writes that are atomic, all or nothing,
// and never go through a link.
//
// Every output file is first written to a temporary in the target's own folder, created
// exclusively (O_CREAT | O_EXCL | O_NOFOLLOW: a file or link planted under that name is never
// opened, a fresh name is taken), then renamed over the target; rename(2) replaces a link at
// the target with the file and never writes through it. So a reader sees the old file or the
// new one, never half of one, and nothing outside the folder is touched.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace uavplan {

// The output could not be written (a full disk, a read-only folder, a name too long): not bad
// input. The message names the file and the OS error ("No space left on device (ENOSPC)").
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Throws InputError (naming the file) when it cannot be read.
std::string read_text_file(const std::string& path);

// Throws InputError when `dir` cannot be an output folder: an empty name (it would mean the
// file system's root or the current folder by accident).
void check_output_dir(const std::string& dir, const std::string& option = "-o");

// Files written into one folder all or nothing: add() writes each to its temporary (an error
// there removes every temporary so far and leaves the folder as it was), commit() renames them
// all into place. What is not committed is removed when the object goes.
class StagedFiles {
 public:
  // Creates the folder when missing; removes temporaries a killed run left there when asked
  // (a scan of the folder: a caller writing many files asks once).
  explicit StagedFiles(std::string dir, bool remove_stale = true);
  ~StagedFiles();
  StagedFiles(const StagedFiles&) = delete;
  StagedFiles& operator=(const StagedFiles&) = delete;

  // `name` is a plain file name inside the folder. Throws OutputError.
  void add(const std::string& name, std::string_view content);
  // Throws OutputError when a rename fails (the temporaries not yet renamed are removed).
  void commit();

 private:
  void discard() noexcept;
  std::string dir_;
  std::vector<std::pair<std::string, std::string>> staged_;  // (temporary path, target path)
};

// One file, atomically, through StagedFiles; creates missing parent folders. Throws InputError
// when `path` is a folder, OutputError on other failures (nothing is left behind).
void write_file_atomic(const std::string& path, const std::string& content);

// The same for one of many files in a folder the caller owns (a batch's plans): no scan of the
// folder for temporaries (that made writing n files O(n^2)); the folder must exist. The caller
// removes what a killed run left once (remove_temporaries).
void write_file_atomic_in(const std::string& path, const std::string& content);
// Removes every temporary ("NAME.tmp.PID[.N]", a regular file) in the folder whose process is gone.
void remove_temporaries(const std::string& dir);

// 64-bit FNV-1a of the bytes, as 16 hex digits: a stable content fingerprint (not a MAC).
std::string content_fingerprint(std::string_view bytes);

}  // namespace uavplan
