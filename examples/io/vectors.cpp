// SPDX-License-Identifier: Apache-2.0
#include "io/vectors.hpp"
#include "io/gdal_session.hpp"
#include "io/ogr_util.hpp"

#include <cmath>
#include <cstdlib>
#include <stdexcept>

#include <lidarfx/core/error.hpp>

#ifdef LIDARFX_HAVE_GDAL
#include <cpl_conv.h>
#include <cpl_error.h>
#include <gdal_priv.h>
#include <ogr_spatialref.h>
#include <ogrsf_frmts.h>

#include <algorithm>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#endif

namespace lidarfx::io {

#ifdef LIDARFX_HAVE_GDAL

namespace {

struct dataset_closer {
    void operator()(GDALDataset* ds) const { GDALClose(GDALDataset::ToHandle(ds)); }
};
using dataset_ptr = std::unique_ptr<GDALDataset, dataset_closer>;

// The CRS `text` names (WKT, "EPSG:n", a URN), x = easting or longitude; false when OGR does not understand it.
bool parse_crs(const std::string& text, OGRSpatialReference& srs)
{
    if (text.empty() || srs.SetFromUserInput(text.c_str()) != OGRERR_NONE) return false;
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    return true;
}

// The first 60 characters of a CRS text, for messages.
std::string crs_head(const std::string& crs)
{
    return crs.size() <= 60 ? crs : crs.substr(0, 60) + "...";
}

// The footprints of one OGR layer, with the checks and the memory estimate of the GeoJSON reader.
class ogr_footprint_reader {
public:
    ogr_footprint_reader(const std::string& path, const footprint_read_options& opt)
        : path_(path), opt_(opt), budget_(footprint_memory_budget(opt))
    {
    }

    footprint_collection read(OGRLayer& layer)
    {
        const OGRSpatialReference* srs = layer.GetSpatialRef();
        // GeoPackage's placeholders for "no CRS" (srs_id -1 and 0) and any engineering CRS: none to place by.
        const char* srs_name = srs != nullptr ? srs->GetName() : nullptr;
        if (srs != nullptr && !srs->IsLocal() &&
            !(srs_name != nullptr && std::string(srs_name).rfind("Undefined geographic SRS", 0) == 0)) {
            char* wkt = nullptr;
            if (srs->exportToWkt(&wkt) == OGRERR_NONE && wkt != nullptr) out_.crs = wkt;
            CPLFree(wkt);
        }
        const std::string field = opt_.id_field.empty() ? "building_id" : opt_.id_field;
        const OGRFeatureDefn* defn = layer.GetLayerDefn();
        field_ = defn->GetFieldIndex(field.c_str());
        if (field_ < 0 && field.size() > 10)  // a Shapefile (dBase) keeps the first 10 characters of a name
            field_ = defn->GetFieldIndex(field.substr(0, 10).c_str());
        if (field_ < 0 && !opt_.id_field.empty()) {
            std::string names;
            for (int i = 0; i < defn->GetFieldCount(); ++i)
                names += std::string(i ? ", " : "") + defn->GetFieldDefn(i)->GetNameRef();
            throw invalid_input(path_ + ": no field \"" + field + "\" for the footprints' ids (its fields: " +
                                (names.empty() ? std::string("none") : names) + ")");
        }
        if (field_ >= 0) {
            const OGRFieldType type = defn->GetFieldDefn(field_)->GetType();
            if (type != OFTInteger && type != OFTInteger64 && type != OFTReal)
                throw invalid_input(path_ + ": field \"" + field + "\" holds " + OGRFieldDefn::GetFieldTypeName(type) +
                                    " values, not integers; name an integer field for the footprints' ids");
        }
        field_name_ = field;
        layer.ResetReading();
        for (OGRFeatureUniquePtr f(layer.GetNextFeature()); f; f.reset(layer.GetNextFeature())) {
            feature(*f);
            ++feature_;
        }
        if (field_ < 0) {
            out_.notes.push_back(
                detail::concat(path_, ": no field \"building_id\": the footprints' ids are their feature ids (FID",
                               fid_offset_ ? " + 1, as this source numbers its features from 0" : "",
                               "); name a field to use instead"));
        }
        out_.peak_bytes = static_cast<std::uint64_t>(peak_);
        return std::move(out_);
    }

private:
    void charge(double transient)
    {
        const double need = kept_bytes_ + transient;
        peak_ = std::max(peak_, need);
        if (budget_ > 0 && need > static_cast<double>(budget_)) {
            throw invalid_input(detail::concat(path_, ": reading the footprints needs more than ",
                                               footprint_size_text(need), " (", kept_vertices_,
                                               " vertices kept by feature ", feature_, "), over the memory budget of ",
                                               footprint_size_text(static_cast<double>(budget_)),
                                               "; split the file into smaller ones or use a larger --memory"));
        }
    }

