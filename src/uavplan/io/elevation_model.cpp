#include "uavplan/io/elevation_model.h"
#include "uavplan/core/tolerances.h"

#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>

#include "uavplan/core/text.h"
#include "uavplan/io/gdal_session.h"
#include "uavplan/io/input_error.h"
#include "uavplan/io/scenario_io.h"

namespace uavplan {
namespace {

// Metres per unit of the band's values; nullopt for a unit that is not a length.
std::optional<double> metres_per_unit(std::string unit) {
  std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return std::tolower(c); });
  if (unit.empty() || unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters")
    return 1.0;
  if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot") return 0.3048;
  if (unit == "us survey foot" || unit == "ftus" || unit == "us-ft") return 1200.0 / 3937.0;
  return std::nullopt;
}

using Transform = std::unique_ptr<OGRCoordinateTransformation, decltype(&OCTDestroyCoordinateTransformation)>;

struct Raster {
  const std::string& file;
  GDALDatasetUniquePtr ds;
  GDALRasterBand* band = nullptr;
  OGRSpatialReference srs, wgs84;
  std::array<double, 6> to_crs{}, to_pixel{};  // geotransforms pixel -> CRS and back
  Transform from_wgs84{nullptr, OCTDestroyCoordinateTransformation},
      to_wgs84{nullptr, OCTDestroyCoordinateTransformation};

  [[noreturn]] void fail(const std::string& what) const { throw InputError(file, 0, "terrain", what); }

  Raster(const std::string& path, const std::string& f) : file(f) {
    ds = open_gdal(path, GdalInput::elevation_model);
    if (!ds)
      fail("GDAL cannot read it as a raster of the formats read here (" +
           gdal_drivers_text(GdalInput::elevation_model) + ")" + gdal_said());
    if (ds->GetRasterCount() < 1) fail("the file has no raster band");
    band = ds->GetRasterBand(1);
    const OGRSpatialReference* s = ds->GetSpatialRef();
    if (!s || s->IsEmpty())
      fail("the raster has no coordinate system (give it one, e.g. gdal_edit.py -a_srs EPSG:... or a .prj file)");
    srs = *s;
    if (ds->GetGeoTransform(to_crs.data()) != CE_None) fail("the raster has no georeferencing (geotransform)");
    for (const double g : to_crs)
      if (!(std::abs(g) <= kMaxCoordinate_m))
        fail("the raster's geotransform holds " + num_text(g) + ": every term must be a finite number within 1e9");
    if (!GDALInvGeoTransform(to_crs.data(), to_pixel.data())) fail("the raster's geotransform cannot be inverted");
    wgs84.SetWellKnownGeogCS("WGS84");
    for (OGRSpatialReference* r : {&srs, &wgs84}) r->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    from_wgs84.reset(OGRCreateCoordinateTransformation(&wgs84, &srs));
    to_wgs84.reset(OGRCreateCoordinateTransformation(&srs, &wgs84));
    if (!from_wgs84 || !to_wgs84)
      fail("no transformation between WGS84 and the raster's coordinate system" + gdal_said());
  }

  int nx() const { return ds->GetRasterXSize(); }
  int ny() const { return ds->GetRasterYSize(); }

  std::string crs_name() const {
    std::string name = srs.GetName() ? srs.GetName() : "unnamed";
    const char* auth = srs.GetAuthorityName(nullptr);
    const char* code = srs.GetAuthorityCode(nullptr);
    if (auth && code) name += std::string(" (") + auth + ":" + code + ")";
    return name;
  }

  // Local points (x, y) to pixel coordinates (column, row) in place.
  void local_to_pixel(const GeoFrame& frame, std::vector<double>& x, std::vector<double>& y) const {
    for (std::size_t k = 0; k < x.size(); ++k) {
      const LatLonAlt g = frame.to_wgs84(Vec3(x[k], y[k], 0.0));
      x[k] = g.lon_deg;
      y[k] = g.lat_deg;
    }
    std::vector<int> ok(x.size(), 0);
    if (!from_wgs84->Transform(x.size(), x.data(), y.data(), nullptr, ok.data()) ||
        std::find(ok.begin(), ok.end(), 0) != ok.end())
      fail("the world's bounds do not map into the raster's coordinate system" + gdal_said());
    for (std::size_t k = 0; k < x.size(); ++k) {
      double px = 0, py = 0;
      GDALApplyGeoTransform(const_cast<double*>(to_pixel.data()), x[k], y[k], &px, &py);
      x[k] = px;
      y[k] = py;
    }
  }

