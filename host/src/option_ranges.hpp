// The ranges of numeric command-line options, as CLI11 validators shared by tvo_sim and tvo_study.
//
// Each validator checks the text before CLI11 converts it, shows its interval in --help ("in [lo, hi]
// unit", a parenthesis for an excluded end) and, on a bad value, says "got 'TEXT', expected a number
// in [lo, hi] unit": CLI11 prefixes the option's name. tests/closed_loop/option_ranges.py reads these
// intervals from --help and walks every numeric option outside them.
#pragma once

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <iomanip>
#include <sstream>
#include <string>
#include <system_error>
#include <type_traits>

#include <CLI/CLI.hpp>

namespace tvo_options {

/// A bound as --help and the errors show it (12 significant digits: every bound here is exact in them).
inline std::string number(double value)
{
    std::ostringstream out;
    out << std::setprecision(12) << value;
    return out.str();
}

enum class End { Closed, Open };

/// An option's values: [lo, hi] in unit, either end possibly excluded.
struct Interval {
    double lo;
    double hi;
    const char* unit;
    End lo_end{End::Closed};
    End hi_end{End::Closed};

    bool contains(double v) const
    {
        return (lo_end == End::Closed ? v >= lo : v > lo) && (hi_end == End::Closed ? v <= hi : v < hi);
    }
    std::string text() const
    {
        std::string out = (lo_end == End::Closed ? "[" : "(") + number(lo) + ", " + number(hi) +
                          (hi_end == End::Closed ? "]" : ")");
        return *unit != '\0' ? out + " " + unit : out;
    }
};

/// A finite number as CLI11 will convert it (no leading blank, nothing after it; no nan, no inf).
inline bool read_real(const std::string& text, double* value)
{
    if (text.empty() || std::isspace(static_cast<unsigned char>(text.front())) != 0) {
        return false;
    }
    return CLI::detail::lexical_cast(text, *value) && std::isfinite(*value);
}

/// A whole number in plain decimal. CLI11's own conversion takes "010" as octal, "0x10" as hex, "-1" as
/// 2^64 - 1 for an unsigned option and clamps a value beyond the type without a word; what passes here
/// converts the same under both.
template <class T>
bool read_whole(const std::string& text, T* value)
{
    const std::size_t digits_from = (!text.empty() && text.front() == '-' && std::is_signed<T>::value) ? 1 : 0;
    const std::string digits = text.substr(digits_from);
    if (digits.empty() || (digits.size() > 1 && digits.front() == '0') ||
        !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        return false;
    }
    const char* end = text.data() + text.size();
    const auto [stop, error] = std::from_chars(text.data(), end, *value);
    return error == std::errc() && stop == end;
}

/// A number within range. element names which of a pair (A,B) it checks, for --help.
inline CLI::Validator real_in(const Interval& range, const std::string& element = "")
{
    const std::string shown = range.text();
    return CLI::Validator(
        [range, shown](std::string& text) {
            double value = 0.0;
            if (read_real(text, &value) && range.contains(value)) {
                return std::string();
            }
            return "got '" + text + "', expected a number in " + shown;
        },
        (element.empty() ? "" : element + " ") + "in " + shown);
}

/// A whole number within [lo, hi].
template <class T>
CLI::Validator whole_in(T lo, T hi, const std::string& unit = "")
{
    const std::string shown =
        "[" + std::to_string(lo) + ", " + std::to_string(hi) + "]" + (unit.empty() ? "" : " " + unit);
    return CLI::Validator(
        [lo, hi, shown](std::string& text) {
            T value{};
            if (read_whole(text, &value) && value >= lo && value <= hi) {
                return std::string();
            }
            return "got '" + text + "', expected a whole number in " + shown;
        },
        "in " + shown);
}

/// Whether --help shows the variable's value as the option's default (NotShown: where that value is no
/// default, e.g. "h/2" or "the scenario's", which the description says instead).
enum class Default { Shown, NotShown };

/// An option whose values range checks (real_in or whole_in): the declaration every ranged option repeats.
template <class T>
CLI::Option* add_ranged(CLI::App& app, const std::string& name, T& value, const std::string& help,
                        const CLI::Validator& range, Default shown = Default::Shown)
{
    CLI::Option* option = app.add_option(name, value, help)->check(range);
    return shown == Default::Shown ? option->capture_default_str() : option;
}

}  // namespace tvo_options