    // The feature's id as written, checked: an integer in 1 .. 2^31 - 1.
    std::int32_t id_of(OGRFeature& f, const std::string& where)
    {
        double id = 0;
        std::string token;
        if (field_ < 0) {
            const GIntBig fid = f.GetFID();
            if (feature_ == 0 && fid == 0) fid_offset_ = 1;
            id = static_cast<double>(fid) + static_cast<double>(fid_offset_);
            token = std::to_string(fid + fid_offset_) + " (FID " + std::to_string(fid) + ")";
        } else {
            if (!f.IsFieldSetAndNotNull(field_))
                throw invalid_input(where + ": no integer \"" + field_name_ + "\" value (every footprint needs one)");
            if (f.GetFieldDefnRef(field_)->GetType() == OFTReal) {
                id = f.GetFieldAsDouble(field_);
                std::ostringstream s;
                s << std::setprecision(17) << id;
                token = s.str();
            } else {
                const GIntBig v = f.GetFieldAsInteger64(field_);
                id = static_cast<double>(v);
                token = std::to_string(v);
            }
        }
        if (!std::isfinite(id) || id != std::floor(id) || id < 1 || id > 2147483647.0)
            throw invalid_input(detail::concat(where, ": ", field_ < 0 ? std::string("the id ") : field_name_ + " ",
                                               token, " is not an integer in 1 .. 2147483647"));
        const auto building = static_cast<std::int32_t>(id);
        if (const auto [it, fresh] = first_feature_of_.emplace(building, feature_); !fresh)
            throw invalid_input(detail::concat(where, ": building_id ", building, " is used by feature ", it->second,
                                               " too; ids must be unique"));
        return building;
    }

    // One ring as lidarfx keeps it (closed), its coordinates checked.
    std::vector<std::array<double, 2>> ring_of(const OGRLinearRing& ring, const std::string& at, std::size_t& vertex)
    {
        const int n = ring.getNumPoints();
        if (n < 4) throw invalid_input(at + ": every ring needs at least 4 positions (closed, 3 distinct corners)");
        std::vector<std::array<double, 2>> r;
        r.reserve(static_cast<std::size_t>(n) + 1);
        for (int i = 0; i < n; ++i, ++vertex) {
            const double xy[2] = {ring.getX(i), ring.getY(i)};
            for (int axis = 0; axis < 2; ++axis) {
                if (!(std::abs(xy[axis]) <= footprint_max_abs_coordinate)) {
                    throw invalid_input(detail::concat(at, ": coordinate ", axis == 0 ? "x" : "y", " = ", xy[axis],
                                                       " of vertex ", vertex,
                                                       " is beyond +-1e9, the largest magnitude a footprint "
                                                       "coordinate may have (units of the file's CRS)"));
                }
            }
            r.push_back({xy[0], xy[1]});
        }
        if (r.front() != r.back()) r.push_back(r.front());
        return r;
    }

