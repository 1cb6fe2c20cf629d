// libFuzzer target: the partition reader (carto::load_partition: OGR layers into faces,
// labelled lines, orientations and densities) on a GeoPackage file made of the fuzzer's
// bytes. Seeds are small valid GeoPackages (fuzz/corpus/partition_raw), so mutations
// reach SQLite, GDAL's GeoPackage driver and the reader behind it. The only expected
// failure is carto::Error.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <filesystem>

#include "carto/error.hpp"
#include "carto/partition.hpp"
#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    fuzz::quiet_gdal();
    const std::string& path = fuzz::temp_gpkg();
    std::filesystem::remove(path);
    std::filesystem::remove(path + "-wal");
    std::filesystem::remove(path + "-shm");
    {
        std::FILE* f = std::fopen(path.c_str(), "wb");
        if (!f) return 0;
        std::fwrite(data, 1, size, f);
        std::fclose(f);
    }
    carto::PartitionOptions o;
    o.path = path;
    try {
        (void)carto::load_partition(o, fuzz::working_wkt());
    } catch (const carto::Error&) {
    }
    return 0;
}
