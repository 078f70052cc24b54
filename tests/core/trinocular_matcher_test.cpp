// The trinocular matcher on synthetic images made by shifting a random texture: the
// true disparity is known exactly.
#include "core/stereo/trinocular_matcher.h"

#include <cmath>
#include <cstdio>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "tests/core/box_scene.h"

namespace coopmap {
namespace {

TrinocularRig rig160() {
  TrinocularRig rig;
  rig.intrinsics = CameraIntrinsics::fromFov(160, 120, M_PI / 2);
  return rig;
}

// A smooth random texture, larger than the image so shifted views have no border.
cv::Mat texture(int w, int h, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_int_distribution<int> u(0, 255);
  cv::Mat t(h, w, CV_8UC1);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) t.at<uint8_t>(y, x) = static_cast<uint8_t>(u(rng));
  cv::GaussianBlur(t, t, cv::Size(0, 0), 1.0);
  cv::normalize(t, t, 0, 255, cv::NORM_MINMAX);
  return t;
}

// Views of a fronto-parallel plane at integer disparity d for the default L-rig: the
// horizontal partner sees the scene shifted left by d, the vertical one shifted down by d.
struct Views {
  cv::Mat ref, hor, ver;
};
Views planeViews(const cv::Mat& tex, int d) {
  const int m = 40;
  Views v;
  v.ref = tex(cv::Rect(m, m, 160, 120)).clone();
  v.hor = tex(cv::Rect(m + d, m, 160, 120)).clone();  // hor(x) = ref(x + d)
  v.ver = tex(cv::Rect(m, m - d, 160, 120)).clone();  // ver(y) = ref(y - d)
  return v;
}

// Valid pixels in a rectangle, and how many of them lie within 0.25 px of d.
struct Agreement {
  int valid = 0, good = 0;
};
Agreement agreement(const cv::Mat& disp, const cv::Rect& r, double d) {
  Agreement a;
  for (int y = r.y; y < r.y + r.height; ++y)
    for (int x = r.x; x < r.x + r.width; ++x) {
      const float got = disp.at<float>(y, x);
      if (got == kInvalidDisparity) continue;
      ++a.valid;
      a.good += std::abs(got - d) < 0.25;
    }
  return a;
}

TEST(TrinocularMatcherTest, RecoversIntegerDisparityOfTexturedPlane) {
  const cv::Mat tex = texture(240, 200, 1);
  TrinocularMatcher m(rig160(), StereoConfig{});
  for (int d : {3, 8, 17}) {
    const Views v = planeViews(tex, d);
    cv::Mat disp;
    const StereoStats st = m.compute(v.ref, v.hor, v.ver, disp);
    const auto [valid, good] = agreement(disp, cv::Rect(0, 0, 160, 120), d);
    EXPECT_EQ(valid, st.valid);
    EXPECT_GT(valid, 0.85 * 160 * 120) << "d=" << d;
    EXPECT_GT(good, 0.99 * valid) << "d=" << d;
  }
}

TEST(TrinocularMatcherTest, SubpixelShiftIsRecovered) {
  // Shift by 5.5 px by averaging the views at 5 and 6: linear interpolation of the texture.
  const cv::Mat tex = texture(240, 200, 2);
  const Views a = planeViews(tex, 5), b = planeViews(tex, 6);
  Views v;
  v.ref = a.ref;
  cv::addWeighted(a.hor, 0.5, b.hor, 0.5, 0.0, v.hor);
  cv::addWeighted(a.ver, 0.5, b.ver, 0.5, 0.0, v.ver);
  TrinocularMatcher m(rig160(), StereoConfig{});
  cv::Mat disp;
  m.compute(v.ref, v.hor, v.ver, disp);
  double sum = 0;
  int n = 0;
  for (int y = 20; y < 100; ++y)
    for (int x = 20; x < 140; ++x)
      if (disp.at<float>(y, x) != kInvalidDisparity) {
        sum += disp.at<float>(y, x);
        ++n;
      }
  ASSERT_GT(n, 5000);
  EXPECT_NEAR(sum / n, 5.5, 0.15);
}

TEST(TrinocularMatcherTest, TexturelessRegionIsInvalid) {
  cv::Mat flat(120, 160, CV_8UC1, cv::Scalar(128));
  TrinocularMatcher m(rig160(), StereoConfig{});
  cv::Mat disp;
  const StereoStats st = m.compute(flat, flat, flat, disp);
  EXPECT_EQ(st.valid, 0);
  EXPECT_GT(st.rejected_texture, 100 * 100);
}

TEST(TrinocularMatcherTest, PairSumResolvesRepeatedTextureThatFoolsOnePair) {
  // Vertical stripes with period 6 px: the horizontal pair alone cannot tell d from d +/- 6;
  // the vertical pair sees a texture that varies along y and fixes it.
  cv::Mat tex(200, 240, CV_8UC1);
  const cv::Mat noise = texture(240, 200, 3);
  for (int y = 0; y < 200; ++y)
    for (int x = 0; x < 240; ++x) {
      const double stripe = 127.5 + 127.5 * std::sin(2 * M_PI * x / 6.0);
      // Rows vary slowly with noise so the vertical pair has signal; the horizontal
      // direction is dominated by the periodic stripes.
      tex.at<uint8_t>(y, x) =
          cv::saturate_cast<uint8_t>(0.8 * stripe + 0.2 * noise.at<uint8_t>(y, 0));
    }
  const Views v = planeViews(tex, 10);
  auto accuracy = [&](const StereoConfig& cfg) {
    TrinocularMatcher m(rig160(), cfg);
    cv::Mat disp;
    m.compute(v.ref, v.hor, v.ver, disp);
    // Pixels where both partners see the whole window at every disparity searched.
    int correct = 0;
    for (int y = 10; y < 85; ++y)
      for (int x = 40; x < 150; ++x) correct += std::abs(disp.at<float>(y, x) - 10.0f) < 0.5f;
    return correct / (75.0 * 110.0);
  };
  StereoConfig horizontal_only;
  horizontal_only.use_vertical = false;
  horizontal_only.uniqueness = 0.0;  // let the single pair guess, to show it guesses wrong
  StereoConfig both;
  both.uniqueness = 0.0;
  const double single = accuracy(horizontal_only), pair_sum = accuracy(both);
  EXPECT_LT(single, 0.6);
  EXPECT_GT(pair_sum, 0.95);
}

// Valid pixels of the background columns `k` px left and right of the box, and how many
// of them took the box's disparity (within 1 px): "foreground fattening".
Agreement besideTheBox(const cv::Mat& disp, const test::BoxScene& s, int k) {
  Agreement a;
  for (int x : {s.box.x - k, s.box.x + s.box.width - 1 + k})
    for (int y = s.box.y; y < s.box.y + s.box.height; ++y) {
      const float got = disp.at<float>(y, x);
      if (got == kInvalidDisparity) continue;
      ++a.valid;
      a.good += std::abs(got - s.box_disparity) < 1.0;
    }
  return a;
}

TEST(TrinocularMatcherTest, ShiftableWindowsDoNotFattenTheForeground) {
  const test::BoxScene scene;
  const test::BoxViews v = test::renderBoxScene(scene);
  StereoConfig centred;
  centred.window_shift = 0;
  StereoConfig shiftable;
  shiftable.window_shift = 2;
  const int r = shiftable.window / 2, s = shiftable.window_shift;
  ASSERT_GT(s, 0);
  cv::Mat d_centred, d_shiftable;
  TrinocularMatcher(rig160(), centred).compute(v.ref, v.hor, v.ver, d_centred);
  TrinocularMatcher(rig160(), shiftable).compute(v.ref, v.hor, v.ver, d_shiftable);
  const int column_pixels = 2 * scene.box.height;  // one column each side
  for (int k = 1; k <= r; ++k) {
    const Agreement fat_centred = besideTheBox(d_centred, scene, k);
    const Agreement fat_shiftable = besideTheBox(d_shiftable, scene, k);
    std::printf(
        "%d px beside the box, with its disparity: centred %d of %d valid, shiftable %d of %d\n", k,
        fat_centred.good, fat_centred.valid, fat_shiftable.good, fat_shiftable.valid);
    // Centred 7 x 7 windows give the background up to r px beside the box its disparity ...
    EXPECT_GT(fat_centred.good, column_pixels / 2) << k;
    // ... windows that may move s px off the edge leave at most r - s px of it.
    if (k > r - s) {
      EXPECT_LT(fat_shiftable.good, column_pixels / 20) << k;
    }
  }
  // The box itself is matched as densely and exactly as before.
  const cv::Rect inside(scene.box.x + 1, scene.box.y + 1, scene.box.width - 2,
                        scene.box.height - 2);
  const Agreement in_shiftable = agreement(d_shiftable, inside, scene.box_disparity);
  EXPECT_GT(in_shiftable.valid, 0.95 * inside.area());
  EXPECT_GT(in_shiftable.good, 0.98 * in_shiftable.valid);
}

TEST(TrinocularMatcherTest, ConfigValidationNamesTheField) {
  StereoConfig c;
  c.window = 8;
  try {
    c.validate();
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'window'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("odd"), std::string::npos) << e.what();
  }
  c = StereoConfig{};
  c.window_shift = 4;  // more than half the 7 px window: the pixel would leave its window
  try {
    c.validate();
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'window_shift'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("got 4"), std::string::npos) << e.what();
  }
  c.window_shift = -1;
  EXPECT_THROW(c.validate(), std::invalid_argument);
  c.window_shift = 0;
  EXPECT_NO_THROW(c.validate());
}

}  // namespace
}  // namespace coopmap

