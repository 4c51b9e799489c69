#include "uavplan/planning/params.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>

#include "uavplan/core/text.h"

namespace uavplan {
namespace {

std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::string range_text(double lo, double hi) { return "[" + shortest(lo) + ", " + shortest(hi) + "]"; }

}  // namespace

std::string_view to_string(ParamKind k) {
  switch (k) {
    case ParamKind::number:
      return "number";
    case ParamKind::integer:
      return "integer";
    case ParamKind::boolean:
      return "boolean";
    case ParamKind::choice:
      return "choice";
  }
  return "number";
}

const std::string* ParamReader::find(ParamDecl decl) {
  const std::string key = decl.key;
  if (std::none_of(declared_.begin(), declared_.end(), [&](const ParamDecl& d) { return d.key == key; }))
    declared_.push_back(std::move(decl));
  const auto it = params_.find(key);
  return it == params_.end() ? nullptr : &it->second;
}

void ParamReader::problem(const std::string& text) {
  if (mode_ == Mode::strict) throw std::invalid_argument(text);
  problems_.push_back(text);
}

double ParamReader::number(const std::string& key, double fallback, double lo, double hi, const char* doc) {
  const std::string* s = find({key, ParamKind::number, lo, hi, {}, shortest(fallback), doc});
  if (!s) return fallback;
  double v = 0.0;
  const char* end = s->data() + s->size();
  const auto [ptr, ec] = std::from_chars(s->data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v)) {
    problem("planner.params." + key + ": expected a finite number, got '" + *s + "'");
    return fallback;
  }
  if (v < lo || v > hi) {
    problem("planner.params." + key + ": " + *s + " is outside " + range_text(lo, hi));
    return fallback;
  }
  return v;
}

// A whole number within [lo, hi], also in exponent notation (1e6 is a million: counts are
// written that way); nan when it is not one (the problem said).
double ParamReader::whole(const std::string& key, const std::string& text, double lo, double hi) {
  double x = 0.0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, x);
  if (ec != std::errc() || ptr != end || !std::isfinite(x) || x != std::floor(x)) {
    problem("planner.params." + key + ": expected a whole number, got '" + text + "'");
    return std::nan("");
  }
  if (x < lo || x > hi) {
    problem("planner.params." + key + ": " + text + " is outside " + range_text(lo, hi));
    return std::nan("");
  }
  return x;
}

int ParamReader::integer(const std::string& key, int fallback, int lo, int hi, const char* doc) {
  const std::string* s = find({key, ParamKind::integer, double(lo), double(hi), {}, std::to_string(fallback), doc});
  if (!s) return fallback;
  const double x = whole(key, *s, lo, hi);
  return std::isnan(x) ? fallback : static_cast<int>(x);
}

std::int64_t ParamReader::count(const std::string& key, std::int64_t fallback, std::int64_t lo, std::int64_t hi,
                                const char* doc) {
  const std::string* s = find({key, ParamKind::integer, double(lo), double(hi), {}, std::to_string(fallback), doc});
  if (!s) return fallback;
  const double x = whole(key, *s, static_cast<double>(lo), static_cast<double>(hi));
  return std::isnan(x) ? fallback : static_cast<std::int64_t>(x);
}

bool ParamReader::boolean(const std::string& key, bool fallback, const char* doc) {
  const std::string* s = find({key, ParamKind::boolean, 0, 1, {"true", "false"}, fallback ? "true" : "false", doc});
  if (!s) return fallback;
  if (*s == "true" || *s == "1" || *s == "yes") return true;
  if (*s == "false" || *s == "0" || *s == "no") return false;
  problem("planner.params." + key + ": expected true or false, got '" + *s + "'");
  return fallback;
}

std::string ParamReader::choice(const std::string& key, const std::string& fallback,
                                const std::vector<std::string>& choices, const char* doc) {
  const std::string* s = find({key, ParamKind::choice, 0, 0, choices, fallback, doc});
  if (!s) return fallback;
  if (std::find(choices.begin(), choices.end(), *s) != choices.end()) return *s;
  problem("planner.params." + key + ": expected " + word_list(choices) + ", got '" + *s + "'");
  return fallback;
}

void ParamReader::require(bool holds, const std::string& key, const std::string& why) {
  if (!holds) problem("planner.params." + key + ": " + why);
}

void ParamReader::finish() {
  for (const auto& given : params_) {
    const std::string& key = given.first;
    if (std::any_of(declared_.begin(), declared_.end(), [&](const ParamDecl& d) { return d.key == key; })) continue;
    std::vector<std::string> keys;
    for (const ParamDecl& d : declared_) keys.push_back(d.key);
    std::sort(keys.begin(), keys.end());
    std::string why = "planner.params." + key + ": unknown parameter for planner '" + owner_ + "' (known: ";
    for (std::size_t i = 0; i < keys.size(); ++i) why.append(i ? ", " : "").append(keys[i]);
    problem(why + ")");
  }
}

}  // namespace uavplan
