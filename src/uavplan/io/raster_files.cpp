#include "uavplan/io/raster_files.h"

#include <cpl_minixml.h>
#include <sys/stat.h>

#include <cstdio>
#include <memory>
#include <set>
#include <string_view>
#include <vector>

#include "uavplan/io/files.h"
#include "uavplan/io/input_error.h"

namespace uavplan {
namespace {

namespace fs = std::filesystem;

struct Checker {
  const std::string& label;
  fs::path root;                       // canonical: files a VRT names must lie inside it
  std::set<std::string> checked = {};  // canonical paths: a VRT naming one file many times reads it once

  [[noreturn]] void fail(const std::string& what) const { throw InputError(label, 0, "terrain", what); }

  static bool inside(const fs::path& p, const fs::path& folder) {
    const std::string a = p.string(), b = folder.string();
    return a.size() > b.size() && a.compare(0, b.size(), b) == 0 && (b.back() == '/' || a[b.size()] == '/');
  }

  // A regular file, not empty, within the size limit.
  void regular_file(const fs::path& p, const std::string& named) const {
    struct stat st {};
    if (::stat(p.c_str(), &st) != 0) fail(named + "'" + p.string() + "' cannot be read (no such file)");
    if (S_ISDIR(st.st_mode)) fail(named + "'" + p.string() + "' is a folder, not a file");
    if (!S_ISREG(st.st_mode))
      fail(named + "'" + p.string() + "' is not a regular file (a FIFO, device or socket would block or never end)");
    if (st.st_size == 0) fail(named + "'" + p.string() + "' is empty (or a kernel file, whose size reads 0)");
    if (static_cast<std::uint64_t>(st.st_size) > kMaxRasterFileBytes)
      fail(named + "'" + p.string() + "' is " + std::to_string(st.st_size >> 20) + " MiB; a raster file is at most " +
           std::to_string(kMaxRasterFileBytes >> 20) + " MiB");
  }

  // Nothing beside `p` that GDAL may open as its sidecar is a FIFO, device or socket.
  void sidecars(const fs::path& p) const {
    const std::string stem = p.stem().string();
    std::error_code ec;
    for (const fs::directory_entry& e : fs::directory_iterator(p.parent_path().empty() ? "." : p.parent_path(), ec)) {
      const std::string name = e.path().filename().string();
      if (name.compare(0, stem.size(), stem) != 0) continue;
      std::error_code ec2;
      const fs::file_status s = fs::status(e.path(), ec2);
      if (ec2 || fs::is_regular_file(s) || fs::is_directory(s)) continue;
      if (!fs::exists(s)) continue;  // a dangling link opens nothing
      fail("'" + e.path().string() + "' beside '" + p.string() +
           "' is not a regular file (GDAL would open it as a sidecar and block on it)");
    }
  }