    void feature(OGRFeature& f)
    {
        const std::string where = detail::concat(path_, ": feature ", feature_);
        const std::int32_t building = id_of(f, where);
        const std::string at = detail::concat(where, " (building_id ", building, ")");
        const OGRGeometry* g = f.GetGeometryRef();
        if (g == nullptr) throw invalid_input(at + ": no Polygon or MultiPolygon geometry");
        const OGRwkbGeometryType type = wkbFlatten(g->getGeometryType());
        if (type != wkbPolygon && type != wkbMultiPolygon)
            throw invalid_input(at + ": geometry type " + g->getGeometryName() + " is not Polygon or MultiPolygon");
        if (g->IsEmpty())
            throw invalid_input(at + (type == wkbMultiPolygon ? ": an empty MultiPolygon"
                                                              : ": a Polygon needs at least its exterior ring"));
        std::vector<const OGRPolygon*> polygons;
        if (type == wkbPolygon)
            polygons.push_back(g->toPolygon());
        else
            for (const OGRPolygon* p : *g->toMultiPolygon()) polygons.push_back(p);
        double vertices = 0;
        for (const OGRPolygon* p : polygons)
            for (const OGRLinearRing* ring : *p) vertices += ring->getNumPoints();
        charge(48.0 * vertices);  // its coordinates, its rings and the validity check's copy

        footprint fp{building, {}, feature_};
        std::size_t vertex = 0;
        for (const OGRPolygon* p : polygons) {
            if (p->IsEmpty())
                throw invalid_input(at + ": an empty ring or part (every ring needs at least 4 positions)");
            polygon part;
            for (const OGRLinearRing* ring : *p) part.rings.push_back(ring_of(*ring, at, vertex));
            fp.parts.push_back(std::move(part));
        }
        keep_footprint(std::move(fp), at, out_, kept_bytes_, kept_vertices_);
    }

