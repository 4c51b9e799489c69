// Outcome of planning: expected results are a status, misuse is an exception.
#pragma once

#include <optional>
#include <string_view>

namespace uavplan {

enum class Status { solved, partial, failed };

constexpr std::string_view to_string(Status s) {
  switch (s) {
    case Status::solved: return "solved";
    case Status::partial: return "partial";
    case Status::failed: return "failed";
  }
  return "failed";
}

inline std::optional<Status> status_from_string(std::string_view s) {
  if (s == "solved") return Status::solved;
  if (s == "partial") return Status::partial;
  if (s == "failed") return Status::failed;
  return std::nullopt;
}

}  // namespace uavplan
