// Percent-decoding of glTF's file URIs (io/uri_path.h): every %XY with two
// hexadecimal digits of either case becomes its byte, wherever it stands
// (the last three characters too); a '%' without two digits stays.
#include "io/uri_path.h"

#include <gtest/gtest.h>

namespace quiver {
namespace {

TEST(PercentDecoded, EveryEscapeOfTwoHexDigitsBecomesItsByte) {
  EXPECT_EQ(percent_decoded("my%20buffer.bin"), "my buffer.bin");
  EXPECT_EQ(percent_decoded("%4A%4a%6A%6a"), "JJjj");  // upper- and lower-case digits alike
  EXPECT_EQ(percent_decoded("%C3%A9t%C3%A9.png"), "\xC3\xA9t\xC3\xA9.png");
  EXPECT_EQ(percent_decoded("texture%41"), "textureA");  // an escape at the very end
  EXPECT_EQ(percent_decoded("%41"), "A");
  EXPECT_EQ(percent_decoded("%%41"), "%A");
}

TEST(PercentDecoded, APercentWithoutTwoHexDigitsStays) {
  EXPECT_EQ(percent_decoded("100%"), "100%");
  EXPECT_EQ(percent_decoded("a%4"), "a%4");
  EXPECT_EQ(percent_decoded("%G1%1G%"), "%G1%1G%");
  EXPECT_EQ(percent_decoded("plain.bin"), "plain.bin");
  EXPECT_EQ(percent_decoded(""), "");
}

}  // namespace
}  // namespace quiver