    const std::string& path_;
    const footprint_read_options& opt_;
    std::uint64_t budget_;
    int field_ = -1;
    std::string field_name_;
    GIntBig fid_offset_ = 0;
    std::size_t feature_ = 0, kept_vertices_ = 0;
    double kept_bytes_ = 0, peak_ = 0;
    std::map<std::int32_t, std::size_t> first_feature_of_;
    footprint_collection out_;
};

}  // namespace

bool vectors_available() noexcept
{
    return true;
}

footprint_collection read_footprints_ogr(const std::string& path, const footprint_read_options& opt)
{
    register_gdal_drivers();
    quiet_gdal quiet;
    dataset_ptr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (!ds) throw std::runtime_error(path + ": cannot open the footprint file as vectors" + gdal_message());
    if (ds->GetLayerCount() < 1) throw invalid_input(path + ": holds no vector layer of footprints");
    OGRLayer* layer = ds->GetLayer(0);
    footprint_collection c = ogr_footprint_reader(path, opt).read(*layer);
    if (ds->GetLayerCount() > 1) {
        c.notes.push_back(detail::concat(path, ": holds ", ds->GetLayerCount(), " layers; the footprints are those of ",
                                         "the first, ", layer->GetName()));
    }
    return c;
}

int epsg_of_crs(const std::string& crs)
{
    register_gdal_drivers();
    quiet_gdal quiet;
    OGRSpatialReference srs;
    if (!parse_crs(crs, srs)) return 0;
    const auto code_of = [](const OGRSpatialReference& s) {
        const char* name = s.GetAuthorityName(nullptr);
        const char* code = s.GetAuthorityCode(nullptr);
        return name != nullptr && code != nullptr && EQUAL(name, "EPSG") ? std::atoi(code) : 0;
    };
    if (const int code = code_of(srs)) return code;
    if (srs.AutoIdentifyEPSG() == OGRERR_NONE)
        if (const int code = code_of(srs)) return code;
    int n = 0;
    int* confidence = nullptr;
    OGRSpatialReferenceH* matches = srs.FindMatches(nullptr, &n, &confidence);
    int code = 0;
    if (n > 0 && confidence != nullptr && confidence[0] == 100)
        code = code_of(*OGRSpatialReference::FromHandle(matches[0]));
    OSRFreeSRSArray(matches);
    CPLFree(confidence);
    return code;
}

bool same_crs(const std::string& a, const std::string& b)
{
    if (a == b) return true;
    register_gdal_drivers();
    quiet_gdal quiet;
    OGRSpatialReference sa, sb;
    if (!parse_crs(a, sa) || !parse_crs(b, sb)) return false;
    for (OGRSpatialReference* srs : {&sa, &sb}) {
        if (srs->IsCompound()) srs->StripVertical();  // footprints are 2D: the horizontal CRS places them
    }
    if (sa.IsSame(&sb)) return true;
    const int ea = epsg_of_crs(a);
    return ea > 0 && ea == epsg_of_crs(b);
}

void reproject_footprints(footprint_collection& c, const std::string& from, const std::string& to,
                          const std::string& source)
{
    register_gdal_drivers();
    quiet_gdal quiet;
    OGRSpatialReference a, b;
    if (!parse_crs(from, a))
        throw invalid_input(source + ": the footprints' CRS is not one OGR understands: " + crs_head(from));
    if (!parse_crs(to, b))
        throw invalid_input(source + ": the survey's CRS is not one OGR understands: " + crs_head(to));
    for (OGRSpatialReference* srs : {&a, &b}) {
        if (!srs->IsCompound()) continue;
        srs->StripVertical();  // footprints are 2D: the horizontal CRS places them
        srs->SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    }
    const std::unique_ptr<OGRCoordinateTransformation> ct(OGRCreateCoordinateTransformation(&a, &b));
    if (!ct) {
        throw invalid_input(source + ": no transformation from the footprints' CRS (" + crs_head(from) +
                            ") to the survey's" + gdal_message());
    }
    std::vector<footprint> kept;
    for (footprint& fp : c.footprints) {
        for (polygon& p : fp.parts) {
            for (auto& ring : p.rings) {
                std::vector<double> x(ring.size()), y(ring.size());
                for (std::size_t i = 0; i < ring.size(); ++i) {
                    x[i] = ring[i][0];
                    y[i] = ring[i][1];
                }
                std::vector<int> ok(ring.size(), 0);
                if (!ct->Transform(static_cast<int>(ring.size()), x.data(), y.data(), nullptr, ok.data()) ||
                    std::find(ok.begin(), ok.end(), 0) != ok.end()) {
                    throw invalid_input(
                        detail::concat(source, ": feature ", fp.feature, " (building_id ", fp.building_id,
                                       "): a vertex cannot be transformed to the survey's CRS", gdal_message()));
                }
                for (std::size_t i = 0; i < ring.size(); ++i) ring[i] = {x[i], y[i]};
            }
        }
        std::string problem;
        try {
            problem = footprint_geometry_problem(fp);
        } catch (const std::exception& e) {
            problem = std::string("the polygon checks failed: ") + e.what();
        }
        if (!problem.empty()) {
            c.problems.push_back({fp.building_id, fp.feature, "after reprojection to the survey's CRS: " + problem});
            continue;
        }
        orient_footprint(fp);
        kept.push_back(std::move(fp));
    }
    c.footprints = std::move(kept);
}

void write_geopackage_layers(const std::string& path, const std::vector<geopackage_layer_source>& layers,
                             const std::string& crs_wkt, int epsg, const char* fn)
{
    // Per layer, fields in the order they first appear, typed by their first non-null value.
    std::vector<std::vector<std::pair<std::string, OGRFieldType>>> fields(layers.size());
    std::vector<std::map<std::string, std::size_t>> field_index(layers.size());
    for (std::size_t l = 0; l < layers.size(); ++l) {
        for (std::size_t f = 0; f < layers[l].properties.size(); ++f) {
            std::set<std::string> names;
            for (const auto& [name, value] : *layers[l].properties[f]) {
                if (!names.insert(name).second)
                    throw invalid_input(detail::concat(fn, ": feature ", f, " has property '", name, "' twice"));
                const auto [it, fresh] = field_index[l].emplace(name, fields[l].size());
                if (fresh) fields[l].emplace_back(name, OFTString);
                OGRFieldType& type = fields[l][it->second].second;
                if (fresh || type == OFTString) {
                    const auto& v = value.value();
                    if (std::holds_alternative<bool>(v))
                        type = OFTInteger;
                    else if (std::holds_alternative<std::int64_t>(v) || std::holds_alternative<std::uint64_t>(v))
                        type = OFTInteger64;
                    else if (std::holds_alternative<double>(v))
                        type = OFTReal;
                }
            }
        }
    }

    register_gdal_drivers();
    quiet_gdal quiet;  // the GPKG driver warns about the temporary name's extension
    // The file's only time stamp (gpkg_contents.last_change) fixed, so that the same run writes the same bytes.
    struct fixed_date {
        fixed_date() { CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", "1970-01-01T00:00:00.000Z"); }
        ~fixed_date() { CPLSetThreadLocalConfigOption("OGR_CURRENT_DATE", nullptr); }
        fixed_date(const fixed_date&) = delete;
        fixed_date& operator=(const fixed_date&) = delete;
    } date;
    OGRSpatialReference srs;
    const bool has_crs = epsg > 0 ? srs.importFromEPSG(epsg) == OGRERR_NONE : parse_crs(crs_wkt, srs);
    if (!has_crs && (epsg > 0 || !crs_wkt.empty()))
        throw invalid_input(
            detail::concat(fn, ": the CRS is not one OGR understands (EPSG ", epsg, ", WKT ", crs_head(crs_wkt), ")"));
    if (!has_crs)  // GeoPackage's "Undefined cartesian SRS" (srs_id -1): coordinates without a CRS
        srs.SetFromUserInput(R"(LOCAL_CS["Undefined cartesian SRS",UNIT["metre",1]])");
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
    GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GPKG");
    if (driver == nullptr) throw std::runtime_error(path + ": this GDAL has no GeoPackage driver");
    dataset_ptr ds(driver->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr));
    if (!ds) throw std::runtime_error(path + ": cannot create the GeoPackage" + gdal_message());
    for (std::size_t l = 0; l < layers.size(); ++l) {
        const geopackage_layer_source& layer = layers[l];
        OGRLayer* out = ds->CreateLayer(layer.name.c_str(), &srs, layer.type, nullptr);
        if (out == nullptr) throw std::runtime_error(path + ": cannot create the layer " + layer.name + gdal_message());
        for (const auto& [name, type] : fields[l]) {
            OGRFieldDefn defn(name.c_str(), type);
            if (type == OFTInteger) defn.SetSubType(OFSTBoolean);
            if (out->CreateField(&defn) != OGRERR_NONE)
                throw std::runtime_error(path + ": cannot create the field " + name + gdal_message());
        }
        if (out->StartTransaction() != OGRERR_NONE)
            throw std::runtime_error(path + ": cannot start writing" + gdal_message());
        for (std::size_t f = 0; f < layer.properties.size(); ++f) {
            OGRFeature feature(out->GetLayerDefn());
            for (const auto& [name, value] : *layer.properties[f]) {
                const int i = static_cast<int>(field_index[l].at(name));
                const auto& v = value.value();
                if (const auto* b = std::get_if<bool>(&v))
                    feature.SetField(i, *b ? 1 : 0);
                else if (const auto* s = std::get_if<std::int64_t>(&v))
                    feature.SetField(i, static_cast<GIntBig>(*s));
                else if (const auto* u = std::get_if<std::uint64_t>(&v))
                    feature.SetField(i, static_cast<GIntBig>(*u));
                else if (const auto* d = std::get_if<double>(&v); d != nullptr && std::isfinite(*d))
                    feature.SetField(i, *d);
                else if (const auto* t = std::get_if<std::string>(&v))
                    feature.SetField(i, t->c_str());
                else
                    feature.SetFieldNull(i);  // null, NaN, infinite
            }
            feature.SetGeometryDirectly(layer.geometry(f).release());
            if (out->CreateFeature(&feature) != OGRERR_NONE) {
                throw std::runtime_error(
                    detail::concat(path, ": cannot write feature ", f, " of layer ", layer.name, gdal_message()));
            }
        }
        if (out->CommitTransaction() != OGRERR_NONE)
            throw std::runtime_error(path + ": cannot finish writing" + gdal_message());
    }
    CPLErrorReset();
    ds.reset();  // closes the file
    if (CPLGetLastErrorType() == CE_Failure || CPLGetLastErrorType() == CE_Fatal)
        throw std::runtime_error(path + ": cannot close the GeoPackage" + gdal_message());
}

void write_geopackage(const std::string& path, const std::string& layer, const std::vector<geojson_feature>& features,
                      const std::string& crs_wkt, int epsg)
{
    constexpr const char* fn = "write_geopackage";
    detail::require(epsg >= 0, fn, "epsg", ">= 0", epsg);
    std::vector<std::vector<geo_ring>> rings;  // checked before the file exists
    rings.reserve(features.size());
    for (std::size_t f = 0; f < features.size(); ++f) rings.push_back(checked_rings(features[f], f, fn));
    geopackage_layer_source source{layer, wkbPolygon, {}, nullptr};
    source.geometry = [&](std::size_t f) -> std::unique_ptr<OGRGeometry> {
        auto poly = std::make_unique<OGRPolygon>();
        for (const geo_ring& ring : rings[f]) {
            auto r = std::make_unique<OGRLinearRing>();
            r->setNumPoints(static_cast<int>(ring.size()), FALSE);
            for (std::size_t k = 0; k < ring.size(); ++k) r->setPoint(static_cast<int>(k), ring[k][0], ring[k][1]);
            poly->addRingDirectly(r.release());
        }
        return poly;
    };
    for (const geojson_feature& feature : features) source.properties.push_back(&feature.properties);
    write_geopackage_layers(path, {std::move(source)}, crs_wkt, epsg, fn);
}

#else  // without GDAL

bool vectors_available() noexcept
{
    return false;
}

footprint_collection read_footprints_ogr(const std::string& path, const footprint_read_options&)
{
    throw std::runtime_error(path + ": reading this footprint format needs OGR; " + vectors_rebuild_hint);
}

namespace {

// The EPSG code at the end of "EPSG:n", "urn:ogc:def:crs:EPSG::n" or "http://www.opengis.net/def/crs/EPSG/0/n".
int trailing_epsg(const std::string& crs)
{
    const std::size_t at = crs.find("EPSG");
    const std::size_t digits = crs.find_last_not_of("0123456789");
    if (at == std::string::npos || digits == std::string::npos || digits + 1 >= crs.size() || digits < at) return 0;
    return std::atoi(crs.c_str() + digits + 1);
}

}  // namespace

int epsg_of_crs(const std::string& crs)
{
    return trailing_epsg(crs);
}

bool same_crs(const std::string& a, const std::string& b)
{
    const int code = trailing_epsg(a);
    return a == b || (code > 0 && code == trailing_epsg(b));
}

void reproject_footprints(footprint_collection&, const std::string&, const std::string&, const std::string& source)
{
    throw std::runtime_error(source + ": reprojecting footprints needs OGR/PROJ; " + vectors_rebuild_hint);
}

void write_geopackage(const std::string& path, const std::string&, const std::vector<geojson_feature>&,
                      const std::string&, int)
{
    throw std::runtime_error(path + ": GeoPackage output needs OGR; " + vectors_rebuild_hint);
}

#endif

}  // namespace lidarfx::io
