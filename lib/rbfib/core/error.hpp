#pragma once
// Errors the library raises. Every message names the field (or solve) and the offending value,
// so that a user can fix the input without reading the source.
#include <sstream>
#include <stdexcept>
#include <string>

namespace rbfib {

/// Bad input: a field of a scene, grid or parameter set has a value the method cannot use.
class InputError : public std::invalid_argument {
 public:
  InputError(const std::string& field, const std::string& value, const std::string& why)
      : std::invalid_argument(field + " = " + value + ": " + why), field_(field) {}
  const std::string& field() const { return field_; }

 private:
  std::string field_;
};

/// What stopped a computation numerically (the cause a run's stop records, so that a caller can
/// tell a refused step from a blow-up without reading the message).
enum class Cause {
  stopping_condition,  ///< eq. 5.4: dt > (1/4) sqrt(h rho / ||f||_inf)
  non_finite,          ///< a NaN or Inf in a position, velocity, force or solution
  degenerate_site,     ///< a surface metric or triangle degenerate at a site (det G <= 0)
  inverted_cell,       ///< an inverted cell or triangle, an undefined energy (det C <= 0)
  solver,              ///< a solve or factorization that failed: no convergence, singular, a library's error
};

/// The cause as a short name: "eq. 5.4", "non-finite", "degenerate site", "inverted cell", "solver".
inline const char* to_string(Cause c) {
  switch (c) {
    case Cause::stopping_condition: return "eq. 5.4";
    case Cause::non_finite: return "non-finite";
    case Cause::degenerate_site: return "degenerate site";
    case Cause::inverted_cell: return "inverted cell";
    case Cause::solver: return "solver";
  }
  return "unknown";
}

/// A numerical failure: an iterative solve that did not converge, a NaN, a blow-up; with its cause.
class NumericalError : public std::runtime_error {
 public:
  NumericalError(Cause cause, const std::string& what) : std::runtime_error(what), cause_(cause) {}
  Cause cause() const { return cause_; }

 private:
  Cause cause_;
};

template <class T>
std::string to_text(const T& v) {
  std::ostringstream s;
  s.precision(17);
  s << v;
  return s.str();
}

/// Throws InputError(field, value, why) unless ok.
template <class T>
void require(bool ok, const std::string& field, const T& value, const std::string& why) {
  if (!ok) throw InputError(field, to_text(value), why);
}

}  // namespace rbfib
