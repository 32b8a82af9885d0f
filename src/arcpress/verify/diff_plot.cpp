// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/diff_plot.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace arcpress {
namespace {

constexpr double kWidthPx = 1200, kMarginPx = 40, kLegendPx = 150;
/// The widest a character of the 14 px sans-serif text is taken to be: a line of text holds
/// at most (kWidthPx - 2 kMarginPx) / kCharPx characters, so none runs off the picture.
constexpr double kCharPx = 9;
constexpr size_t kLineChars = size_t((kWidthPx - 2 * kMarginPx) / kCharPx);
/// Colour buckets from 0 to the band; one more for beyond it.
constexpr int kBuckets = 10;


std::string bucket_colour(int b) {
  if (b >= kBuckets) return "#c000c0";  // outside the band
  double t = double(b) / (kBuckets - 1);  // green -> yellow -> red
  int r = int(std::lround(255 * std::min(1.0, 2 * t))), g = int(std::lround(200 * std::min(1.0, 2 * (1 - t))));
  return fmt::format("#{:02x}{:02x}20", r, g);
}

std::string xml_escape(const std::string& s) {
  std::string o;
  for (char c : s) {
    if (c == '<') o += "&lt;";
    else if (c == '>') o += "&gt;";
    else if (c == '&') o += "&amp;";
    else if (c == '"') o += "&quot;";
    else o += c;
  }
  return o;
}

/// `text` cut to at most `chars` characters (UTF-8 sequences counted as one), its middle
/// replaced by "..." where it is longer: a path keeps its start and its file name.
std::string elided(const std::string& text, size_t chars) {
  std::vector<size_t> starts;  // byte offset of each character
  for (size_t k = 0; k < text.size(); ++k)
    if ((static_cast<unsigned char>(text[k]) & 0xC0) != 0x80) starts.push_back(k);
  if (starts.size() <= chars) return text;
  const size_t keep = chars > 3 ? chars - 3 : 0, head = keep / 3, tail = keep - head;
  return text.substr(0, starts[head]) + "..." + text.substr(starts[starts.size() - tail]);
}

class Canvas {
 public:
  Canvas(Plane plane, double min_u, double min_v, double scale, double height_px)
      : ax_(axes_of(plane)), plane_(plane), min_u_(min_u), min_v_(min_v), scale_(scale), height_px_(height_px) {}

  Vec2 px(const Vec3& p) const {
    return {kMarginPx + (p[ax_.first] - min_u_) * scale_, height_px_ - kMarginPx - (p[ax_.second] - min_v_) * scale_};
  }

  /// Appends move i to `d` (an SVG path's data), starting a new subpath when it does not
  /// continue the last drawn point.
  void add_move(const Interpretation& in, size_t i, std::string& d) {
    const Move& m = in.moves[i];
    Vec3 from(in.from(i)[kX], in.from(i)[kY], in.from(i)[kZ]);
    Vec2 s = px(from);
    if (!has_last_ || (s - last_).norm() > 0.5) {
      d += fmt::format("M{:.1f} {:.1f}", s.x(), s.y());
      last_ = s;
      has_last_ = true;
    }
    bool arc = m.kind == MoveKind::ArcCW || m.kind == MoveKind::ArcCCW;
    Vec2 e = px(m.xyz());
    if (arc && m.plane == plane_ && m.turns <= 1) {
      Vec2 c = px(m.center);
      double r = (s - c).norm();
      bool ccw = m.kind == MoveKind::ArcCCW;
      double a0 = std::atan2(-(s - c).y(), (s - c).x()), a1 = std::atan2(-(e - c).y(), (e - c).x());
      double sweep = a1 - a0;
      if (ccw && sweep <= 0) sweep += 2 * kPi;
      if (!ccw && sweep >= 0) sweep -= 2 * kPi;
      if ((e - s).norm() < 1e-9) {  // full circle: two halves
        Vec2 opp = 2 * c - s;
        d += fmt::format("A{:.1f} {:.1f} 0 0 {} {:.1f} {:.1f}", r, r, ccw ? 0 : 1, opp.x(), opp.y());
      }
      if (r * std::abs(sweep) < 0.5) {
        d += fmt::format("L{:.1f} {:.1f}", e.x(), e.y());
      } else {
        d += fmt::format("A{:.1f} {:.1f} 0 {} {} {:.1f} {:.1f}", r, r, std::abs(sweep) > kPi ? 1 : 0, ccw ? 0 : 1,
                         e.x(), e.y());
      }
      last_ = e;
      return;
    }
    pts_.clear();
    move_path(in, i, 0.5 / scale_, pts_);
    for (const Vec3& q : pts_) {
      Vec2 p = px(q);
      if ((p - last_).norm() < 0.5 && &q != &pts_.back()) continue;  // decimate: under half a pixel
      d += fmt::format("L{:.1f} {:.1f}", p.x(), p.y());
      last_ = p;
    }
  }
  void lift() { has_last_ = false; }

 private:
  PlaneAxes ax_;
  Plane plane_;
  double min_u_, min_v_, scale_, height_px_;
  Vec2 last_{0, 0};
  bool has_last_ = false;
  std::vector<Vec3> pts_;
};

}  // namespace

