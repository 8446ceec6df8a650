#pragma once
// Results tables whose only units are seconds: the common case of the drivers' tables.
#include "common/study.hpp"

#include <string>
#include <vector>

namespace rbfib::study {

/// An empty results table (as table(columns, units)) with unit "s" for the timing columns
/// ("seconds" and "*_seconds") and none for the others.
Json table(const std::vector<std::string>& columns);

}  // namespace rbfib::study
