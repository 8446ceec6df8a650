// Quantities with units, as the seed writes them, converted to CGS at the edge: each of the
// seed's notations gives its CGS value and dimension, and every malformed or mismatched text is
// an InputError naming the field, the text and the expected dimension.
#include "../common/errors.hpp"
#include "rbfib/core/error.hpp"
#include "rbfib/core/quantity.hpp"
#include "rbfib/core/units.hpp"

#include <gtest/gtest.h>

namespace rbfib {
namespace {

TEST(Quantity, TheSeedsNotationsGiveCgsValues) {
  struct Case {
    const char* text;
    const char* unit;
    double cgs;
  };
  const Case cases[] = {
      {"16 um", "cm", 16 * units::um},
      {"0.2um", "cm", 0.2 * units::um},
      {"1 cP", "P", units::cP},
      {"1.2 cP", "g cm^-1 s^-1", 1.2 * units::cP},
      {"50 ns", "s", 50 * units::ns},
      {"0.1 us", "s", 0.1 * units::us},
      {"2.5e-3 dyn/cm", "dyn/cm", 2.5e-3},
      {"2e-12 erg", "erg", 2e-12},
      {"12 mm/s", "cm/s", 1.2},
      {"1000 1/s", "1/s", 1000.0},
      {"1000 Hz", "1/s", 1000.0},
      {"2.5e-7 dyn s/cm", "dyn s/cm", 2.5e-7},
      {"2.5e-7 dyn*s/cm", "dyn s/cm", 2.5e-7},
      {"1 g/cm^3", "g/cm^3", 1.0},
      {"0.08 pN/um^3", "dyn/cm^3", 8.0e3},  // Chapter 3's background force, 8.0e3 dyn/cm^3
      {"2.45 pN/um", "dyn/cm", 2.45e-3},    // Chapter 3's tether constant
      {"1 pN um", "erg", 1e-11},
      {"1 Pa", "dyn/cm^2", 10.0},
      {"3 s^-1", "1/s", 3.0},
      {"4", "", 4.0},
  };
  for (const Case& c : cases) EXPECT_NEAR(parse_quantity(c.text, c.unit, "f"), c.cgs, 1e-12 * std::abs(c.cgs)) << c.text;
  const Quantity q = parse_quantity("2.5e-7 dyn s/cm", "f");
  EXPECT_EQ(q.dimension, (Dimension{0, 1, -1}));
  EXPECT_EQ(describe(q.dimension), "force time / length");
  EXPECT_EQ(describe(Dimension{2, 0, -3}), "length^2 time^-3");
}

TEST(Quantity, BadTextNamesTheFieldTheValueAndWhatWasExpected) {
  auto message = [](const char* text, const char* unit) {
    return testing::message_of<InputError>([&] { parse_quantity(text, unit, "domain.size"); });
  };
  const std::string wrong = message("16", "um");
  EXPECT_NE(wrong.find("domain.size = '16'"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("dimensionless"), std::string::npos) << wrong;
  EXPECT_NE(wrong.find("expected length"), std::string::npos) << wrong;
  EXPECT_NE(message("16 us", "um").find("has the dimension time; expected length"), std::string::npos);
  EXPECT_NE(message("16 parsec", "um").find("unknown unit 'parsec'"), std::string::npos);
  EXPECT_NE(message("um", "um").find("expected a number"), std::string::npos);
  EXPECT_NE(message("nan um", "um").find("must be finite"), std::string::npos);
  EXPECT_NE(message("1e400 um", "um").find("must be finite"), std::string::npos);
  EXPECT_NE(message("1 um/s/s", "um/s^2").find("at most one '/'"), std::string::npos);
  EXPECT_NE(message("1 cm^x", "cm^2").find("integer"), std::string::npos);
  EXPECT_NE(message("1 dyn/", "dyn").find("nothing after '/'"), std::string::npos);
}

}  // namespace
}  // namespace rbfib
