// SPDX-License-Identifier: GPL-3.0-or-later
#include "arcpress/verify/diff_report.hpp"

#include <fmt/format.h>

namespace arcpress {

std::string json_string(const std::string& s) {
  std::string out = "\"";
  for (char c : s) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) out += fmt::format("\\u{:04x}", int(c));
        else out += c;
    }
  }
  return out + "\"";
}

namespace {

std::string place_json(const DiffPlace& p) {
  return fmt::format("{{\"deviation_mm\": {:.9f}, \"x\": {:.6f}, \"y\": {:.6f}, \"z\": {:.6f}, \"line_a\": {}, \"line_b\": {}}}",
                     p.deviation_mm, p.at.x(), p.at.y(), p.at.z(), p.line_a, p.line_b);
}

std::string summary_json(const ProgramSummary& s, const std::string& name) {
  return fmt::format(
      "{{\"file\": {}, \"blocks\": {}, \"bytes\": {}, \"feed_moves\": {}, \"rapids\": {}, \"sections\": {}, "
      "\"non_motion_blocks\": {}, \"path_mm\": {:.6f}, \"unplaced_feed_moves\": {}, \"first_unplaced_line\": {}, "
      "\"unplaced_reason\": {}, \"entry_moves\": {}, \"first_entry_line\": {}, \"entry_reason\": {}, "
      "\"unmeasured_arcs\": {}, \"first_unmeasured_line\": {}, \"far_moves\": {}, \"first_far_line\": {}{}}}",
      json_string(name), s.blocks, s.bytes, s.feed_moves, s.rapids, s.sections, s.non_motion, s.path_mm,
      s.unplaced_feed_moves, s.first_unplaced_line, json_string(s.unplaced_reason), s.entry_moves,
      s.first_entry_line, json_string(s.entry_reason), s.unmeasured_arcs, s.first_unmeasured_line, s.far_moves,
      s.first_far_line, s.rate ? ", \"block_rate\": " + block_rate_json(*s.rate) : std::string());
}

std::string side_json(const ProgramDiff& d) {
  if (!d.band_side) return "null";
  const auto& s = *d.band_side;
  return fmt::format("{{\"side\": \"{}\", \"measured\": {}, \"why_not\": {}, \"max_wrong_side_mm\": {:.9f}, "
                     "\"allowed_mm\": {:.9f}, \"line_a\": {}, \"line_b\": {}}}",
                     s.side == BandSide::Left ? "left" : "right", s.measured, json_string(s.why_not),
                     s.max_wrong_side_mm, s.allowance_mm, s.line_a, s.line_b);
}

const char* verdict_word(ProgramDiff::Verdict v, bool upper) {
  switch (v) {
    case ProgramDiff::Verdict::Same: return upper ? "SAME" : "same";
    case ProgramDiff::Verdict::Different: return upper ? "DIFFERENT" : "different";
    case ProgramDiff::Verdict::Incomplete: break;
  }
  return upper ? "INCOMPLETE" : "incomplete";
}

}  // namespace

