// The report viewer's script and style sheet, bundled from web/ (three.js, uPlot) at build time
// and compiled into the library, so a report is one offline file and the binary needs no data dir.
#pragma once

#include <string_view>

namespace uavplan {

std::string_view report_js();
std::string_view report_css();

}  // namespace uavplan
