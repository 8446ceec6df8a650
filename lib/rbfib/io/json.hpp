#pragma once
// A small JSON value for machine-readable results (the studies' results.json, harness/FORMAT.md):
// objects keep their insertion order; writing only.
#include <cmath>
#include <initializer_list>
#include <map>
#include <memory>
#include <ostream>
#include <list>
#include <string>
#include <variant>
#include <vector>

namespace rbfib::io {

class Json {
 public:
  /// Keeps insertion order; a list, so that a reference to a member (Json& par = r["parameters"])
  /// stays valid while more members are added (a vector would move them).
  using Object = std::list<std::pair<std::string, Json>>;
  using Array = std::vector<Json>;

  Json() : v_(nullptr) {}
  Json(double x) : v_(x) {}
  Json(int x) : v_(double(x)) {}
  Json(long x) : v_(double(x)) {}
  Json(long long x) : v_(double(x)) {}
  Json(bool x) : v_(x) {}
  Json(const char* s) : v_(std::string(s)) {}
  Json(std::string s) : v_(std::move(s)) {}
  Json(const std::vector<double>& xs) : v_(Array(xs.begin(), xs.end())) {}
  Json(const std::vector<std::string>& xs) : v_(Array(xs.begin(), xs.end())) {}
  Json(Array a) : v_(std::move(a)) {}

  static Json object() { Json j; j.v_ = Object{}; return j; }
  static Json array() { Json j; j.v_ = Array{}; return j; }

  /// Object member access; creates the member (and turns null into an object) if absent.
  Json& operator[](const std::string& key);
  /// Appends to an array (turns null into an array).
  Json& push(Json value);

  void write(std::ostream& os, int indent = 0) const;

 private:
  std::variant<std::nullptr_t, bool, double, std::string, Array, Object> v_;
};

/// One row of a results table: row({x, y, "label"}).
inline Json row(std::initializer_list<Json> values) { return Json(Json::Array(values)); }

/// A number, or null when it is not finite (JSON has no NaN or infinity).
inline Json number(double x) { return std::isfinite(x) ? Json(x) : Json(); }

}  // namespace rbfib::io
