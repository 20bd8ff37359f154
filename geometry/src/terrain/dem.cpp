// DEM loading through GDAL: one adapter, so GDAL stays inside geometry/src/terrain.
#include "kiri/geometry/terrain/dem.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <memory>
#include <mutex>
#include <optional>
#include <system_error>
#include <vector>

#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "kiri/geometry/core/error.hpp"
#include "terrain/geodesy.hpp"
#include "terrain/nodata_fill.hpp"

namespace kiri::geometry {
namespace {

namespace fs = std::filesystem;

// Silences GDAL's own printing for the lifetime of the object (this thread) and keeps its
// failure messages, so that they end up in our exception instead of on stderr.
class GdalErrors {
public:
    GdalErrors()
    {
        CPLPushErrorHandlerEx(&GdalErrors::collect, this);
        CPLErrorReset();
    }
    ~GdalErrors() { CPLPopErrorHandler(); }
    GdalErrors(const GdalErrors&) = delete;
    GdalErrors& operator=(const GdalErrors&) = delete;

    //! " (GDAL: ...)" or "" when GDAL said nothing.
    std::string suffix() const { return messages_.empty() ? std::string() : " (GDAL: " + messages_ + ")"; }

private:
    std::string messages_;
    static void CPL_STDCALL collect(CPLErr level, CPLErrorNum, const char* message)
    {
        auto* self = static_cast<GdalErrors*>(CPLGetErrorHandlerUserData());
        if (!self || level < CE_Failure || !message || self->messages_.size() > 300)
            return;
        std::string m(message);
        std::replace(m.begin(), m.end(), '\n', ' ');  // the CLI prints one line
        self->messages_ += (self->messages_.empty() ? "" : "; ") + m;
    }
};

struct DatasetClose {
    void operator()(GDALDataset* ds) const { GDALClose(GDALDataset::ToHandle(ds)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetClose>;

// An opened raster and how its pixels map to the local frame.
struct Raster {
    std::string file;
    DatasetPtr ds;
    GDALRasterBand* band = nullptr;
    std::string driver;
    int width = 0, height = 0;
    bool georeferenced = false;
    double gt[6] = {0, 1, 0, 0, 0, -1};
    bool geographic = false;
    std::string crs_wkt, crs_name;
    double dx_m = 1.0, dy_m = 1.0;          // cell size in metres
    bool flip_rows = true;                  // source row 0 is the north edge
    bool flip_cols = false;                 // source column 0 is the east edge
    double centre_x = 0.0, centre_y = 0.0;  // source-CRS coordinates of the data's centre
    double z_scale = 1.0, z_offset = 0.0;   // metres = z_offset + z_scale * raw
    std::optional<double> nodata;
    bool nodata_float32 = false;
    double exaggeration = 1.0;  // inside z_scale and z_offset; the plausible range is checked before it
    std::vector<std::string> warnings;
};

// Elevations on Earth lie within these (the Challenger Deep -10.9 km, Everest 8.85 km): beyond
// them a value of a georeferenced raster is a fill value, whatever the file declares. (Images
// without georeferencing, such as a game's PNG heightmap, may hold any height their scale gives.)
constexpr double lowest_elevation_m = -12000.0, highest_elevation_m = 9000.0;

// Fill values real exports write without declaring them as nodata: the float limits (GDAL's
// and ArcGIS's -3.4e38), the 16-bit ones (SRTM voids) and -9999 (ESRI and most GIS tools).
bool undeclared_fill_value(double raw)
{
    return std::abs(raw) >= 3.0e38 || raw == -32768.0 || raw == -32767.0 || raw == -9999.0;
}

// Without a CRS, a geotransform whose cells are under 0.1 and whose extent fits the globe's
// longitudes and latitudes is plainly in degrees (a metric grid that small would be centimetres
// within a few metres of its origin).
bool plainly_degrees(const double gt[6], int width, int height)
{
    const double x0 = gt[0], x1 = gt[0] + width * gt[1], y0 = gt[3], y1 = gt[3] + height * gt[5];
    const auto inside = [](double v, double limit) { return std::abs(v) <= limit + 1e-9; };
    return std::abs(gt[1]) <= 0.1 && std::abs(gt[5]) <= 0.1 && inside(x0, 180.0) && inside(x1, 180.0) &&
        inside(y0, 90.0) && inside(y1, 90.0);
}

// Metres per unit of a unit's name as GDAL and its drivers spell it; 0 when it names no length.
double metres_per_unit_named(std::string unit)
{
    std::transform(unit.begin(), unit.end(), unit.begin(), [](unsigned char c) { return std::tolower(c); });
    std::replace(unit.begin(), unit.end(), '_', ' ');
    if (unit == "ft" || unit == "foot" || unit == "feet" || unit == "international foot")
        return 0.3048;
    if (unit == "us-ft" || unit == "us survey foot" || unit == "ftus" || unit == "foot us" || unit == "us foot")
        return 1200.0 / 3937.0;
    if (unit == "m" || unit == "metre" || unit == "meter" || unit == "metres" || unit == "meters")
        return 1.0;
    return 0.0;
}

// The band's own unit first; else the vertical CRS's (a compound CRS such as NAD83 + NAVD88
// height in feet); else metres.
double metres_per_unit_of_band(GDALRasterBand* band, const OGRSpatialReference* srs)
{
    if (const double m = metres_per_unit_named(band->GetUnitType()); m > 0.0)
        return m;
    if (srs && srs->IsCompound()) {
        const double m = srs->GetTargetLinearUnits("VERT_CS");
        if (m > 0.0 && std::isfinite(m))
            return m;
    }
    return 1.0;
}

Raster open_raster(const fs::path& path, const DemOptions& options, const GdalErrors& errors)
{
    static std::once_flag registered;
    std::call_once(registered, [] { GDALAllRegister(); });

    Raster r;
    r.file = path.string();
    std::error_code ec;
    if (!fs::exists(path, ec))
        throw InputError(r.file, "file", "no such file");
    if (fs::is_regular_file(path, ec) && fs::file_size(path, ec) == 0)
        throw InputError(r.file, "size", "empty file (0 bytes), not a raster");

    r.ds.reset(GDALDataset::Open(r.file.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!r.ds)
        throw InputError(r.file, "format", "not a raster GDAL can read" + errors.suffix());
    r.driver = r.ds->GetDriver() ? r.ds->GetDriver()->GetDescription() : "";
    if (r.ds->GetRasterCount() < 1)
        throw InputError(r.file, "bands", "the file holds no raster band");
    r.width = r.ds->GetRasterXSize();
    r.height = r.ds->GetRasterYSize();
    if (r.width <= 0 || r.height <= 0)
        throw InputError(r.file, "size",
                         "zero-size raster (" + std::to_string(r.width) + " x " + std::to_string(r.height) + ")");
    r.band = r.ds->GetRasterBand(1);
    if (r.band->GetColorInterpretation() == GCI_RedBand || r.band->GetColorInterpretation() == GCI_PaletteIndex)
        throw InputError(r.file, "bands", "a colour image, not a heightmap: expected one grey band");

    // Geotransform: only north-up or south-up grids (no rotation, no shear).
    r.georeferenced = r.ds->GetGeoTransform(r.gt) == CE_None;
    CPLErrorReset();
    if (r.georeferenced) {
        if (r.gt[2] != 0.0 || r.gt[4] != 0.0)
            throw InputError(r.file, "geotransform", "rotated or sheared rasters are not supported");
        if (!(r.gt[1] != 0.0 && r.gt[5] != 0.0 && std::isfinite(r.gt[1]) && std::isfinite(r.gt[5]) &&
              std::isfinite(r.gt[0]) && std::isfinite(r.gt[3])))
            throw InputError(r.file, "geotransform", "zero or non-finite pixel size");
    } else {
        if (!(options.cell_size > 0.0 && std::isfinite(options.cell_size)))
            throw InputError(r.file, "cell_size",
                             "the raster has no georeferencing: give its cell size in metres (> 0)");
        // An image: row 0 is the top (north), cells are cell_size metres.
        const double g[6] = {0.0, options.cell_size, 0.0, 0.0, 0.0, -options.cell_size};
        std::copy(g, g + 6, r.gt);
    }
    r.flip_cols = r.gt[1] < 0.0;
    r.flip_rows = r.gt[5] < 0.0;
    // Centre of the data: the middle of the pixel-centre span, in source units.
    r.centre_x = r.gt[0] + 0.5 * r.width * r.gt[1];
    r.centre_y = r.gt[3] + 0.5 * r.height * r.gt[5];

    double mx = 1.0, my = 1.0;  // metres per source unit along x and y
    const OGRSpatialReference* srs = r.ds->GetSpatialRef();
    if (!srs && r.georeferenced && plainly_degrees(r.gt, r.width, r.height)) {
        r.geographic = true;
        const double lat = r.centre_y;
        const LocalScale s = wgs84_metres_per_degree(lat);
        mx = s.east;
        my = s.north;
        OGRSpatialReference wgs84;
        wgs84.SetWellKnownGeogCS("WGS84");
        char* wkt = nullptr;
        if (wgs84.exportToWkt(&wkt) == OGRERR_NONE && wkt)
            r.crs_wkt = wkt;
        CPLFree(wkt);
        r.crs_name = "WGS 84 (assumed)";
        char note[200];
        std::snprintf(note, sizeof note,
                      "no CRS, but the coordinates are plainly degrees (cells of %.3g, centre %.4f, %.4f): read as "
                      "WGS 84 longitude and latitude",
                      std::abs(r.gt[1]), r.centre_x, r.centre_y);
        r.warnings.push_back(r.file + ": crs: " + note);
    } else if (srs && r.georeferenced) {
        char* wkt = nullptr;
        if (srs->exportToWkt(&wkt) == OGRERR_NONE && wkt)
            r.crs_wkt = wkt;
        CPLFree(wkt);
        r.crs_name = srs->GetName() ? srs->GetName() : "";
        if (srs->IsGeographic()) {
            r.geographic = true;
            const double degrees_per_unit = srs->GetAngularUnits() * 180.0 / M_PI;
            const double lat = r.centre_y * degrees_per_unit;
            if (!(std::abs(lat) <= 90.0))
                throw InputError(r.file, "geotransform", "centre latitude outside [-90, 90] degrees");
            const LocalScale s = wgs84_metres_per_degree(lat);
            mx = s.east * degrees_per_unit;
            my = s.north * degrees_per_unit;
        } else if (srs->IsProjected() || srs->IsLocal()) {
            mx = my = srs->GetLinearUnits();
        }
    }
    r.dx_m = std::abs(r.gt[1]) * mx;
    r.dy_m = std::abs(r.gt[5]) * my;
    if (!(r.dx_m > 0.0 && r.dy_m > 0.0 && std::isfinite(r.dx_m) && std::isfinite(r.dy_m)))
        throw InputError(r.file, "geotransform", "cell size in metres is zero or not finite");

    int has_scale = 0, has_offset = 0, has_nodata = 0;
    const double band_scale = r.band->GetScale(&has_scale), band_offset = r.band->GetOffset(&has_offset);
    const double unit = metres_per_unit_of_band(r.band, r.georeferenced ? srs : nullptr);
    if (!(options.exaggeration > 0.0) || !std::isfinite(options.exaggeration))
        throw InputError(r.file, "exaggeration", "must be a finite number > 0");
    r.exaggeration = options.exaggeration;
    const double scale = options.vertical_scale * options.exaggeration;
    r.z_scale = scale * (has_scale ? band_scale : 1.0) * unit;
    r.z_offset = options.vertical_offset * options.exaggeration + scale * (has_offset ? band_offset : 0.0) * unit;
    if (!std::isfinite(r.z_scale) || !std::isfinite(r.z_offset))
        throw InputError(r.file, "vertical_scale", "vertical scale or offset is not finite");
    const double nd = r.band->GetNoDataValue(&has_nodata);
    if (has_nodata)
        r.nodata = nd;
    r.nodata_float32 = r.band->GetRasterDataType() == GDT_Float32;
    CPLErrorReset();
    return r;
}

// Bytes the loader holds per cell: the raw read (8), the heights (8) and the mask (1).
constexpr double kBytesPerCell = 17.0;

void check_limit(const Raster& r, const DemOptions& options)
{
    const double cells = double(r.width) * double(r.height);
    if (cells > double(options.max_cells)) {
        const double mib = cells * kBytesPerCell / (1024.0 * 1024.0);
        char reason[256];
        std::snprintf(reason, sizeof reason,
                      "%d x %d = %.0f cells would need %.0f MiB; the limit is %zu cells (DemOptions::max_cells)",
                      r.width, r.height, cells, mib, options.max_cells);
        throw LimitError(r.file, "size", reason);
    }
    // GDAL decodes a whole block (tile or strip) at a time, with every band's samples where they
    // are interleaved by pixel: a raster of a few cells may declare a block of gigabytes, which
    // a corrupt or hostile file then makes GDAL allocate and fill.
    int bx = 0, by = 0;
    r.band->GetBlockSize(&bx, &by);
    const char* interleave = r.ds->GetMetadataItem("INTERLEAVE", "IMAGE_STRUCTURE");
    const double samples = interleave && EQUAL(interleave, "PIXEL") ? r.ds->GetRasterCount() : 1.0;
    const double block_cells = double(bx) * double(by) * samples;
    if (block_cells > double(options.max_cells)) {
        const double mib = block_cells * GDALGetDataTypeSizeBytes(r.band->GetRasterDataType()) / (1024.0 * 1024.0);
        char reason[256];
        std::snprintf(reason, sizeof reason,
                      "one block (tile or strip) of %d x %d cells x %.0f bands would need %.0f MiB to decode; the "
                      "limit is %zu cells (DemOptions::max_cells)",
                      bx, by, samples, mib, options.max_cells);
        throw LimitError(r.file, "block size", reason);
    }
}

// Raw band values in source order (row 0 first) and the validity mask in local order.
struct Samples {
    std::vector<double> z;  // local order: j = 0 south, i = 0 west; already in metres
    std::vector<std::uint8_t> valid;
    std::size_t nodata_count = 0;
    std::vector<std::string> warnings;
};

std::string cells_text(std::size_t n) { return std::to_string(n) + (n == 1 ? " cell" : " cells"); }

Samples read_samples(const Raster& r, const GdalErrors& errors)
{
    const std::size_t w = std::size_t(r.width), h = std::size_t(r.height);
    std::vector<double> raw(w * h);
    if (r.band->RasterIO(GF_Read, 0, 0, r.width, r.height, raw.data(), r.width, r.height, GDT_Float64, 0, 0, nullptr) !=
        CE_None)
        throw InputError(r.file, "data",
                         "cannot read the raster values (truncated or corrupt file?)" + errors.suffix());
    Samples s;
    s.z.resize(w * h);
    s.valid.resize(w * h);
    std::size_t fills = 0, out_of_range = 0, finite = 0;
    double outlier = 0.0;  // one height outside the range, for the message
    const double lo = lowest_elevation_m * r.exaggeration, hi = highest_elevation_m * r.exaggeration;
    for (std::size_t row = 0; row < h; ++row) {
        const std::size_t j = r.flip_rows ? h - 1 - row : row;
        for (std::size_t col = 0; col < w; ++col) {
            const std::size_t i = r.flip_cols ? w - 1 - col : col;
            const double v = raw[row * w + col];
            bool ok = std::isfinite(v);
            if (ok && r.nodata)
                ok = r.nodata_float32 ? float(v) != float(*r.nodata) : v != *r.nodata;
            const double z = r.z_offset + r.z_scale * v;
            ok = ok && std::isfinite(z);
            if (ok) {
                ++finite;
                if (undeclared_fill_value(v)) {
                    ok = false;
                    ++fills;
                } else if (r.georeferenced && !(z >= lo && z <= hi)) {
                    ok = false;
                    ++out_of_range;
                    outlier = z / r.exaggeration;
                }
            }
            s.z[j * w + i] = ok ? z : 0.0;
            s.valid[j * w + i] = ok ? 1 : 0;
            s.nodata_count += ok ? 0 : 1;
        }
    }
    char height[64];
    std::snprintf(height, sizeof height, "%.6g m", outlier);
    // Mostly outside the Earth's range: the units are wrong, not a few cells.
    if (out_of_range > 0 && 2 * out_of_range > finite - fills)
        throw InputError(r.file, "vertical_scale",
                         cells_text(out_of_range) + " of " + std::to_string(finite - fills) +
                             " lie outside -12 km..+9 km (e.g. " + height +
                             "): give the metres per raster unit (/terrain/vertical_scale)");
    if (s.nodata_count == w * h)
        throw InputError(r.file, "nodata", "every cell is nodata (or NaN/Inf): no elevation to load");
    if (fills > 0)
        s.warnings.push_back(r.file + ": nodata: " + cells_text(fills) + (fills == 1 ? " holds" : " hold") +
                             " an undeclared fill value (-3.4e38, -32768, -32767 or -9999): treated as voids");
    if (out_of_range > 0)
        s.warnings.push_back(r.file + ": nodata: " + cells_text(out_of_range) + (out_of_range == 1 ? " lies" : " lie") +
                             " outside -12 km..+9 km (e.g. " + height + "): treated as voids");
    return s;
}

}  // namespace

Heightfield load_dem(const fs::path& path, const DemOptions& options)
{
    const GdalErrors errors;
    const Raster r = open_raster(path, options, errors);
    check_limit(r, options);
    if (r.width < 2 || r.height < 2)
        throw InputError(r.file, "size",
                         "a terrain needs at least 2 x 2 cells, this raster has " + std::to_string(r.width) + " x " +
                             std::to_string(r.height));
    Samples s = read_samples(r, errors);

    Heightfield hf;
    hf.nx = r.width;
    hf.ny = r.height;
    hf.dx = r.dx_m;
    hf.dy = r.dy_m;
    // Local origin at the data's centre (DESIGN "world frame").
    hf.x0 = -0.5 * (hf.nx - 1) * hf.dx;
    hf.y0 = -0.5 * (hf.ny - 1) * hf.dy;
    hf.z = std::move(s.z);
    hf.valid = std::move(s.valid);
    hf.warnings = r.warnings;
    hf.warnings.insert(hf.warnings.end(), s.warnings.begin(), s.warnings.end());
    if (s.nodata_count > 0)
        fill_voids_smoothly(hf.nx, hf.ny, hf.z, hf.valid);

    GeoReference& g = hf.georef;
    g.crs_wkt = r.crs_wkt;
    g.geographic = r.geographic;
    g.origin_x = r.centre_x;
    g.origin_y = r.centre_y;
    std::copy(r.gt, r.gt + 6, g.geotransform);
    g.source_width = r.width;
    g.source_height = r.height;
    return hf;
}

DemInfo dem_info(const fs::path& path, const DemOptions& options)
{
    const GdalErrors errors;
    const Raster r = open_raster(path, options, errors);
    check_limit(r, options);
    const Samples s = read_samples(r, errors);

    DemInfo info;
    info.driver = r.driver;
    info.width = r.width;
    info.height = r.height;
    info.cell_dx_m = r.dx_m;
    info.cell_dy_m = r.dy_m;
    info.extent_x_m = r.width * r.dx_m;
    info.extent_y_m = r.height * r.dy_m;
    info.z_min = INFINITY;
    info.z_max = -INFINITY;
    for (std::size_t k = 0; k < s.z.size(); ++k)
        if (s.valid[k]) {
            info.z_min = std::min(info.z_min, s.z[k]);
            info.z_max = std::max(info.z_max, s.z[k]);
        }
    info.nodata_count = s.nodata_count;
    info.geographic = r.geographic;
    info.crs_name = r.crs_name;
    info.centre_x = r.centre_x;
    info.centre_y = r.centre_y;
    info.warnings = r.warnings;
    info.warnings.insert(info.warnings.end(), s.warnings.begin(), s.warnings.end());
    return info;
}

Heightfield resample(const Heightfield& source, int nx, int ny)
{
    if (source.nx < 2 || source.ny < 2 || source.size() != std::size_t(source.nx) * std::size_t(source.ny))
        throw InputError("", "source", "resample needs a heightfield of at least 2 x 2 samples");
    if (nx < 2 || ny < 2)
        throw InputError("", "nx, ny", "resample needs at least 2 x 2 samples");
    const double cells = double(nx) * double(ny);
    if (cells > double(DemOptions{}.max_cells))
        throw LimitError("", "nx, ny",
                         std::to_string(nx) + " x " + std::to_string(ny) + " samples exceed the limit of " +
                             std::to_string(DemOptions{}.max_cells) + " cells (DemOptions::max_cells)");
    Heightfield out;
    out.nx = nx;
    out.ny = ny;
    out.x0 = source.x0;
    out.y0 = source.y0;
    out.dx = (source.x_max() - source.x0) / (nx - 1);
    out.dy = (source.y_max() - source.y0) / (ny - 1);
    out.georef = source.georef;
    out.z.resize(std::size_t(nx) * ny);
    out.valid.resize(out.z.size());
    const bool has_mask = source.valid.size() == source.size();
    for (int j = 0; j < ny; ++j) {
        // Source grid coordinate, clamped so the last sample lands exactly on the last cell.
        const double fy = std::min(double(j) * (source.ny - 1) / (ny - 1), double(source.ny - 1));
        const int sj = std::min(int(fy), source.ny - 2);
        const double ty = fy - sj;
        for (int i = 0; i < nx; ++i) {
            const double fx = std::min(double(i) * (source.nx - 1) / (nx - 1), double(source.nx - 1));
            const int si = std::min(int(fx), source.nx - 2);
            const double tx = fx - si;
            const double z = (1 - ty) * ((1 - tx) * source.at(si, sj) + tx * source.at(si + 1, sj)) +
                ty * ((1 - tx) * source.at(si, sj + 1) + tx * source.at(si + 1, sj + 1));
            const std::size_t k = std::size_t(j) * nx + i;
            out.z[k] = z;
            // A sample is as valid as the source sample nearest to it.
            const int ni = si + (tx >= 0.5 ? 1 : 0), nj = sj + (ty >= 0.5 ? 1 : 0);
            out.valid[k] = has_mask ? source.valid[std::size_t(nj) * source.nx + ni] : 1;
        }
    }
    return out;
}

}  // namespace kiri::geometry
