// One definition per user-facing option: its name, kind, default (the Options struct's own),
// range, unit and help line, bound to the field it sets. Each module keeps the table of its
// Options struct beside it; the command line's --help and parsing, Python's keyword arguments
// and docstrings, and every range error are made from these tables.
#pragma once

#include "surfcomp/core/error.hpp"
#include "surfcomp/core/option_names.hpp"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <variant>
#include <vector>

namespace surfcomp::options {

/// What an option's value is, and how it is spelt on a command line.
enum class Kind {
  real,     ///< a finite number
  integer,  ///< a whole number
  text,     ///< any text (a residue name, a file)
  choice,   ///< one of Spec::choices
  flag,     ///< a switch: present or absent (true or false)
  spheres,  ///< repeatable; each x,y,z,r with r > 0 (A)
};

/// The names of the kinds, indexed by Kind (as the Python module's option tables give them).
inline constexpr std::array<const char*, 6> kind_names = {"real",   "integer", "text",
                                                          "choice", "flag",    "spheres"};

/// A sphere given as an option: centre x, y, z and radius, A.
using Sphere = std::array<double, 4>;

/// An option's value. Kind::real holds a double, integer an int64, text and choice a string,
/// flag a bool, spheres a list of Sphere.
using Value = std::variant<bool, std::int64_t, double, std::string, std::vector<Sphere>>;

/// What the user sees of an option.
struct Spec {
  Spec() = default;
  /// Every field in order; the trailing ones may be left out (a pure number, any value).
  Spec(std::string name_, Kind kind_, std::string help_, std::string unit_ = "", double lo_ = 0.0,
       double hi_ = 0.0, bool lo_open_ = false, std::vector<std::string> choices_ = {},
       bool optional_ = false)
      : name(std::move(name_)),
        kind(kind_),
        help(std::move(help_)),
        unit(std::move(unit_)),
        lo(lo_),
        hi(hi_),
        lo_open(lo_open_),
        choices(std::move(choices_)),
        optional(optional_) {}

  std::string name;  ///< as typed after "--": lower case, words joined by '-'
  Kind kind = Kind::real;
  /// One line, no unit or range (those are added from the fields below). An option it names is
  /// written {field} ("with {refine_top} > 0"), and help_line() spells it as named() does.
  std::string help;
  std::string unit;  ///< "A", "degrees", "bytes", ... or "" for a pure number
  /// Kind::real and integer: the value must lie in [lo, hi], or (lo, hi] with lo_open.
  double lo = 0.0, hi = 0.0;
  bool lo_open = false;
  /// Kind::choice: the names. Kind::integer: when not empty, the only values allowed (in the
  /// range), as text.
  std::vector<std::string> choices;
  /// No default: absent unless given (a text "" or an integer 0 means absent). Python shows
  /// None as its default.
  bool optional = false;
};

/// One option of the Options struct `Settings`: what the user sees, and how the value is read
/// from and written to its field.
template <class Settings>
struct Option {
  Spec spec;
  /// The field's value in `settings`, as an option value of the spec's kind.
  std::function<Value(const Settings&)> get;
  /// Sets the field from a value that has passed check() (OptionError for an unknown choice).
  std::function<void(Settings&, const Value&)> set;
};

/// The user's options of one Options struct, in the order --help lists them.
template <class Settings>
using Table = std::vector<Option<Settings>>;

/// The option's name as a Python keyword: '-' becomes '_'.
std::string python_name(const std::string& name);

/// `value` as the command line spells it: a number in its shortest exact form (1.4, not
/// 1.3999999999999999), a flag as true/false, spheres as x,y,z,r separated by spaces.
std::string format(const Value& value);

/// The range of a real or integer option as text ("[0, 10]", "(0, 100]"); "" for other kinds.
std::string range_text(const Spec& spec);

/// The help line with the options it names spelled (named()) and the unit and range appended:
/// "probe radius (A, [0, 10])".
std::string help_line(const Spec& spec);

/// Throws OptionError "SHOWN: ..." unless `value` is of the spec's kind and inside its domain:
/// a finite number in the range, one of the choices, spheres with finite centres and r > 0.
/// `shown` is the option as the user typed it ("--probe-radius" or "probe_radius").
void check(const Spec& spec, const Value& value, const std::string& shown);

/// The value of command-line `text` for the option (OptionError naming `shown` when it is not
/// a number, an integer or x,y,z,r as the kind needs), checked as check() does. Spheres: one
/// sphere per call; the caller collects repeated options.
Value parse(const Spec& spec, const std::string& text, const std::string& shown);

/// The sphere written "x,y,z,r" (four comma-separated numbers, A), or none when `text` is not
/// that or the centre is not finite or r is not finite and > 0.
std::optional<Sphere> parse_sphere(const std::string& text);

/// The option of `table` named `name` (command-line spelling), or nullptr.
template <class Settings>
const Option<Settings>* find(const Table<Settings>& table, const std::string& name) {
  for (const Option<Settings>& option : table) {
    if (option.spec.name == name) return &option;
  }
  return nullptr;
}

/// check() of every option's current value in `settings`, naming each as named() does.
template <class Settings>
void check_all(const Table<Settings>& table, const Settings& settings) {
  for (const Option<Settings>& option : table) {
    check(option.spec, option.get(settings), named(python_name(option.spec.name)));
  }
}

namespace detail {

template <class Field>
constexpr Kind kind_of() {
  if constexpr (std::is_same_v<Field, bool>) {
    return Kind::flag;
  } else if constexpr (std::is_floating_point_v<Field>) {
    return Kind::real;
  } else if constexpr (std::is_integral_v<Field>) {
    return Kind::integer;
  } else {
    static_assert(std::is_same_v<Field, std::string>, "an option field is a number or text");
    return Kind::text;
  }
}

template <class Field>
Value to_value(const Field& field) {
  if constexpr (std::is_same_v<Field, bool> || std::is_same_v<Field, std::string>) {
    return field;
  } else if constexpr (std::is_floating_point_v<Field>) {
    return static_cast<double>(field);
  } else if constexpr (std::is_unsigned_v<Field> && sizeof(Field) >= sizeof(std::int64_t)) {
    // An unsigned count beyond int64's range (SIZE_MAX as "no limit") shows as its largest.
    constexpr auto largest = static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max());
    return static_cast<std::int64_t>(std::min<std::uint64_t>(field, largest));
  } else {
    return static_cast<std::int64_t>(field);
  }
}

template <class Field>
Field from_value(const Value& value) {
  if constexpr (std::is_same_v<Field, bool> || std::is_same_v<Field, std::string>) {
    return std::get<Field>(value);
  } else if constexpr (std::is_floating_point_v<Field>) {
    return static_cast<Field>(std::get<double>(value));
  } else {
    return static_cast<Field>(std::get<std::int64_t>(value));
  }
}

}  // namespace detail

