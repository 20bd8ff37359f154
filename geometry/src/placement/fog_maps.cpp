// GDAL adapter of the fog maps: GDAL stays inside geometry/src, behind a small adapter, as CGAL
// and OpenSubdiv do.
#include "kiri/geometry/placement/fog_maps.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <mutex>

#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>

#include "kiri/geometry/core/error.hpp"
#include "kiri/geometry/placement/fog_placement.hpp"

namespace kiri::geometry {
namespace {

void register_gdal()
{
    static std::once_flag once;
    std::call_once(once, [] { GDALAllRegister(); });
}

// Silences GDAL's printing while alive and keeps its last failure for the exception.
struct QuietGdal {
    QuietGdal()
    {
        CPLPushErrorHandler(CPLQuietErrorHandler);
        CPLErrorReset();
    }
    ~QuietGdal() { CPLPopErrorHandler(); }
    QuietGdal(const QuietGdal&) = delete;
    QuietGdal& operator=(const QuietGdal&) = delete;
    static std::string last()
    {
        const char* m = CPLGetLastErrorMsg();
        return m && *m ? std::string(" (GDAL: ") + m + ")" : std::string();
    }
};

struct Close {
    void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using Dataset = std::unique_ptr<GDALDataset, Close>;

// Geotransform of the grid in the source's CRS, and whether rows/columns run against j/i.
struct Placement {
    double gt[6];
    bool flip_rows, flip_cols;
    std::string wkt;
};

Placement placement_of(const Heightfield& g)
{
    Placement p{};
    const GeoReference& r = g.georef;
    if (r.source_width < 2 || r.source_height < 2) {
        // No source raster: local metres, north up.
        const double gt[6] = {g.x0 - 0.5 * g.dx, g.dx, 0.0, g.y_max() + 0.5 * g.dy, 0.0, -g.dy};
        std::copy(gt, gt + 6, p.gt);
        p.flip_rows = true;
        p.flip_cols = false;
        return p;
    }
    std::copy(r.geotransform, r.geotransform + 6, p.gt);
    p.wkt = r.crs_wkt;
    p.flip_rows = r.geotransform[5] < 0.0;
    p.flip_cols = r.geotransform[1] < 0.0;
    if (g.nx != r.source_width || g.ny != r.source_height) {
        // Resampled over the same extent of sample centres (dem.hpp resample).
        const double px = r.geotransform[1] * (r.source_width - 1) / double(g.nx - 1);
        const double py = r.geotransform[5] * (r.source_height - 1) / double(g.ny - 1);
        p.gt[0] = r.geotransform[0] + 0.5 * r.geotransform[1] - 0.5 * px;
        p.gt[3] = r.geotransform[3] + 0.5 * r.geotransform[5] - 0.5 * py;
        p.gt[1] = px;
        p.gt[5] = py;
    }
    return p;
}

std::size_t source_index(const Placement& p, const Heightfield& g, int i, int j)
{
    const int row = p.flip_rows ? g.ny - 1 - j : j;
    const int col = p.flip_cols ? g.nx - 1 - i : i;
    return std::size_t(row) * g.nx + col;
}

}  // namespace

void write_geotiff_map(const std::filesystem::path& path, const Heightfield& g, const std::vector<double>& values,
                       const std::vector<std::uint8_t>& defined, double scale, const std::string& description,
                       const std::vector<std::pair<std::string, std::string>>& metadata)
{
    if (values.size() != g.size() || (!defined.empty() && defined.size() != g.size()))
        throw IoError(path.string(), "map", "values do not match the grid");
    register_gdal();
    const QuietGdal quiet;
    const Placement p = placement_of(g);
    std::vector<float> data(g.size());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t k = std::size_t(j) * g.nx + i;
            const double v = values[k] * scale;
            data[source_index(p, g, i, j)] =
                (defined.empty() || defined[k]) && std::isfinite(v) ? float(v) : float(kMapNodata);
        }
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
    if (!driver)
        throw IoError(path.string(), "map", "GDAL has no GTiff driver");
    char** options = nullptr;
    options = CSLSetNameValue(options, "COMPRESS", "DEFLATE");
    options = CSLSetNameValue(options, "PREDICTOR", "3");
    Dataset ds(driver->Create(path.c_str(), g.nx, g.ny, 1, GDT_Float32, options));
    CSLDestroy(options);
    if (!ds)
        throw IoError(path.string(), "map", "cannot create the GeoTIFF" + QuietGdal::last());
    double gt[6];
    std::copy(p.gt, p.gt + 6, gt);
    ds->SetGeoTransform(gt);
    if (!p.wkt.empty())
        ds->SetProjection(p.wkt.c_str());
    for (const auto& [name, value] : metadata)
        ds->SetMetadataItem(name.c_str(), value.c_str());
    GDALRasterBand* band = ds->GetRasterBand(1);
    band->SetNoDataValue(kMapNodata);
    band->SetDescription(description.c_str());
    band->SetUnitType("m");
    if (band->RasterIO(GF_Write, 0, 0, g.nx, g.ny, data.data(), g.nx, g.ny, GDT_Float32, 0, 0, nullptr) != CE_None)
        throw IoError(path.string(), "map", "cannot write the values" + QuietGdal::last());
    ds.reset();  // closing writes the file
    if (CPLGetLastErrorType() >= CE_Failure)
        throw IoError(path.string(), "map", "cannot write the GeoTIFF" + QuietGdal::last());
}

void write_mask_png(const std::filesystem::path& path, const Heightfield& g, const std::vector<std::uint8_t>& mask)
{
    if (mask.size() != g.size())
        throw IoError(path.string(), "mask", "the mask does not match the grid");
    register_gdal();
    const QuietGdal quiet;
    std::vector<std::uint8_t> data(g.size());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i)
            data[std::size_t(g.ny - 1 - j) * g.nx + i] = mask[std::size_t(j) * g.nx + i] ? 255 : 0;
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    GDALDriver* png = GetGDALDriverManager()->GetDriverByName("PNG");
    if (!mem || !png)
        throw IoError(path.string(), "mask", "GDAL has no PNG driver");
    Dataset src(mem->Create("", g.nx, g.ny, 1, GDT_Byte, nullptr));
    if (!src ||
        src->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, g.nx, g.ny, data.data(), g.nx, g.ny, GDT_Byte, 0, 0, nullptr) !=
            CE_None)
        throw IoError(path.string(), "mask", "cannot build the image" + QuietGdal::last());
    // No georeferencing in the PNG (no .aux.xml beside it): the mask is a plain picture.
    char** options = CSLSetNameValue(nullptr, "WORLDFILE", "NO");
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO");
    Dataset out(png->CreateCopy(path.c_str(), src.get(), FALSE, options, nullptr, nullptr));
    CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr);
    CSLDestroy(options);
    if (!out)
        throw IoError(path.string(), "mask", "cannot write the PNG" + QuietGdal::last());
}

