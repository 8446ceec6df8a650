#include "rbfib/io/json.hpp"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace rbfib::io {

Json& Json::operator[](const std::string& key) {
  if (std::holds_alternative<std::nullptr_t>(v_)) v_ = Object{};
  auto* obj = std::get_if<Object>(&v_);
  if (!obj) throw std::logic_error("json: member '" + key + "' of a non-object");
  for (auto& kv : *obj)
    if (kv.first == key) return kv.second;
  obj->emplace_back(key, Json());
  return obj->back().second;
}

Json& Json::push(Json value) {
  if (std::holds_alternative<std::nullptr_t>(v_)) v_ = Array{};
  auto* arr = std::get_if<Array>(&v_);
  if (!arr) throw std::logic_error("json: push onto a non-array");
  arr->push_back(std::move(value));
  return arr->back();
}

static void write_string(std::ostream& os, const std::string& s) {
  os << '"';
  for (char c : s) {
    switch (c) {
      case '"': os << "\\\""; break;
      case '\\': os << "\\\\"; break;
      case '\n': os << "\\n"; break;
      case '\t': os << "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", c);
          os << buf;
        } else {
          os << c;
        }
    }
  }
  os << '"';
}

void Json::write(std::ostream& os, int indent) const {
  const std::string pad(indent + 2, ' '), end(indent, ' ');
  if (std::holds_alternative<std::nullptr_t>(v_)) os << "null";
  else if (auto* b = std::get_if<bool>(&v_)) os << (*b ? "true" : "false");
  else if (auto* x = std::get_if<double>(&v_)) {
    if (!std::isfinite(*x)) {
      os << "null";  // JSON has no NaN/Inf; the harness treats null as a failed value
    } else {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.17g", *x);
      os << buf;
    }
  } else if (auto* s = std::get_if<std::string>(&v_)) write_string(os, *s);
  else if (auto* a = std::get_if<Array>(&v_)) {
    bool flat = true;
    for (auto& e : *a) flat = flat && !std::holds_alternative<Array>(e.v_) && !std::holds_alternative<Object>(e.v_);
    os << '[';
    for (size_t i = 0; i < a->size(); ++i) {
      if (i) os << (flat ? ", " : ",");
      if (!flat) os << '\n' << pad;
      (*a)[i].write(os, indent + 2);
    }
    if (!flat && !a->empty()) os << '\n' << end;
    os << ']';
  } else if (auto* o = std::get_if<Object>(&v_)) {
    os << '{';
    bool first = true;
    for (const auto& kv : *o) {
      os << (first ? "\n" : ",\n") << pad;
      first = false;
      write_string(os, kv.first);
      os << ": ";
      kv.second.write(os, indent + 2);
    }
    if (!o->empty()) os << '\n' << end;
    os << '}';
  }
}

}  // namespace rbfib::io
