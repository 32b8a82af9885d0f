#include "arcpress/verify/program_diff.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <tuple>

#include "arcpress/core/deviation.hpp"
#include "arcpress/verify/segment_index.hpp"

namespace arcpress {
namespace {

bool is_feed(MoveKind k) { return k == MoveKind::Line || k == MoveKind::ArcCW || k == MoveKind::ArcCCW; }

Vec3 xyz(const AxisValues& v) { return {v[kX], v[kY], v[kZ]}; }

/// One program's feed path as segments: segment s runs from ends[2s] to ends[2s+1],
/// belongs to move move_of[s] and section section_of[s]; within a section the segments
/// follow each other along the path.
struct Path {
  std::vector<Vec3> ends;
  std::vector<uint32_t> move_of, section_of;
  std::vector<double> section_length_mm, section_e;  ///< per section
  std::vector<uint32_t> rapids;                      ///< move indices of known rapids
  size_t feed_moves = 0;

  size_t size() const { return move_of.size(); }
  Vec3 a(size_t s) const { return ends[2 * s]; }
  Vec3 b(size_t s) const { return ends[2 * s + 1]; }
};

/// Longest piece of a path put into the index, mm.
constexpr double kPieceMm = 2.0;

Path path_of(const Interpretation& in, double chord_mm) {
  Path p;
  std::vector<Vec3> pts;
  bool in_section = false;
  for (size_t i = 0; i < in.moves.size(); ++i) {
    const Move& m = in.moves[i];
    if (!is_feed(m.kind) || !m.known) {
      if (m.kind == MoveKind::Rapid && m.known) p.rapids.push_back(uint32_t(i));
      in_section = false;
      continue;
    }
    if (!in_section) {
      p.section_length_mm.push_back(0);
      p.section_e.push_back(0);
      in_section = true;
    }
    ++p.feed_moves;
    uint32_t sec = uint32_t(p.section_length_mm.size() - 1);
    p.section_e[sec] += m.to[kE] - in.from(i)[kE];
    Vec3 prev = xyz(in.from(i));
    pts.clear();
    move_path(in, i, chord_mm, pts);
    for (const Vec3& q : pts) {
      // Long segments are cut into pieces: an AABB over a long diagonal box is hit by
      // nearly every query (travel moves across a printed layer).
      double len = (q - prev).norm();
      int pieces = std::max(1, int(std::ceil(len / kPieceMm)));
      for (int k = 1; k <= pieces; ++k) {
        Vec3 r = k == pieces ? q : Vec3(prev + (q - prev) * (double(k) / pieces));
        p.ends.push_back(k == 1 ? prev : p.ends.back());
        p.ends.push_back(r);
        p.move_of.push_back(uint32_t(i));
        p.section_of.push_back(sec);
      }
      p.section_length_mm[sec] += len;
      prev = q;
    }
  }
  return p;
}

/// The key by which non-motion blocks are compared: their M, T, S words, a dwell, and
/// their comment, so that units, spacing and modal G-codes do not count.
std::string non_motion_key(const Program& p, const Block& b) {
  std::string key;
  bool dwell = false;
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w) {
    if (w->letter == 'G' && !w->is_expr && std::lround(w->value * 10) == 40) dwell = true;
  }
  for (auto* w = p.words_begin(b); w != p.words_end(b); ++w) {
    if (w->letter == 'M' || w->letter == 'T' || w->letter == 'S' || (dwell && (w->letter == 'P' || w->letter == 'G'))) {
      if (!key.empty()) key += ' ';
      key += p.raw(b, *w);
    }
  }
  if (b.has_comment) {
    std::string_view raw = p.raw(b);
    size_t c = std::min(raw.find('('), raw.find(';'));
    if (c != std::string_view::npos) {
      if (!key.empty()) key += ' ';
      key.append(raw.substr(c));
    }
  }
  for (char& c : key) c = char(std::toupper(static_cast<unsigned char>(c)));
  return key;
}

struct NonMotion {
  std::vector<std::string> keys;
  std::vector<uint32_t> lines;
};

NonMotion non_motion_of(const Program& p, const Interpretation& in) {
  NonMotion n;
  for (size_t bi = 0; bi < p.blocks.size(); ++bi) {
    const Block& b = p.blocks[bi];
    if (b.kind == BlockKind::Empty || b.kind == BlockKind::Percent) continue;
    if (bi < in.move_of_block.size() && in.move_of_block[bi] >= 0 && !b.has_comment) continue;
    std::string key = non_motion_key(p, b);
    if (key.empty()) continue;
    n.keys.push_back(std::move(key));
    n.lines.push_back(b.line);
  }
  return n;
}

/// Measures the distance from every point of `from` to `to` (one direction), updating the
/// running maximum. See the header for why no point between evaluations can be farther.
class Directed {
 public:
  Directed(const Path& from, const Path& to, const SegmentIndex& index, double precision_mm, double& max_mm)
      : from_(from), to_(to), index_(index), precision_mm_(precision_mm), max_mm_(max_mm) {}