/// The option bound to the field `access(settings)` returns (a generic lambda
/// `[](auto& s) -> auto& { return s.field; }`, so that it serves const and non-const access).
/// The kind follows the field's type: bool a flag, a floating-point number real, an integer
/// integer, std::string text. The value has passed check() when it is set.
template <class Settings, class Access>
Option<Settings> field(Spec spec, Access access) {
  using Field = std::decay_t<decltype(access(std::declval<Settings&>()))>;
  spec.kind = detail::kind_of<Field>();
  return {std::move(spec),
          [access](const Settings& s) { return detail::to_value<Field>(access(s)); },
          [access](Settings& s, const Value& v) { access(s) = detail::from_value<Field>(v); }};
}

/// The option of an enum field whose values are named by `names` (the enum's name table,
/// indexed by the enum's value).
template <class Settings, class Access, std::size_t N>
Option<Settings> choice(Spec spec, Access access, const std::array<const char*, N>& names) {
  using Field = std::decay_t<decltype(access(std::declval<Settings&>()))>;
  static_assert(std::is_enum_v<Field>, "a choice option sets an enum field");
  spec.kind = Kind::choice;
  spec.choices.assign(names.begin(), names.end());
  return {std::move(spec),
          [access, names](const Settings& s) {
            const auto index = static_cast<std::size_t>(access(s));
            return Value(std::string(index < N ? names[index] : "?"));
          },
          [access, names](Settings& s, const Value& v) {
            const auto& name = std::get<std::string>(v);
            for (std::size_t i = 0; i < N; ++i) {
              if (name == names[i]) {
                access(s) = static_cast<Field>(i);
                return;
              }
            }
            throw OptionError("'" + name + "' is not a choice of this option");
          }};
}

/// The options of `table`, an Inner struct's, as options of an Outer struct that holds an
/// Inner at `part(outer)` (a generic lambda as for field()). Options named in `skip` are left
/// out.
template <class Outer, class Inner, class Part>
void append(Table<Outer>& out, const Table<Inner>& table, Part part,
            const std::vector<std::string>& skip = {}) {
  for (const Option<Inner>& option : table) {
    bool skipped = false;
    for (const std::string& name : skip) skipped = skipped || name == option.spec.name;
    if (skipped) continue;
    out.push_back({option.spec, [get = option.get, part](const Outer& o) { return get(part(o)); },
                   [set = option.set, part](Outer& o, const Value& v) { set(part(o), v); }});
  }
}

/// The options of `table` named in `names`, in the table's order.
template <class Settings>
Table<Settings> pick(const Table<Settings>& table, const std::vector<std::string>& names) {
  Table<Settings> picked;
  for (const Option<Settings>& option : table) {
    for (const std::string& name : names) {
      if (name == option.spec.name) picked.push_back(option);
    }
  }
  return picked;
}

/// The worker-thread option every job shares: 0 means all cores, at most 1,024.
template <class Settings, class Access>
Option<Settings> threads_option(Access access) {
  return field<Settings>({"threads", Kind::integer, "worker threads (0: all cores)", "", 0, 1024},
                         access);
}

}  // namespace surfcomp::options
