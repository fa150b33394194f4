// Tests of the .shoalgrid cache: save/load round trip, one clear InputError per kind of bad
// file, atomic saving, and load_or_build's reuse and rebuild decisions.

#include <shoal/grid/grid_cache.hpp>
#include <shoal/grid/grid_builder.hpp>

#include <gdal_priv.h>
#include <unistd.h>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <span>
#include <string>
#include <vector>

#include "test_support.hpp"
#include "util/fast_hash.hpp"
#include <shoal/util/error.hpp>

namespace {

namespace fs = std::filesystem;
using shoal::InputError;
using shoal::UsageError;
using shoal::geo::XY;
using shoal::grid::BuildRequest;
using shoal::grid::CoastGrid;
using shoal::grid::GridFile;
using shoal::grid::LoadReport;
using testing::AllOf;
using testing::HasSubstr;
using testing::ThrowsMessage;
namespace t = shoal::test;

/// Header layout from grid_cache.hpp: magic (8) | version u32 | byte-order mark u32 | payload
/// size u64 | XXH3 u64 | payload.
constexpr std::size_t version_offset = 8, size_offset = 16, header_size = 32;

std::vector<std::string> files_in(const fs::path& dir) {
    std::vector<std::string> out;
    for (const auto& e : fs::directory_iterator(dir)) out.push_back(e.path().filename().string());
    return out;
}

class GridCache : public testing::Test {
protected:
    static void SetUpTestSuite() {
        BuildRequest req;
        req.cell_m = 500;
        s_grid = new CoastGrid(shoal::grid::build_grid({t::data_path("coast/uk_solent_land.geojson")}, req, nullptr));
        s_bytes = new std::vector<char>(GridFile::serialize(*s_grid));
    }
    static void TearDownTestSuite() {
        delete s_grid;
        delete s_bytes;
        s_grid = nullptr;
        s_bytes = nullptr;
    }
    /// Writes `bytes` as a grid file in the temp folder and returns its path.
    std::string write_grid(const std::vector<char>& bytes, const std::string& name = "g.shoalgrid") const {
        const std::string path = tmp.file(name);
        t::write_bytes(path, bytes);
        return path;
    }

