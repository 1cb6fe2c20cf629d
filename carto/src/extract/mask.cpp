#include "mask.hpp"

#include <gdal_alg.h>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <memory>

#include "../gdal_scope.hpp"

namespace carto::extraction {

NonRock non_rock_pieces(const Grid& g, const std::vector<char>& rock, const std::vector<float>& dem,
                        const std::vector<char>& inside_mask, bool eight) {
    std::vector<char> non_rock(g.size());
    for (std::size_t i = 0; i < g.size(); ++i) non_rock[i] = !rock[i];
    NonRock out;
    int n = 0;
    out.lab = components(g, non_rock, eight, n);
    out.size.assign(std::size_t(n), 0);
    out.open.assign(std::size_t(n), 0);
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c) {
            const std::size_t i = g.at(c, r);
            const int l = out.lab[i];
            if (l < 0) continue;
            ++out.size[l];
            if (c == 0 || r == 0 || c == g.w - 1 || r == g.h - 1 || std::isnan(dem[i]) ||
                (!inside_mask.empty() && !inside_mask[i]))
                out.open[l] = 1;
        }
    return out;
}

std::vector<char> rasterize_mask(const std::string& path, const Raster& grid) {
    const std::string what = "--mask '" + path + "'";
    if (!std::filesystem::exists(path)) throw Error(Code::InputMissing, what + ": no such file");
    register_gdal();
    const QuietGdal quiet;
    std::unique_ptr<GDALDataset> ds(GDALDataset::FromHandle(
        GDALOpenEx(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY, nullptr, nullptr, nullptr)));
    if (!ds) throw Error(Code::InputMissing, what + ": not a vector dataset OGR can read");
    OGRLayer* layer = nullptr;
    for (int i = 0; i < ds->GetLayerCount() && !layer; ++i) {
        const auto t = wkbFlatten(ds->GetLayer(i)->GetGeomType());
        if (t == wkbPolygon || t == wkbMultiPolygon) layer = ds->GetLayer(i);
    }
    if (!layer) throw Error(Code::BadLayer, what + ": no polygon layer");
    const OGRSpatialReference* srs = layer->GetSpatialRef();
    const char* srs_name = srs ? srs->GetName() : nullptr;
    if (!srs || srs->IsEmpty() ||
        (srs_name && std::string(srs_name).find("Undefined") != std::string::npos))
        throw Error(Code::NoCrs,
                    what + ": layer '" + std::string(layer->GetName()) + "' has no CRS");
    OGRSpatialReference src(*srs), dst;
    src.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    dst.importFromWkt(grid.crs_wkt.c_str());
    dst.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    std::unique_ptr<OGRCoordinateTransformation> ct;
    if (!src.IsSame(&dst)) {
        ct.reset(OGRCreateCoordinateTransformation(&src, &dst));
        if (!ct) throw Error(Code::NoCrs, what + ": cannot reproject the layer to the DEM's CRS");
    }
    std::vector<std::unique_ptr<OGRGeometry>> geoms;
    // An OSM land-cover layer (natural=* as a field, or in GDAL's other_tags): its bare rock only.
    const OGRFeatureDefn* defn = layer->GetLayerDefn();
    const int natural = defn->GetFieldIndex("natural"), other_tags = defn->GetFieldIndex("other_tags");
    auto is_rock = [&](OGRFeature& f) {
        if (natural >= 0) return f.IsFieldSetAndNotNull(natural) && std::string(f.GetFieldAsString(natural)) == "bare_rock";
        if (other_tags >= 0)
            return f.IsFieldSetAndNotNull(other_tags) &&
                   std::string(f.GetFieldAsString(other_tags)).find("\"natural\"=>\"bare_rock\"") != std::string::npos;
        return true;
    };
    layer->ResetReading();
    for (auto& f : *layer) {
        if (!f->GetGeometryRef() || !is_rock(*f)) continue;
        std::unique_ptr<OGRGeometry> g(f->GetGeometryRef()->clone());
        if (ct) g->transform(ct.get());
        geoms.push_back(std::move(g));
    }
    if (geoms.empty())
        throw Error(Code::BadLayer,
                    what + ": layer '" + std::string(layer->GetName()) + "' holds no polygon" +
                        (natural >= 0 || other_tags >= 0 ? " tagged natural=bare_rock" : ""));
    GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
    std::unique_ptr<GDALDataset> ras(
        mem->Create("", grid.width, grid.height, 1, GDT_Byte, nullptr));
    ras->SetGeoTransform(const_cast<double*>(grid.gt.data()));
    std::vector<OGRGeometryH> handles;
    std::vector<double> burn;
    for (auto& g : geoms) {
        handles.push_back(OGRGeometry::ToHandle(g.get()));
        burn.push_back(1.0);
    }
    int band = 1;
    if (GDALRasterizeGeometries(GDALDataset::ToHandle(ras.get()), 1, &band, int(handles.size()),
                                handles.data(), nullptr, nullptr, burn.data(), nullptr, nullptr,
                                nullptr) != CE_None)
        throw Error(Code::BadLayer, what + ": cannot rasterize the polygons");
    std::vector<char> out(std::size_t(grid.width) * grid.height);
    if (ras->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, grid.width, grid.height, out.data(),
                                        grid.width, grid.height, GDT_Byte, 0, 0) != CE_None)
        throw Error(Code::Failure, what + ": cannot read the rasterized mask");
    return out;
}