std::string diff_svg(const Interpretation& ia, const Interpretation& ib, const ProgramDiff& d, Plane plane,
                     double tol, const DiffNames& names) {
  auto ax = axes_of(plane);
  double min_u = HUGE_VAL, min_v = HUGE_VAL, max_u = -HUGE_VAL, max_v = -HUGE_VAL;
  for (const Interpretation* in : {&ia, &ib})
    for (const Move& m : in->moves) {
      if (!is_feed(m.kind) || !m.known) continue;
      min_u = std::min(min_u, m.to[ax.first]);
      max_u = std::max(max_u, m.to[ax.first]);
      min_v = std::min(min_v, m.to[ax.second]);
      max_v = std::max(max_v, m.to[ax.second]);
    }
  if (min_u > max_u) min_u = max_u = min_v = max_v = 0;
  double span = std::max({max_u - min_u, max_v - min_v, 1e-3});
  double scale = (kWidthPx - 2 * kMarginPx) / span;
  double height = (max_v - min_v) * scale + 2 * kMarginPx;
  double total_h = height + kLegendPx;
  Canvas canvas(plane, min_u, min_v, scale, height);
  const char* plane_name = plane == Plane::XY ? "XY" : plane == Plane::ZX ? "ZX" : "YZ";

  std::string svg = fmt::format(
      "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{:.0f}\" height=\"{:.0f}\" viewBox=\"0 0 {:.0f} {:.0f}\" "
      "font-family=\"sans-serif\" font-size=\"14\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n",
      kWidthPx, total_h, kWidthPx, total_h);
  svg += fmt::format("<text x=\"{}\" y=\"24\">arcpress diff, {} plane: A grey, B coloured by deviation</text>\n",
                     kMarginPx, plane_name);
  // A: one thin grey path.
  std::string da;
  for (size_t i = 0; i < ia.moves.size(); ++i) {
    if (!is_feed(ia.moves[i].kind) || !ia.moves[i].known) {
      canvas.lift();
      continue;
    }
    canvas.add_move(ia, i, da);
  }
  svg += fmt::format("<path id=\"path-a\" d=\"{}\" fill=\"none\" stroke=\"#909090\" stroke-width=\"2.5\"/>\n", da);
  // B: one path per run of moves in the same colour bucket.
  canvas.lift();
  std::string db;
  int bucket = -1;
  auto flush = [&]() {
    if (!db.empty())
      svg += fmt::format("<path class=\"path-b\" d=\"{}\" fill=\"none\" stroke=\"{}\" stroke-width=\"1\"/>\n", db,
                         bucket_colour(bucket));
    db.clear();
  };
  for (size_t i = 0; i < ib.moves.size(); ++i) {
    if (!is_feed(ib.moves[i].kind) || !ib.moves[i].known) {
      canvas.lift();
      continue;
    }
    double dev = i < d.deviation_of_b.size() ? d.deviation_of_b[i] : 0;
    int b = dev > tol ? kBuckets : std::min(kBuckets - 1, int(dev / tol * kBuckets));
    if (b != bucket) {
      flush();
      bucket = b;
      canvas.lift();
    }
    canvas.add_move(ib, i, db);
  }
  flush();
  // The worst place: a ring on the drawing, its numbers in the legend below it, so that no
  // text covers the paths.
  if (!d.worst.empty()) {
    const Vec2 p = canvas.px(d.worst.front().at);
    svg += fmt::format(
        "<circle id=\"worst\" cx=\"{:.1f}\" cy=\"{:.1f}\" r=\"9\" fill=\"none\" stroke=\"#c000c0\" stroke-width=\"2\"/>\n",
        p.x(), p.y());
  }
  // Legend: each line of text no wider than the picture.
  double ly = height + 20;
  auto line = [&](double y, const std::string& text, const char* attributes = "") {
    svg += fmt::format("<text x=\"{}\" y=\"{:.0f}\"{}>{}</text>\n", kMarginPx, y, attributes,
                       xml_escape(elided(text, kLineChars)));
  };
  svg += "<g id=\"legend\">\n<defs><linearGradient id=\"band\">";
  for (int k = 0; k < kBuckets; ++k)
    svg += fmt::format("<stop offset=\"{:.2f}\" stop-color=\"{}\"/>", double(k) / (kBuckets - 1), bucket_colour(k));
  svg += "</linearGradient></defs>\n";
  svg += fmt::format("<rect x=\"{}\" y=\"{:.0f}\" width=\"400\" height=\"16\" fill=\"url(#band)\"/>\n", kMarginPx, ly);
  svg += fmt::format("<rect x=\"{}\" y=\"{:.0f}\" width=\"40\" height=\"16\" fill=\"{}\"/>\n", kMarginPx + 410, ly,
                     bucket_colour(kBuckets));
  svg += fmt::format("<text x=\"{}\" y=\"{:.0f}\">0</text><text x=\"{}\" y=\"{:.0f}\">{} mm</text>"
                     "<text x=\"{}\" y=\"{:.0f}\">&gt; tolerance {} mm</text>\n",
                     kMarginPx, ly + 34, kMarginPx + 360, ly + 34, tol, kMarginPx + 460, ly + 34, tol);
  const char* verdict = d.verdict(tol) == ProgramDiff::Verdict::Same        ? "SAME"
                        : d.verdict(tol) == ProgramDiff::Verdict::Different ? "DIFFERENT"
                                                                             : "INCOMPLETE";
  line(ly + 58, fmt::format("{}: B deviates from A by {:.6f} mm at most, tolerance {} mm", verdict,
                            d.max_deviation_mm, tol));
  if (!d.worst.empty()) {
    const DiffPlace& w = d.worst.front();
    line(ly + 78, fmt::format("worst {:.6f} mm (ringed): A line {}, B line {}", w.deviation_mm, w.line_a, w.line_b),
         " id=\"worst-label\" fill=\"#800080\"");
  }
  line(ly + 98, "A: " + names.a);
  line(ly + 118, "B: " + names.b);
  svg += "</g>\n</svg>\n";
  return svg;
}

}  // namespace arcpress
