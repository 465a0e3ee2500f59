// Decodes libFuzzer's bytes into the numbers a pose problem is made of. Every read succeeds: past
// the end of the input it returns zeros, so any byte string is a valid (if short) problem.
#ifndef TRIGRAV_TESTS_FUZZ_FUZZ_INPUT_H_
#define TRIGRAV_TESTS_FUZZ_FUZZ_INPUT_H_

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <limits>

namespace trigrav {
namespace fuzz {

class FuzzInput {
 public:
  FuzzInput(const std::uint8_t* data, std::size_t size) : data_(data), size_(size) {}

  bool empty() const { return position_ >= size_; }

  std::uint8_t Byte() { return empty() ? 0 : data_[position_++]; }

  // An integer in [0, count), count >= 1.
  int Index(int count) { return Byte() % count; }

  std::uint32_t Uint32() {
    std::uint32_t value = 0;
    for (int i = 0; i < 4; ++i) value = (value << 8) | Byte();
    return value;
  }

  // A value from one of these families, chosen by a tag byte, so that the values that break
  // numerical code come up often:
  //   special: NaN, +-Inf, +-0, the smallest subnormal, the smallest normal, the largest double,
  //            +-1e300, +-1e-300, +-1e-12, +-1;
  //   small:   a 16-bit fixed-point number in [-8, 8);
  //   scaled:  that number times 10^e, e in [-20, 20);
  //   raw:     any 8 bytes as a double.
  double Double() {
    const std::uint8_t tag = Byte();
    switch (tag % 4) {
      case 0:
        return Special(tag / 4);
      case 1:
        return FixedPoint();
      case 2: {
        const double mantissa = FixedPoint();
        return mantissa * Power10(Index(40) - 20);
      }
      default: {
        std::uint64_t bits = 0;
        for (int i = 0; i < 8; ++i) bits = (bits << 8) | Byte();
        double value;
        std::memcpy(&value, &bits, sizeof(value));
        return value;
      }
    }
  }

  Eigen::Vector3d Vector3() {
    const double x = Double();
    const double y = Double();
    return Eigen::Vector3d(x, y, Double());
  }

 private:
  static double Special(int which) {
    constexpr double kInf = std::numeric_limits<double>::infinity();
    constexpr double kValues[] = {std::numeric_limits<double>::quiet_NaN(),
                                  kInf,
                                  -kInf,
                                  0.0,
                                  -0.0,
                                  std::numeric_limits<double>::denorm_min(),
                                  std::numeric_limits<double>::min(),
                                  std::numeric_limits<double>::max(),
                                  1e300,
                                  -1e300,
                                  1e-300,
                                  -1e-300,
                                  1e-12,
                                  -1e-12,
                                  1.0,
                                  -1.0};
    return kValues[which % (sizeof(kValues) / sizeof(kValues[0]))];
  }

  double FixedPoint() {
    const int raw = static_cast<int>(Byte()) << 8 | Byte();
    return (raw - 32768) / 4096.0;
  }

  static double Power10(int exponent) {
    double value = 1.0;
    for (int i = 0; i < (exponent < 0 ? -exponent : exponent); ++i) value *= 10.0;
    return exponent < 0 ? 1.0 / value : value;
  }

  const std::uint8_t* data_;
  std::size_t size_;
  std::size_t position_ = 0;
};

}  // namespace fuzz
}  // namespace trigrav

#endif  // TRIGRAV_TESTS_FUZZ_FUZZ_INPUT_H_
