// libtex_image: a tiled map's raster written through OpenImageIO and read back.
#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstdio>
#include <filesystem>

#include "helpers.hpp"
#include "libtex/tiled_image.hpp"

#include "scratch.hpp"

using namespace tex;

TEST(TiledImage, WritesWhatItRasterised) {
    const TiledMap t = GridPartition(StripesProperties(0.3, 12), StripesProperties(1.9, 17), Tiled());
    const Raster r = Rasterize(t, Region::rectangle(0, 0, 90, 70).bbox(), 0.5, 1.0);
    for (const char* ext : {".png", ".tif"}) {
        const std::string path =
            rh_test::scratch("tiled_image" + std::string(ext));
        WriteImage(r, path);
        auto in = OIIO::ImageInput::open(path);
        ASSERT_TRUE(in) << path;
        const OIIO::ImageSpec& spec = in->spec();
        EXPECT_EQ(spec.width, r.width);
        EXPECT_EQ(spec.height, r.height);
        EXPECT_EQ(spec.nchannels, 1);
        std::vector<std::uint8_t> back(std::size_t(spec.width) * std::size_t(spec.height));
        ASSERT_TRUE(in->read_image(0, 0, 0, 1, OIIO::TypeDesc::UINT8, back.data()));
        in->close();
        EXPECT_EQ(back, r.pixels) << ext;
        std::remove(path.c_str());
    }
}

TEST(TiledImage, BadFileNamesAreClearErrors) {
    const Raster r = Rasterize(GridPartition(StripesProperties(0, 5), StripesProperties(1, 5), Tiled()),
                               Region::rectangle(0, 0, 10, 10).bbox(), 1.0, 1.0);
    EXPECT_TEX_ERROR(WriteImage(r, "/tmp/rh_tiled_image_test.no-such-format"), "WriteImage", "no-such-format");
    EXPECT_TEX_ERROR(WriteImage(r, "/no/such/dir/x.png"), "WriteImage", "/no/such/dir/x.png");
    EXPECT_TEX_ERROR(WriteImage(Raster{}, "/tmp/x.png"), "WriteImage", "empty");
}
