#include "uavplan/planning/params.h"

#include <charconv>
#include <cmath>
#include <stdexcept>

namespace uavplan {
namespace {
thread_local ParamListing* g_listing = nullptr;

std::string shortest(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}
}  // namespace

ParamListing::ParamListing() { g_listing = this; }
ParamListing::~ParamListing() { g_listing = nullptr; }

const std::string* ParamReader::find(const std::string& key, const std::string& fallback) {
  known_.insert(key);
  if (g_listing) g_listing->defaults.emplace(key, fallback);
  const auto it = params_.find(key);
  return it == params_.end() ? nullptr : &it->second;
}

double ParamReader::number(const std::string& key, double fallback, double lo, double hi) {
  const std::string* s = find(key, shortest(fallback));
  if (!s) return fallback;
  double v = 0.0;
  const char* end = s->data() + s->size();
  const auto [ptr, ec] = std::from_chars(s->data(), end, v);
  if (ec != std::errc() || ptr != end || !std::isfinite(v))
    throw std::invalid_argument("planner.params." + key + ": expected a finite number, got '" + *s + "'");
  if (v < lo || v > hi)
    throw std::invalid_argument("planner.params." + key + ": " + *s + " is outside [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  return v;
}

int ParamReader::integer(const std::string& key, int fallback, int lo, int hi) {
  const std::string* s = find(key, std::to_string(fallback));
  if (!s) return fallback;
  // A whole number, also in exponent notation (1e6 is a million: counts are written that way).
  double x = 0.0;
  const char* end = s->data() + s->size();
  const auto [ptr, ec] = std::from_chars(s->data(), end, x);
  if (ec != std::errc() || ptr != end || !std::isfinite(x) || x != std::floor(x))
    throw std::invalid_argument("planner.params." + key + ": expected a whole number, got '" + *s + "'");
  if (x < lo || x > hi)
    throw std::invalid_argument("planner.params." + key + ": " + *s + " is outside [" + std::to_string(lo) + ", " +
                                std::to_string(hi) + "]");
  return static_cast<int>(x);
}

bool ParamReader::boolean(const std::string& key, bool fallback) {
  const std::string* s = find(key, fallback ? "true" : "false");
  if (!s) return fallback;
  if (*s == "true" || *s == "1" || *s == "yes") return true;
  if (*s == "false" || *s == "0" || *s == "no") return false;
  throw std::invalid_argument("planner.params." + key + ": expected true or false, got '" + *s + "'");
}

std::string ParamReader::text(const std::string& key, const std::string& fallback) {
  const std::string* s = find(key, fallback);
  return s ? *s : fallback;
}

void ParamReader::finish() const {
  for (const auto& [key, value] : params_) {
    if (known_.count(key)) continue;
    std::string list;
    for (const auto& k : known_) list += (list.empty() ? "" : ", ") + k;
    throw std::invalid_argument("planner.params." + key + ": unknown parameter for planner '" + planner_ +
                                "' (known: " + list + ")");
  }
}

}  // namespace uavplan