namespace {

// The disc of radius `rc` cells (at least the 4 neighbours).
std::vector<std::pair<int, int>> disc_of(int rc) {
    std::vector<std::pair<int, int>> disc;
    for (int dr = -rc; dr <= rc; ++dr)
        for (int dc = -rc; dc <= rc; ++dc)
            if (dr * dr + dc * dc <= rc * (rc + 1)) disc.push_back({dc, dr});
    return disc;
}

// `on` dilated (or eroded) by a disc. NoData counts as not rock when dilating and as rock
// when eroding; cells off the grid do not count.
std::vector<char> grow(const Grid& g, const std::vector<char>& on, const std::vector<float>& dem,
                       const std::vector<std::pair<int, int>>& disc, bool dilate) {
    std::vector<char> out(g.size());
    for (int r = 0; r < g.h; ++r)
        for (int c = 0; c < g.w; ++c) {
            bool any = false, all = true;
            for (auto [dc, dr] : disc) {
                if (!g.inside(c + dc, r + dr)) continue;
                const std::size_t j = g.at(c + dc, r + dr);
                const bool v = std::isnan(dem[j]) ? !dilate : on[j] != 0;
                any = any || v;
                all = all && v;
                if (dilate ? any : !all) break;
            }
            out[g.at(c, r)] = dilate ? any : all;
        }
    return out;
}

}  // namespace

void follow_terrain_edge(const Grid& g, std::vector<char>& rock, const std::vector<char>& fine, const std::vector<float>& dem,
                         int band) {
    if (band <= 0) return;
    const auto disc = disc_of(band);
    const std::vector<char> core = grow(g, rock, dem, disc, false);
    const std::vector<char> hull = grow(g, rock, dem, disc, true);
    for (std::size_t i = 0; i < g.size(); ++i) rock[i] = hull[i] && (core[i] || fine[i]);
}

void close_rock(const Grid& g, std::vector<char>& rock, const std::vector<float>& dem,
                const std::vector<char>& inside_mask, int rc, double cell_area, double keep_area) {
    const auto disc = disc_of(rc);
    std::vector<char> closed = grow(g, grow(g, rock, dem, disc, true), dem, disc, false);
    for (std::size_t i = 0; i < g.size(); ++i)
        rock[i] = closed[i] && !std::isnan(dem[i]) && (inside_mask.empty() || inside_mask[i]);
    // Specks: 4-connected rock pieces smaller than the minimum area.
    int n = 0;
    const std::vector<int> lab = components(g, rock, false, n);
    std::vector<std::size_t> size(std::size_t(n), 0);
    for (int l : lab)
        if (l >= 0) ++size[l];
    for (std::size_t i = 0; i < g.size(); ++i)
        if (lab[i] >= 0 && double(size[lab[i]]) * cell_area < keep_area) rock[i] = 0;
    // Gaps: non-rock pieces enclosed by rock, without NoData, below the area. 4-connected,
    // as the face outlines see them: a gap touching a bigger one (or the outside) only at a
    // cell's corner is a hole of its own in the face's polygon.
    const NonRock gaps = non_rock_pieces(g, rock, dem, inside_mask, false);
    for (std::size_t i = 0; i < g.size(); ++i) {
        const int l = gaps.lab[i];
        if (l >= 0 && !gaps.open[l] && double(gaps.size[l]) * cell_area < keep_area) rock[i] = 1;
    }
}

}  // namespace carto::extraction
