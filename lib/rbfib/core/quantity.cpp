#include "rbfib/core/quantity.hpp"

#include "rbfib/core/constants.hpp"

#include "rbfib/core/error.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <map>
#include <tuple>

namespace rbfib {

namespace {

struct Unit {
  double factor;  // to CGS
  Dimension dimension;
};

const std::map<std::string, Unit>& unit_table() {
  static const std::map<std::string, Unit> table = {
      {"m", {1e2, {1, 0, 0}}},     {"cm", {1.0, {1, 0, 0}}},    {"mm", {1e-1, {1, 0, 0}}},    {"um", {1e-4, {1, 0, 0}}},
      {"\u00b5m", {1e-4, {1, 0, 0}}}, {"\u03bcm", {1e-4, {1, 0, 0}}}, {"nm", {1e-7, {1, 0, 0}}},
      {"kg", {1e3, {0, 1, 0}}},    {"g", {1.0, {0, 1, 0}}},     {"mg", {1e-3, {0, 1, 0}}},
      {"s", {1.0, {0, 0, 1}}},     {"ms", {1e-3, {0, 0, 1}}},   {"us", {1e-6, {0, 0, 1}}},    {"\u00b5s", {1e-6, {0, 0, 1}}},
      {"\u03bcs", {1e-6, {0, 0, 1}}}, {"ns", {1e-9, {0, 0, 1}}},
      {"dyn", {1.0, {1, 1, -2}}},  {"N", {1e5, {1, 1, -2}}},    {"pN", {1e-7, {1, 1, -2}}},
      {"erg", {1.0, {2, 1, -2}}},  {"J", {1e7, {2, 1, -2}}},
      {"P", {1.0, {-1, 1, -1}}},   {"cP", {1e-2, {-1, 1, -1}}}, {"Pa", {10.0, {-1, 1, -2}}},
      {"Hz", {1.0, {0, 0, -1}}},
      {"rad", {1.0, {0, 0, 0}}},   {"deg", {rbfib::pi / 180, {0, 0, 0}}},
  };
  return table;
}

bool is_space(char c) { return c == ' ' || c == '\t'; }

/// Parses the unit expression s (after the number) into a factor and dimension; returns false
/// with `why` set on failure.
bool parse_units(const std::string& s, Quantity& q, std::string& why) {
  std::size_t i = 0;
  int sign = 1;  // +1 before the '/', -1 after it
  bool after_slash = false;  // a factor after the '/'
  while (true) {
    while (i < s.size() && (is_space(s[i]) || s[i] == '*')) ++i;
    if (i == s.size()) break;
    if (s[i] == '/') {
      if (sign < 0) {
        why = "at most one '/' in a unit expression";
        return false;
      }
      sign = -1;
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j < s.size() && !is_space(s[j]) && s[j] != '*' && s[j] != '/' && s[j] != '^') ++j;
    const std::string name = s.substr(i, j - i);
    int power = 1;
    if (j < s.size() && s[j] == '^') {
      std::size_t k = j + 1;
      if (k < s.size() && (s[k] == '-' || s[k] == '+')) ++k;
      const std::size_t digits = k;
      while (k < s.size() && std::isdigit(static_cast<unsigned char>(s[k]))) ++k;
      if (k == digits) {
        why = "a power must be an integer, as in 'cm^3'";
        return false;
      }
      power = std::atoi(s.substr(j + 1, k - j - 1).c_str());
      j = k;
    }
    i = j;
    if (name == "1" && power == 1 && sign > 0) continue;  // the numerator of "1/s"
    const auto u = unit_table().find(name);
    if (u == unit_table().end()) {
      why = "unknown unit '" + name + "' (known: m cm mm um nm, kg g mg, s ms us ns, dyn N pN, erg J, P cP Pa, Hz, rad deg)";
      return false;
    }
    const int p = sign * power;
    q.value *= std::pow(u->second.factor, p);
    q.dimension.length += p * u->second.dimension.length;
    q.dimension.mass += p * u->second.dimension.mass;
    q.dimension.time += p * u->second.dimension.time;
    after_slash = sign < 0;
  }
  if (sign < 0 && !after_slash) {
    why = "nothing after '/'";
    return false;
  }
  return true;
}

}  // namespace

Quantity parse_quantity(const std::string& text, const std::string& field) {
  const char* begin = text.c_str();
  char* end = nullptr;
  Quantity q;
  q.value = std::strtod(begin, &end);
  if (end == begin)
    throw InputError(field, "'" + text + "'", "expected a number with its unit, as in '16 um' or '2.5e-3 dyn/cm'");
  std::string why;
  if (!parse_units(std::string(end), q, why)) throw InputError(field, "'" + text + "'", why);
  if (!std::isfinite(q.value)) throw InputError(field, "'" + text + "'", "must be finite");
  return q;
}

double parse_quantity(const std::string& text, const std::string& expected, const std::string& field) {
  const Quantity want = parse_quantity("1 " + expected, "expected unit of " + field);
  const Quantity q = parse_quantity(text, field);
  if (!(q.dimension == want.dimension))
    throw InputError(field, "'" + text + "'",
                     "has the dimension " + describe(q.dimension) + "; expected " + describe(want.dimension) + " (e.g. '" +
                         expected + "')");
  return q.value;
}

std::string describe(const Dimension& d) {
  static const std::map<std::tuple<int, int, int>, std::string> named = {
      {{0, 0, 0}, "dimensionless"},          {{1, 0, 0}, "length"},
      {{0, 1, 0}, "mass"},                   {{0, 0, 1}, "time"},
      {{1, 0, -1}, "velocity"},              {{0, 0, -1}, "rate (1/time)"},
      {{1, 1, -2}, "force"},                 {{0, 1, -2}, "force / length"},
      {{2, 1, -2}, "energy"},                {{-1, 1, -1}, "dynamic viscosity"},
      {{-3, 1, 0}, "density (mass / volume)"}, {{-2, 1, -2}, "force / volume"},
      {{0, 1, -1}, "force time / length"},   {{-1, 1, -2}, "pressure"},
  };
  const auto n = named.find({d.length, d.mass, d.time});
  if (n != named.end()) return n->second;
  std::string s;
  auto add = [&](const char* name, int p) {
    if (p == 0) return;
    if (!s.empty()) s += " ";
    s += name;
    if (p != 1) {
      s += '^';
      s += std::to_string(p);
    }
  };
  add("length", d.length);
  add("mass", d.mass);
  add("time", d.time);
  return s;
}

}  // namespace rbfib
