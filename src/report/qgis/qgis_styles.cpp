#include <cstdio>
#include "report/qgis/qgis_styles.hpp"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <filesystem>

#include <shoal/util/error.hpp>

namespace shoal::report {

namespace detail {
std::string_view style_qml(std::string_view name);  // qgis_styles_data.cpp, generated
}

std::string_view layer_style(std::string_view layer) { return detail::style_qml(layer); }

bool is_shoal_sidecar(const std::string& path) {
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) return false;  // a FIFO or a device is never opened (a FIFO would wait for a writer)
    std::string head;
    if (std::FILE* f = std::fopen(path.c_str(), "rb")) {
        head.resize(4096);
        head.resize(std::fread(head.data(), 1, head.size(), f));
        std::fclose(f);
    }
    return head.find(sidecar_mark) != std::string::npos;
}

std::optional<StagedOutput> stage_sidecar_style(const std::string& qml_path, std::string_view layer, std::string& warning) {
    const std::filesystem::path p(qml_path);
    std::error_code ec;
    if (std::filesystem::exists(p, ec)) {
        if (!is_shoal_sidecar(p.string())) {
            // (Built by appending to a new string: `"'" + text` inserts at a string's front and
            // assign() replaces, where GCC 12 at -O3 warns -Wrestrict, a false positive.)
            std::string w(1, '\'');
            w += p.string();
            w += "' exists and was not written by shoal: left as it is, so the report has no QGIS style beside it "
                 "(move that file, or write the report elsewhere)";
            warning = std::move(w);
            return std::nullopt;
        }
    }
    // The mark goes after the DOCTYPE line (an XML comment: QGIS reads the style as before).
    std::string style(layer_style(layer));
    const std::size_t eol = style.find('\n');
    style.insert(eol == std::string::npos ? 0 : eol + 1, std::string(sidecar_mark) + "\n");
    StagedOutput out(p.string());
    out.write(style);
    return out;
}

namespace {

std::string quote(std::string_view s) {
    std::string out = "'";
    for (char c : s) {
        if (c == '\'') out += '\'';
        out += c;
    }
    return out + "'";
}

void exec(GDALDataset& ds, const std::string& sql) {
    CPLErrorReset();
    OGRLayer* result = ds.ExecuteSQL(sql.c_str(), nullptr, nullptr);
    if (result) ds.ReleaseResultSet(result);
    if (CPLGetLastErrorType() == CE_Failure)
        throw LibraryError("writing QGIS styles into the GeoPackage: " + std::string(CPLGetLastErrorMsg()));
}

}  // namespace

void add_layer_styles(GDALDataset& ds) {
    // The table QGIS reads (and writes) styles from; QGIS 3.22 matches f_table_schema = '',
    // f_table_name and f_geometry_column exactly, preferring useAsDefault then update_time.
    exec(ds,
         "CREATE TABLE layer_styles (id INTEGER PRIMARY KEY AUTOINCREMENT, f_table_catalog TEXT(256), "
         "f_table_schema TEXT(256), f_table_name TEXT(256), f_geometry_column TEXT(256), styleName TEXT(30), "
         "styleQML TEXT, styleSLD TEXT, useAsDefault BOOLEAN, description TEXT, owner TEXT(30), ui TEXT(30), "
         "update_time DATETIME DEFAULT (strftime('%Y-%m-%dT%H:%M:%fZ','now')))");
    // Listed in gpkg_contents as a table of attributes (as QGIS does when it saves a style):
    // a GeoPackage that has other attribute tables lists only those to OGR, and QGIS finds
    // `layer_styles` through OGR.
    exec(ds,
         "INSERT INTO gpkg_contents (table_name, data_type, identifier, description, last_change) "
         "VALUES ('layer_styles', 'attributes', 'layer_styles', 'QGIS styles of the layers', '2000-01-01T00:00:00.000Z')");
    for (const char* layer : {"events", "tracks", "hulls", "encounters", "breaches", "poses", "coast", "learned"}) {
        OGRLayer* l = ds.GetLayerByName(layer);
        if (!l) continue;
        const char* geom = l->GetGeometryColumn();
        exec(ds, "INSERT INTO layer_styles (f_table_catalog, f_table_schema, f_table_name, f_geometry_column, styleName, "
                 "styleQML, styleSLD, useAsDefault, description, owner, ui, update_time) VALUES ('', '', " +
                     quote(layer) + ", " + quote(geom && *geom ? geom : "geom") + ", " + quote(std::string("shoal ") + layer) +
                     ", " + quote(layer_style(layer)) + ", '', 1, 'shoal report style', '', NULL, '2026-01-01T00:00:00.000Z')");
    }
}

}  // namespace shoal::report
