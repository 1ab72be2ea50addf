#include "render/image/ssim.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "sim/core/error.h"
#include "sim/core/parallel.h"

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

// Output rows per task. A band filters its rows plus the window's 10 below it horizontally, so the
// buffers stay cache-sized and no frame-sized planes are allocated; rows shared by two bands are
// filtered by both, with the same operations, so the results do not depend on the banding.
constexpr size_t kBandRows = 32;

// The five windowed moments (x, y, x^2, y^2, xy) of a band's rows after the horizontal pass.
struct Moments {
  size_t width;
  std::vector<double> x, y, xx, yy, xy;
  Moments(size_t w, size_t rows) : width(w), x(w * rows), y(x.size()), xx(x.size()), yy(x.size()), xy(x.size()) {}
};

// Horizontal pass of channel c over image rows [y0, y1) into m (row r at offset (r - y0) * width).
// Loops run over x innermost, so they vectorise; each output sums its taps in window order.
void filter_rows(const ImageRGB8& a, const ImageRGB8& b, int c, size_t y0, size_t y1,
                 const std::array<double, kSsimWindow>& g, Moments& m) {
  const size_t W = size_t(a.width), ow = m.width;
  std::vector<double> u(W), v(W), uu(W), vv(W), uv(W);
  std::fill(m.x.begin(), m.x.end(), 0.0), std::fill(m.y.begin(), m.y.end(), 0.0);
  std::fill(m.xx.begin(), m.xx.end(), 0.0), std::fill(m.yy.begin(), m.yy.end(), 0.0);
  std::fill(m.xy.begin(), m.xy.end(), 0.0);
  for (size_t y = y0; y < y1; ++y) {
    const uint8_t* pa = a.at(0, int(y));
    const uint8_t* pb = b.at(0, int(y));
    for (size_t x = 0; x < W; ++x) {
      u[x] = pa[3 * x + size_t(c)], v[x] = pb[3 * x + size_t(c)];
      uu[x] = u[x] * u[x], vv[x] = v[x] * v[x], uv[x] = u[x] * v[x];  // exact: integers below 2^16
    }
    const size_t o = (y - y0) * ow;
    double *mx = &m.x[o], *my = &m.y[o], *mxx = &m.xx[o], *myy = &m.yy[o], *mxy = &m.xy[o];
    for (size_t k = 0; k < size_t(kSsimWindow); ++k) {
      const double w = g[k];
      for (size_t x = 0; x < ow; ++x) {
        mx[x] += w * u[x + k], my[x] += w * v[x + k];
        mxx[x] += w * uu[x + k], myy[x] += w * vv[x + k], mxy[x] += w * uv[x + k];
      }
    }
  }
}

// Vertical pass and the SSIM formula for output row `out_row` (band-relative), summed over x.
double ssim_row(const Moments& m, size_t out_row, const std::array<double, kSsimWindow>& g,
                std::vector<double> (&acc)[6]) {
  const size_t ow = m.width;
  for (auto& a : acc) std::fill(a.begin(), a.end(), 0.0);
  double *mx = acc[0].data(), *my = acc[1].data(), *mxx = acc[2].data(), *myy = acc[3].data(), *mxy = acc[4].data();
  double* s = acc[5].data();
  for (size_t k = 0; k < size_t(kSsimWindow); ++k) {
    const double w = g[k];
    const size_t row = (out_row + k) * ow;
    for (size_t x = 0; x < ow; ++x) {
      mx[x] += w * m.x[row + x], my[x] += w * m.y[row + x];
      mxx[x] += w * m.xx[row + x], myy[x] += w * m.yy[row + x], mxy[x] += w * m.xy[row + x];
    }
  }
  const double C1 = (kSsimK1 * 255.0) * (kSsimK1 * 255.0), C2 = (kSsimK2 * 255.0) * (kSsimK2 * 255.0);
  // Variances as E[x^2] - mu^2; rounding can push a flat window's variance a hair below zero, and
  // C2 (58.5) dwarfs that, so no clamping is needed.
  for (size_t x = 0; x < ow; ++x) {
    const double vx = mxx[x] - mx[x] * mx[x], vy = myy[x] - my[x] * my[x], cxy = mxy[x] - mx[x] * my[x];
    s[x] = ((2.0 * mx[x] * my[x] + C1) * (2.0 * cxy + C2)) / ((mx[x] * mx[x] + my[x] * my[x] + C1) * (vx + vy + C2));
  }
  double total = 0.0;
  for (size_t x = 0; x < ow; ++x) total += s[x];
  return total;
}

}  // namespace

SsimResult ssim_of_identical(int width, int height) {
  SsimResult r;
  r.defined = width >= kSsimWindow && height >= kSsimWindow;
  if (r.defined) r.mean = 1.0, r.channel = {1.0, 1.0, 1.0};
  return r;
}

SsimResult ssim_rgb(const ImageRGB8& a, const ImageRGB8& b) {
  if (a.width != b.width || a.height != b.height || a.rgb.size() != b.rgb.size())
    fail("SSIM: sizes differ (", a.width, "x", a.height, " vs ", b.width, "x", b.height, ")");
  SsimResult r;
  if (a.width < kSsimWindow || a.height < kSsimWindow) return r;
  const auto g = ssim_gaussian_1d();
  const size_t K = kSsimWindow, ow = size_t(a.width) - K + 1, oh = size_t(a.height) - K + 1;
  const size_t bands = (oh + kBandRows - 1) / kBandRows;
  std::vector<double> row_sum[3];
  for (auto& rs : row_sum) rs.assign(oh, 0.0);
  parallel_for(bands, 1, [&](size_t bb, size_t be) {
    Moments m(ow, kBandRows + K - 1);
    std::vector<double> acc[6];
    for (auto& v : acc) v.resize(ow);
    for (size_t band = bb; band < be; ++band) {
      const size_t y0 = band * kBandRows, y1 = std::min(oh, y0 + kBandRows);
      for (int c = 0; c < 3; ++c) {
        filter_rows(a, b, c, y0, y1 + K - 1, g, m);
        for (size_t y = y0; y < y1; ++y) row_sum[c][y] = ssim_row(m, y - y0, g, acc);
      }
    }
  });
  for (size_t c = 0; c < 3; ++c) {
    double sum = 0.0;
    for (double v : row_sum[c]) sum += v;  // in row order: the same for any thread count
    r.channel[c] = sum / (double(ow) * double(oh));
  }
  r.defined = true;
  r.mean = (r.channel[0] + r.channel[1] + r.channel[2]) / 3.0;
  return r;
}

}  // namespace spume