    static CoastGrid* s_grid;
    static std::vector<char>* s_bytes;
    t::TempDir tmp;
};
CoastGrid* GridCache::s_grid = nullptr;
std::vector<char>* GridCache::s_bytes = nullptr;

void expect_same_grid(const CoastGrid& a, const CoastGrid& b) {
    EXPECT_TRUE(a == b);
    // What `shoal info` prints.
    EXPECT_EQ(a.frame().definition(), b.frame().definition());
    EXPECT_EQ(a.frame().description(), b.frame().description());
    EXPECT_EQ(a.cell_size(), b.cell_size());
    EXPECT_EQ(a.origin(), b.origin());
    EXPECT_EQ(a.nx(), b.nx());
    EXPECT_EQ(a.ny(), b.ny());
    EXPECT_EQ(a.has_land_side(), b.has_land_side());
    EXPECT_EQ(a.cell_count(), b.cell_count());
    EXPECT_EQ(a.coast_cell_count(), b.coast_cell_count());
    EXPECT_EQ(a.land_cell_count(), b.land_cell_count());
    EXPECT_EQ(a.segment_count(), b.segment_count());
    EXPECT_EQ(a.memory_bytes(), b.memory_bytes());
    EXPECT_EQ(a.source().inputs, b.source().inputs);
    EXPECT_EQ(a.source().layers, b.source().layers);
    EXPECT_EQ(a.source().layer_option, b.source().layer_option);
    EXPECT_EQ(a.source().source_crs, b.source().source_crs);
    EXPECT_EQ(a.source().fingerprint, b.source().fingerprint);
    EXPECT_EQ(a.source().input_vertices, b.source().input_vertices);
    EXPECT_EQ(a.source().polylines, b.source().polylines);
    EXPECT_EQ(a.source().land_polylines, b.source().land_polylines);
    // And it answers the same.
    std::mt19937_64 rng(1);
    const auto e = a.extent();
    std::uniform_real_distribution<double> ux(e.minx, e.maxx), uy(e.miny, e.maxy);
    for (int k = 0; k < 2000; ++k) {
        const XY p{ux(rng), uy(rng)};
        ASSERT_EQ(a.is_land(p), b.is_land(p));
        ASSERT_EQ(a.frame().forward(a.frame().inverse(p)), b.frame().forward(b.frame().inverse(p)));
    }
}

TEST_F(GridCache, SaveLoadRoundTripGivesAnIdenticalGrid) {
    const std::string path = tmp.file("solent.shoalgrid");
    GridFile::save(*s_grid, path);
    EXPECT_EQ(files_in(tmp.path()), std::vector<std::string>{"solent.shoalgrid"}) << "a temporary file was left behind";
    EXPECT_TRUE(shoal::grid::looks_like_grid(path));
    const CoastGrid back = GridFile::load(path);
    expect_same_grid(*s_grid, back);
    EXPECT_EQ(GridFile::serialize(back), *s_bytes);
    // The solent grid as the importer describes it: 13 rings of 1977 vertices, all land.
    EXPECT_EQ(back.source().input_vertices, 1977u);
    EXPECT_EQ(back.source().polylines, 13u);
    EXPECT_EQ(back.source().land_polylines, 13u);
    EXPECT_GT(back.land_cell_count(), 0u);
    EXPECT_GT(back.coast_cell_count(), 0u);
    ASSERT_EQ(back.source().layers.size(), 1u);
    EXPECT_THAT(back.source().layers[0], HasSubstr("uk_solent_land"));
}

TEST_F(GridCache, RoundTripKeepsLayerOptionsAndSourceCrs) {
    BuildRequest req;
    req.cell_m = 300;
    req.import.layers = {"LNDARE"};
    req.crs = "EPSG:32618";  // UTM 18N covers Chesapeake Bay
    const CoastGrid g = shoal::grid::build_grid({t::data_path("coast/US4MD81M_cut.000")}, req, nullptr);
    const std::string path = tmp.file("s57.shoalgrid");
    GridFile::save(g, path);
    const CoastGrid back = GridFile::load(path);
    expect_same_grid(g, back);
    EXPECT_EQ(back.source().layer_option, std::vector<std::string>{"LNDARE"});
    EXPECT_THAT(back.frame().description(), HasSubstr("EPSG:32618"));
}

TEST_F(GridCache, OverwritingAnExistingGridIsAtomic) {
    const std::string path = tmp.file("g.shoalgrid");
    t::write_bytes(path, {'o', 'l', 'd'});
    GridFile::save(*s_grid, path);
    EXPECT_EQ(t::read_bytes(path), *s_bytes);
    EXPECT_EQ(files_in(tmp.path()), std::vector<std::string>{"g.shoalgrid"});
}

TEST_F(GridCache, MissingFile) {
    const std::string path = tmp.file("nope.shoalgrid");
    EXPECT_THAT([&] { GridFile::load(path); }, ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("no such file"))));
}

TEST_F(GridCache, FileThatIsNotAGrid) {
    const std::string path = t::data_path("coast/uk_solent_land.geojson");
    EXPECT_FALSE(shoal::grid::looks_like_grid(path));
    EXPECT_THAT([&] { GridFile::load(path); }, ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("not a shoal grid file"))));
    const std::string empty = write_grid({}, "empty.shoalgrid");
    EXPECT_THAT([&] { GridFile::load(empty); }, ThrowsMessage<InputError>(AllOf(HasSubstr(empty), HasSubstr("not a shoal grid file"))));
    EXPECT_THAT([&] { GridFile::load(tmp.path().string()); }, ThrowsMessage<InputError>(HasSubstr("directory")));
}

TEST_F(GridCache, WrongMagic) {
    std::vector<char> bytes = *s_bytes;
    bytes[7] = 'X';  // SHOALGRX
    const std::string path = write_grid(bytes);
    EXPECT_FALSE(shoal::grid::looks_like_grid(path));
    EXPECT_THAT([&] { GridFile::load(path); }, ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("not a shoal grid file"))));
}

TEST_F(GridCache, AnotherFormatVersion) {
    std::vector<char> bytes = *s_bytes;
    const std::uint32_t v = shoal::grid::grid_format_version + 1;
    std::memcpy(bytes.data() + version_offset, &v, sizeof v);
    const std::string path = write_grid(bytes);
    EXPECT_TRUE(shoal::grid::looks_like_grid(path));
    EXPECT_THAT([&] { GridFile::load(path); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("format version " + std::to_string(v)), HasSubstr("rebuild"))));
}