std::string diff_text(const ProgramDiff& d, const DiffNames& n, double tol) {
  std::string t;
  for (auto [name, s] : {std::pair{n.a, d.a}, std::pair{n.b, d.b}}) {
    t += fmt::format("{}: {} blocks, {} bytes, {} feed moves in {} sections, {} rapids, {:.3f} mm of feed path\n", name,
                     s.blocks, s.bytes, s.feed_moves, s.sections, s.rapids, s.path_mm);
    if (s.rate) t += fmt::format("{}: block rate at the programmed feeds: {}\n", name, block_rate_text(*s.rate));
    if (s.entry_moves > 0)
      t += fmt::format("{}: {} feed move(s) from an unknown position, compared by their end points (first at line {}: {})\n",
                       name, s.entry_moves, s.first_entry_line, s.entry_reason);
    if (s.unmeasured_arcs > 0)
      t += fmt::format("{}: {} arc(s) too big to follow within a tenth of the band, not compared (first at line {})\n",
                       name, s.unmeasured_arcs, s.first_unmeasured_line);
    if (s.far_moves > 0)
      t += fmt::format("{}: {} feed move(s) too far from the origin to measure within the band, not compared (first "
                       "at line {})\n",
                       name, s.far_moves, s.first_far_line);
    if (s.identical_unmeasured > 0)
      t += fmt::format("{}: {} feed move(s) too far from the origin or arc(s) too big to measure, each the same as "
                       "the other program's: compared as identical\n",
                       name, s.identical_unmeasured);
    if (s.unplaced_feed_moves > 0)
      t += fmt::format("{}: {} feed move(s) not compared: their position is not known (first at line {}: {})\n", name,
                       s.unplaced_feed_moves, s.first_unplaced_line, s.unplaced_reason);
  }
  t += fmt::format("max deviation {:.6f} mm (band {} mm; measured to {:.1e} mm)\n", d.max_deviation_mm, tol,
                   d.arc_chord_mm);
  for (size_t k = 0; k < d.worst.size(); ++k) {
    const DiffPlace& p = d.worst[k];
    t += fmt::format("  #{} {:.6f} mm at X{:.4f} Y{:.4f} Z{:.4f} ({} line {}, {} line {})\n", k + 1, p.deviation_mm,
                     p.at.x(), p.at.y(), p.at.z(), n.a, p.line_a, n.b, p.line_b);
  }
  t += fmt::format("rapid end points: max {:.6f} mm apart", d.max_rapid_mm);
  if (d.max_rapid_mm > 0) t += fmt::format(" ({} line {}, {} line {})", n.a, d.worst_rapid.line_a, n.b, d.worst_rapid.line_b);
  t += "\n";
  if (d.extra_axes_compared) {
    t += fmt::format("extra axes (A/B/C in degrees, U/V/W in mm): max {:.6f} apart", d.max_extra_axis);
    if (d.extra_axis >= 0)
      t += fmt::format(" ({} at X{:.4f} Y{:.4f} Z{:.4f}, {} line {}, {} line {})", kAxisLetters[d.extra_axis],
                       d.worst_extra_axis.at.x(), d.worst_extra_axis.at.y(), d.worst_extra_axis.at.z(), n.a,
                       d.worst_extra_axis.line_a, n.b, d.worst_extra_axis.line_b);
    t += "\n";
  }
  if (d.a.entry_moves + d.b.entry_moves > 0) {
    t += fmt::format("feed moves from an unknown position: end points max {:.6f} mm apart", d.max_entry_mm);
    if (d.max_entry_mm > 0) t += fmt::format(" ({} line {}, {} line {})", n.a, d.worst_entry.line_a, n.b, d.worst_entry.line_b);
    t += "\n";
  }
  t += fmt::format(
      "feed: max {:.4f} % apart, compared along {:.1f} % of B's feed path{}; extrusion: max {:.5f} mm of E per "
      "section, {:.3f} % per mm of path\n",
      d.max_feed_difference_pct, 100 * d.feed_compared_share,
      d.feed_unpaired_mm > 0 ? fmt::format(" ({:.3f} mm of it with no counterpart on A, first at B line {})",
                                           d.feed_unpaired_mm, d.feed_unpaired_line_b)
                             : std::string(),
      d.max_extrusion_difference_mm, d.max_extrusion_per_mm_difference_pct);
  t += fmt::format("non-motion blocks (M, T, S, dwell{}): {} in A, {} in B, {} differ\n",
                   d.comments_compared ? ", comments" : "; comments not compared", d.a.non_motion, d.b.non_motion,
                   d.non_motion_differences);
  for (const auto& f : d.findings) t += "difference: " + f + "\n";
  const size_t unplaced = d.a.not_compared() + d.b.not_compared();
  if (const auto& s = d.band_side) {
    const char* side = s->side == BandSide::Left ? "left" : "right";
    t += s->measured ? fmt::format("band side {}: B lies at most {:.6f} mm on the other side of A (allowed {:.6f} mm, the "
                                   "rounding of printed centres){}\n",
                                   side, s->max_wrong_side_mm, s->allowance_mm,
                                   s->line_b ? fmt::format(", A line {}, B line {}", s->line_a, s->line_b) : "")
                     : fmt::format("band side {}: not measured: {}\n", side, s->why_not);
  }
  t += fmt::format("{}: max deviation {:.6f} mm {} the {} mm band{}{}{}{}\n", verdict_word(d.verdict(tol), true),
                   d.max_deviation_mm, d.max_deviation_mm <= tol ? "within" : "outside", tol,
                   d.max_extra_axis <= tol || d.extra_axis < 0
                       ? ""
                       : fmt::format(", {} {:.6f} apart", kAxisLetters[d.extra_axis], d.max_extra_axis),
                   d.findings.empty() ? "" : fmt::format(", {} other difference(s)", d.findings.size()),
                   unplaced == 0 ? "" : fmt::format(", {} feed move(s) not compared", unplaced),
                   d.feed_unpaired_mm == 0 ? "" : fmt::format(", the feed along {:.3f} mm of B's path not compared",
                                                              d.feed_unpaired_mm));
  return t;
}

