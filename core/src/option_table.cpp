#include "surfcomp/core/option_table.hpp"

#include <charconv>
#include <cmath>
#include <limits>
#include <regex>

namespace surfcomp::options {
namespace {

std::string number_text(double value) {
  char text[32];
  const auto end = std::to_chars(text, text + sizeof text, value).ptr;
  return std::string(text, end);
}

std::string sphere_text(const Sphere& sphere) {
  return number_text(sphere[0]) + "," + number_text(sphere[1]) + "," + number_text(sphere[2]) +
         "," + number_text(sphere[3]);
}

/// The double of the whole of `text` ("nan" and "inf" included), or none when it is not one
/// number.
std::optional<double> whole_number(const std::string& text) {
  // std::from_chars, unlike strtod, does not follow the locale (a decimal comma).
  const char* first = text.data();
  const char* last = text.data() + text.size();
  if (first != last && *first == '+') ++first;
  double value = 0.0;
  const auto [end, error] = std::from_chars(first, last, value);
  if (text.empty() || end != last) return std::nullopt;
  if (error == std::errc::result_out_of_range) {
    return text.find('-') == 0 ? -std::numeric_limits<double>::infinity()
                               : std::numeric_limits<double>::infinity();
  }
  if (error != std::errc()) return std::nullopt;
  return value;
}

/// A finite centre and a finite radius > 0.
bool valid_sphere(const Sphere& sphere) {
  return std::isfinite(sphere[0]) && std::isfinite(sphere[1]) && std::isfinite(sphere[2]) &&
         std::isfinite(sphere[3]) && sphere[3] > 0.0;
}

void check_sphere(const Sphere& sphere, const std::string& shown) {
  if (!valid_sphere(sphere)) {
    throw OptionError(shown + " '" + sphere_text(sphere) + "': expected x,y,z,r with r > 0 (A)");
  }
}

}  // namespace

std::optional<Sphere> parse_sphere(const std::string& text) {
  Sphere sphere{};
  std::size_t start = 0;
  for (std::size_t k = 0; k < 4; ++k) {
    const std::size_t end = k < 3 ? text.find(',', start) : text.size();
    if (end == std::string::npos) return std::nullopt;
    std::string number = text.substr(start, end - start);
    const std::size_t first = number.find_first_not_of(" \t");
    const std::size_t last = number.find_last_not_of(" \t");
    number = first == std::string::npos ? "" : number.substr(first, last - first + 1);
    const std::optional<double> x = whole_number(number);
    if (!x) return std::nullopt;
    sphere[k] = *x;
    start = end + 1;
  }
  if (!valid_sphere(sphere)) return std::nullopt;
  return sphere;
}

std::string python_name(const std::string& name) {
  std::string out = name;
  for (char& c : out) c = c == '-' ? '_' : c;
  return out;
}

std::string format(const Value& value) {
  struct Formatter {
    std::string operator()(bool flag) const { return flag ? "true" : "false"; }
    std::string operator()(std::int64_t n) const { return std::to_string(n); }
    std::string operator()(double x) const { return number_text(x); }
    std::string operator()(const std::string& text) const { return text; }
    std::string operator()(const std::vector<Sphere>& spheres) const {
      std::string out;
      for (const Sphere& s : spheres) out += (out.empty() ? "" : " ") + sphere_text(s);
      return out;
    }
  };
  return std::visit(Formatter{}, value);
}

std::string range_text(const Spec& spec) {
  if (spec.kind != Kind::real && spec.kind != Kind::integer) return "";
  return (spec.lo_open ? "(" : "[") + number_text(spec.lo) + ", " + number_text(spec.hi) + "]";
}

std::string help_line(const Spec& spec) {
  // The options the help names, {field}, as the installed spelling writes them.
  static const std::regex named_option(R"(\{([a-z][a-z0-9_]*)\})");
  std::string help;
  auto at = spec.help.cbegin();
  for (std::sregex_iterator found(spec.help.begin(), spec.help.end(), named_option), end;
       found != end; ++found) {
    help.append(at, (*found)[0].first).append(named((*found)[1].str()));
    at = (*found)[0].second;
  }
  help.append(at, spec.help.cend());
  std::string extra = spec.unit;
  const std::string range = range_text(spec);
  if (!range.empty() && spec.choices.empty()) extra += (extra.empty() ? "" : ", ") + range;
  if (!spec.choices.empty()) {
    for (const std::string& name : spec.choices) extra += (extra.empty() ? "" : " | ") + name;
  }
  return extra.empty() ? help : help + " (" + extra + ")";
}

void check(const Spec& spec, const Value& value, const std::string& shown) {
  switch (spec.kind) {
    case Kind::real:
    case Kind::integer: {
      const double x = spec.kind == Kind::real ? std::get<double>(value)
                                               : static_cast<double>(std::get<std::int64_t>(value));
      const bool above_lo = spec.lo_open ? x > spec.lo : x >= spec.lo;
      if (spec.optional && spec.kind == Kind::integer && x == 0.0) return;
      if (!(std::isfinite(x) && above_lo && x <= spec.hi)) {
        throw OptionError(shown + ": value " + format(value) + " is outside " + range_text(spec));
      }
      if (spec.choices.empty()) return;
      std::string list;
      for (const std::string& choice : spec.choices) {
        if (format(value) == choice) return;
        list += (list.empty() ? "" : "|") + choice;
      }
      throw OptionError(shown + ": value " + format(value) + " is not one of " + list);
    }
    case Kind::choice: {
      const auto& name = std::get<std::string>(value);
      std::string list;
      for (const std::string& choice : spec.choices) {
        if (name == choice) return;
        list += (list.empty() ? "" : "|") + choice;
      }
      throw OptionError(shown + ": '" + name + "' is not one of " + list);
    }
    case Kind::spheres:
      for (const Sphere& sphere : std::get<std::vector<Sphere>>(value)) check_sphere(sphere, shown);
      return;
    case Kind::text:
    case Kind::flag:
      return;
  }
}

Value parse(const Spec& spec, const std::string& text, const std::string& shown) {
  Value value;
  switch (spec.kind) {
    case Kind::real: {
      const std::optional<double> x = whole_number(text);
      if (!x) throw OptionError(shown + ": '" + text + "' is not a number");
      value = *x;
      break;
    }
    case Kind::integer: {
      std::int64_t n = 0;
      const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), n);
      if (!text.empty() && end == text.data() + text.size() &&
          error == std::errc::result_out_of_range) {
        throw OptionError(shown + ": value " + text + " is outside " + range_text(spec));
      }
      if (text.empty() || error != std::errc() || end != text.data() + text.size()) {
        // Scientific notation of a whole number (1e6, as --help prints the ranges) is taken too.
        const std::optional<double> x = whole_number(text);
        if (!x || std::isnan(*x) || (std::isfinite(*x) && std::floor(*x) != *x)) {
          throw OptionError(shown + ": '" + text + "' is not a whole number");
        }
        if (!std::isfinite(*x) || std::abs(*x) >= 9.2e18) {
          throw OptionError(shown + ": value " + text + " is outside " + range_text(spec));
        }
        n = static_cast<std::int64_t>(*x);
      }
      value = n;
      break;
    }
    case Kind::flag:
      if (text != "true" && text != "false") {
        throw OptionError(shown + ": '" + text + "' is not true or false");
      }
      value = text == "true";
      break;
    case Kind::spheres: {
      const std::optional<Sphere> sphere = parse_sphere(text);
      if (!sphere) throw OptionError(shown + " '" + text + "': expected x,y,z,r with r > 0 (A)");
      value = std::vector<Sphere>{*sphere};
      break;
    }
    case Kind::text:
    case Kind::choice:
      value = text;
      break;
  }
  check(spec, value, shown);
  return value;
}

}  // namespace surfcomp::options