TEST_F(GridCache, WrongWriterBehindAValidChecksum) {
    // What a checksum cannot catch (a writer that wrote wrong values and their checksum): a
    // segment's coordinate that is not finite, a cell slot beyond the coast cells, a segment of
    // a polyline beyond the table; each named, with the checksum made right again.
    auto resum = [](std::vector<char>& bytes) {
        const std::uint64_t sum = shoal::util::xxh3_64(bytes.data() + header_size, bytes.size() - header_size);
        std::memcpy(bytes.data() + header_size - 8, &sum, sizeof sum);
    };
    {
        std::vector<char> bytes = *s_bytes;
        resum(bytes);
        EXPECT_NO_THROW(GridFile::load(write_grid(bytes)));  // the resumming alone changes nothing
    }
    // The segments: their array's count (u64) then each segment's four doubles, then the
    // segments' polyline table (count, then a u32 each).
    std::span<const shoal::grid::Segment> first_cell;
    for (int j = 0; j < s_grid->ny() && first_cell.empty(); ++j)
        for (int i = 0; i < s_grid->nx() && first_cell.empty(); ++i) first_cell = s_grid->segments(i, j);
    ASSERT_FALSE(first_cell.empty());
    const shoal::grid::Segment sg = first_cell.front();
    const auto at = std::search(s_bytes->begin() + header_size, s_bytes->end(), reinterpret_cast<const char*>(&sg),
                                reinterpret_cast<const char*>(&sg) + sizeof sg);
    ASSERT_NE(at, s_bytes->end());
    const std::size_t seg_at = static_cast<std::size_t>(at - s_bytes->begin());
    for (double bad : {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity()})
        for (std::size_t coord = 0; coord < 4; ++coord) {
            std::vector<char> bytes = *s_bytes;
            std::memcpy(bytes.data() + seg_at + 8 * coord, &bad, sizeof bad);
            resum(bytes);
            const std::string path = write_grid(bytes);
            EXPECT_THAT([&] { GridFile::load(path); }, ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("non-finite segment"))))
                << bad << " at coordinate " << coord;
        }
    std::uint64_t n_segments = 0;
    std::memcpy(&n_segments, s_bytes->data() + seg_at - 8, sizeof n_segments);
    ASSERT_GT(n_segments, 0u);
    const std::size_t info_at = seg_at + n_segments * sizeof(shoal::grid::Segment) + 8;
    // The polyline table's kinds follow the segments' table: its count is the number of polylines.
    std::uint64_t n_polylines = 0;
    std::memcpy(&n_polylines, s_bytes->data() + info_at + 4 * n_segments, sizeof n_polylines);
    ASSERT_GT(n_polylines, 0u);
    for (std::uint64_t index : {std::uint64_t{0x7FFFFFFF}, n_polylines, n_polylines - 1}) {  // past any table, just past it, the last
        for (std::uint32_t boundary : {0u, 0x80000000u}) {
            std::vector<char> bytes = *s_bytes;
            const std::uint32_t info = static_cast<std::uint32_t>(index) | boundary;
            std::memcpy(bytes.data() + info_at + 4 * (n_segments / 2), &info, sizeof info);
            resum(bytes);
            if (index < n_polylines)
                EXPECT_NO_THROW(GridFile::load(write_grid(bytes))) << index;
            else
                EXPECT_THAT([&] { GridFile::load(write_grid(bytes)); }, ThrowsMessage<InputError>(HasSubstr("segment of a polyline out of range")))
                    << index;
        }
    }
    // The cell slots: nx * ny of them after their count, the first array after the head.
    const std::uint64_t n_cells = static_cast<std::uint64_t>(s_grid->nx()) * static_cast<std::uint64_t>(s_grid->ny());
    const auto count_at = std::search(s_bytes->begin() + header_size, s_bytes->end(), reinterpret_cast<const char*>(&n_cells),
                                      reinterpret_cast<const char*>(&n_cells) + sizeof n_cells);
    ASSERT_NE(count_at, s_bytes->end());
    const std::size_t slots_at = static_cast<std::size_t>(count_at - s_bytes->begin()) + 8;
    // The coast cells' count: every coast index appears once among the slots (land and water
    // are the two values above every index).
    std::uint32_t n_coast = 0;
    for (std::uint64_t k = 0; k < n_cells; ++k) {
        std::uint32_t v = 0;
        std::memcpy(&v, s_bytes->data() + slots_at + 4 * k, sizeof v);
        if (v < 0xFFFFFFFEu) n_coast = std::max(n_coast, v + 1);
    }
    ASSERT_GT(n_coast, 0u);
    for (std::uint32_t bad : {0x7FFFFFFFu, 0xFFFFFFFDu, n_coast, n_coast - 1}) {  // past the coast cells, just past, the last index
        std::vector<char> bytes = *s_bytes;
        std::memcpy(bytes.data() + slots_at + 4 * (n_cells / 3), &bad, sizeof bad);
        resum(bytes);
        if (bad < n_coast)
            EXPECT_NO_THROW(GridFile::load(write_grid(bytes))) << bad;
        else
            EXPECT_THAT([&] { GridFile::load(write_grid(bytes)); }, ThrowsMessage<InputError>(HasSubstr("cell slot out of range"))) << bad;
    }
}

