#pragma once
// A small, fast, seeded random source for sensor noise: xoshiro256** seeded through splitmix64,
// normals by Marsaglia's polar method, and (normal_fast, the LiDAR's range noise) by a Ziggurat
// (Marsaglia & Tsang 2000 in Doornik's ZIGNOR form, 128 layers). Written
// out so the same seed gives the same numbers on every standard library:
// std::normal_distribution's algorithm is unspecified, and the table is given bit for bit.
#include <cmath>
#include <cstdint>

namespace brickyard::sim {

namespace zig {
// Layer edges of the 128-layer Ziggurat for exp(-x²/2): x[1] = R = 3.442619855899 (where the tail
// starts), x[i + 1] from x[i] so that every layer has the area V = 9.91256303526217e-3, x[0] =
// V / f(R) (the base layer's width as a rectangle), x[128] = 0. Computed once offline in double
// precision (x[i + 1] = sqrt(-2 log(V / x[i] + f(x[i])))) and written as hex literals: the same
// table everywhere, whatever the libm.
inline constexpr double kX[129] = {
    0x1.db4668fe7e4a4p+1, 0x1.b8a7c476d2be8p+1, 0x1.9c8e0c7c8098fp+1, 0x1.8aa73e440ffbcp+1,
    0x1.7d45eb36eb842p+1, 0x1.7279dd4ac3f9dp+1, 0x1.695c2be68edc9p+1, 0x1.616dff7c8f54ap+1,
    0x1.5a61edf7e8f32p+1, 0x1.54052012a04a4p+1, 0x1.4e3456b0e3a1bp+1, 0x1.48d61806d6010p+1,
    0x1.43d75b60bca1dp+1, 0x1.3f29848d3b416p+1, 0x1.3ac11b8e206d6p+1, 0x1.3694f3a3740d9p+1,
    0x1.329d9725e32f7p+1, 0x1.2ed4df8099571p+1, 0x1.2b35aa5ebee3ep+1, 0x1.27bba2b5dbc92p+1,
    0x1.246317a6b53c0p+1, 0x1.2128dd36bdf09p+1, 0x1.1e0a342cf08f6p+1, 0x1.1b04b731f6bccp+1,
    0x1.18164be0c1c39p+1, 0x1.153d16d45743dp+1, 0x1.12777201834f3p+1, 0x1.0fc3e4d95f278p+1,
    0x1.0d211dd28b00fp+1, 0x1.0a8ded0ec371ap+1, 0x1.08093fe3e40e1p+1, 0x1.05921d1c4d769p+1,
    0x1.0327a1cc4cf5ep+1, 0x1.00c8fea1720d4p+1, 0x1.fceaeb2ca5f17p+0, 0x1.f858aff31cbf0p+0,
    0x1.f3da097460823p+0, 0x1.ef6dcddc7d392p+0, 0x1.eb12e91486bbcp+0, 0x1.e6c85a849b015p+0,
    0x1.e28d331c6723cp+0, 0x1.de609397e09b9p+0, 0x1.da41aaf79a344p+0, 0x1.d62fb52580b86p+0,
    0x1.d229f9bfeefdbp+0, 0x1.ce2fcb05f8c34p+0, 0x1.ca4084e091e34p+0, 0x1.c65b8c04dbac2p+0,
    0x1.c2804d2c6b16fp+0, 0x1.beae3c60cd0e4p+0, 0x1.bae4d457ee119p+0, 0x1.b72395df5b73bp+0,
    0x1.b36a075498d64p+0, 0x1.afb7b428fe7a1p+0, 0x1.ac0c2c6fc6382p+0, 0x1.a867047516e4fp+0,
    0x1.a4c7d45d01a31p+0, 0x1.a12e37c983369p+0, 0x1.9d99cd86b58b4p+0, 0x1.9a0a373c73f21p+0,
    0x1.967f1924c7b06p+0, 0x1.92f819c682bf5p+0, 0x1.8f74e1b37c6b8p+0, 0x1.8bf51b49ef337p+0,
    0x1.88787278810a6p+0, 0x1.84fe9484873b9p+0, 0x1.81872fd21db73p+0, 0x1.7e11f3adaeb92p+0,
    0x1.7a9e90168b8eep+0, 0x1.772cb58a39dd6p+0, 0x1.73bc14d01a2c9p+0, 0x1.704c5ec50cb81p+0,
    0x1.6cdd4426b88a5p+0, 0x1.696e755e16b84p+0, 0x1.65ffa248e016dp+0, 0x1.62907a0176ebfp+0,
    0x1.5f20aaa4dfc1ap+0, 0x1.5bafe11654817p+0, 0x1.583dc8bff3219p+0, 0x1.54ca0b4ffd349p+0,
    0x1.515450720f455p+0, 0x1.4ddc3d83a5b84p+0, 0x1.4a617543306ccp+0, 0x1.46e39778de063p+0,
    0x1.436240982ad9dp+0, 0x1.3fdd09591d2a4p+0, 0x1.3c538647ef792p+0, 0x1.38c54749b9033p+0,
    0x1.3531d7146a43ep+0, 0x1.3198ba982d911p+0, 0x1.2df97057e7efbp+0, 0x1.2a536fae30e33p+0,
    0x1.26a627fb9d120p+0, 0x1.22f0ffbaa1e55p+0, 0x1.1f335374a10f8p+0, 0x1.1b6c7492c9735p+0,
    0x1.179ba80463fecp+0, 0x1.13c024b2c7ec6p+0, 0x1.0fd911b97f236p+0, 0x1.0be58456ff4aep+0,
    0x1.07e47d87a40f6p+0, 0x1.03d4e7391c5b7p+0, 0x1.ff6b21fffe31ap-1, 0x1.f70a5866c8f46p-1,
    0x1.ee848e956826fp-1, 0x1.e5d6909f51b6ap-1, 0x1.dcfccc51c59f0p-1, 0x1.d3f340dda611cp-1,
    0x1.cab56ac6a38d3p-1, 0x1.c13e2b014e85cp-1, 0x1.b787a7c516f3bp-1, 0x1.ad8b2506a137cp-1,
    0x1.a340d1baf5b18p-1, 0x1.989f85c753b2cp-1, 0x1.8d9c6a9d35e3dp-1, 0x1.822a858af0e7dp-1,
    0x1.763a1600eec74p-1, 0x1.69b7b213f3f69p-1, 0x1.5c8afdbf0217bp-1, 0x1.4e94c08c0bab7p-1,
    0x1.3fabee1911cd7p-1, 0x1.2f98d6bb4f41fp-1, 0x1.1e0ce6b5969b3p-1, 0x1.0a936da5e55adp-1,
    0x1.e8e576e43fbefp-2, 0x1.b4c8fece48e83p-2, 0x1.73949184db9dfp-2, 0x1.16db47e193e1ap-2,
    0x0.0p+0,
};
inline constexpr double kR = 3.442619855899;
// kX[i + 1] / kX[i]: below it, a point of layer i is under the curve whatever its height.
struct Ratios {
  double r[128];
  constexpr Ratios() : r{} {
    for (int i = 0; i < 128; ++i) r[i] = kX[i + 1] / kX[i];
  }
};
inline constexpr Ratios kRatio{};
}  // namespace zig

class Rng {
 public:
  explicit Rng(std::uint64_t seed = 1) {
    for (auto& w : s_) {
      seed += 0x9E3779B97F4A7C15ull;
      std::uint64_t z = seed;
      z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
      z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
      w = z ^ (z >> 31);
    }
  }
  std::uint64_t next() {
    const std::uint64_t result = rotl(s_[1] * 5, 7) * 9, t = s_[1] << 17;
    s_[2] ^= s_[0]; s_[3] ^= s_[1]; s_[1] ^= s_[2]; s_[0] ^= s_[3];
    s_[2] ^= t; s_[3] = rotl(s_[3], 45);
    return result;
  }
  // Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  // Uniform in (0, 1]: log() of it is finite.
  double uniform_open() { return static_cast<double>((next() >> 11) + 1) * 0x1.0p-53; }
  // Standard normal by Marsaglia's polar form of Box-Muller (the GNSS, IMU and wheel noise).
  double normal() {
    if (has_spare_) { has_spare_ = false; return spare_; }
    // Marsaglia's polar form of Box-Muller: no sine or cosine (they were 6% of a LiDAR frame).
    double u, v, q;
    do {
      u = 2.0 * uniform() - 1.0;
      v = 2.0 * uniform() - 1.0;
      q = u * u + v * v;
    } while (q >= 1.0 || q == 0.0);
    const double f = std::sqrt(-2.0 * std::log(q) / q);
    spare_ = v * f;
    has_spare_ = true;
    return u * f;
  }
  // Standard normal by the Ziggurat, for the LiDAR's range noise (18k normals a frame): one 64-bit
  // draw gives the layer (7 low bits) and a signed uniform (the 53 high bits); 98.8 % of draws
  // return from the rectangle test (a compare and a multiply), the rest take the wedge test (two
  // exp) or the tail beyond R (two log). The polar method cost 8.5 ns a normal, mostly its log.
  // The other sensors keep the polar method: they draw a few normals a step, and the full-stack
  // graphs' outcomes depend on their noise realisations (docs/performance.md, Simulator).
  double normal_fast() {
    for (;;) {
      const std::uint64_t b = next();
      const int i = static_cast<int>(b & 127);
      const double u = static_cast<double>(static_cast<std::int64_t>(b) >> 11) * 0x1.0p-52;  // [-1, 1)
      if (std::abs(u) < zig::kRatio.r[i]) return u * zig::kX[i];
      if (i == 0) {  // the tail beyond R (Marsaglia 1964)
        double x, y;
        do {
          x = std::log(uniform_open()) / zig::kR;
          y = std::log(uniform_open());
        } while (-2 * y < x * x);
        return u < 0 ? x - zig::kR : zig::kR - x;
      }
      // The wedge between the layer's inner rectangle and the curve.
      const double x = u * zig::kX[i];
      const double f0 = std::exp(-0.5 * (zig::kX[i] * zig::kX[i] - x * x));
      const double f1 = std::exp(-0.5 * (zig::kX[i + 1] * zig::kX[i + 1] - x * x));
      if (f1 + uniform() * (f0 - f1) < 1.0) return x;
    }
  }
  double normal(double sigma) { return sigma * normal(); }
  double normal_fast(double sigma) { return sigma * normal_fast(); }

 private:
  static std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
  std::uint64_t s_[4];
  double spare_ = 0;
  bool has_spare_ = false;
};

}  // namespace brickyard::sim