  // Pixel coordinates to local points, in place.
  void pixel_to_local(const GeoFrame& frame, std::vector<double>& x, std::vector<double>& y) const {
    for (std::size_t k = 0; k < x.size(); ++k)
      GDALApplyGeoTransform(const_cast<double*>(to_crs.data()), x[k], y[k], &x[k], &y[k]);
    std::vector<int> ok(x.size(), 0);
    if (!to_wgs84->Transform(x.size(), x.data(), y.data(), nullptr, ok.data()) ||
        std::find(ok.begin(), ok.end(), 0) != ok.end())
      fail("the raster's corners do not map to WGS84" + gdal_said());
    for (std::size_t k = 0; k < x.size(); ++k) {
      const Vec3 p = frame.to_local(y[k], x[k], frame.origin().alt_m);
      x[k] = p.x();
      y[k] = p.y();
    }
  }
};

// The raster's footprint in the local frame: its box, and its pixel's ground size (smaller side).
void place_footprint(const Raster& r, const GeoFrame& frame, ElevationSource& src) {
  constexpr int kPerSide = 64;
  std::vector<double> x, y;
  for (int k = 0; k <= kPerSide; ++k) {
    const double u = static_cast<double>(k) / kPerSide;
    for (const auto& [px, py] : std::array<std::pair<double, double>, 4>{
             {{u * r.nx(), 0.0}, {u * r.nx(), r.ny()}, {0.0, u * r.ny()}, {r.nx(), u * r.ny()}}}) {
      x.push_back(px);
      y.push_back(py);
    }
  }
  const double cx = 0.5 * r.nx(), cy = 0.5 * r.ny();  // one pixel at the middle, for its size
  for (const auto& [px, py] : std::array<std::pair<double, double>, 3>{{{cx, cy}, {cx + 1, cy}, {cx, cy + 1}}}) {
    x.push_back(px);
    y.push_back(py);
  }
  r.pixel_to_local(frame, x, y);
  const std::size_t n = x.size() - 3;
  src.extent_min = Vec2(*std::min_element(x.begin(), x.begin() + n), *std::min_element(y.begin(), y.begin() + n));
  src.extent_max = Vec2(*std::max_element(x.begin(), x.begin() + n), *std::max_element(y.begin(), y.begin() + n));
  const Vec2 c(x[n], y[n]);
  src.raster_cell_m = std::min((Vec2(x[n + 1], y[n + 1]) - c).norm(), (Vec2(x[n + 2], y[n + 2]) - c).norm());
}

// Fills cells without a height (NaN) from their neighbours' highest, one ring at a time.
std::size_t fill_gaps(std::vector<double>& h, int nx, int ny) {
  const auto neighbours = [nx, ny](std::size_t k, const auto& f) {  // 8-connected, inside the grid
    const int i = static_cast<int>(k % nx), j = static_cast<int>(k / nx);
    for (int b = std::max(0, j - 1); b <= std::min(ny - 1, j + 1); ++b)
      for (int a = std::max(0, i - 1); a <= std::min(nx - 1, i + 1); ++a)
        if (a != i || b != j) f(static_cast<std::size_t>(b) * nx + a);
  };
  const auto highest_beside = [&](std::size_t k) {
    double top = -World::kInf;
    neighbours(k, [&](std::size_t n) {
      if (!std::isnan(h[n])) top = std::max(top, h[n]);
    });
    return top;
  };
  std::vector<std::size_t> ring;
  std::vector<char> queued(h.size(), 0);
  for (std::size_t k = 0; k < h.size(); ++k)
    if (std::isnan(h[k]) && highest_beside(k) > -World::kInf) {
      ring.push_back(k);
      queued[k] = 1;
    }
  std::size_t filled = 0;
  while (!ring.empty()) {
    std::vector<double> value(ring.size());  // from the heights before this ring
    for (std::size_t r = 0; r < ring.size(); ++r) value[r] = highest_beside(ring[r]);
    std::vector<std::size_t> next;
    for (std::size_t r = 0; r < ring.size(); ++r) {
      h[ring[r]] = value[r];
      neighbours(ring[r], [&](std::size_t n) {
        if (std::isnan(h[n]) && !queued[n]) {
          queued[n] = 1;
          next.push_back(n);
        }
      });
    }
    filled += ring.size();
    ring = std::move(next);
  }
  return filled;
}

// Turns the band's values into metres above mean sea level (NaN without data); a value that is
// a height but beyond +-1e9 m (an undeclared NoData such as -3.4e38) is refused.
struct HeightScale {
  double nodata = 0.0, scale = 1.0, offset = 0.0, unit = 1.0;
  float nodata_f = 0.0f;  // Float32 rasters keep it as a float
  bool has_nodata = false;