TEST_F(GridCache, TruncatedFile) {
    for (std::size_t keep : {s_bytes->size() - 1, s_bytes->size() / 2, header_size, header_size - 4, std::size_t{12}}) {
        std::vector<char> bytes(s_bytes->begin(), s_bytes->begin() + static_cast<std::ptrdiff_t>(keep));
        const std::string path = write_grid(bytes);
        EXPECT_THAT([&] { GridFile::load(path); }, ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("cut short"))))
            << "kept " << keep << " bytes";
    }
    // Shorter than the magic number: not recognisable as a grid at all.
    const std::string path = write_grid(std::vector<char>(s_bytes->begin(), s_bytes->begin() + 5));
    EXPECT_THAT([&] { GridFile::load(path); }, ThrowsMessage<InputError>(HasSubstr("not a shoal grid file")));
}

TEST_F(GridCache, OneFlippedByteFailsTheChecksum) {
    std::mt19937_64 rng(4);
    std::uniform_int_distribution<std::size_t> pos(header_size, s_bytes->size() - 1);
    std::vector<std::size_t> where = {header_size, s_bytes->size() - 1};
    for (int k = 0; k < 20; ++k) where.push_back(pos(rng));
    for (std::size_t at : where) {
        std::vector<char> bytes = *s_bytes;
        bytes[at] = static_cast<char>(bytes[at] ^ 0x10);
        const std::string path = write_grid(bytes);
        EXPECT_THAT([&] { GridFile::load(path); }, ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("checksum"))))
            << "byte " << at << " flipped";
    }
    // A flipped bit in the stored checksum itself.
    std::vector<char> bytes = *s_bytes;
    bytes[header_size - 1] = static_cast<char>(bytes[header_size - 1] ^ 0x01);
    EXPECT_THAT([&] { GridFile::load(write_grid(bytes)); }, ThrowsMessage<InputError>(HasSubstr("checksum")));
    // A flipped byte in the payload size: the length no longer matches.
    bytes = *s_bytes;
    bytes[size_offset] = static_cast<char>(bytes[size_offset] ^ 0x01);
    EXPECT_THAT([&] { GridFile::load(write_grid(bytes)); }, ThrowsMessage<InputError>(HasSubstr("its header says")));
}

TEST_F(GridCache, SaveIntoAMissingFolderFailsAndLeavesNoTemporaryFile) {
    const std::string path = (tmp.path() / "no" / "such" / "folder" / "g.shoalgrid").string();
    EXPECT_THAT([&] { GridFile::save(*s_grid, path); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("does not exist"))));
    EXPECT_TRUE(files_in(tmp.path()).empty());
    // Over a directory: refused, nothing left either.
    fs::create_directory(tmp.path() / "d");
    EXPECT_THROW(GridFile::save(*s_grid, (tmp.path() / "d").string()), InputError);
    EXPECT_EQ(files_in(tmp.path()), std::vector<std::string>{"d"});
    EXPECT_TRUE(files_in(tmp.path() / "d").empty());
}

// ---------------------------------------------------------------------------------------------
// load_or_build

class LoadOrBuild : public testing::Test {
protected:
    void SetUp() override {
        fs::create_directory(tmp.path() / "src");
        source = (tmp.path() / "src" / "solent.geojson").string();
        fs::copy_file(t::data_path("coast/uk_solent_land.geojson"), source);
        request.cell_m = 500;
        request.cache_dir = (tmp.path() / "cache").string();
    }
    t::TempDir tmp;
    std::string source;
    BuildRequest request;
};