std::string diff_json(const ProgramDiff& d, const DiffNames& n, double tol) {
  std::string worst;
  for (const auto& p : d.worst) worst += (worst.empty() ? "" : ", ") + place_json(p);
  std::string findings;
  for (const auto& f : d.findings) findings += (findings.empty() ? "" : ", ") + json_string(f);
  return fmt::format(
      "{{\n  \"verdict\": \"{}\",\n  \"tolerance_mm\": {},\n  \"a\": {},\n  \"b\": {},\n"
      "  \"max_deviation_mm\": {:.9f},\n  \"arc_precision_mm\": {:.9f},\n  \"worst\": [{}],\n"
      "  \"rapids\": {{\"max_end_point_distance_mm\": {:.9f}, \"worst\": {}}},\n"
      "  \"entries\": {{\"max_end_point_distance_mm\": {:.9f}, \"worst\": {}}},\n"
      "  \"extra_axes\": {{\"compared\": {}, \"max_difference\": {:.9f}, \"axis\": {}, \"worst\": {}}},\n"
      "  \"feed\": {{\"max_difference_percent\": {:.6f}, \"line_a\": {}, \"line_b\": {}, "
      "\"compared_share\": {:.6f}, \"unpaired_mm\": {:.9f}, \"unpaired_line_b\": {}}},\n"
      "  \"extrusion\": {{\"max_section_difference_mm\": {:.9f}, \"max_per_mm_difference_percent\": {:.6f}}},\n"
      "  \"non_motion\": {{\"blocks_a\": {}, \"blocks_b\": {}, \"differences\": {}, \"comments\": {}}},\n"
      "  \"differences\": [{}],\n  \"band_side\": {}\n}}\n",
      verdict_word(d.verdict(tol), false), tol, summary_json(d.a, n.a), summary_json(d.b, n.b), d.max_deviation_mm,
      d.arc_chord_mm, worst, d.max_rapid_mm, place_json(d.worst_rapid), d.max_entry_mm, place_json(d.worst_entry),
      d.extra_axes_compared, d.max_extra_axis,
      d.extra_axis < 0 ? std::string("null") : json_string(std::string(1, kAxisLetters[d.extra_axis])),
      place_json(d.worst_extra_axis), d.max_feed_difference_pct, d.worst_feed.line_a, d.worst_feed.line_b, d.feed_compared_share, d.feed_unpaired_mm,
      d.feed_unpaired_line_b,
      d.max_extrusion_difference_mm, d.max_extrusion_per_mm_difference_pct, d.a.non_motion, d.b.non_motion,
      d.non_motion_differences, d.comments_compared, findings, side_json(d));
}

}  // namespace arcpress
