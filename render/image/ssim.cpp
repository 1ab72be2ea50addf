#include "ssim.h"

#include <cmath>
#include <vector>

#include "core/error.h"
#include "core/parallel.h"

namespace spume {

std::array<double, kSsimWindow> ssim_gaussian_1d() {
  std::array<double, kSsimWindow> g{};
  double sum = 0.0;
  for (int i = 0; i < kSsimWindow; ++i) {
    const double x = double(i - kSsimWindow / 2);
    g[size_t(i)] = std::exp(-x * x / (2.0 * kSsimSigma * kSsimSigma));
    sum += g[size_t(i)];
  }
  for (double& v : g) v /= sum;
  return g;
}

namespace {

// The five windowed moments (x, y, x^2, y^2, xy) after the horizontal pass, one plane each.
struct Moments {
  int width = 0, height = 0;  // width = image width - window + 1 (valid positions), height = image height
  std::vector<double> x, y, xx, yy, xy;
  Moments(int w, int h) : width(w), height(h) {
    const size_t n = size_t(w) * size_t(h);
    x.resize(n), y.resize(n), xx.resize(n), yy.resize(n), xy.resize(n);
  }
};

double channel_ssim(const ImageRGB8& a, const ImageRGB8& b, int c, const std::array<double, kSsimWindow>& g) {
  const int W = a.width, H = a.height, K = kSsimWindow;
  const int ow = W - K + 1, oh = H - K + 1;
  // The Gaussian window is separable: filter rows first, then columns of the row results.
  Moments m(ow, H);
  parallel_for(size_t(H), 8, [&](size_t yb, size_t ye) {
    std::vector<double> ra(static_cast<size_t>(W)), rb(static_cast<size_t>(W));
    for (size_t yy = yb; yy < ye; ++yy) {
      const uint8_t* pa = a.at(0, int(yy));
      const uint8_t* pb = b.at(0, int(yy));
      for (int x = 0; x < W; ++x) ra[size_t(x)] = pa[3 * x + c], rb[size_t(x)] = pb[3 * x + c];
      for (int x = 0; x < ow; ++x) {
        double sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
        for (int k = 0; k < K; ++k) {
          const double w = g[size_t(k)], u = ra[size_t(x + k)], v = rb[size_t(x + k)];
          sx += w * u, sy += w * v, sxx += w * u * u, syy += w * v * v, sxy += w * u * v;
        }
        const size_t i = yy * size_t(ow) + size_t(x);
        m.x[i] = sx, m.y[i] = sy, m.xx[i] = sxx, m.yy[i] = syy, m.xy[i] = sxy;
      }
    }
  });
  const double C1 = (kSsimK1 * 255.0) * (kSsimK1 * 255.0), C2 = (kSsimK2 * 255.0) * (kSsimK2 * 255.0);
  std::vector<double> row_sum(size_t(oh), 0.0);
  parallel_for(size_t(oh), 8, [&](size_t yb, size_t ye) {
    for (size_t y0 = yb; y0 < ye; ++y0) {
      double total = 0.0;
      for (int x = 0; x < ow; ++x) {
        double mx = 0, my = 0, mxx = 0, myy = 0, mxy = 0;
        for (int k = 0; k < K; ++k) {
          const double w = g[size_t(k)];
          const size_t i = (y0 + size_t(k)) * size_t(ow) + size_t(x);
          mx += w * m.x[i], my += w * m.y[i], mxx += w * m.xx[i], myy += w * m.yy[i], mxy += w * m.xy[i];
        }
        // Variances as E[x^2] - mu^2; rounding can push a flat window's variance a hair below zero,
        // and C2 (58.5) dwarfs that, so no clamping is needed.
        const double vx = mxx - mx * mx, vy = myy - my * my, cxy = mxy - mx * my;
        total += ((2.0 * mx * my + C1) * (2.0 * cxy + C2)) / ((mx * mx + my * my + C1) * (vx + vy + C2));
      }
      row_sum[y0] = total;
    }
  });
  double sum = 0.0;
  for (double s : row_sum) sum += s;  // in row order: the same for any thread count
  return sum / (double(ow) * double(oh));
}

}  // namespace

SsimResult ssim_rgb(const ImageRGB8& a, const ImageRGB8& b) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
    fail("SSIM: sizes differ (", a.width, "x", a.height, " vs ", b.width, "x", b.height, ")");
  SsimResult r;
  if (a.width < kSsimWindow || a.height < kSsimWindow) return r;
  const auto g = ssim_gaussian_1d();
  for (int c = 0; c < 3; ++c) r.channel[size_t(c)] = channel_ssim(a, b, c, g);
  r.defined = true;
  r.mean = (r.channel[0] + r.channel[1] + r.channel[2]) / 3.0;
  return r;
}

}  // namespace spume