  explicit HeightScale(const Raster& r) {
    int has = 0, has_scale = 0, has_offset = 0;
    nodata = r.band->GetNoDataValue(&has);
    has_nodata = has != 0;
    nodata_f = static_cast<float>(nodata);
    scale = r.band->GetScale(&has_scale);
    offset = r.band->GetOffset(&has_offset);
    if (!has_scale) scale = 1.0;
    if (!has_offset) offset = 0.0;
    const auto u = metres_per_unit(r.band->GetUnitType());
    if (!u) r.fail("the heights' unit '" + printable(r.band->GetUnitType()) + "' is not metres or feet");
    unit = *u;
  }

  double metres(double z) const {
    if (has_nodata && (z == nodata || static_cast<float>(z) == nodata_f)) return std::nan("");
    if (!std::isfinite(z)) return std::nan("");
    return (z * scale + offset) * unit;
  }
};

// The world's terrain cells: `c` metres over the bounds' x, y, larger where more than max_cells.
struct Cells {
  Vec2 lo, hi;
  double c = 0.0;
  int nx = 0, ny = 0;
};

Cells world_cells(const Aabb& bounds, double c, std::size_t max_cells) {
  Cells w{bounds.min.head<2>(), bounds.max.head<2>(), c, 0, 0};
  const auto count = [](double size, double cell) {
    return std::max(1, static_cast<int>(std::ceil(size / cell - kWholeNumberSlack)));
  };
  w.nx = count(w.hi.x() - w.lo.x(), c);
  w.ny = count(w.hi.y() - w.lo.y(), c);
  if (static_cast<double>(w.nx) * w.ny > static_cast<double>(max_cells)) {
    w.c *= std::sqrt(static_cast<double>(w.nx) * w.ny / static_cast<double>(max_cells)) * 1.001;
    w.nx = count(w.hi.x() - w.lo.x(), w.c);
    w.ny = count(w.hi.y() - w.lo.y(), w.c);
  }
  return w;
}

constexpr double kEdge_px = 1e-6;  // a corner on a pixel edge touches only one side

// The raster's pixels under the cells' corners (px, py): known before any is read.
struct Window {
  int x0 = 0, y0 = 0, w = 1, h = 1;
};

// Where the model lies far beyond the world (farther than any local map reaches), what that
// most likely is: an origin with lat and lon swapped or wrong.
std::string far_away_hint(const Cells& cells, const ElevationSource& src) {
  const Aabb world{Vec3(cells.lo.x(), cells.lo.y(), 0.0), Vec3(cells.hi.x(), cells.hi.y(), 0.0)};
  const Aabb model{Vec3(src.extent_min.x(), src.extent_min.y(), 0.0),
                   Vec3(src.extent_max.x(), src.extent_max.y(), 0.0)};
  const double away_m = world.distance(model);
  if (away_m <= kFarBeyondAnyMap_m) return {};
  return "; it lies " + num_text(std::round(away_m / 1000.0)) +
         " km from the world: is the scenario's origin right (lat and lon swapped?)";
}

Window window_under(const Raster& r, const std::vector<double>& px, const std::vector<double>& py, const Cells& cells,
                    const ElevationSource& src) {
  const auto [px_lo, px_hi] = std::minmax_element(px.begin(), px.end());
  const auto [py_lo, py_hi] = std::minmax_element(py.begin(), py.end());
  if (*px_lo < -kEdge_px || *py_lo < -kEdge_px || *px_hi > r.nx() + kEdge_px || *py_hi > r.ny() + kEdge_px)
    r.fail("the world's bounds (x " + num_text(cells.lo.x()) + ".." + num_text(cells.hi.x()) + ", y " +
           num_text(cells.lo.y()) + ".." + num_text(cells.hi.y()) +
           ") reach beyond the elevation model, which covers x " + num_text(std::round(src.extent_min.x())) + ".." +
           num_text(std::round(src.extent_max.x())) + ", y " + num_text(std::round(src.extent_min.y())) + ".." +
           num_text(std::round(src.extent_max.y())) + " m in the scenario's frame (its footprint's box)" +
           far_away_hint(cells, src));
  Window w;
  w.x0 = std::max(0, static_cast<int>(std::floor(*px_lo + kEdge_px)));
  w.y0 = std::max(0, static_cast<int>(std::floor(*py_lo + kEdge_px)));
  w.w = std::max(1, std::min(r.nx(), static_cast<int>(std::ceil(*px_hi - kEdge_px))) - w.x0);
  w.h = std::max(1, std::min(r.ny(), static_cast<int>(std::ceil(*py_hi - kEdge_px))) - w.y0);
  return w;
}

// A cell's pixel box within the window: columns [a0, a1), rows [b0, b1).
struct PixelBox {
  int a0, a1, b0, b1;
};

PixelBox cell_box(const Cells& cells, const std::vector<double>& px, const std::vector<double>& py, const Window& win,
                  int i, int j) {
  const auto corner = [&](int a, int b) { return static_cast<std::size_t>(b) * (cells.nx + 1) + a; };
  double x_lo = World::kInf, x_hi = -World::kInf, y_lo = World::kInf, y_hi = -World::kInf;
  for (const std::size_t k : {corner(i, j), corner(i + 1, j), corner(i, j + 1), corner(i + 1, j + 1)}) {
    x_lo = std::min(x_lo, px[k]);
    x_hi = std::max(x_hi, px[k]);
    y_lo = std::min(y_lo, py[k]);
    y_hi = std::max(y_hi, py[k]);
  }
  PixelBox b{};
  b.a0 = std::clamp(static_cast<int>(std::floor(x_lo + kEdge_px)) - win.x0, 0, win.w - 1);
  b.a1 = std::clamp(static_cast<int>(std::ceil(x_hi - kEdge_px)) - win.x0, b.a0 + 1, win.w);
  b.b0 = std::clamp(static_cast<int>(std::floor(y_lo + kEdge_px)) - win.y0, 0, win.h - 1);
  b.b1 = std::clamp(static_cast<int>(std::ceil(y_hi - kEdge_px)) - win.y0, b.b0 + 1, win.h);
  return b;
}

// The window is read in strips of whole rows, at most strip_bytes each: memory stays bounded
// whatever the window, and the stop is checked between strips. Rows per strip: whole blocks of
// the raster where they fit, so each block is decoded once.
std::size_t strip_rows(const Raster& r, const Window& win, std::size_t strip_bytes) {
  int block_w = 0, block_h = 0;
  r.band->GetBlockSize(&block_w, &block_h);
  const std::size_t fit = std::max<std::size_t>(1, strip_bytes / (sizeof(double) * static_cast<std::size_t>(win.w)));
  const std::size_t block = static_cast<std::size_t>(std::max(1, block_h));
  return std::min<std::size_t>(fit >= block ? fit / block * block : fit, static_cast<std::size_t>(win.h));
}

// Refuses a window past the pixel cap or the memory cap before a pixel is read.
void check_window(const Raster& r, const Window& win, const Cells& cells, const ElevationReadOptions& o) {
  const double pixels = static_cast<double>(win.w) * win.h;
  if (pixels > static_cast<double>(kMaxElevationPixels) || win.w > kMaxElevationRowPixels)
    r.fail("the world's bounds need a window of " + std::to_string(win.w) + " x " + std::to_string(win.h) +
           " pixels of the elevation model; at most " + std::to_string(kMaxElevationPixels) +
           " pixels (rows of at most " + std::to_string(kMaxElevationRowPixels) +
           ") are read for one world: crop the model to the world (gdal_translate -projwin) or coarsen it "
           "(gdalwarp -r max -tr)");
  const std::uint64_t corners = static_cast<std::uint64_t>(cells.nx + 1) * (cells.ny + 1);
  const std::uint64_t bytes = (std::uint64_t{kGdalCacheMiB} << 20) +
                              strip_rows(r, win, o.strip_bytes) * static_cast<std::uint64_t>(win.w) * sizeof(double) +
                              corners * 2 * sizeof(double) +
                              static_cast<std::uint64_t>(cells.nx) * cells.ny * (sizeof(double) + 1);
  try {
    o.stop.require_memory(bytes, "reading the elevation model (" + std::to_string(cells.nx) + " x " +
                                     std::to_string(cells.ny) + " cells from " + std::to_string(win.w) + " x " +
                                     std::to_string(win.h) + " pixels)");
  } catch (const std::invalid_argument& e) {
    r.fail(e.what());
  }
}

// Each cell's highest and lowest pixel of those its corners' pixel box touches (NaN where all are
// NoData), the window read a strip at a time.
struct CellPixels {
  std::vector<double> high, low;
};
CellPixels cell_pixels(const Raster& r, const Cells& cells, const std::vector<double>& px,
                       const std::vector<double>& py, const Window& win, const ElevationReadOptions& o) {
  std::vector<double> h(static_cast<std::size_t>(cells.nx) * cells.ny, std::nan(""));
  std::vector<double> lows = h;
  std::vector<std::pair<int, int>> row_span(cells.ny, {win.h, 0});  // pixel rows a row of cells touches
  for (int j = 0; j < cells.ny; ++j) {
    if (j % 256 == 0) o.stop.throw_if_stopped();
    for (int i = 0; i < cells.nx; ++i) {
      const PixelBox b = cell_box(cells, px, py, win, i, j);
      row_span[j] = {std::min(row_span[j].first, b.b0), std::max(row_span[j].second, b.b1)};
    }
  }
  const HeightScale scale(r);
  const std::size_t rows = strip_rows(r, win, o.strip_bytes);
  std::vector<double> strip(rows * static_cast<std::size_t>(win.w));
  for (int s0 = 0; s0 < win.h; s0 += static_cast<int>(rows)) {
    o.stop.throw_if_stopped();
    const int s1 = std::min(win.h, s0 + static_cast<int>(rows));
    if (r.band->RasterIO(GF_Read, win.x0, win.y0 + s0, win.w, s1 - s0, strip.data(), win.w, s1 - s0, GDT_Float64, 0,
                         0) != CE_None)
      r.fail("GDAL cannot read the raster's heights" + gdal_said());
    for (std::size_t k = 0; k < static_cast<std::size_t>(s1 - s0) * win.w; ++k) {
      strip[k] = scale.metres(strip[k]);
      if (std::abs(strip[k]) > kMaxCoordinate_m)
        r.fail("a height of " + num_text(strip[k]) + " m at pixel (" + std::to_string(win.x0 + k % win.w) + ", " +
               std::to_string(win.y0 + s0 + k / win.w) +
               ") is beyond +-1e9 m: declare the raster's NoData value (gdal_edit.py -a_nodata VALUE)");
    }
    for (int j = 0; j < cells.ny; ++j) {
      if (row_span[j].second <= s0 || row_span[j].first >= s1) continue;
      for (int i = 0; i < cells.nx; ++i) {
        const PixelBox b = cell_box(cells, px, py, win, i, j);
        double& top = h[static_cast<std::size_t>(j) * cells.nx + i];
        double& bottom = lows[static_cast<std::size_t>(j) * cells.nx + i];
        for (int y = std::max(b.b0, s0); y < std::min(b.b1, s1); ++y)
          for (int x = b.a0; x < b.a1; ++x) {
            const double z = strip[static_cast<std::size_t>(y - s0) * win.w + x];
            if (!std::isnan(z) && !(z <= top)) top = z;
            if (!std::isnan(z) && !(z >= bottom)) bottom = z;
          }
      }
    }
  }
  return {std::move(h), std::move(lows)};
}

// The corners of the world's cells in the raster's pixels, every kStride-th corner (a knot)
// transformed exactly, those between interpolated bilinearly (the mapping is smooth: over
// kStride cells of a few metres its second-order term is micrometres, where each transformed
// point costs a projection and a datum shift). The knots alone bound every corner (a bilinear
// mix stays within its four knots): the window is known from them before the corners are made.
struct Knots {
  std::vector<int> ki, kj;     // the knots' cell indices along x and y
  std::vector<double> kx, ky;  // their pixel coordinates, row by row
};

Vec2 corner_at(const Cells& cells, int i, int j) {
  return {std::min(cells.lo.x() + i * cells.c, cells.hi.x()), std::min(cells.lo.y() + j * cells.c, cells.hi.y())};
}

Knots knots_to_pixels(const Raster& r, const GeoFrame& frame, const Cells& cells) {
  constexpr int kStride = 8;
  const auto knots = [](int n) {
    std::vector<int> k;
    for (int i = 0; i < n; i += kStride) k.push_back(i);
    k.push_back(n);
    return k;
  };
  Knots k{knots(cells.nx), knots(cells.ny), {}, {}};
  for (const int j : k.kj)
    for (const int i : k.ki) {
      k.kx.push_back(corner_at(cells, i, j).x());
      k.ky.push_back(corner_at(cells, i, j).y());
    }
  r.local_to_pixel(frame, k.kx, k.ky);
  return k;
}

void corners_to_pixels(const Knots& k, const Cells& cells, std::vector<double>& px, std::vector<double>& py) {
  const int nx = cells.nx;
  px.assign(static_cast<std::size_t>(nx + 1) * (cells.ny + 1), 0.0);
  py.assign(px.size(), 0.0);
  for (std::size_t b = 0; b + 1 < k.kj.size(); ++b)
    for (std::size_t a = 0; a + 1 < k.ki.size(); ++a) {
      const std::size_t k00 = b * k.ki.size() + a, k10 = k00 + 1, k01 = k00 + k.ki.size(), k11 = k01 + 1;
      const Vec2 p00 = corner_at(cells, k.ki[a], k.kj[b]), p11 = corner_at(cells, k.ki[a + 1], k.kj[b + 1]);
      for (int j = k.kj[b]; j <= k.kj[b + 1]; ++j)
        for (int i = k.ki[a]; i <= k.ki[a + 1]; ++i) {
          const Vec2 q = corner_at(cells, i, j);
          const double u = p11.x() > p00.x() ? (q.x() - p00.x()) / (p11.x() - p00.x()) : 0.0;
          const double v = p11.y() > p00.y() ? (q.y() - p00.y()) / (p11.y() - p00.y()) : 0.0;
          const auto mix = [&](const std::vector<double>& f) {
            return (1 - u) * (1 - v) * f[k00] + u * (1 - v) * f[k10] + (1 - u) * v * f[k01] + u * v * f[k11];
          };
          const std::size_t c = static_cast<std::size_t>(j) * (nx + 1) + i;
          px[c] = mix(k.kx);
          py[c] = mix(k.ky);
        }
    }
}

}  // namespace