TEST_F(LoadOrBuild, BuildsThenReusesTheCacheThenRebuildsWhenTheSourceChanges) {
    LoadReport r1;
    const CoastGrid g1 = shoal::grid::load_or_build({source}, request, &r1);
    EXPECT_EQ(r1.how, "built and cached");
    EXPECT_TRUE(fs::exists(r1.cache_path));
    EXPECT_EQ(fs::path(r1.cache_path).parent_path(), fs::path(request.cache_dir));
    EXPECT_EQ(files_in(request.cache_dir).size(), 1u);

    LoadReport r2;
    const CoastGrid g2 = shoal::grid::load_or_build({source}, request, &r2);
    EXPECT_THAT(r2.how, HasSubstr("reused"));
    EXPECT_EQ(r2.cache_path, r1.cache_path);
    EXPECT_TRUE(g1 == g2);
    EXPECT_EQ(r2.build.clip_calls, 0u) << "nothing should be built when the cache is reused";

    // Change one digit of one coordinate: same size, different bytes.
    std::vector<char> bytes = t::read_bytes(source);
    const std::string text(bytes.begin(), bytes.end());
    const auto at = text.find("-1.5900206");
    ASSERT_NE(at, std::string::npos);
    bytes[at + 9] = '7';
    t::write_bytes(source, bytes);
    LoadReport r3;
    const CoastGrid g3 = shoal::grid::load_or_build({source}, request, &r3);
    EXPECT_EQ(r3.how, "built and cached");
    EXPECT_NE(r3.cache_path, r1.cache_path);
    EXPECT_NE(g3.source().fingerprint, g1.source().fingerprint);
    EXPECT_FALSE(g1 == g3);
    EXPECT_GT(r3.build.clip_calls, 0u);

    // Another cell size is another grid too.
    request.cell_m = 400;
    LoadReport r4;
    const CoastGrid g4 = shoal::grid::load_or_build({source}, request, &r4);
    EXPECT_EQ(r4.how, "built and cached");
    EXPECT_EQ(g4.cell_size(), 400);
}

TEST_F(LoadOrBuild, DamagedCacheIsRebuiltWithAWarning) {
    LoadReport r1;
    const CoastGrid g1 = shoal::grid::load_or_build({source}, request, &r1);
    std::vector<char> bytes = t::read_bytes(r1.cache_path);
    bytes[bytes.size() / 2] = static_cast<char>(bytes[bytes.size() / 2] ^ 0x40);
    t::write_bytes(r1.cache_path, bytes);
    LoadReport r2;
    const CoastGrid g2 = shoal::grid::load_or_build({source}, request, &r2);
    EXPECT_EQ(r2.how, "built and cached");
    EXPECT_TRUE(g1 == g2);
    ASSERT_FALSE(r2.warnings.empty());
    EXPECT_THAT(r2.warnings.front(), AllOf(HasSubstr("cached grid unusable"), HasSubstr("checksum")));
    LoadReport r3;
    shoal::grid::load_or_build({source}, request, &r3);
    EXPECT_THAT(r3.how, HasSubstr("reused"));
}

TEST_F(LoadOrBuild, UnwritableCacheFolderStillGivesTheGrid) {
    t::write_bytes(tmp.file("plain-file"), {'x'});
    request.cache_dir = (tmp.path() / "plain-file" / "cache").string();
    LoadReport r;
    const CoastGrid g = shoal::grid::load_or_build({source}, request, &r);
    EXPECT_THAT(r.how, HasSubstr("not cached"));
    ASSERT_FALSE(r.warnings.empty());
    EXPECT_THAT(r.warnings.back(), HasSubstr("could not cache"));
    EXPECT_GT(g.coast_cell_count(), 0u);
}

TEST_F(LoadOrBuild, AGridFileIsLoadedAsIs) {
    LoadReport r1;
    const CoastGrid g1 = shoal::grid::load_or_build({source}, request, &r1);
    LoadReport r2;
    const CoastGrid g2 = shoal::grid::load_or_build({r1.cache_path}, request, &r2);
    EXPECT_EQ(r2.how, "loaded grid");
    EXPECT_TRUE(g1 == g2);
    EXPECT_THAT([&] { shoal::grid::load_or_build({r1.cache_path, source}, request); },
                ThrowsMessage<UsageError>(HasSubstr("is a grid file")));
}

TEST_F(LoadOrBuild, MissingSourceIsAnInputError) {
    const std::string missing = tmp.file("src/none.geojson");
    EXPECT_THAT([&] { shoal::grid::load_or_build({missing}, request); },
                ThrowsMessage<InputError>(AllOf(HasSubstr(missing), HasSubstr("no such file"))));
}

}  // namespace

namespace {

/// GDAL's own answer: what GetFileList lists after opening `path`, sorted; the path itself when
/// it lists none (it cannot open it), as dataset_files gives it.
std::vector<std::string> gdal_file_list(const std::string& path) {
    std::vector<std::string> files;
    GDALDatasetUniquePtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
    if (ds)
        if (char** list = ds->GetFileList()) {
            for (char** f = list; *f; ++f) files.emplace_back(*f);
            CSLDestroy(list);
        }
    std::sort(files.begin(), files.end());
    if (files.empty()) files.push_back(path);
    return files;
}

}  // namespace

