// Planner parameters as given in a scenario's `planner.params` or on the command line, read
// into a planner's options struct with range checks; unknown keys are errors (usually typos).
// The code that reads an options struct is its declaration (OMPL's declareParam is the model):
// each call names the key, its type, range, default and meaning, so one read gives the values,
// the table `info --planners` and the docs show (declarations()), or whether a value would be
// taken (Mode::collect: problems are listed, not thrown).
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace uavplan {

using Params = std::map<std::string, std::string>;

enum class ParamKind { number, integer, boolean, choice };

// One parameter as its reader declares it.
struct ParamDecl {
  std::string key;
  ParamKind kind = ParamKind::number;
  double lo = 0.0, hi = 0.0;         // number, integer: the range
  std::vector<std::string> choices;  // choice: the words it takes
  std::string default_value;         // as text (0, nan or inf where the value is derived)
  std::string doc;                   // one line
};

std::string_view to_string(ParamKind k);

class ParamReader {
 public:
  // strict: the first malformed, out-of-range or unknown value throws std::invalid_argument
  // naming the key; collect: values that would fail are listed in problems() and the default
  // kept.
  enum class Mode { strict, collect };
  ParamReader(const Params& params, std::string owner, Mode mode = Mode::strict)
      : params_(params), owner_(std::move(owner)), mode_(mode) {}

  double number(const std::string& key, double fallback, double lo, double hi, const char* doc);
  int integer(const std::string& key, int fallback, int lo, int hi, const char* doc);
  std::int64_t count(const std::string& key, std::int64_t fallback, std::int64_t lo, std::int64_t hi, const char* doc);
  bool boolean(const std::string& key, bool fallback, const char* doc);
  std::string choice(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices,
                     const char* doc);
  // A rule between values (or beyond a range): when `holds` is false, `key`'s value is refused
  // for `why`.
  void require(bool holds, const std::string& key, const std::string& why);

  // Every given key must have been read (else a problem naming the known ones).
  void finish();

  const std::vector<ParamDecl>& declarations() const { return declared_; }
  const std::vector<std::string>& problems() const { return problems_; }

 private:
  const std::string* find(ParamDecl decl);
  void problem(const std::string& text);
  double whole(const std::string& key, const std::string& text, double lo, double hi);
  const Params& params_;
  std::string owner_;
  Mode mode_;
  std::vector<ParamDecl> declared_;
  std::vector<std::string> problems_;
};

}  // namespace uavplan
