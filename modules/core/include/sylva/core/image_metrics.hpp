#pragma once
// Image error metrics (DESIGN.md §2 "Measurements are first-class"): what sylva-bench and the
// render tests use to put a number on how far a level-of-detail render is from its reference.
//
// Inputs are sylva::Image (float per channel; normalised 0..1 for images read from 8/16-bit
// files). Pixel values are used as stored: no sRGB decoding, no clamping.
//
// Failure (every function): Result error kInvalidArgument when an image is empty, when the two
// images differ in width, height or channel count (the message names both, "256x144x3 vs
// 128x72x4"), or when an image holds NaN/Inf (the message gives their count and first pixel).
// Functions with a parameter reject out-of-range values naming the parameter.

#include <sylva/core/image.hpp>
#include <sylva/core/result.hpp>

#include <glm/glm.hpp>

#include <cstddef>
#include <vector>

namespace sylva {

// Mean squared error over every channel of every pixel.
Result<double> mse(const Image& a, const Image& b);
// Root mean squared error: sqrt(mse). A constant offset d on every value gives exactly |d|.
Result<double> rmse(const Image& a, const Image& b);
// Peak signal-to-noise ratio in dB: 10 log10(peak^2 / mse). Identical images give +infinity
// (std::numeric_limits<double>::infinity()), which callers print as "inf". peak > 0.
Result<double> psnr(const Image& a, const Image& b, double peak = 1.0);

// SSIM after Wang, Bovik, Sheikh, Simoncelli 2004 ("Image quality assessment: from error
// visibility to structural similarity"): 11x11 Gaussian window with sigma 1.5 (normalised to
// sum 1), C1 = (0.01 L)^2, C2 = (0.03 L)^2 with L = dynamic_range, and
//   SSIM(x, y) = (2 mu_x mu_y + C1)(2 sigma_xy + C2) / ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 + C2))
// per window. Identical images give exactly 1; the range is [-1, 1].
enum class SsimChannels {
  kLuminance,   // one plane: channel 0 for 1-2 channel images, Rec. 709 luma
                // (0.2126 R + 0.7152 G + 0.0722 B) for 3-4 channels; alpha ignored
  kPerChannel,  // every channel (alpha included) separately; the mean is their average
};
enum class SsimBorder {
  kValid,      // as the reference MATLAB code: only windows wholly inside the image, so the map
               // is (w - 10) x (h - 10); images smaller than 11x11 are an error
  kTruncated,  // every pixel, with the window cut at the image border and renormalised; the map
               // has the image's size (works for any size, differs from kValid near borders)
};
struct SsimOptions {
  SsimChannels channels = SsimChannels::kLuminance;
  SsimBorder border = SsimBorder::kValid;
  double dynamic_range = 1.0;  // L: 1 for normalised images, > 0
};
struct SsimResult {
  double mean = 0.0;                // mean SSIM (over the map and, for kPerChannel, channels)
  std::vector<double> per_channel;  // mean per plane (one entry for kLuminance)
  Image map;                        // per-window SSIM, one channel per plane
};
Result<SsimResult> ssim(const Image& a, const Image& b, const SsimOptions& options = {});

// Share (0..1) of pixels whose largest channel difference |a - b| exceeds `threshold` (>= 0).
struct DifferenceCount {
  std::size_t pixels = 0;    // pixels over the threshold
  std::size_t total = 0;     // all pixels
  double share = 0.0;        // pixels / total
  float max_difference = 0;  // largest channel difference anywhere
};
Result<DifferenceCount> count_exceeding(const Image& a, const Image& b, float threshold);
Result<double> share_exceeding(const Image& a, const Image& b, float threshold);

// Silhouettes: which pixels of a mask image are foreground.
struct MaskOptions {
  int channel = -1;        // -1: alpha (the last channel) of 2- and 4-channel images, else channel 0
  float threshold = 0.5f;  // foreground where value > threshold
};
struct SilhouetteStats {
  std::size_t reference_pixels = 0;  // |R|
  std::size_t test_pixels = 0;       // |T|
  std::size_t intersection = 0;      // |R and T|
  std::size_t union_pixels = 0;      // |R or T|
  // |R and T| / |R|: how much of the reference silhouette the test covers. An empty reference
  // counts as fully covered (1).
  double coverage = 1.0;
  // |R and T| / |R or T|. Both empty: 1.
  double iou = 1.0;
};
// Errors as above, plus a channel outside the images' channel range.
Result<SilhouetteStats> silhouette_coverage(const Image& reference, const Image& test,
                                            const MaskOptions& options = {});

// One-channel mask (1 foreground, 0 background) of the pixels whose colour differs from
// `background` by more than `tolerance` in some channel; channels beyond 4 are not compared and
// only the image's first channels of `background` are used (a render cleared to magenta:
// background = {1, 0, 1, 1}). tolerance >= 0.
Result<Image> mask_from_background(const Image& image, glm::vec4 background, float tolerance);

// |a - b| * gain per channel, same size and channel count (values are not clamped). gain >= 0.
Result<Image> difference_image(const Image& a, const Image& b, float gain = 1.0f);
// RGB heat map of the largest channel difference per pixel: 0 is black, then red, yellow and
// white at max_error and above (luminance rises monotonically). max_error > 0.
Result<Image> difference_heatmap(const Image& a, const Image& b, float max_error);

}  // namespace sylva