  /// `visit(from_segment, to_segment, distance, point)` for every evaluated point.
  template <class Visit>
  void run(Visit&& visit) {
    if (index_.empty()) return;
    SegmentIndex::Nearest n0{};
    Vec3 last(NAN, NAN, NAN);
    for (size_t s = 0; s < from_.size(); ++s) {
      Vec3 p0 = from_.a(s), p1 = from_.b(s);
      if (!(p0 == last)) n0 = index_.nearest(p0);
      SegmentIndex::Nearest n1 = index_.nearest(p1);
      visit(s, n0, p0);
      visit(s, n1, p1);
      refine(s, p0, n0, p1, n1, 0, visit);
      n0 = n1;
      last = p1;
    }
  }

 private:
  template <class Visit>
  void refine(size_t s, const Vec3& p0, const SegmentIndex::Nearest& n0, const Vec3& p1,
              const SegmentIndex::Nearest& n1, int depth, Visit& visit) {
    double bound = chain_bound(p0, n0, p1, n1);
    if (bound <= max_mm_ + precision_mm_ || depth > 40 || (p1 - p0).norm() <= precision_mm_) return;
    Vec3 m = (p0 + p1) / 2;
    SegmentIndex::Nearest nm = index_.nearest(m);
    visit(s, nm, m);
    refine(s, p0, n0, m, nm, depth + 1, visit);
    refine(s, m, nm, p1, n1, depth + 1, visit);
  }

  /// Upper bound of the distance to `to_` along p0 -> p1: pair p0 -> p1 with the walk along
  /// `to_`'s path between their nearest points (both in one section); the pairing is linear
  /// between the walk's vertices, so the largest gap is at one of them. Unpaired: Lipschitz.
  double chain_bound(const Vec3& p0, const SegmentIndex::Nearest& n0, const Vec3& p1,
                     const SegmentIndex::Nearest& n1) const {
    double lipschitz = (n0.distance_mm + n1.distance_mm + (p1 - p0).norm()) / 2;
    uint32_t i = n0.segment, j = n1.segment;
    if (to_.section_of[i] != to_.section_of[j]) return lipschitz;
    if (i == j) return std::max(n0.distance_mm, n1.distance_mm);
    if ((i < j ? j - i : i - j) > kMaxChain) return lipschitz;
    walk_.clear();
    walk_.push_back(n0.point);
    if (i < j)
      for (uint32_t k = i; k < j; ++k) walk_.push_back(to_.b(k));
    else
      for (uint32_t k = i; k > j; --k) walk_.push_back(to_.a(k));
    walk_.push_back(n1.point);
    double total = 0;
    for (size_t k = 1; k < walk_.size(); ++k) total += (walk_[k] - walk_[k - 1]).norm();
    double run = 0, bound = std::max(n0.distance_mm, n1.distance_mm);
    for (size_t k = 1; k + 1 < walk_.size(); ++k) {
      run += (walk_[k] - walk_[k - 1]).norm();
      double t = total > 0 ? run / total : 0.5;
      bound = std::max(bound, (p0 + t * (p1 - p0) - walk_[k]).norm());
    }
    return std::min(bound, lipschitz);
  }

  static constexpr uint32_t kMaxChain = 4096;
  const Path& from_;
  const Path& to_;
  const SegmentIndex& index_;
  double precision_mm_;
  double& max_mm_;
  mutable std::vector<Vec3> walk_;
};

}  // namespace