// The files a source consists of (what its fingerprint covers) are those GDAL lists after
// opening it, also where JSON is told by its driver alone (not opened: not parsed).
TEST(DatasetFiles, AreTheFilesGdalListsForEveryKindOfSource) {
    // On a copy of the committed coasts: other tests, run at the same time, open them (and a
    // companion file that appears between the two lists would tell them apart). What another
    // process makes beside them for a while (SQLite's, GDAL's) is not copied; a file that is
    // gone before it is copied is passed over.
    const t::TempDir scratch;
    const fs::path copy = scratch.path() / "coast";
    const fs::path from = t::data_path("coast");
    fs::create_directories(copy);
    for (const auto& e : fs::recursive_directory_iterator(from)) {
        const std::string name = e.path().filename().string();
        auto ends = [&](const std::string& tail) { return name.size() >= tail.size() && name.compare(name.size() - tail.size(), tail.size(), tail) == 0; };
        if (ends("-wal") || ends("-shm") || ends("-journal") || ends(".aux.xml")) continue;
        std::error_code ec;
        const fs::path to = copy / fs::relative(e.path(), from);
        if (e.is_directory(ec)) fs::create_directories(to, ec);
        else if (e.is_regular_file(ec)) fs::copy_file(e.path(), to, ec);
    }
    int json = 0;
    for (const auto& e : fs::recursive_directory_iterator(copy)) {
        const std::string path = e.path().string();
        if (!e.is_regular_file() || e.path().extension() == ".md" || e.path().extension() == ".py") continue;
        std::vector<std::string> ours = shoal::grid::dataset_files(path);
        std::sort(ours.begin(), ours.end());
        EXPECT_EQ(ours, gdal_file_list(path)) << path;
        json += e.path().extension() == ".geojson";
    }
    EXPECT_GE(json, 8);  // the committed coasts hold GeoJSON, Shapefiles, GeoPackages and S-57 cells
    // Inside a zip (GDAL's virtual file), and a file that is not there.
    const fs::path zip = scratch.path() / "dataset_files.zip";
    const std::string zipped = "/vsizip/" + zip.string() + "/solent.geojson";
    ASSERT_EQ(CPLCopyFile(zipped.c_str(), t::data_path("coast/uk_solent_land.geojson").c_str()), 0);
    EXPECT_EQ(shoal::grid::dataset_files(zipped), std::vector<std::string>{zipped});
    EXPECT_EQ(shoal::grid::dataset_files(zipped), gdal_file_list(zipped));
    fs::remove(zip);
    const std::string missing = t::data_path("coast/no_such.geojson");
    EXPECT_EQ(shoal::grid::dataset_files(missing), std::vector<std::string>{missing});
}

