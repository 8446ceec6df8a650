#include "rbfib/core/error_norms.hpp"

#include "rbfib/core/error.hpp"

#include <algorithm>
#include <cmath>

namespace rbfib {

MaxNormError max_norm_error(const std::vector<double>& x, const std::vector<double>& exact) {
  require(x.size() == exact.size(), "max_norm_error: length of the approximation", x.size(),
          "must equal the reference's " + to_text(exact.size()));
  MaxNormError e;
  double scale = 0;
  for (std::size_t i = 0; i < x.size(); ++i) {
    e.abs = std::max(e.abs, std::abs(x[i] - exact[i]));
    scale = std::max(scale, std::abs(exact[i]));
  }
  e.rel = e.abs / scale;
  return e;
}

}  // namespace rbfib
