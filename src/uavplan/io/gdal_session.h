// What every reader that goes through GDAL needs: its drivers registered once per process, and
// its messages kept from the terminal while it reads (the library never prints), to be quoted in
// ours.
#pragma once

#include <string>

namespace uavplan {

// Registers GDAL's drivers (once; thread-safe).
void register_gdal_drivers();

// While alive, GDAL's errors on this thread go to no handler that prints; gdal_said() quotes the
// last one.
class QuietGdal {
 public:
  QuietGdal();
  ~QuietGdal();
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
};

// " (GDAL: <its last message>)", or empty when it said nothing.
std::string gdal_said();

}  // namespace uavplan
