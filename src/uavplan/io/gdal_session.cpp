#include "uavplan/io/gdal_session.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <cpl_vsi_virtual.h>
#include <gdal.h>
#include <ogr_srs_api.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <mutex>
#include <set>
#include <string>
#include <string_view>

namespace uavplan {
namespace {

constexpr std::array<const char*, 6> kRasterDrivers{"GTiff", "AAIGrid", "SRTMHGT", "DTED", "EHdr", "VRT"};
constexpr std::array<const char*, 2> kKmlDrivers{"LIBKML", "KML"};

bool allowed_driver(std::string_view name) {
  const auto in = [&](const auto& list) {
    return std::any_of(list.begin(), list.end(), [&](const char* d) { return name == d; });
  };
  return in(kRasterDrivers) || in(kKmlDrivers);
}

// A virtual file system that holds nothing: installed over every prefix but /vsimem/, so that no
// name a file holds reaches the network, standard input or an archive that could wrap either.
class NoFileSystem final : public VSIFilesystemHandler {
 public:
  VSIVirtualHandle* Open(const char*, const char*, bool set_error, CSLConstList) override {
    errno = ENOENT;
    if (set_error) VSIError(VSIE_FileError, "virtual file systems are off in uavplan");
    return nullptr;
  }
  int Stat(const char*, VSIStatBufL*, int) override {
    errno = ENOENT;
    return -1;
  }
};

// Each prefix gets a handler of its own (GDAL deletes those it holds when it is cleaned up); the
// handlers replaced are deleted here, once each (one may serve several prefixes), nothing having
// been opened through them yet.
void close_virtual_file_systems() {
  char** prefixes = VSIFileManager::GetPrefixes();
  VSIFilesystemHandler* const kept = VSIFileManager::GetHandler("/vsimem/");
  std::set<VSIFilesystemHandler*> replaced;
  for (char** p = prefixes; p && *p; ++p) {
    if (std::string_view(*p) == "/vsimem/") continue;
    VSIFilesystemHandler* old = VSIFileManager::GetHandler(*p);
    VSIFileManager::InstallHandler(*p, new NoFileSystem);
    if (old != kept) replaced.insert(old);
  }
  CSLDestroy(prefixes);
  for (VSIFilesystemHandler* h : replaced) delete h;
}

void keep_allowed_drivers() {
  GDALDriverManager* manager = GetGDALDriverManager();
  for (int k = manager->GetDriverCount() - 1; k >= 0; --k) {
    GDALDriver* d = manager->GetDriver(k);
    if (!allowed_driver(d->GetDescription())) {
      manager->DeregisterDriver(d);
      delete d;  // GDALDestroyDriver's work; the manager no longer owns it
    }
  }
}

void set_policy() {
  // Options that make GDAL read outside the file it opens, off whatever the environment says.
  for (const auto& [key, value] : std::array<std::pair<const char*, const char*>, 6>{{
           {"GDAL_VRT_ENABLE_RAWRASTERBAND", "NO"},
           {"GDAL_VRT_ENABLE_PYTHON", "NO"},
           {"GDAL_VRT_PYTHON_TRUSTED_MODULES", ""},
           {"LIBKML_RESOLVE_STYLE", "NO"},
           {"LIBKML_EXTERNAL_STYLE", "NO"},
           {"GDAL_HTTP_MAX_RETRY", "0"},
       }})
    CPLSetConfigOption(key, value);
  CPLSetConfigOption("GDAL_CACHEMAX", std::to_string(kGdalCacheMiB).c_str());
  OSRSetPROJEnableNetwork(FALSE);
  GDALAllRegister();
  keep_allowed_drivers();
  close_virtual_file_systems();
}

template <std::size_t N>
std::string joined(const std::array<const char*, N>& names) {
  std::string out;
  for (const char* n : names) out += (out.empty() ? "" : ", ") + std::string(n);
  return out;
}

}  // namespace

void register_gdal_drivers() {
  static std::once_flag registered;
  std::call_once(registered, set_policy);
}

GDALDatasetUniquePtr open_gdal(const std::string& path, GdalInput kind) {
  register_gdal_drivers();
  const bool raster = kind == GdalInput::elevation_model;
  std::vector<const char*> drivers;
  if (raster)
    drivers.assign(kRasterDrivers.begin(), kRasterDrivers.end());
  else
    drivers.assign(kKmlDrivers.begin(), kKmlDrivers.end());
  drivers.push_back(nullptr);
  const unsigned flags = (raster ? GDAL_OF_RASTER : GDAL_OF_VECTOR) | GDAL_OF_READONLY | GDAL_OF_VERBOSE_ERROR;
  return GDALDatasetUniquePtr(GDALDataset::Open(path.c_str(), flags, drivers.data()));
}

std::string gdal_drivers_text(GdalInput kind) {
  return kind == GdalInput::elevation_model ? joined(kRasterDrivers) : joined(kKmlDrivers);
}

QuietGdal::QuietGdal() {
  CPLPushErrorHandler(CPLQuietErrorHandler);
  CPLErrorReset();
}

QuietGdal::~QuietGdal() { CPLPopErrorHandler(); }

std::string gdal_said() {
  const std::string m = CPLGetLastErrorMsg();
  return m.empty() ? std::string() : " (GDAL: " + m + ")";
}

}  // namespace uavplan
