// SPDX-License-Identifier: BSD-3-Clause
// SPDX-FileCopyrightText: 2026 The ebgeom authors
#pragma once
// Validators for numeric options that say the rule in words ("must be > 0") instead of CLI11's
// range with a 309-digit bound, and that refuse nan and inf.

#include <CLI/CLI.hpp>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

namespace ebgeom::jobs {

/// The rule a numeric option's value must satisfy.
enum class NumberRule { positive, non_negative, percent_range };

/// A CLI11 validator: the value must parse whole as a finite number and satisfy `rule`
/// (`positive`: > 0; `non_negative`: >= 0; `percent_range`: 0 to 100). With `integer`, it must
/// also be a whole number that fits an int.
inline CLI::Validator number_rule(NumberRule rule, bool integer = false) {
  const char* words = rule == NumberRule::positive       ? "> 0"
                      : rule == NumberRule::non_negative ? ">= 0"
                                                         : "between 0 and 100";
  const std::string desc = std::string(integer ? "an integer " : "a finite number ") + words;
  return CLI::Validator(
      [=](std::string& s) -> std::string {
        const std::string what = "must be " + desc + ", got '" + s + "'";
        const char* b = s.c_str();
        char* e = nullptr;
        errno = 0;
        const double v = std::strtod(b, &e);
        if (e == b || *e != '\0' || !std::isfinite(v) || errno == ERANGE) return what;
        if (integer && (v != std::floor(v) || std::abs(v) > 2147483647.0)) return what;
        if (rule == NumberRule::positive && !(v > 0)) return what;
        if (rule == NumberRule::non_negative && !(v >= 0)) return what;
        if (rule == NumberRule::percent_range && !(v >= 0 && v <= 100)) return what;
        return {};
      },
      std::string(integer ? "INT " : "NUMBER ") + words);
}

} // namespace ebgeom::jobs