ProgramDiff diff_programs(const Program& a, const Interpretation& ia, const Program& b, const Interpretation& ib,
                          const DiffOptions& opt) {
  ProgramDiff d;
  d.arc_chord_mm = std::max(opt.tolerance_mm * 1e-3, 1e-7);
  const double precision_mm = opt.tolerance_mm * 1e-3;
  Path pa = path_of(ia, d.arc_chord_mm), pb = path_of(ib, d.arc_chord_mm);
  auto summary = [](const Program& p, const Path& path) {
    ProgramSummary s;
    s.blocks = p.blocks.size();
    s.bytes = p.text.size();
    s.feed_moves = path.feed_moves;
    s.rapids = path.rapids.size();
    s.sections = path.section_length_mm.size();
    for (double l : path.section_length_mm) s.path_mm += l;
    return s;
  };
  d.a = summary(a, pa);
  d.b = summary(b, pb);
  d.deviation_of_b.assign(ib.moves.size(), 0.0);

  // Feed paths, both ways. Per pair of moves, the largest distance seen and where.
  SegmentIndex index_a(pa.ends), index_b(pb.ends);
  // The worst place seen on each move of A and of B.
  std::vector<DiffPlace> worst_on_a(ia.moves.size()), worst_on_b(ib.moves.size());
  auto note = [&](uint32_t move_a, uint32_t move_b, double dist, const Vec3& at) {
    d.deviation_of_b[move_b] = std::max(d.deviation_of_b[move_b], dist);
    for (DiffPlace* pl : {&worst_on_a[move_a], &worst_on_b[move_b]})
      if (dist > pl->deviation_mm || pl->line_a == 0)
        *pl = {dist, at, a.blocks[ia.moves[move_a].block].line, b.blocks[ib.moves[move_b].block].line};
  };
  if (!pa.ends.empty() && !pb.ends.empty()) {
    Directed(pa, pb, index_b, precision_mm, d.max_deviation_mm).run([&](size_t s, const SegmentIndex::Nearest& n, const Vec3& p) {
      d.max_deviation_mm = std::max(d.max_deviation_mm, n.distance_mm);
      note(pa.move_of[s], pb.move_of[n.segment], n.distance_mm, p);
    });
    Directed(pb, pa, index_a, precision_mm, d.max_deviation_mm).run([&](size_t s, const SegmentIndex::Nearest& n, const Vec3& p) {
      d.max_deviation_mm = std::max(d.max_deviation_mm, n.distance_mm);
      note(pa.move_of[n.segment], pb.move_of[s], n.distance_mm, p);
    });
    // Feed along the path: at the middle of each of B's segments (away from the joints,
    // where two moves meet), against the nearest A move that runs the same way.
    for (size_t sgm = 0; sgm < pb.size(); ++sgm) {
      Vec3 mid = (pb.a(sgm) + pb.b(sgm)) / 2;
      SegmentIndex::Nearest n = index_a.nearest(mid);
      const Move& mb = ib.moves[pb.move_of[sgm]];
      const Move& ma = ia.moves[pa.move_of[n.segment]];
      if (ma.feed_mm_min <= 0 || n.distance_mm > opt.tolerance_mm) continue;
      // A path crossing or retracing another is not its counterpart.
      Vec3 db = pb.b(sgm) - pb.a(sgm), da = pa.b(n.segment) - pa.a(n.segment);
      if (db.norm() <= kLengthEpsMm || da.norm() <= kLengthEpsMm ||
          db.normalized().dot(da.normalized()) < std::cos(deg_to_rad(10)))
        continue;
      double pct = 100.0 * std::abs(mb.feed_mm_min - ma.feed_mm_min) / ma.feed_mm_min;
      if (pct > d.max_feed_difference_pct) {
        d.max_feed_difference_pct = pct;
        d.worst_feed = {0, mid, a.blocks[ma.block].line, b.blocks[mb.block].line};
      }
    }
  } else if (pa.ends.empty() != pb.ends.empty()) {
    d.findings.push_back(fmt::format("only {} has feed moves", pa.ends.empty() ? "B" : "A"));
  }
  std::vector<DiffPlace> all;
  for (auto* list : {&worst_on_a, &worst_on_b})
    for (const DiffPlace& pl : *list)
      if (pl.line_a != 0) all.push_back(pl);
  std::sort(all.begin(), all.end(), [](const DiffPlace& x, const DiffPlace& y) {
    return x.deviation_mm != y.deviation_mm ? x.deviation_mm > y.deviation_mm
                                            : std::tie(x.line_a, x.line_b) < std::tie(y.line_a, y.line_b);
  });
  std::set<std::pair<uint32_t, uint32_t>> seen;
  for (const DiffPlace& pl : all) {
    if (d.worst.size() >= opt.top) break;
    if (seen.insert({pl.line_a, pl.line_b}).second) d.worst.push_back(pl);
  }

  if (d.a.sections != d.b.sections)
    d.findings.push_back(fmt::format("cutting sections between rapids: {} in A, {} in B", d.a.sections, d.b.sections));

  // Rapids: end points in order.
  if (pa.rapids.size() != pb.rapids.size())
    d.findings.push_back(fmt::format("rapid moves: {} in A, {} in B", pa.rapids.size(), pb.rapids.size()));
  for (size_t k = 0; k < std::min(pa.rapids.size(), pb.rapids.size()); ++k) {
    const Move& ma = ia.moves[pa.rapids[k]];
    const Move& mb = ib.moves[pb.rapids[k]];
    double dist = (xyz(ma.to) - xyz(mb.to)).norm();
    if (dist > d.max_rapid_mm) {
      d.max_rapid_mm = dist;
      d.worst_rapid = {dist, xyz(ma.to), a.blocks[ma.block].line, b.blocks[mb.block].line};
    }
  }

  // Extrusion per section.
  for (size_t k = 0; k < std::min(pa.section_e.size(), pb.section_e.size()); ++k) {
    double ea = pa.section_e[k], eb = pb.section_e[k];
    d.max_extrusion_difference_mm = std::max(d.max_extrusion_difference_mm, std::abs(ea - eb));
    double la = pa.section_length_mm[k], lb = pb.section_length_mm[k];
    if (la > 0 && lb > 0 && std::abs(ea) > 0)
      d.max_extrusion_per_mm_difference_pct =
          std::max(d.max_extrusion_per_mm_difference_pct, 100.0 * std::abs(eb / lb - ea / la) / std::abs(ea / la));
  }
  constexpr double kExtrusionMm = 1e-4;  // E printed with 5 decimals: sums agree far closer
  if (d.max_extrusion_difference_mm > kExtrusionMm)
    d.findings.push_back(fmt::format("extrusion per section differs by up to {:.5f} mm of E", d.max_extrusion_difference_mm));
  constexpr double kFeedPct = 0.01;
  if (d.max_feed_difference_pct > kFeedPct)
    d.findings.push_back(fmt::format("feed differs by up to {:.3f} % (A line {}, B line {})", d.max_feed_difference_pct,
                                     d.worst_feed.line_a, d.worst_feed.line_b));

  // Everything that is not geometry, in order.
  NonMotion na = non_motion_of(a, ia), nb = non_motion_of(b, ib);
  d.a.non_motion = na.keys.size();
  d.b.non_motion = nb.keys.size();
  size_t common = std::min(na.keys.size(), nb.keys.size());
  bool first = true;
  for (size_t k = 0; k < common; ++k) {
    if (na.keys[k] == nb.keys[k]) continue;
    ++d.non_motion_differences;
    if (first)
      d.findings.push_back(fmt::format("non-motion block differs: A line {} '{}', B line {} '{}'", na.lines[k],
                                       na.keys[k], nb.lines[k], nb.keys[k]));
    first = false;
  }
  if (na.keys.size() != nb.keys.size()) {
    d.non_motion_differences += std::max(na.keys.size(), nb.keys.size()) - common;
    d.findings.push_back(fmt::format("non-motion blocks (M, T, S, dwell, comments): {} in A, {} in B", na.keys.size(),
                                     nb.keys.size()));
  }
  return d;
}

}  // namespace arcpress
