#pragma once
// SSIM, the structural similarity index of Wang, Bovik, Sheikh and Simoncelli, "Image Quality
// Assessment: From Error Visibility to Structural Similarity", IEEE TIP 13(4), 2004, as the paper
// defines it: local statistics under an 11x11 circular-symmetric Gaussian window (sigma 1.5,
// normalised to unit sum), SSIM = (2 mu_x mu_y + C1)(2 sigma_xy + C2) /
// ((mu_x^2 + mu_y^2 + C1)(sigma_x^2 + sigma_y^2 + C2)) with C1 = (0.01 L)^2, C2 = (0.03 L)^2, L = 255,
// evaluated at every window position that lies wholly inside the image (no padding, no
// down-sampling) and averaged (the paper's mean SSIM). Colour: each of R, G and B on its 8-bit code
// values, and the frame's SSIM is the mean of the three channels' mean SSIM, so a change of hue that
// keeps the luminance still counts.
#include <array>

#include "render/image/image.h"

namespace spume {

constexpr int kSsimWindow = 11;
constexpr double kSsimSigma = 1.5;
constexpr double kSsimK1 = 0.01, kSsimK2 = 0.03;

struct SsimResult {
  bool defined = false;               // false when the image is smaller than the window
  double mean = 0.0;                  // mean of the three channels; 1 for identical images
  std::array<double, 3> channel{};    // mean SSIM of R, G, B
};

// The same result for any thread count: every window position is computed alone and the sums run
// row by row in a fixed order. Throws Error when the sizes differ.
SsimResult ssim_rgb(const ImageRGB8& reference, const ImageRGB8& candidate);

// What ssim_rgb returns for two equal images of this size, without the work: every window's two
// factors have equal numerator and denominator bit for bit, so each is exactly 1.
SsimResult ssim_of_identical(int width, int height);

// The normalised 1-D Gaussian whose outer product is the 2-D window.
std::array<double, kSsimWindow> ssim_gaussian_1d();

}  // namespace spume
