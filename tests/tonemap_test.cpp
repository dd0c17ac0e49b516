#include "radiosity/analysis/tonemap.h"

#include <gtest/gtest.h>

#include <cmath>

namespace dynrad::rad {
namespace {

TEST(ToneMap, SrgbEncodingMatchesTheStandardCurve) {
  EXPECT_EQ(encode_srgb(0.0), 0);
  EXPECT_EQ(encode_srgb(1.0), 255);
  EXPECT_EQ(encode_srgb(2.0), 255);
  EXPECT_EQ(encode_srgb(-1.0), 0);
  EXPECT_EQ(encode_srgb(std::nan("")), 0);
  EXPECT_EQ(encode_srgb(0.5), 188);       // 1.055 * 0.5^(1/2.4) - 0.055 = 0.7354
  EXPECT_EQ(encode_srgb(0.2158), 128);    // the inverse of sRGB 128
  EXPECT_EQ(encode_srgb(0.0031308), 10);  // end of the linear segment: 12.92 * x * 255
  int previous = 0;
  for (int i = 0; i <= 1000; ++i) {
    const int value = encode_srgb(i / 1000.0);
    EXPECT_GE(value, previous);
    previous = value;
  }
}

TEST(ToneMap, AutoExposureMapsThe99thPercentileTo0_9) {
  std::vector<Rgb> values;
  for (int i = 1; i <= 100; ++i) values.emplace_back(i);  // luminance i
  values.emplace_back(1e6);                               // an emitter, excluded
  std::vector<char> include(values.size(), 1);
  include.back() = 0;
  const double exposure = auto_exposure(values, include);
  EXPECT_NEAR(exposure, 0.9 / 100.0, 1e-12);
  EXPECT_DOUBLE_EQ(auto_exposure({}, {}), 1.0);
}

TEST(ToneMap, QualityIsLinearLuminance) {
  const VertexValues v = tone_map({Rgb(1, 0, 0), Rgb(0, 1, 0), Rgb(0, 0, 1)}, 1.0, "radiosity");
  EXPECT_NEAR(v.quality[0], 0.2126, 1e-6);
  EXPECT_NEAR(v.quality[1], 0.7152, 1e-6);
  EXPECT_NEAR(v.quality[2], 0.0722, 1e-6);
  EXPECT_EQ(v.display[0][0], 255);
  EXPECT_EQ(v.display[0][1], 0);
}

}  // namespace
}  // namespace dynrad::rad
