// A part of a scenario file as a mission type reads it (Mission::read_section): a value, a
// mapping or a list, with the checks every reader needs. The io layer supplies it over the parsed
// YAML (io/scenario_io.cpp); every failure names the file, the line and the key path, and is bad
// input (exit 2). Missions read their keys through it without knowing the file format.
#pragma once

#include <cstddef>
#include <cstdint>
#include <initializer_list>
#include <memory>
#include <string>

#include "uavplan/core/vec.h"
#include "uavplan/world/world.h"

namespace uavplan {

class Section {
 public:
  virtual ~Section() = default;
  // Fails (throws the io layer's input error) naming this place.
  [[noreturn]] virtual void fail(const std::string& what) const = 0;
  // Whether this mapping has the key with a value.
  virtual bool has(const char* key) const = 0;
  // The value at the key (which may be missing: has() tells), or the key that must be there.
  virtual std::unique_ptr<Section> at(const char* key) const = 0;
  virtual std::unique_ptr<Section> req(const char* key) const = 0;
  // List access: a failure unless this is a list.
  virtual std::size_t size() const = 0;
  virtual std::unique_ptr<Section> item(std::size_t i) const = 0;
  virtual bool is_map() const = 0;
  virtual void expect_seq() const = 0;
  // Fails on a key not in `allowed`, listing them.
  virtual void keys(std::initializer_list<const char*> allowed) const = 0;
  // Scalars: a finite number, one within +-kMaxCoordinate_m that is > 0 or >= 0, an integer, text.
  virtual double number() const = 0;
  virtual double positive() const = 0;
  virtual double non_negative() const = 0;
  virtual std::int64_t integer() const = 0;
  virtual std::string text() const = 0;
  virtual Vec3 vec3() const = 0;
};

// Fails at `at` unless p is inside the bounds and free; a point on the ground (the terrain there,
// or the bottom of the bounds) is a UAV standing on it: only obstacles count. `what` names it.
void check_placed(const Section& at, const Vec3& p, const World& world, const std::string& what);

}  // namespace uavplan
