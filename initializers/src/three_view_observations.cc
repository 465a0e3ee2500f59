#include "trigrav/initializers/three_view_observations.h"

#include <cmath>
#include <sstream>
#include <stdexcept>
#include <string>

#include "input_checks.h"

namespace trigrav {

bool PinholeCamera::IsValid() const {
  return fx > 0.0 && fy > 0.0 && std::isfinite(fx) && std::isfinite(fy) && std::isfinite(cx) &&
         std::isfinite(cy);
}

void ThreeViewObservations::Check() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("trigrav: ThreeViewObservations: " + what);
  };
  for (int k = 0; k < 3; ++k) {
    if (!cameras[k].IsValid()) {
      fail("camera " + std::to_string(k + 1) +
           " needs positive, finite focal lengths and a finite principal point");
    }
    if (!internal::IsUsableDirection(gravity_in_cam[k])) {
      const double g = gravity_in_cam[k].norm();
      fail("gravity_in_cam[" + std::to_string(k) + "] is " +
           (!gravity_in_cam[k].allFinite() ? "not finite"
            : g > 0.0                      ? "too long (its squared length overflows)"
                                           : "zero"));
    }
    if (pixels[k].size() != pixels[0].size()) {
      std::ostringstream message;
      message << "pixels of the three views differ in size (" << pixels[0].size() << ", "
              << pixels[1].size() << ", " << pixels[2].size() << ")";
      fail(message.str());
    }
    for (std::size_t n = 0; n < pixels[k].size(); ++n) {
      // The ray K^-1 [u v 1]^T has z = 1, so it is usable unless a pixel is not finite or, finite
      // but far from the principal point (or with a focal length near the smallest double),
      // overflows the ray or its squared length (found by tests/fuzz).
      if (internal::IsUsableDirection(cameras[k].Ray(pixels[k][n]))) continue;
      fail("pixels[" + std::to_string(k) + "][" + std::to_string(n) + "] is " +
           (!pixels[k][n].allFinite()
                ? "not finite"
                : "too far from the principal point for the focal length (its ray overflows)"));
    }
  }
}

}  // namespace trigrav
