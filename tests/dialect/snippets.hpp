// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// Small programs that exercise arc output: each is a circle (or part of one, or a helix)
// sampled finely enough that one or two arcs replace it within 0.01 mm.
#include <fmt/format.h>

#include <cmath>
#include <string>
#include <vector>

#include "arcpress/core/geometry.hpp"

namespace arcpress::test {

struct Snippet {
  std::string name;
  std::string text;
  Plane plane = Plane::XY;
  bool helical = false;
  bool inch = false;
};

/// `sweep_deg` of a circle of radius `r` about the origin, starting on the plane's first
/// axis, in `n` moves; `climb` along the normal axis over the whole sweep. Numbers always
/// have a decimal point, so every dialect reads them as whole units.
inline Snippet circle_snippet(std::string name, Plane plane, double sweep_deg, double r, int n, double climb = 0,
                              bool inch = false) {
  auto ax = axes_of(plane);
  const char* letters = "XYZ";
  auto num = [](double v) {
    std::string s = fmt::format("{:.4f}", v);
    while (s.back() == '0') s.pop_back();
    return s == "-0." ? std::string("0.") : s;
  };
  std::string t = fmt::format("{} G90 {}\n", inch ? "G20" : "G21",
                              plane == Plane::XY ? "G17" : plane == Plane::ZX ? "G18" : "G19");
  auto point = [&](double a, double h) {
    double p[3] = {0, 0, 0};
    p[ax.first] = r * std::cos(a);
    p[ax.second] = r * std::sin(a);
    p[ax.normal] = h;
    return fmt::format("X{} Y{} Z{}", num(p[0]), num(p[1]), num(p[2]));
  };
  t += "G0 " + point(0, 0) + "\n";
  for (int k = 1; k <= n; ++k) {
    double f = double(k) / n;
    t += (k == 1 ? "G1 " : "") + point(deg_to_rad(sweep_deg) * f, climb * f) + (k == 1 ? " F300." : "") + "\n";
  }
  t += "M30\n";
  return {std::move(name), std::move(t), plane, climb != 0, inch};
}

inline std::vector<Snippet> arc_snippets() {
  return {
      circle_snippet("quarter circle", Plane::XY, 90, 10, 48),
      circle_snippet("full circle", Plane::XY, 360, 10, 192),
      circle_snippet("270 degree arc", Plane::XY, 270, 10, 144),
      circle_snippet("helix", Plane::XY, 360, 10, 192, -2.0),
      circle_snippet("G18 quarter circle", Plane::ZX, 90, 10, 48),
      circle_snippet("G19 quarter circle", Plane::YZ, 90, 10, 48),
      circle_snippet("inch quarter circle", Plane::XY, 90, 0.5, 48, 0, true),
  };
}

}  // namespace arcpress::test
