// File access for the io layer: whole-file reads and atomic writes.
#pragma once

#include <string>

namespace uavplan {

// Throws InputError (naming the file) when it cannot be read.
std::string read_text_file(const std::string& path);

// Writes through a temporary file in the same directory and renames it into place, so a
// reader never sees a half-written file; creates missing parent directories; removes temporary
// files of the same target that a killed run left (their process is gone). Throws
// InputError when `path` is a folder, std::runtime_error on other failures (the temporary file
// is removed).
void write_file_atomic(const std::string& path, const std::string& content);

// The same for one of many files in a folder the caller owns (a batch's plans): no scan of the
// folder for temporaries (that made writing n files O(n^2)); the folder must exist. The caller
// removes what a killed run left once (remove_temporaries).
void write_file_atomic_in(const std::string& path, const std::string& content);
// Removes every "NAME.tmp.PID" file in the folder whose process is gone.
void remove_temporaries(const std::string& dir);

}  // namespace uavplan
