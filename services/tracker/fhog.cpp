// FHOG feature maps (see fhog.hpp). Follows Felzenszwalb's features.cc: orientation snapped to one of 18
// directions, magnitude spread bilinearly over the 4 nearest cells, block normalisation, truncation 0.2.
#include "fhog.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

namespace gpilot {
namespace {

constexpr int kOrients = 18;
constexpr float kTruncate = 0.2f;
constexpr float kEps = 1e-4f;
// 1 / sqrt(18): the texture channels' weight in features.cc.
constexpr float kTextureWeight = 0.2357f;

// Orientation bin (0..17, bin o centred on o * 20 degrees) of every integer gradient (dx, dy) of 8-bit
// images, |dx|, |dy| <= 255: one table lookup per pixel instead of an atan2.
class OrientationTable {
 public:
  OrientationTable() : bins_(511 * 511) {
    for (int dy = -255; dy <= 255; ++dy)
      for (int dx = -255; dx <= 255; ++dx) {
        double a = std::atan2(static_cast<double>(dy), static_cast<double>(dx));
        if (a < 0) a += 2.0 * M_PI;
        int o = static_cast<int>(a * kOrients / (2.0 * M_PI) + 0.5);
        if (o >= kOrients) o -= kOrients;
        bins_[static_cast<size_t>((dy + 255) * 511 + dx + 255)] = static_cast<uint8_t>(o);
      }
  }
  int bin(int dx, int dy) const { return bins_[static_cast<size_t>((dy + 255) * 511 + dx + 255)]; }

