#include <gtest/gtest.h>

#include "kiri/geometry/core/error.hpp"

TEST(InputError, MessageJoinsFileFieldReason)
{
    const kiri::InputError e("scene.json", "/sun/direction", "expected an array of 3 numbers");
    EXPECT_STREQ(e.what(), "scene.json: /sun/direction: expected an array of 3 numbers");
    EXPECT_EQ(e.field(), "/sun/direction");
}

TEST(InputError, EmptyPartsAreLeftOut)
{
    EXPECT_STREQ(kiri::InputError("a.tif", "", "not a raster").what(), "a.tif: not a raster");
    EXPECT_STREQ(kiri::LimitError("", "width", "too large").what(), "width: too large");
}
