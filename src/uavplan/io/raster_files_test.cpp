#include "uavplan/io/raster_files.h"

#include <gtest/gtest.h>
#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "uavplan/io/gdal_session.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/io_test_fixtures.h"

namespace uavplan {
namespace {

namespace fs = std::filesystem;

std::string refusal(const fs::path& file, const fs::path& folder) {
  try {
    check_elevation_files(file, folder, file.string());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void write_vrt(const fs::path& p, const std::string& band_attrs, const std::string& inside) {
  std::ofstream(p) << "<VRTDataset rasterXSize=\"4\" rasterYSize=\"4\"><SRS>EPSG:21781</SRS>"
                      "<GeoTransform>780000, 100, 0, 186400, 0, -100</GeoTransform>"
                      "<VRTRasterBand dataType=\"Float32\" band=\"1\""
                   << band_attrs << ">" << inside << "</VRTRasterBand></VRTDataset>\n";
}

std::string source(const std::string& name, const char* relative = "1") {
  return std::string("<SimpleSource><SourceFilename relativeToVRT=\"") + relative + "\">" + name +
         "</SourceFilename><SourceBand>1</SourceBand></SimpleSource>";
}

struct Folder {
  test::TempDir d{"raster_files"};
  Folder() { std::ofstream(d.path / "src.asc") << "ncols 1\nnrows 1\nxllcorner 0\nyllcorner 0\ncellsize 1\n5\n"; }
};

TEST(RasterFiles, AVrtOfPlainSourcesInsideItsFolderPasses) {
  const Folder f;
  write_vrt(f.d.path / "ok.vrt", "", source("src.asc"));
  fs::create_directories(f.d.path / "sub");
  write_vrt(f.d.path / "sub" / "inner.vrt", "", source("../src.asc"));  // '..' is refused, even inside
  write_vrt(f.d.path / "outer.vrt", "", source("ok.vrt"));              // a VRT naming a VRT, checked in turn
  EXPECT_EQ(refusal(f.d.path / "ok.vrt", f.d.path), "");
  EXPECT_EQ(refusal(f.d.path / "outer.vrt", f.d.path), "");
  EXPECT_NE(refusal(f.d.path / "sub" / "inner.vrt", f.d.path).find("without '..'"), std::string::npos);
}

TEST(RasterFiles, SourcesThatReachOutsideAreRefusedByName) {
  const Folder f;
  const fs::path v = f.d.path / "v.vrt";
  const auto refused = [&](const std::string& attrs, const std::string& inside, const std::string& part) {
    write_vrt(v, attrs, inside);
    const std::string e = refusal(v, f.d.path);
    EXPECT_NE(e.find(part), std::string::npos) << "expected '" << part << "' in: " << e;
  };
  refused(" subClass=\"VRTRawRasterBand\"", "<SourceFilename relativetoVRT=\"0\">/proc/self/environ</SourceFilename>",
          "VRTRawRasterBand");
  refused(" subClass=\"VRTDerivedRasterBand\"", "<PixelFunctionType>sum</PixelFunctionType>" + source("src.asc"),
          "VRTDerivedRasterBand");
  refused("", "<PixelFunctionType>sum</PixelFunctionType>", "PixelFunctionType");
  refused("", source("/etc/passwd", "0"), "relative to the VRT");
  refused("", source("/vsicurl/http://127.0.0.1:9/x.tif"), "/vsi");
  refused("", source("MEM:::DATAPOINTER=0x1000,PIXELS=4,LINES=4"), "MEM:::");
  refused("", source("vrt://src.asc"), "vrt://");
  refused("", source("missing.asc"), "no such file");
  refused("",
          "<SimpleSource><SourceFilename relativeToVRT=\"1\">src.asc</SourceFilename>"
          "<OpenOptions><OOI key=\"ROOT_PATH\">/</OOI></OpenOptions></SimpleSource>",
          "OpenOptions");
}

TEST(RasterFiles, LinksFifosAndKernelFilesAreRefused) {
  const Folder f;
  fs::create_symlink("/etc/passwd", f.d.path / "passwd.asc");
  write_vrt(f.d.path / "link.vrt", "", source("passwd.asc"));
  EXPECT_NE(refusal(f.d.path / "link.vrt", f.d.path).find("leads out of"), std::string::npos);
  EXPECT_NE(refusal(f.d.path / "passwd.asc", f.d.path).find("leads out of"), std::string::npos);
  fs::create_symlink("/proc/self/environ", f.d.path / "environ.asc");
  EXPECT_NE(refusal(f.d.path / "environ.asc", f.d.path).find("is empty"), std::string::npos);
  ASSERT_EQ(::mkfifo((f.d.path / "fifo.asc").c_str(), 0600), 0);
  write_vrt(f.d.path / "fifo.vrt", "", source("fifo.asc"));
  EXPECT_NE(refusal(f.d.path / "fifo.vrt", f.d.path).find("not a regular file"), std::string::npos);
  ASSERT_EQ(::mkfifo((f.d.path / "src.asc.aux.xml").c_str(), 0600), 0);
  EXPECT_NE(refusal(f.d.path / "src.asc", f.d.path).find("sidecar"), std::string::npos);
}

TEST(RasterFiles, AFileNamedOpenlyOutsideTheFolderIsRead) {
  const Folder f;
  fs::create_directories(f.d.path / "scenario");
  // "../src.asc" from the scenario's folder: the scenario says where it reads.
  EXPECT_EQ(refusal(f.d.path / "scenario" / ".." / "src.asc", f.d.path / "scenario"), "");
}

TEST(RasterFiles, VrtsNestAFewDeep) {
  const Folder f;
  std::string prev = "src.asc";
  for (int k = 0; k <= kMaxVrtDepth; ++k) {
    const std::string name = "n" + std::to_string(k) + ".vrt";
    write_vrt(f.d.path / name, "", source(prev));
    prev = name;
  }
  EXPECT_NE(refusal(f.d.path / prev, f.d.path).find("nest more than"), std::string::npos);
}

// The process keeps only the drivers it reads with, and no virtual file system reaches out.
TEST(GdalSession, OnlyTheAllowedDriversAndNoNetwork) {
  register_gdal_drivers();
  GDALDriverManager* m = GetGDALDriverManager();
  for (int k = 0; k < m->GetDriverCount(); ++k) {
    const std::string name = m->GetDriver(k)->GetDescription();
    EXPECT_TRUE(gdal_drivers_text(GdalInput::elevation_model).find(name) != std::string::npos ||
                gdal_drivers_text(GdalInput::kml_zones).find(name) != std::string::npos)
        << name;
  }
  EXPECT_EQ(GDALGetDriverByName("MEM"), nullptr);
  EXPECT_EQ(GDALGetDriverByName("OGR_VRT"), nullptr);
  for (const char* p :
       {"/vsicurl/http://127.0.0.1:9/x.tif", "/vsistdin/", "/vsizip//vsicurl/http://127.0.0.1:9/a.zip"}) {
    VSIStatBufL st;
    EXPECT_NE(VSIStatL(p, &st), 0) << p;
    EXPECT_EQ(VSIFOpenL(p, "rb"), nullptr) << p;
  }
  const QuietGdal quiet;
  EXPECT_EQ(open_gdal("/vsicurl/http://127.0.0.1:9/x.tif", GdalInput::elevation_model), nullptr);
}

}  // namespace
}  // namespace uavplan