 private:
  std::vector<uint8_t> bins_;
};

const OrientationTable& orientation_table() {
  static const OrientationTable table;
  return table;
}

}  // namespace

Fhog::Fhog() { orientation_table(); }

void Fhog::compute(const cv::Mat& patch, int cell, std::vector<cv::Mat>& out, size_t first) {
  CV_Assert(patch.depth() == CV_8U && (patch.channels() == 1 || patch.channels() == 3) && cell >= 1);
  const int rows = patch.rows / cell;
  const int cols = patch.cols / cell;
  if (out.size() < first + kChannels) out.resize(first + kChannels);
  float* dst[kChannels];
  for (int c = 0; c < kChannels; ++c) {
    out[first + c].create(std::max(rows, 1), std::max(cols, 1), CV_32F);
    dst[c] = out[first + c].ptr<float>();
  }
  if (rows < 1 || cols < 1) {
    for (int c = 0; c < kChannels; ++c) out[first + c].setTo(0);
    return;
  }
  hist_.create(rows * cols, kOrients, CV_32F);
  hist_.setTo(0);
  norm_.create(rows, cols, CV_32F);

  const int nch = patch.channels();
  const int h = rows * cell;
  const int w = cols * cell;
  const float inv_cell = 1.0f / static_cast<float>(cell);
  const OrientationTable& table = orientation_table();
  float* hist = hist_.ptr<float>();
  // Bilinear spatial weights depend on x only through these: computed once per call.
  gdx_.resize(static_cast<size_t>(w));
  gdy_.resize(static_cast<size_t>(w));
  gv_.resize(static_cast<size_t>(w));
  xcell_.resize(static_cast<size_t>(w));
  xw_.resize(static_cast<size_t>(w));
  for (int x = 0; x < w; ++x) {
    const float xp = (static_cast<float>(x) + 0.5f) * inv_cell - 0.5f;
    xcell_[static_cast<size_t>(x)] = static_cast<int>(std::floor(xp));
    xw_[static_cast<size_t>(x)] = xp - std::floor(xp);
  }

  for (int y = 0; y < h; ++y) {
    const uchar* up = patch.ptr<uchar>(std::max(y - 1, 0));
    const uchar* mid = patch.ptr<uchar>(y);
    const uchar* dn = patch.ptr<uchar>(std::min(y + 1, patch.rows - 1));
    const float yp = (static_cast<float>(y) + 0.5f) * inv_cell - 0.5f;
    const int iy = static_cast<int>(std::floor(yp));
    const float vy0 = yp - static_cast<float>(iy);
    const float vy1 = 1.0f - vy0;
    // Pass 1: the strongest channel's gradient of every pixel of the row (branch-free, vectorisable).
    int* gdx = gdx_.data();
    int* gdy = gdy_.data();
    int* gv = gv_.data();
    const auto strongest = [&](int x, int xl, int xr) {
      int bdx = static_cast<int>(mid[xr]) - static_cast<int>(mid[xl]);
      int bdy = static_cast<int>(dn[x * nch]) - static_cast<int>(up[x * nch]);
      int bv = bdx * bdx + bdy * bdy;
      for (int c = 1; c < nch; ++c) {
        const int dx = static_cast<int>(mid[xr + c]) - static_cast<int>(mid[xl + c]);
        const int dy = static_cast<int>(dn[x * nch + c]) - static_cast<int>(up[x * nch + c]);
        const int v = dx * dx + dy * dy;
        const bool better = v > bv;
        bdx = better ? dx : bdx;
        bdy = better ? dy : bdy;
        bv = better ? v : bv;
      }
      gdx[x] = bdx;
      gdy[x] = bdy;
      gv[x] = bv;
    };
    // The first and last columns (replicated border) on their own; the columns between, with both neighbours in
    // the patch, in a loop per channel count (the general one, with its clamped neighbours and a channel loop of
    // run-time length, made FHOG a fifth slower on a colour patch).
    const int inner_end = std::min(w, patch.cols - 1);
    strongest(0, 0, std::min(1, patch.cols - 1) * nch);
    if (nch == 3) {
      for (int x = 1; x < inner_end; ++x) {
        const uchar* m = mid + 3 * x;
        const uchar* u = up + 3 * x;
        const uchar* d = dn + 3 * x;
        int bdx = m[3] - m[-3], bdy = d[0] - u[0];
        int bv = bdx * bdx + bdy * bdy;
        const int dx1 = m[4] - m[-2], dy1 = d[1] - u[1], v1 = dx1 * dx1 + dy1 * dy1;
        bdx = v1 > bv ? dx1 : bdx;
        bdy = v1 > bv ? dy1 : bdy;
        bv = v1 > bv ? v1 : bv;
        const int dx2 = m[5] - m[-1], dy2 = d[2] - u[2], v2 = dx2 * dx2 + dy2 * dy2;
        bdx = v2 > bv ? dx2 : bdx;
        bdy = v2 > bv ? dy2 : bdy;
        bv = v2 > bv ? v2 : bv;
        gdx[x] = bdx;
        gdy[x] = bdy;
        gv[x] = bv;
      }
    } else {
      for (int x = 1; x < inner_end; ++x) {
        const int dx = mid[x + 1] - mid[x - 1], dy = dn[x] - up[x];
        gdx[x] = dx;
        gdy[x] = dy;
        gv[x] = dx * dx + dy * dy;
      }
    }
    for (int x = std::max(1, inner_end); x < w; ++x) strongest(x, (x - 1) * nch, std::min(x + 1, patch.cols - 1) * nch);
    // Pass 2: orientation bin and bilinear vote into the 4 nearest cells.
    for (int x = 0; x < w; ++x) {
      const int best_v = gv[x];
      if (best_v == 0) continue;
      const int best_dx = gdx[x], best_dy = gdy[x];
      const float mag = std::sqrt(static_cast<float>(best_v));
      const int o = table.bin(best_dx, best_dy);
      const int ix = xcell_[static_cast<size_t>(x)];
      const float vx0 = xw_[static_cast<size_t>(x)];
      const float vx1 = 1.0f - vx0;
      if (iy >= 0) {
        if (ix >= 0) hist[(iy * cols + ix) * kOrients + o] += vx1 * vy1 * mag;
        if (ix + 1 < cols) hist[(iy * cols + ix + 1) * kOrients + o] += vx0 * vy1 * mag;
      }
      if (iy + 1 < rows) {
        if (ix >= 0) hist[((iy + 1) * cols + ix) * kOrients + o] += vx1 * vy0 * mag;
        if (ix + 1 < cols) hist[((iy + 1) * cols + ix + 1) * kOrients + o] += vx0 * vy0 * mag;
      }
    }
  }

  for (int i = 0; i < rows * cols; ++i) {
    const float* hc = hist + i * kOrients;
    float e = 0;
    for (int o = 0; o < kOrients / 2; ++o) {
      const float s = hc[o] + hc[o + kOrients / 2];
      e += s * s;
    }
    norm_.ptr<float>()[i] = e;
  }

  // Energy of the 2x2 block whose top-left cell is (by, bx), the block index clamped into the map so that
  // border cells get the nearest inner blocks (features.cc drops the border instead).
  const int brows = std::max(rows - 1, 1);
  const int bcols = std::max(cols - 1, 1);
  // Each block's inverse norm once (a cell takes four blocks, a block serves four cells).
  block_norm_.create(brows, bcols, CV_32F);
  for (int by = 0; by < brows; ++by) {
    const int by1 = std::min(by + 1, rows - 1);
    const float* n = norm_.ptr<float>();
    float* out = block_norm_.ptr<float>(by);
    for (int bx = 0; bx < bcols; ++bx) {
      const int bx1 = std::min(bx + 1, cols - 1);
      const float s = n[by * cols + bx] + n[by * cols + bx1] + n[by1 * cols + bx] + n[by1 * cols + bx1];
      out[bx] = 1.0f / std::sqrt(s + kEps);
    }
  }
  auto block = [&](int by, int bx) {
    return block_norm_.at<float>(std::clamp(by, 0, brows - 1), std::clamp(bx, 0, bcols - 1));
  };

  for (int y = 0; y < rows; ++y) {
    for (int x = 0; x < cols; ++x) {
      const float n1 = block(y, x);
      const float n2 = block(y, x - 1);
      const float n3 = block(y - 1, x);
      const float n4 = block(y - 1, x - 1);
      const float* hc = hist + (y * cols + x) * kOrients;
      const int i = y * cols + x;
      float t1 = 0, t2 = 0, t3 = 0, t4 = 0;
      for (int o = 0; o < kOrients; ++o) {
        const float h1 = std::min(hc[o] * n1, kTruncate);
        const float h2 = std::min(hc[o] * n2, kTruncate);
        const float h3 = std::min(hc[o] * n3, kTruncate);
        const float h4 = std::min(hc[o] * n4, kTruncate);
        dst[o][i] = 0.5f * (h1 + h2 + h3 + h4);
        t1 += h1;
        t2 += h2;
        t3 += h3;
        t4 += h4;
      }
      for (int o = 0; o < kOrients / 2; ++o) {
        const float s = hc[o] + hc[o + kOrients / 2];
        const float h1 = std::min(s * n1, kTruncate);
        const float h2 = std::min(s * n2, kTruncate);
        const float h3 = std::min(s * n3, kTruncate);
        const float h4 = std::min(s * n4, kTruncate);
        dst[kOrients + o][i] = 0.5f * (h1 + h2 + h3 + h4);
      }
      dst[27][i] = kTextureWeight * t1;
      dst[28][i] = kTextureWeight * t2;
      dst[29][i] = kTextureWeight * t3;
      dst[30][i] = kTextureWeight * t4;
    }
  }
}

}  // namespace gpilot
