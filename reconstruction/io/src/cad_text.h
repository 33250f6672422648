#pragma once
// Internal: text shared by the CAD exchange writers (IGES, STEP).

#include <array>
#include <charconv>
#include <cstdlib>
#include <ctime>
#include <string>
#include <string_view>

namespace interlin::detail {

// Reals: the shortest decimal that reads back to the same double (std::to_chars), always with a
// decimal point and an upper-case E exponent ("1.", "0.25", "1.5E-07"), as both standards require
// of real literals.
inline std::string cad_real(double x) {
  std::array<char, 64> buf{};
  const auto res = std::to_chars(buf.data(), buf.data() + buf.size(), x);
  const std::string s(buf.data(), res.ptr);
  const auto e = s.find('e');
  std::string mantissa = s.substr(0, e);
  if (mantissa.find('.') == std::string::npos)
    mantissa += '.';
  return e == std::string::npos ? mantissa : mantissa + "E" + s.substr(e + 1);
}

// UTC time of the file, formatted by strftime `format`: now, or SOURCE_DATE_EPOCH when that
// environment variable holds a non-negative integer (reproducible output).
inline std::string file_time(const char* format) {
  std::time_t t = std::time(nullptr);
  if (const char* epoch = std::getenv("SOURCE_DATE_EPOCH")) {
    long long value = 0;
    const std::string_view e(epoch);
    const auto res = std::from_chars(e.data(), e.data() + e.size(), value);
    if (res.ec == std::errc() && res.ptr == e.data() + e.size() && value >= 0)
      t = static_cast<std::time_t>(value);
  }
  std::tm tm{};
  gmtime_r(&t, &tm);
  std::array<char, 64> buf{};
  std::strftime(buf.data(), buf.size(), format, &tm);
  return buf.data();
}

} // namespace interlin::detail