  void check(const fs::path& p, const std::string& named, int depth);
  void check_vrt(const fs::path& p, int depth);
  void check_source(const fs::path& vrt, const CPLXMLNode* node, int depth);
};

// GDAL's VRT driver looks for "<VRTDataset" in the first 1,024 bytes; this looks further.
bool is_vrt(const fs::path& p) {
  std::unique_ptr<std::FILE, int (*)(std::FILE*)> f(std::fopen(p.c_str(), "rb"), &std::fclose);
  if (!f) return false;
  std::vector<char> head(64 << 10);
  const std::size_t n = std::fread(head.data(), 1, head.size(), f.get());
  return std::string_view(head.data(), n).find("<VRTDataset") != std::string_view::npos;
}

void Checker::check(const fs::path& p, const std::string& named, int depth) {
  regular_file(p, named);
  std::error_code ec;
  const fs::path real = fs::canonical(p, ec);
  if (ec) fail(named + "'" + p.string() + "' cannot be resolved: " + ec.message());
  if (!inside(real, root))
    fail(named + "'" + p.string() + "' leads out of '" + root.string() + "' (to '" + real.string() +
         "'): a file the scenario reaches through a link or a VRT must lie inside the folder it is named from" +
         (depth == 0 ? " (name the file itself in the scenario, by its path: " + real.string() + ")" : std::string()));
  if (!checked.insert(real.string()).second) return;  // named again: checked once
  sidecars(p);
  if (is_vrt(p)) check_vrt(p, depth);
}

// Elements of a VRT that read something other than a plain raster file's pixels.
constexpr std::string_view kRefused[] = {"PixelFunctionType",      "PixelFunctionLanguage", "PixelFunctionCode",
                                         "PixelFunctionArguments", "SourceDataset",         "OpenOptions",
                                         "SourceTransferType"};

void Checker::check_vrt(const fs::path& p, int depth) {
  if (depth >= kMaxVrtDepth)
    fail("'" + p.string() + "': VRTs nest more than " + std::to_string(kMaxVrtDepth) + " deep");
  std::string text;
  try {
    text = read_text_file(p.string());
  } catch (const InputError& e) {
    fail(e.what());
  }
  std::unique_ptr<CPLXMLNode, void (*)(CPLXMLNode*)> tree(CPLParseXMLString(text.c_str()), &CPLDestroyXMLNode);
  if (!tree) fail("'" + p.string() + "' is not valid VRT XML");
  const auto walk = [&](const auto& self, const CPLXMLNode* n) -> void {
    for (; n; n = n->psNext) {
      if (n->eType != CXT_Element) continue;
      const std::string_view name = n->pszValue;
      for (const std::string_view r : kRefused)
        if (name == r)
          fail("'" + p.string() + "': <" + std::string(name) + "> is not read (VRTs of plain sources only)");
      if (name == "VRTDataset" || name == "VRTRasterBand") {
        const char* sub = CPLGetXMLValue(n, "subClass", nullptr);
        if (sub && std::string_view(sub) != "VRTSourcedRasterBand")
          fail("'" + p.string() + "': <" + std::string(name) + " subClass=\"" + sub +
               "\"> is not read (raw bands read any file's bytes; VRTs of plain sources only)");
      }
      if (name == "SourceFilename") check_source(p, n, depth);
      self(self, n->psChild);
    }
  };
  walk(walk, tree.get());
}

void Checker::check_source(const fs::path& vrt, const CPLXMLNode* node, int depth) {
  const std::string at = "'" + vrt.string() + "' source ";
  const char* rel = CPLGetXMLValue(node, "relativeToVRT", "0");
  const std::string name = CPLGetXMLValue(node, nullptr, "");
  if (std::string_view(rel) != "1")
    fail(at + "'" + name + "': a source must be a path relative to the VRT (relativeToVRT=\"1\")");
  const fs::path rp(name);
  bool bad = name.empty() || rp.is_absolute();
  for (const char c : name)
    bad = bad || c == ':' || c == '<' || c == '>' || c == '\\' || static_cast<unsigned char>(c) < 0x20;
  for (const fs::path& part : rp) bad = bad || part == "..";
  if (bad)
    fail(at + "'" + name +
         "' is refused: a source is a relative path inside the VRT's folder, without '..', ':' (no /vsi*, MEM:::, "
         "vrt:// or driver prefixes) or markup");
  check(vrt.parent_path() / rp, at + "names ", depth + 1);
}

}  // namespace

void check_elevation_files(const fs::path& path, const fs::path& scenario_folder, const std::string& label) {
  std::error_code ec;
  const fs::path folder = fs::canonical(scenario_folder.empty() ? fs::path(".") : scenario_folder, ec);
  if (ec) throw InputError(label, 0, "terrain", "the scenario's folder cannot be resolved: " + ec.message());
  // A path the scenario writes out of its folder ("../data/dem.tif") names that file openly; one
  // inside it may not leave through a link. A VRT's sources stay inside the VRT's own folder.
  const fs::path lexical =
      (fs::absolute(folder) / path.lexically_relative(scenario_folder.empty() ? "." : scenario_folder))
          .lexically_normal();
  const bool openly_outside = !Checker::inside(lexical, folder);
  Checker c{label, openly_outside ? fs::canonical(path.parent_path().empty() ? "." : path.parent_path(), ec) : folder};
  if (ec) throw InputError(label, 0, "terrain", "'" + path.string() + "' cannot be resolved: " + ec.message());
  c.check(path, "the elevation model ", 0);
}

}  // namespace uavplan
