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

/// A numerical failure: an iterative solve that did not converge, a NaN, a blow-up.
class NumericalError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
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
