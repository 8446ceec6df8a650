#include "common/tables.hpp"

#include "common/study.hpp"

namespace rbfib::study {

Json table(const std::vector<std::string>& columns) {
  std::vector<std::string> units;
  for (const std::string& c : columns) {
    const bool timing = c == "seconds" || (c.size() > 8 && c.compare(c.size() - 8, 8, "_seconds") == 0);
    units.push_back(timing ? "s" : "");
  }
  return table(columns, units);
}

}  // namespace rbfib::study