namespace coopmap {
namespace {

// Views of a plane at disparity d for a rig whose partners sit at any side and baseline
// ratio: the horizontal partner sees the texture shifted by -sh * d along x, the vertical
// one by -sv * d along y (sh = tx / b, sv = ty / b for offsets (tx, 0) and (0, ty)).
Views shiftedViews(const cv::Mat& tex, int d, int sh, int sv) {
  const int m = 70;
  Views v;
  v.ref = tex(cv::Rect(m, m, 160, 120)).clone();
  v.hor = tex(cv::Rect(m + sh * d, m, 160, 120)).clone();
  v.ver = tex(cv::Rect(m, m + sv * d, 160, 120)).clone();
  return v;
}

TEST(TrinocularMatcherTest, AnySignAndBaselineRatio) {
  const cv::Mat tex = texture(300, 260, 5);
  struct Case {
    double tx, ty;  // partner offsets in baselines of the horizontal pair
  } cases[] = {{1, -1}, {-1, -1}, {1, 1}, {-1, 1}, {1, -2}, {1, 2}};
  for (const Case& c : cases) {
    TrinocularRig rig = rig160();
    rig.horizontal_offset = {0.1 * c.tx, 0.0, 0.0};
    rig.vertical_offset = {0.0, 0.1 * c.ty, 0.0};
    const int d = 6;
    // Partner pixel = reference pixel shifted by -(offset / b) * d.
    const Views v = shiftedViews(tex, d, static_cast<int>(c.tx), static_cast<int>(c.ty));
    TrinocularMatcher m(rig, StereoConfig{});
    cv::Mat disp;
    m.compute(v.ref, v.hor, v.ver, disp);
    const auto [valid, good] = agreement(disp, cv::Rect(20, 20, 120, 80), d);
    EXPECT_GT(valid, 0.8 * 80 * 120) << "offsets " << c.tx << ", " << c.ty;
    EXPECT_GT(good, 0.98 * valid) << "offsets " << c.tx << ", " << c.ty;
  }
}

TEST(TrinocularMatcherTest, DiagonalPartnerIsRejectedClearly) {
  TrinocularRig rig = rig160();
  rig.vertical_offset = {0.05, -0.1, 0.0};
  try {
    TrinocularMatcher m(rig, StereoConfig{});
    FAIL() << "expected an exception";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("vertical_offset"), std::string::npos) << e.what();
  }
}

TEST(TrinocularMatcherTest, WiderDisparityRangesMatchToo) {
  const cv::Mat tex = texture(300, 260, 6);
  for (int nd : {16, 48, 64, 40}) {
    StereoConfig c;
    c.num_disparities = nd;
    TrinocularMatcher m(rig160(), c);
    const int d = nd / 2 - 1;
    const Views v = shiftedViews(tex, d, 1, -1);
    cv::Mat disp;
    m.compute(v.ref, v.hor, v.ver, disp);
    const auto [valid, good] = agreement(disp, cv::Rect(70, 10, 80, 100), d);
    EXPECT_GT(valid, 1000) << nd;
    EXPECT_GT(good, 0.98 * valid) << nd;
  }
}

}  // namespace
}  // namespace coopmap