// A coast inside a zip or a gzip, named by GDAL's paths (/vsizip/, /vsigzip/), is read as the
// file itself: the same grid, point for point, and the same fingerprint (its bytes and file
// names), which a member changed by one coordinate changes. A bare zip or gzip that OGR cannot
// open is refused, naming the path to give; a member not there is no such file.
TEST(GridSources, ACoastInsideAZipOrAGzipIsTheFileItself) {
    t::TempDir dir;
    const std::string zip = dir.file("coasts.zip"), gz = dir.file("solent.geojson.gz");
    const std::string shp = "gr_saronic_piraeus_land";
    for (const char* ext : {".shp", ".shx", ".dbf", ".prj"})
        ASSERT_EQ(CPLCopyFile(("/vsizip/" + zip + "/land/" + shp + ext).c_str(), t::data_path("coast/" + shp + ext).c_str()), 0) << ext;
    ASSERT_EQ(CPLCopyFile(("/vsizip/" + zip + "/uk_solent_land.geojson").c_str(), t::data_path("coast/uk_solent_land.geojson").c_str()), 0);
    ASSERT_EQ(CPLCopyFile(("/vsigzip/" + gz).c_str(), t::data_path("coast/uk_solent_land.geojson").c_str()), 0);
    BuildRequest req;
    req.cell_m = 1000;
    auto build = [&](const std::string& path) { return shoal::grid::build_grid({path}, req, nullptr); };
    const CoastGrid plain_shp = build(t::data_path("coast/" + shp + ".shp"));
    CoastGrid zipped_shp = build("/vsizip/" + zip + "/land/" + shp + ".shp");
    EXPECT_EQ(zipped_shp.source().inputs, std::vector<std::string>{"/vsizip/" + zip + "/land/" + shp + ".shp"});
    zipped_shp.source().inputs = plain_shp.source().inputs;  // all else (operator==) the same
    EXPECT_TRUE(zipped_shp == plain_shp);
    EXPECT_EQ(zipped_shp.source().fingerprint, plain_shp.source().fingerprint);
    const CoastGrid plain_json = build(t::data_path("coast/uk_solent_land.geojson"));
    const std::string solent = t::data_path("coast/uk_solent_land.geojson");
    for (const std::string& packed : {"/vsizip/" + zip + "/uk_solent_land.geojson", "/vsigzip/" + gz}) {
        CoastGrid g = build(packed);
        // The same bytes under the same name: the same fingerprint (the gzip's name is another).
        if (packed.rfind("/vsizip/", 0) == 0) {
            EXPECT_EQ(g.source().fingerprint, plain_json.source().fingerprint);
        }
        CoastGrid same_inputs = g;
        same_inputs.source().inputs = plain_json.source().inputs;
        same_inputs.source().fingerprint = plain_json.source().fingerprint;
        EXPECT_TRUE(same_inputs == plain_json) << packed;
        EXPECT_NE(g.source().fingerprint, 0u);
        // A report of a run on the grid file draws its chart from the source, read again.
        const std::string grid_file = dir.file("packed.shoalgrid");
        t::write_bytes(grid_file, GridFile::serialize(g));
        EXPECT_EQ(shoal::grid::coast_sources({grid_file}, g), std::vector<std::string>{packed});
    }
    // One coordinate changed in the zipped GeoJSON: another fingerprint.
    std::string text = t::read_text(solent);
    const std::size_t digit = text.find_first_of("123456789", text.find("\"coordinates\""));
    ASSERT_NE(digit, std::string::npos);
    text[digit] = text[digit] == '9' ? '8' : static_cast<char>(text[digit] + 1);
    const std::string changed = dir.file("changed.geojson");
    t::write_bytes(changed, std::vector<char>(text.begin(), text.end()));
    const std::string zip2 = dir.file("changed.zip");
    ASSERT_EQ(CPLCopyFile(("/vsizip/" + zip2 + "/uk_solent_land.geojson").c_str(), changed.c_str()), 0);
    EXPECT_NE(build("/vsizip/" + zip2 + "/uk_solent_land.geojson").source().fingerprint, plain_json.source().fingerprint);
    // Refusals.
    EXPECT_THAT([&] { build("/vsizip/" + zip + "/nothere.geojson"); }, ThrowsMessage<InputError>(HasSubstr("no such file or directory")));
    EXPECT_THAT([&] { build(zip); }, ThrowsMessage<InputError>(AllOf(HasSubstr(zip), HasSubstr("/vsizip/" + zip + "/"))));
    EXPECT_THAT([&] { build(gz); }, ThrowsMessage<InputError>(AllOf(HasSubstr(gz), HasSubstr("/vsigzip/" + gz))));
    EXPECT_THAT([&] { build("/vsistdin/"); }, ThrowsMessage<InputError>(HasSubstr("standard input")));
    // A changed gzip of the same name: another fingerprint too.
    fs::create_directories(dir.path() / "other");
    const std::string gz2 = (dir.path() / "other" / "solent.geojson.gz").string();
    ASSERT_EQ(CPLCopyFile(("/vsigzip/" + gz2).c_str(), changed.c_str()), 0);
    EXPECT_NE(build("/vsigzip/" + gz2).source().fingerprint, build("/vsigzip/" + gz).source().fingerprint);
    // A file named "-" is that file, as before (a coast is never read from standard input).
    const fs::path here = fs::current_path();
    fs::current_path(dir.path());
    fs::copy_file(solent, "-");
    CoastGrid dash = build("-");
    fs::copy_file(changed, "-", fs::copy_options::overwrite_existing);  // its bytes are fingerprinted
    const std::uint64_t dash_changed = build("-").source().fingerprint;
    fs::current_path(here);
    EXPECT_NE(dash_changed, dash.source().fingerprint);
    EXPECT_EQ(dash.source().inputs, std::vector<std::string>{"-"});
    dash.source().inputs = plain_json.source().inputs;
    dash.source().fingerprint = plain_json.source().fingerprint;
    EXPECT_TRUE(dash == plain_json);
}

