// Scoring disparity images against ground truth, and pictures of them for people.
#pragma once

#include <opencv2/core/mat.hpp>

namespace coopmap {

struct DisparityScore {
  double bad_pixel_rate = 0.0;  // of the valid pixels with ground truth: |error| > threshold
  double mae = 0.0;             // mean absolute error (px) of those pixels
  // Mean signed error (px, estimate minus truth) of the good pixels (|error| <= threshold):
  // a systematic sub-pixel offset, which turns into a range error growing with depth.
  double bias = 0.0;
  // Mean relative depth error of the good pixels (truth / estimate - 1): a range scale
  // error, which a distance measured from stereo inherits whole.
  double depth_scale_error = 0.0;
  int good = 0;          // valid pixels with |error| <= threshold
  double density = 0.0;  // valid pixels / pixels with ground truth
  int evaluated = 0;     // pixels with ground truth (inside the border)
  int valid = 0;
  int bad = 0;
};

// Scores `disparity` (CV_32F, <= 0 invalid) against `truth` (CV_32F, <= 0 unknown), both
// in the same disparity units, skipping `border` pixels on every side.
DisparityScore scoreDisparity(const cv::Mat& disparity, const cv::Mat& truth,
                              double bad_threshold = 1.0, int border = 0);

// Ground-truth disparity (CV_32F) from a depth image (CV_32F metres, <= 0 unknown):
// focal_baseline / depth.
cv::Mat disparityFromDepth(const cv::Mat& depth, double focal_baseline);

// A colour picture (CV_8UC3, BGR) of a disparity image: near warm, far cool, invalid black.
cv::Mat colourDisparity(const cv::Mat& disparity, double max_disparity);

// Errors against ground truth (CV_8UC3, BGR): good grey by depth, bad (> threshold) red,
// invalid black, no ground truth dark blue.
cv::Mat errorPicture(const cv::Mat& disparity, const cv::Mat& truth, double bad_threshold = 1.0);

}  // namespace coopmap