std::vector<std::uint8_t> read_mask(const std::filesystem::path& path, const Heightfield& g, const std::string& label,
                                    const std::string& field)
{
    register_gdal();
    const QuietGdal quiet;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec))
        throw InputError(label, field, "no such mask file: " + path.string());
    Dataset ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds || ds->GetRasterCount() < 1)
        throw InputError(label, field, "not a raster GDAL can read: " + path.string() + QuietGdal::last());
    const int w = ds->GetRasterXSize(), h = ds->GetRasterYSize();
    if (w != g.nx || h != g.ny)
        throw InputError(label, field,
                         "the mask " + path.filename().string() + " is " + std::to_string(w) + " x " +
                             std::to_string(h) + " pixels, the terrain " + std::to_string(g.nx) + " x " +
                             std::to_string(g.ny) + " cells");
    std::vector<double> raw(std::size_t(w) * h);
    if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, w, h, raw.data(), w, h, GDT_Float64, 0, 0, nullptr) != CE_None)
        throw InputError(label, field, "cannot read the mask " + path.string() + QuietGdal::last());
    double gt[6] = {0, 1, 0, 0, 0, -1};
    const bool georeferenced = ds->GetGeoTransform(gt) == CE_None;
    const bool flip_rows = !georeferenced || gt[5] < 0.0, flip_cols = georeferenced && gt[1] < 0.0;
    std::vector<std::uint8_t> mask(g.size());
    for (int j = 0; j < g.ny; ++j)
        for (int i = 0; i < g.nx; ++i) {
            const std::size_t src = std::size_t(flip_rows ? g.ny - 1 - j : j) * g.nx + (flip_cols ? g.nx - 1 - i : i);
            mask[std::size_t(j) * g.nx + i] = raw[src] != 0.0 && std::isfinite(raw[src]);
        }
    return mask;
}

double terrain_latitude(const Heightfield& g, double fallback)
{
    const GeoReference& r = g.georef;
    if (r.crs_wkt.empty())
        return fallback;
    register_gdal();
    const QuietGdal quiet;
    OGRSpatialReference source, wgs84;
    if (source.importFromWkt(r.crs_wkt.c_str()) != OGRERR_NONE || wgs84.SetWellKnownGeogCS("WGS84") != OGRERR_NONE)
        return fallback;
    source.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    wgs84.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> t(OGRCreateCoordinateTransformation(&source, &wgs84));
    double x = r.origin_x, y = r.origin_y;
    if (!t || !t->Transform(1, &x, &y) || !(std::abs(y) <= 90.0))
        return fallback;
    return y;
}

}  // namespace kiri::geometry
