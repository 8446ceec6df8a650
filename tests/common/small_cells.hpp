#pragma once
// Cell types small enough for unit tests.
#include "rbfib/cells/presets.hpp"
#include "rbfib/core/units.hpp"

#include <memory>

namespace rbfib::testing {

/// A Skalak sphere type: R = 3 um, 144 data and 800 sample sites (built once).
inline const std::shared_ptr<const cells::CellType>& small_sphere() {
  static const auto t = cells::skalak_sphere(3 * units::um, 144, 800);
  return t;
}

}  // namespace rbfib::testing