namespace coopmap {
namespace {

// Cameras differ in gain and offset (the Triclops's three sensors do): on a low-contrast
// texture a few grey levels of offset defeat raw SAD; normalising the partners fixes it.
TEST(TrinocularMatcherTest, PhotometricNormalisationForgivesGainAndOffset) {
  cv::Mat tex = texture(240, 200, 7);
  tex.convertTo(tex, CV_8U, 24.0 / 255.0, 116.0);  // grey 116..140: weak texture
  const int d = 9;
  Views v = planeViews(tex, d);
  v.hor.convertTo(v.hor, CV_8U, 1.04, 5.0);
  v.ver.convertTo(v.ver, CV_8U, 0.97, -6.0);
  auto goodPixels = [&](StereoConfig::Photometric p) {
    StereoConfig c;
    c.min_texture = 1.0;
    c.photometric = p;
    TrinocularMatcher m(rig160(), c);
    cv::Mat disp;
    m.compute(v.ref, v.hor, v.ver, disp);
    return agreement(disp, cv::Rect(0, 0, 160, 120), d).good;
  };
  const int none = goodPixels(StereoConfig::Photometric::kNone);
  const int global = goodPixels(StereoConfig::Photometric::kGlobal);
  const int local = goodPixels(StereoConfig::Photometric::kLocalMean);
  std::printf("good pixels: none %d, global %d, local %d of %d\n", none, global, local, 160 * 120);
  EXPECT_GT(global, 0.8 * 160 * 120);
  EXPECT_GT(local, 0.8 * 160 * 120);
  EXPECT_LT(none, 0.5 * global);
}

TEST(TrinocularMatcherTest, PhotometricModeNamesRoundTrip) {
  for (auto p : {StereoConfig::Photometric::kNone, StereoConfig::Photometric::kGlobal,
                 StereoConfig::Photometric::kLocalMean})
    EXPECT_EQ(parsePhotometric(toString(p)), p);
  try {
    parsePhotometric("census");
    FAIL() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("'photometric'"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("census"), std::string::npos) << e.what();
  }
  StereoConfig c;
  c.prefilter_window = 4;
  EXPECT_THROW(c.validate(), std::invalid_argument);
}

}  // namespace
}  // namespace coopmap
