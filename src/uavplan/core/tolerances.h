// Named tolerances of the code's floating-point comparisons, each with what it means. They are
// far below any length, time or angle a scenario can state (coordinates are within 1e9 m, so
// 1e-9 m is below a double's resolution only beyond 1e7 m): they decide ties of arithmetic, not
// of geometry. What the verifier allows a plan is the contract's, in
// coordination/contract/violation.h (kPositionTolerance_m, kDistanceTolerance_m).
#pragma once

namespace uavplan {

// Two points closer than this are one point: a segment between them has no direction.
inline constexpr double kSamePoint_m = 1e-9;
// Two instants closer than this are one: a row at most this much after another adds nothing.
inline constexpr double kSameTime_s = 1e-9;
// A quotient within this of a whole number is that number (cells or pieces counted over a
// length: 100 m of 10 m cells is 10 cells, not 9 or 11 by rounding).
inline constexpr double kWholeNumberSlack = 1e-9;
// A turn limit within this of pi, or a climb limit within this of pi/2, is no limit.
inline constexpr double kUnlimitedAngleSlack_rad = 1e-9;
// Costs whose relative difference is below this tie (a better one must be better by more).
inline constexpr double kRelativeTie = 1e-9;
// The least positive divisor where a quantity may be zero (a rate, an extent): keeps a
// quotient finite without changing any that matters.
inline constexpr double kTinyDivisor = 1e-9;

}  // namespace uavplan