ElevationModel read_elevation_model(const std::string& path, const std::string& file, const GeoFrame& frame,
                                    const Aabb& bounds, std::optional<double> cell_m, const ElevationReadOptions& o) {
  const QuietGdal quiet;
  const Raster r(path, file);
  ElevationSource src;
  src.file = file;
  src.crs = r.crs_name();
  src.driver = r.ds->GetDriver() ? r.ds->GetDriver()->GetDescription() : "";
  src.raster_nx = r.nx();
  src.raster_ny = r.ny();
  place_footprint(r, frame, src);
  const Cells cells =
      world_cells(bounds, cell_m.value_or(std::max(0.01, std::round(src.raster_cell_m * 100.0) / 100.0)), o.max_cells);
  src.cell_m = cells.c;
  const Knots knots = knots_to_pixels(r, frame, cells);
  const Window win = window_under(r, knots.kx, knots.ky, cells, src);
  check_window(r, win, cells, o);  // before the corners, the strip and the cells are allocated
  std::vector<double> px, py;      // the cells' corners in pixels
  corners_to_pixels(knots, cells, px, py);
  auto [h, lows] = cell_pixels(r, cells, px, py, win, o);
  if (std::all_of(h.begin(), h.end(), [](double z) { return std::isnan(z); }))
    r.fail("the elevation model has no height within the world's bounds (every pixel there is NoData)");
  src.nodata_filled = fill_gaps(h, cells.nx, cells.ny);
  const auto [h_lo, h_hi] = std::minmax_element(h.begin(), h.end());
  src.min_amsl_m = *h_lo;
  src.max_amsl_m = *h_hi;
  for (std::size_t k = 0; k < h.size(); ++k) {
    if (std::isnan(lows[k])) lows[k] = h[k];  // a filled cell is flat at its fill
    h[k] -= frame.origin().alt_m;
    lows[k] -= frame.origin().alt_m;
  }
  return {TerrainGrid(cells.lo, cells.c, cells.nx, cells.ny, std::move(h), std::move(lows)), std::move(src)};
}

}  // namespace uavplan