// A grid imported from a folder (of Shapefiles) names the folder as its source, which a report of
// a run on the grid file reads again for its chart (it was said to be "not there any more").
TEST(GridSources, AGridFromAFolderDrawsItsChartFromTheFolder) {
    t::TempDir dir;
    const std::string shp = "gr_saronic_piraeus_land";
    fs::create_directories(dir.path() / "land");
    for (const char* ext : {".shp", ".shx", ".dbf", ".prj"}) fs::copy_file(t::data_path("coast/" + shp + ext), dir.path() / "land" / (shp + ext));
    BuildRequest req;
    req.cell_m = 1000;
    const std::string folder = dir.file("land");
    const CoastGrid g = shoal::grid::build_grid({folder}, req, nullptr);
    const std::string grid_file = dir.file("land.shoalgrid");
    t::write_bytes(grid_file, GridFile::serialize(g));
    EXPECT_EQ(shoal::grid::coast_sources({grid_file}, g), std::vector<std::string>{folder});
    fs::remove_all(dir.path() / "land");
    EXPECT_TRUE(shoal::grid::coast_sources({grid_file}, g).empty()) << "gone: not read";
}

// A plain *.geojson file whose first character that is not blank is '{' is told to be its one
// file without GDAL (a check may then never load GDAL): the same answer as GDAL's, on every
// committed GeoJSON and on files made at the edges of that rule (blanks, a byte order mark,
// arrays, sequences, garbage, other formats under the name, other JSON drivers' documents) and
// on random mutations of a real one's beginning.
TEST(DatasetFiles, PlainGeoJsonToldWithoutGdalIsWhatGdalLists) {
    const fs::path dir = fs::temp_directory_path() / ("shoal_plain_geojson_" + std::to_string(::getpid()));
    fs::create_directories(dir);
    const std::string real = t::read_text(t::data_path("coast/island_with_lake.geojson"));
    ASSERT_EQ(real.substr(0, 1), "{");
    std::vector<std::pair<std::string, std::string>> cases = {  // name, content
        {"real.geojson", real},
        {"blanks.geojson", " \t\r\n  " + real},
        {"upper.GeoJSON", real},
        {"bom.geojson", "\xEF\xBB\xBF" + real},
        {"array.geojson", "[" + real + "]"},
        {"empty.geojson", ""},
        {"blank.geojson", "   \n"},
        {"garbage.geojson", "{not json at all"},
        {"minimal.geojson", R"({"type":"FeatureCollection","features":[]})"},
        {"seq_rs.geojson", "\x1e" + std::string(R"({"type":"Feature","geometry":{"type":"Point","coordinates":[1,2]},"properties":{}})") + "\n"},
        {"seq_lines.geojson", std::string(R"({"type":"Feature","geometry":{"type":"Point","coordinates":[1,2]},"properties":{}})") + "\n" +
                                  R"({"type":"Feature","geometry":{"type":"Point","coordinates":[3,4]},"properties":{}})" + "\n"},
        {"esri.geojson", R"({"geometryType":"esriGeometryPoint","spatialReference":{"wkid":4326},"fields":[],"features":[{"geometry":{"x":1,"y":2},"attributes":{}}]})"},
        {"topo.geojson", R"({"type":"Topology","objects":{"a":{"type":"GeometryCollection","geometries":[{"type":"Point","coordinates":[1,2]}]}},"arcs":[]})"},
        {"metadata.geojson", R"({"name":"x","format":"pbf","json":"{\"vector_layers\":[]}"})"},
        {"shp.geojson", t::read_text(t::data_path("coast/gr_saronic_piraeus_land.shp"))},
        {"gpkg.geojson", t::read_text(t::data_path("coast/uk_solent.gpkg"))},
        {"s57.geojson", t::read_text(t::data_path("coast/US4MD81M_cut.000"))},
        {"real.json", real},
        {"real.geojson.txt", real},
    };
    std::mt19937 rng(40);
    const std::string alphabet = "{}[] \t\r\n\":,0aeFT\x1e\xEF";
    for (int k = 0; k < 120; ++k) {
        std::string c = real;
        const int edits = 1 + static_cast<int>(rng() % 6);
        for (int e = 0; e < edits; ++e) c[rng() % 64] = alphabet[rng() % alphabet.size()];
        if (k % 3 == 0) c = c.substr(0, rng() % 200);
        cases.emplace_back("random_" + std::to_string(k) + ".geojson", c);
    }
    int claimed = 0;
    for (const auto& [name, content] : cases) {
        const std::string path = (dir / name).string();
        std::ofstream(path, std::ios::binary) << content;
        std::vector<std::string> ours = shoal::grid::dataset_files(path);
        std::sort(ours.begin(), ours.end());
        EXPECT_EQ(ours, gdal_file_list(path)) << name;
        const std::size_t first = content.find_first_not_of(" \t\r\n");
        claimed += first != std::string::npos && content[first] == '{';
    }
    EXPECT_GE(claimed, 60);  // the rule was taken often, not only its fallback through GDAL
    fs::remove_all(dir);
}
