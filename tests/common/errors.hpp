#pragma once
// The message of the exception of type E that fn throws ("" when it throws none), and the field an
// InputError names, for tests that check what an error names.
#include "rbfib/core/error.hpp"

#include <functional>
#include <string>

namespace rbfib::testing {

template <class E>
std::string message_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const E& e) {
    return e.what();
  }
  return "";
}

/// The field named by the InputError that fn throws ("" when it throws none).
inline std::string field_of(const std::function<void()>& fn) {
  try {
    fn();
  } catch (const InputError& e) {
    return e.field();
  }
  return "";
}

}  // namespace rbfib::testing
