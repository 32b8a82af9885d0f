// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The fitter's shared machinery, private to fit/: the angles it turns by, and RunFitter,
// which fits one stretch of a run, to the limits in search_limits.hpp. Its members are
// defined in the files named for what they do: run_fitter.cpp (the run, its vertices and
// stretches), tangents.cpp, scan.cpp and candidate.cpp (the machinery every method shares),
// then one file per method (bound_search, greedy, beam, layered, range_search, lowe,
// stream) and tangency.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_map>
#include <unordered_set>

#include "arcpress/core/deviation.hpp"
#include "arcpress/fit/fit_angles.hpp"
#include "arcpress/fit/fitter.hpp"
#include "arcpress/fit/search_limits.hpp"

namespace arcpress::fit_detail {

/// The start tangents at a free start whose circles reach vertex e inside the band: their
/// tangent-chord angles (radians, positive to the left of the chord) from lo to hi.
struct StartRange {
  uint32_t e;
  double lo, hi;
};

/// One way to end the primitive that starts at `a`: at vertex e with curvature k.
struct Candidate {
  uint32_t e;
  double k;  // signed curvature, 1/mm (> 0 turns left)
  bool line;
};

/// A move of a chain that its fit leaves as it is (a lone move, an input arc, or a move of a
/// run fitted in another plane), with the path's direction in the chain's plane where it
/// leaves the move before and where it enters the move after (none where unknown). Where
/// that direction is a fitted line's that replaced several moves (a run fitted in another
/// plane), the joint there is new, and judged as the fit's own joints are.
struct FixedMove {
  bool fixed = false;
  std::optional<Vec2> start, end;
  bool fitted_start = false, fitted_end = false;
};

struct Chosen {
  Primitive prim;
  Vec2 end_tangent{1, 0};
  bool kinked = false;  ///< starts with a tangent change at a joint where the input is smooth
};

class RunFitter : private FitAngles {
 public:
  /// `run` spans the moves to fit; `fixed` (per move, empty: none) says which stay as they
  /// are, and `pinned` (per vertex, empty: none) where a primitive must end (where one run
  /// meets the next or a fixed move), the tangent going on there.
  RunFitter(const Interpretation& in, const Run& run, const FitOptions& o, const std::vector<FixedMove>& fixed = {},
            std::vector<uint8_t> pinned = {});
  /// The primitives over all moves (fixed moves as themselves), each marked `kinked` where
  /// the tangent breaks at a smooth joint because the band allows nothing tangent there.
  /// Their end vertices are the run's.
  std::vector<Chosen> fit();
  /// The run's vertices the fitter works on: all, less those that only repeat the one before
  /// (after a move that goes nowhere: no direction, so no corner either), which the
  /// primitive over their neighbours steps over. Where such a vertex must stay
  /// (the run's end, a pinned vertex) the one it repeats goes instead, unless that must stay
  /// too. (The keep method never gets here: fit_chain() keeps every move itself.)
  static void vertices_kept(const Interpretation& in, const Run& run, const std::vector<FixedMove>& fixed,
                            const std::vector<uint8_t>& pinned, std::vector<uint32_t>& at);

 private:
  std::vector<Chosen> fit_kept();
  /// The chain over the stretch from `a` to `limit` (in_tangent_, out_tangent_, the scan
  /// limits and heading_ set for it) by the options' method, `forced` counting its forced
  /// kinks.
  std::vector<Chosen> fit_stretch(uint32_t a, uint32_t limit, size_t& forced);
  /// A chain that still wiggles may be paying with S-bends, all the way along, for one joint
  /// the path cannot pass tangentially: a hook, where the input turns at a vertex by more
  /// than a primitive ending there can follow within the band (a pass clipped to the floor it
  /// meets), so every chain that keeps the tangent leaves that vertex heading off the path.
  /// The tangent breaks instead at the joint where the first wiggle starts, or at the one
  /// before or after it, when that at least halves the primitives after the joint and saves
  /// kKinkWorth of them for each kink it adds, or, where the chain after the joint kinks as
  /// often as the restart with its break, saves any; the break is a forced kink. The chain after
  /// the break may meet such a joint again further on (the next of plum's inner tips), so
  /// it is mended the same way, up to kUntangleDepth joints deep, before it is weighed:
  /// mended only at its first wiggle, a greedy chain over plum crept through the rest in
  /// S-bends (sampled with 6 000 points and turned by 0.7 rad, at 0.005 mm: 667 blocks; 59
  /// now, with two kinks). The restarts are fitted by the search where `search`, else by the
  /// greedy walk.
  void untangle(uint32_t a, uint32_t limit, std::vector<Chosen>& chain, size_t& forced, bool search) const;
  /// The chain a restart at vertex v fits after a break, before it is mended, and its forced
  /// kinks: the levels of untangle() restart at the same vertices again and again (plum at
  /// 0.005 mm: 20 restarts at 8 vertices), and a restart's chain depends on its vertex alone.
  struct Restart {
    uint32_t v;
    std::vector<Chosen> chain;
    size_t forced;
  };
  /// untangle() `depth` levels down, with the restarts fitted so far in the same call.
  void untangle_at(uint32_t a, uint32_t limit, std::vector<Chosen>& chain, size_t& forced, bool search, int depth,
                   std::vector<Restart>& restarts) const;
  /// The index of the first primitive of the first wiggle in `chain` (see wiggles()), or
  /// its size when none.
  size_t wiggle_start(const std::vector<Chosen>& chain) const;
  /// Whether `chain` wiggles: several arcs in a row, each turning the other way from the one
  /// before, as a chain does that left a narrow place (plum's inner tips) with a tangent it
  /// can only bring back to the path by S-bends, all tangent, all inside the band, and many.
  bool wiggles(const std::vector<Chosen>& chain) const { return wiggle_start(chain) < chain.size(); }
  /// Whether the joint at vertex v, after a move that is fixed or not, is one the fit made:
  /// between two moves left as they are it is the input's own, unless one side is a line
  /// that replaced several moves in another plane.
  bool made_joint(uint32_t v, bool fixed_before) const;
  /// Marks as kinked the joints of `chain` (the whole fit) that are corners only because a
  /// spike next to them was skipped, where the tangent breaks there: the verifier, which
  /// skips no spikes, judges them as smooth joints.
  void report_spike_corners(std::vector<Chosen>& chain) const;
  std::vector<Chosen> keep() const;
  /// Vertex v in the plane (its first two coordinates).
  const Vec2& q(uint32_t v) const { return q_[v]; }
  /// Whether a change of extrusion rate lies strictly between vertices a and e (it would end
  /// a primitive there).
  bool soft_between(uint32_t a, uint32_t e) const { return next_soft_[a] < e; }
  /// All ends e in (a, limit] for which the arc (or line) leaving `a` along `T` and passing
  /// exactly through vertex e keeps every vertex in between inside the band. For a fixed
  /// start and tangent, each vertex allows an interval of curvatures (exact for the full
  /// circle), so the scan is linear and stops when the intervals no longer meet.
  void scan(uint32_t a, const Vec2& T, uint32_t limit, std::vector<Candidate>& out) const;
  /// What scan_ends() holds each end to besides the band, read off the options and the
  /// stretch (lim_: once a stretch, not at each of the few million scans).
  struct ScanLimits {
    double max_alpha, min_alpha, line_alpha;  // pseudo-angles, see FitAngles()
    double min_curvature, max_curvature;      // 1/mm: those of the largest and smallest radius
    double min_arc_length_mm;
    uint32_t min_arc_moves;
    bool arcs, helical;
    uint32_t stretch_end;
    const Vec2* out_tangent;  // null: none
    BandSide side;
  };
  ScanLimits scan_limits() const;
  /// scan() handing each end to `sink` in order, nothing stored.
  template <class Sink>
  void scan_ends(uint32_t a, const Vec2& T, uint32_t limit, Sink&& sink) const;
  /// scan_ends() along each of `count` (<= kFanLanes) tangents T[0..count) at once, handing
  /// `sink` (lane, candidate) for each end from `first_end` on: for each end in order, the
  /// lanes in order.
  template <class Sink>
  void fan_ends(uint32_t a, const Vec2* T, int count, uint32_t limit, uint32_t first_end, Sink&& sink) const;
  /// fan_ends() of at most `Lanes` tangents, where every vertex of the run lies at one
  /// height (`level`: then no primitive climbs, which the compiler can see) or not.
  template <bool level, int Lanes, class Sink>
  void fan_ends_in(uint32_t a, const Vec2* T, int count, uint32_t limit, uint32_t first_end, Sink& sink) const;
  /// Builds and checks the primitive for candidate `c` from `a` along `T`.
  std::optional<Chosen> make(uint32_t a, const Vec2& T, const Candidate& c) const;
  /// Whether every extra axis that moves, carried linearly from vertex a to vertex e with
  /// the block's progress as the controller carries it, comes within the band of its value
  /// at each vertex between where the block passes nearest that vertex, within kFitNearShare
  /// of the band (`window(m)`: line_progress_near() or arc_progress_near(), as the check
  /// reads it, within more: kCheckNearShare; at an arc's centre every point is as near;
  /// the band's number read in the axis's unit: mm, or degrees for A/B/C, which keeps a
  /// point within the band up to 57 mm from the axis). The vertices' rates per mm agree with
  /// their neighbours' (soft_), but a rate that drifts slowly would still bend the axis away
  /// from the line over a long primitive.
  template <class Window>
  bool extra_axes_linear(uint32_t a, uint32_t e, const Window& window) const;
  /// Whether a primitive from vertex a to vertex e, `length_mm` long, which extrudes its E
  /// evenly along itself as the controller does, keeps every move it replaces at its own
  /// rate: each move's E per mm within the extrusion variance of the primitive's (a share
  /// of the larger). Neighbouring moves' rates agree (soft_), but rates that drift move by
  /// move would put the plastic elsewhere along a long primitive: a wall whose width grows
  /// 4 % a move, twelvefold over a quarter circle, printed at its average width.
  bool extrusion_even(uint32_t a, uint32_t e, double length_mm) const;
  /// The line from vertex a to vertex e, if the moves between stay inside the band.
  std::optional<Chosen> make_line(uint32_t a, uint32_t e, const Vec2& fallback_tangent) const;
  /// The arc from vertex a to vertex e about `center`, if the moves between stay inside the
  /// band (in-plane share when it climbs) and the arc keeps the options' limits.
  std::optional<Chosen> make_arc(uint32_t a, uint32_t e, const Vec2& center, bool ccw) const;
  /// How far the chain reaches in one more step from vertex `e` along `T`: the last end
  /// the curvature scan allows (not yet checked exactly), or `e` itself when nothing fits.
  /// A corner or the end of the stretch counts as reaching the end.
  uint32_t reach_after(uint32_t e, const Vec2& T, uint32_t limit) const;
  /// The input's own direction at vertex e, from each side apart: the mean of the tangents
  /// at e of the circles through e and two vertices behind it, and through e and two ahead
  /// (0.1 mm apart or more). Where the curvature jumps (a fillet meeting a straight side),
  /// each circle follows its own curve, where one circle through both sides would bend the
  /// tangent towards the tighter (by 0.46° at the end of a 5 mm fillet written in 0.2 mm
  /// moves, more than a joint may turn). input_tangent() where a side lacks the vertices.
  std::optional<Vec2> sided_tangent(uint32_t e, uint32_t lo, uint32_t hi) const;
  /// The input's own direction at vertex e: tangent at e of the circle through e-w, e, e+w,
  /// with w wide enough (0.1 mm each side) that 4-decimal rounding does not steer it.
  /// Nothing at the ends of the stretch [lo, hi].
  std::optional<Vec2> input_tangent(uint32_t e, uint32_t lo, uint32_t hi) const;
  /// Ranks a primitive ending at vertex e with `end_tangent`: primitives that leave the chain
  /// heading where the input heads come first, then those after which the chain reaches
  /// further, then longer ones. Keeps the chain from zigzagging along a straight stretch with
  /// a tangent that is off by a few degrees.
  struct Score {
    bool on_course = true;
    uint32_t reach = 0;
    uint32_t end = 0;
    bool operator>(const Score& o) const {
      if (on_course != o.on_course) return on_course;
      if (reach != o.reach) return reach > o.reach;
      return end > o.end;
    }
  };
  struct Ranked {
    size_t i;
    Score sc;
  };
  Score score(const Chosen& c, uint32_t limit) const;
  /// The score of `c`, after which the chain reaches `reach`.
  Score scored(const Chosen& c, uint32_t reach) const;
  /// Up to `count` primitives from `a` along `T` that pass the exact check, spread over the
  /// longer half of the scan's candidates, longest first. After a failure the walk steps
  /// back by growing strides to bound the work, and still tries the shortest candidate.
  void checked_from(uint32_t a, const Vec2& T, uint32_t limit, int count, std::vector<Chosen>& out) const;
  /// A scan a greedy step made in the searches (best_near()), with the reach of each end it
  /// scored: the beam expands the node the greedy chain is at (its guide) along the same
  /// tangents from the same vertex, and takes the ends and reaches from here instead of
  /// scanning again. Valid in the stretch it was made in (the scans read the stretch's limits).
  struct GuideScan {
    uint64_t stretch = 0;  // 0: none
    uint32_t a = 0, limit = 0;
    Vec2 T{0, 0};
    std::vector<Candidate> ends;
    std::vector<std::pair<uint32_t, uint32_t>> reach;  // (end vertex, reach_after())
  };
  /// Up to `count` candidates from `a` along `T`, spread over the longer half of what the
  /// scan allows, longest first; not yet checked exactly. With `next_to_longest`, also the
  /// one before the longest: where a straight stretch turns into a fillet, the primitive
  /// that ends at the turn, one vertex short of the furthest the band lets it overshoot, is
  /// the one the next can follow (a rounded rectangle: 11 blocks without it, 8 with).
  /// While a greedy step is taken in a search (s_.guide_record), the scan is kept as a
  /// GuideScan; with `reuse` (the beam, expanding its guide), a greedy step's scan from `a`
  /// along T is taken again when there is one. Returns that GuideScan, else null.
  GuideScan* pick(uint32_t a, const Vec2& T, uint32_t limit, int count, std::vector<Candidate>& out,
                  bool next_to_longest = false, bool reuse = false) const;
  /// The greedy steps' scan from `a` along exactly `T` in this stretch, or null.
  GuideScan* guide_scan(uint32_t a, const Vec2& T, uint32_t limit) const;
  /// score() of `c`, a candidate of scan `g`, with the reach the greedy step found when it
  /// scored it too.
  Score guide_score(const GuideScan& g, const Chosen& c, uint32_t limit) const;
  /// What candidate `c` from `a` along `T` would be, for scoring before the exact check: its
  /// end vertex and end tangent (T reflected about the chord; a line's is the chord).
  Chosen unchecked(uint32_t a, const Vec2& T, const Candidate& c) const;
  /// Among the checked primitives from `a` along `T`, the one after which the chain reaches
  /// furthest in the next step (two-step look-ahead over a few long candidates); ties go
  /// to the longer primitive. A primitive after which the chain cannot go on tangentially
  /// is taken only when there is no other. `scored`, where given, receives its score.
  std::optional<Chosen> best_from(uint32_t a, const Vec2& T, uint32_t limit, Score* scored = nullptr) const;
  /// The chain may turn by less than the G1 angle at a joint. When the exact tangent only
  /// allows a short primitive (the incoming tangent is slightly off the input's), tangents
  /// turned by up to 0.9 of that angle (near_turns_) are tried too, and the one reaching
  /// furthest wins.
  std::optional<Chosen> best_near(uint32_t a, const Vec2& T, uint32_t limit) const;
  /// Keeps in `best` whichever of it and the best primitive along `T` scores higher. With
  /// `incoming` (the tangent the chain arrives with, T being turned from it), a primitive
  /// that leaves by more than kJointShare of the G1 angle from it is not taken: a line's chord
  /// may lie off T by the line allowance, on top of the turn.
  void consider(uint32_t a, const Vec2& T, uint32_t limit, std::optional<Chosen>& best, Score& best_score,
                const Vec2* incoming = nullptr) const;
  /// The greedy chain from `a` to `limit`, built one primitive at a time, each the
  /// best-scoring of a few checked candidates, and walked only as far as it is asked for.
  /// Where nothing leaves a smooth joint tangentially, the tangent breaks there and `forced`
  /// counts it.
  struct GreedyWalk {
    const RunFitter& f;
    uint32_t a, limit;
    std::optional<Vec2> tangent;
    std::vector<Chosen> chain;
    size_t forced = 0;

    GreedyWalk(const RunFitter& fitter, uint32_t start, uint32_t end)
        : f(fitter), a(start), limit(end), tangent(fitter.in_tangent_) {}
    /// Its k-th primitive (from 0), walking on to it; null past its end.
    const Chosen* at(size_t k) {
      while (chain.size() <= k && a < limit) step();
      return k < chain.size() ? &chain[k] : nullptr;
    }
    /// Whether it has more than k primitives, walking on only as far as that takes: once it
    /// has k, whether the k-th ends short of `limit` (a step always adds one).
    bool longer_than(size_t k) {
      while (chain.size() < k && a < limit) step();
      return chain.size() > k || (chain.size() == k && a < limit);
    }
    /// The fewest primitives it can end with, walked as far as it is now: those it has, and
    /// one more unless it reached `limit`.
    size_t at_least() const { return chain.size() + (a < limit ? 1 : 0); }
    /// Walks again from `start`, as new.
    void restart(uint32_t start) {
      a = start;
      tangent = f.in_tangent_;
      chain.clear();
      forced = 0;
    }
    /// Walks to `limit`.
    void finish() {
      while (a < limit) step();
    }
    /// Primitives and forced kinks so far (the whole chain's after finish()).
    size_t length() const { return chain.size(); }
    size_t kinks() const { return forced; }

   private:
    void step() {
      std::optional<Chosen> c;
      if (tangent) c = f.best_near(a, *tangent, limit);
      if (!c) {
        c = f.best_free(a, limit);
        if (tangent && a > 0 && !f.hard_[a]) {
          ++forced;
          c->kinked = true;
        }
      }
      chain.push_back(*c);
      a = c->prim.end_vertex;
      tangent = c->end_tangent;
    }
  };
  /// Seeds 001 and 003: each primitive grows one vertex at a time through a window of at
  /// most `stream_window` moves, as a controller would buffer them. The arc through both end
  /// points whose centre, on the chord's bisector, best fits the points between (least
  /// squares) is kept while it stays inside the band; at the first vertex where neither it
  /// nor a line does, the last fit that did is written and the next primitive starts there.
  /// Then the joints are made tangent where the band allows (make_tangent()).
  std::vector<Chosen> stream_chain(uint32_t a, uint32_t limit, size_t& forced) const;
  /// Seed 000's G1 adjustment of a chain from `a` fitted without regard to its joints, joint
  /// by joint from the start. Where the tangent breaks at a smooth joint, the primitive after
  /// it is replaced, where the band allows, by the one through the same end vertex that
  /// leaves along the tangent arriving there, turned within kTurnShare of the G1 angle to
  /// meet the primitive after it (the seed moves the arc's centre so that the tangents
  /// agree); failing that, the two primitives on either side are split again at another
  /// vertex, joined tangentially, leaving the joint before them as the first did and
  /// meeting the one after them (the joint moves, which fixes arcs that overshot it).
  /// Joints that stay broken are marked kinked and counted in `forced`.
  void make_tangent(uint32_t a, std::vector<Chosen>& chain, size_t& forced) const;
  /// Seed 000's line detection (Lowe 1987): the stretch from `a` to `limit` is split
  /// recursively at the vertex farthest from the chord, and each piece is rated by its
  /// significance, largest deviation over length (lower is more significant). Bottom up, a
  /// piece stands for itself where it is inside the band, has no change of extrusion rate
  /// inside, and is at least as significant as the most significant piece below it; else it
  /// stands for its pieces. So the split adapts to the scale of the shape: a straight
  /// stretch stays whole however noisy within the band, a curve is cut down to pieces of
  /// kLoweMinMoves moves, whose ends the arcs may then take. The breakpoints, `a` first.
  std::vector<uint32_t> lowe_breaks(uint32_t a, uint32_t limit) const;
  /// Seed 000: Lowe-style line detection, then arcs over runs of the lines. The breakpoints
  /// come from lowe_breaks(); then, from each, a primitive grows over as many following
  /// breakpoints as a line or the arc through both end points (centre on the chord's
  /// bisector, least squares) keeps inside the band. Then the joints are made tangent where
  /// the band allows (make_tangent()).
  std::vector<Chosen> lowe_chain(uint32_t a, uint32_t limit, size_t& forced) const;
  /// Seed 001's circle: through vertices a and e, centre on the chord's perpendicular
  /// bisector at the offset that minimises the squared algebraic residuals |p - c|² - r² of
  /// the vertices between (linear in the offset, so closed-form); CW or CCW from the polar
  /// angles of the start, second and end vertex about that centre, wrap-around included.
  std::optional<Chosen> through_ends(uint32_t a, uint32_t e) const;
  /// The tangent with which `c`, starting at vertex `from`, leaves it.
  Vec2 start_tangent(const Chosen& c, uint32_t from) const;
  /// The line or arc leaving vertex a along T and ending exactly at vertex e, if scan()
  /// would offer it (not yet checked exactly).
  std::optional<Candidate> through_candidate(uint32_t a, const Vec2& T, uint32_t e) const;
  /// The line or arc leaving vertex a along T and ending exactly at vertex e, checked.
  std::optional<Chosen> through(uint32_t a, const Vec2& T, uint32_t e) const;
  /// scan()'s test of one end: every vertex between `a` and c.e, and for an arc every move's
  /// middle, lies within the band of the full circle (or line) leaving `a` along T with
  /// curvature c.k: scan()'s point test without a division. Cheap, and necessary for the
  /// exact check, so most candidates that would fail it are turned away here.
  bool on_circle(uint32_t a, const Vec2& T, const Candidate& c) const;
  /// Signed angle from a to b, radians.
  static double angle_to(const Vec2& a, const Vec2& b) { return std::atan2(cross2(a, b), a.dot(b)); }
  /// The end tangent of the arc leaving `from` along T through `to`: T reflected about the
  /// chord (a line's is the chord itself, within the line allowance of that).
  Vec2 reflected_end(uint32_t from, const Vec2& T, uint32_t to) const;
  /// The end tangent of the line or arc leaving `from` along T through `to`, as
  /// through_candidate() would make it (not yet checked).
  Vec2 end_along(uint32_t from, const Vec2& T, uint32_t to) const;
  /// The start along `in` turned within kTurnShare of the G1 angle so that the arc from
  /// `from` to `to` ends as close to `out` as it can (`in` itself without `out`); nothing
  /// when even the largest turn misses it.
  std::optional<Vec2> aimed(uint32_t from, const Vec2& in, uint32_t to, const std::optional<Vec2>& out) const;
  /// The directions (rad, near [lo, hi]) leaving vertex v whose primitive reaches vertex e
  /// inside the band (start_range()) that lie within [lo, hi]; none when none does.
  std::optional<std::pair<double, double>> starts_within(uint32_t v, uint32_t e, double lo, double hi) const;
  /// Two primitives from `from` to `to`, the first leaving along T, joined tangentially, the
  /// second turned within kTurnShare of the G1 angle to meet `out` (where given) within it.
  /// Splits whose second primitive can meet `out` are tried longest first; at most `tries`
  /// of them, spread evenly, are checked exactly. (Inlined: tighten() calls it in its
  /// innermost loop, where a call costs 0.3 % of all instructions on the corpus.)
  [[gnu::always_inline]] std::optional<std::pair<Chosen, Chosen>> split_through(uint32_t from, const Vec2& T,
                                                                                uint32_t to,
                                                                                const std::optional<Vec2>& out,
                                                                                size_t tries) const;
  /// tighten() on each tangent-continuous part of a chain that starts at `a`: a forced kink
  /// frees the tangent on both sides of it, as a corner does.
  void tighten_between_kinks(uint32_t a, std::vector<Chosen>& chain) const;
  /// Local merging after the search: wherever two consecutive primitives can become one, or
  /// three can become two, that leave the joint before them and meet the joint after them
  /// within the turn allowed at a joint, they are replaced, and the joint before is tried again.
  /// The tangent at the start is `incoming` (free when none) and at the end free, or a fixed
  /// move's direction where the chain ends at one. Turning an arc's
  /// start tangent by φ turns its end tangent by -φ (the end tangent is the start tangent
  /// reflected about the chord), so the turn that meets the next joint is solved for, and
  /// only primitives that can meet it are checked exactly. Where they end in an arc and a
  /// line follows, they are also tried ending up to kLineShiftMoves earlier or later, the
  /// line starting there instead. The start of a single primitive is also taken from the
  /// range of those that reach its end (starts_within()), within the joint's turn.
  void tighten(uint32_t a, std::vector<Chosen>& chain, const std::optional<Vec2>& incoming) const;
  /// One node of the beam and layered searches: the chain reached vertex `v` and leaves it along `T`.
  struct Node {
    Chosen last;  ///< the primitive that ended here (none at a root)
    int parent;   ///< index of the node it left from; -1 at a root
    uint32_t v;
    Vec2 T;
  };
  /// A beam candidate: scored first, checked exactly only when the beam keeps it.
  struct Made {
    int from;  ///< the node it leaves from; -1 once checked
    Vec2 T;
    Candidate cand;
    Chosen c;                 ///< unchecked(): end vertex and tangent only
    const GuideScan* guide;   ///< the greedy step's scan it came from, whose reaches it takes; or null
    Score sc{};               ///< once the layer is ranked
  };
  /// The one-primitive finish from vertex `v` along exactly `T` to `limit`, as the scan
  /// offers it (not yet checked exactly), or nothing. A test of the one end that fails at the
  /// first vertex off the circle, where the scan would go on to the last end allowed.
  std::optional<Candidate> finish_from(uint32_t v, const Vec2& T, uint32_t limit) const;
  /// A candidate of bound_chain(): `c` along `T`, from a node left along `from`.
  struct BoundTry {
    Candidate c;
    Vec2 T, from;
  };
  /// A chain a beam layer keeps: its end vertex and tangent, and the tangent's bin once needed.
  struct SeenEnd {
    uint32_t v;
    Vec2 T;
    std::optional<long> bin;
  };
  /// The run's data per vertex and per move, and the constructor's own: in the thread's
  /// Scratch, from run to run (one fitter at a time on a thread), so that once grown they
  /// allocate nothing.
  struct RunBuffers {
    std::vector<uint32_t> at;
    std::vector<Vec3> p;
    std::vector<Vec2> q, middle;
    std::vector<uint8_t> hard, plain_hard, soft;
    std::vector<uint32_t> next_soft;
    std::vector<std::optional<Vec2>> heading;
    std::vector<FixedMove> fixed;
    std::vector<double> extra_values, e_values, e_rate;
    std::vector<uint8_t> spike, nowhere, alone, none;  // the constructor's
  };
  /// roots()' start tangents at a free start, for the stretch, start and limit read.
  struct RootsRead {
    uint64_t stretch = 0;  // 0: none
    uint32_t a = 0, limit = 0;
    std::vector<Vec2> tangents;
  };
  /// Buffers the searches reuse from call to call, and from run to run on one thread, so
  /// that once warm they allocate nothing. Each belongs to one function; none of those
  /// calls itself, and none calls another that uses the same buffer.
  struct Scratch {
    RunBuffers run;                                   // the fitter's own per-vertex data (see RunBuffers)
    std::vector<Candidate> scanned;                   // pick()
    std::vector<Candidate> checked_cand;              // checked_from()
    std::vector<Vec3> flat_pts;                       // make_arc(): a helix's vertices in its start plane
    std::vector<Vec2> chord_ends;                     // make_arc(): the firmware's chord ends
    std::vector<Candidate> best_cand;                 // best_from()
    std::vector<Ranked> ranked;                       // best_from()
    std::vector<Chosen> best_made;                    // best_from()
    std::vector<Vec2> free_starts;                    // best_free()
    std::vector<StartRange> reached;                  // start_tangents()
    std::vector<Vec2> inputs;                         // fanned_input_tangents()
    std::vector<Candidate> tighten_cand;              // tighten()
    std::vector<size_t> split;                        // tighten()
    std::vector<Vec2> starts, firsts;                 // tighten()
    std::vector<Vec2> roots;                          // beam_chain()
    std::vector<Node> nodes;                          // beam_chain()
    std::vector<int> layer, next;                     // beam_chain()
    std::vector<Made> made;                           // beam_chain()
    std::vector<Candidate> beam_out;                  // beam_chain()
    std::vector<SeenEnd> seen;                        // beam_chain()
    std::vector<std::pair<uint64_t, uint64_t>> keys;  // beam_chain()
    std::vector<uint64_t> packed_keys;                // beam_chain()
    std::vector<std::pair<uint32_t, Vec2>> expanded;  // beam_chain()
    std::vector<uint64_t> order;                      // beam_chain()
    std::vector<int8_t> straight;                     // beam_chain()
    std::vector<std::pair<int, uint32_t>> root_seeds;  // beam_chain(): (root node, its Seed)
    std::vector<size_t> chain_length;                  // kink_seeds(), per node
    std::vector<int> root_of, shortest;                // kink_seeds(), per node and per vertex
    uint32_t bound_a = 0;                                 // bound_start()
    std::vector<uint32_t> bound_h;                        // bound_start(), per vertex from bound_a
    std::unordered_map<uint64_t, uint32_t> bound_failed;  // bound_chain()
    std::vector<std::vector<BoundTry>> bound_tries;       // bound_chain(), per depth
    std::vector<Vec2> bound_roots;                        // bound_chain()
    RootsRead roots_read;                                 // roots()
    // The greedy steps' latest scans (GuideScan), in turn, and whether best_near() is taking one.
    std::array<GuideScan, 9> guide_scans;
    size_t guide_next = 0;
    bool guide_record = false;
    uint64_t stretches = 0;  // stretches begun on this thread (GuideScan::stretch)
  };
  static Scratch& thread_scratch();
  /// A vertex where the chain may start again after a forced kink, and the chain that
  /// reaches it (the kinks before it included) past what beam_stretch() has settled: the
  /// primitives every seed of a restart starts with.
  struct Seed {
    uint32_t v;
    std::vector<Chosen> prefix;
  };
  /// The G1 chain from `a` to `limit` with the fewest primitives a beam search finds. Layer k
  /// holds the chains of k primitives, at most `beam_width` of them, those reaching furthest
  /// (in the next step, or with this one) with distinct end tangents; each is extended along
  /// its end tangent and along it turned by the whole joint allowance (kJointShare of the G1
  /// angle) each way, and by half of it where the input runs straight ahead (for lines): the
  /// chains' own spread of tangents covers the arcs' turns between. The first chain reaching
  /// `limit` wins. Where the tangent at `a` is free, the roots are start_tangents(). The
  /// greedy chain (read off `greedy` up to its first kink, or chosen again when null) is
  /// always kept. When no chain goes on tangentially, the one reaching furthest is
  /// returned (empty when none leaves `a`), and the caller takes a kink there.
  /// With `seeds` (by prefix length, the last the one the greedy chain starts from), the
  /// chain starts again after a kink at any of their vertices with a free tangent, each
  /// joining the beam in the layer of its prefix's length, and is returned with its seed's
  /// prefix, the first primitive after that marked kinked; `a` is then the lowest of their
  /// vertices.
  std::vector<Chosen> beam_chain(uint32_t a, uint32_t limit, GreedyWalk* greedy,
                                 std::span<const Seed> seeds = {}) const;
  /// The fewest primitives from `a` to `limit` of a chain that may break its tangent at every
  /// joint, each no further than some circle from its start reaches with its vertices in the
  /// band (start_reaches()), where reaching further never costs; and the same from each
  /// vertex between, kept in s_.bound_h for bound_chain(). kBoundMaxPrimitives + 1 where it
  /// is more than that.
  uint32_t bound_start(uint32_t a, uint32_t limit) const;
  /// `try_along(T')` for T' = T, T turned by each of the joint's turns, and where the input
  /// runs straight ahead from vertex v by half the allowance either way: the tangents the
  /// beam leaves a joint along (beam_chain()). Stops at the first that returns true.
  template <class Try>
  bool any_joint_turn(uint32_t v, const Vec2& T, uint32_t limit, Try&& try_along) const;
  /// The bin of direction `t` among bins `share` of the G1 angle wide (of twice
  /// kFinestJointTurnDeg at most): where the searches take two tangents at a vertex as one.
  long tangent_bin(const Vec2& t, double share) const {
    return std::lround(std::atan2(t.y(), t.x()) / (share * deg_to_rad(std::min(o_.g1_angle_deg, 2 * kFinestJointTurnDeg))));
  }
  /// Whether the scan lets one primitive from vertex v reach `limit` along any of the
  /// any_joint_turn() tangents of T (not yet checked exactly).
  bool finishes(uint32_t v, const Vec2& T, uint32_t limit) const;
  /// A G1 chain from `a` to `limit` of as few primitives as bound_start() counts, 2 to
  /// kBoundMaxPrimitives, found depth first with the beam's turns at each joint, ends
  /// furthest first, each end taken only where the count from it leaves room: where the
  /// count is met, the chain has the fewest primitives there are, and the search costs a
  /// few scans a primitive, where the beam scores some 25 candidates a primitive by a scan
  /// each. Empty where the stretch's ends have fixed directions or it closes a loop (the
  /// count says too little there), or no such chain is found within
  /// kBoundChecksPerPrimitive exact checks a primitive.
  std::vector<Chosen> bound_chain(uint32_t a, uint32_t limit) const;
  /// Whether the input runs straight from vertex v for kStraightAheadMm (or to `limit`): every
  /// vertex up to there within the band of the chord there.
  bool straight_ahead(uint32_t v, uint32_t limit) const;
  /// Candidate `cd` from node `nd` along `T` (its tangent, or that turned at the joint),
  /// checked exactly, and held to the joint allowance: a line's chord may lie off T by the
  /// line allowance, on top of the turn. (The beam's and the layered search's.)
  std::optional<Chosen> made_from(const Node& nd, const Vec2& T, const Candidate& cd) const;
  /// The beam search's chain from `a` to `limit`. Where no chain goes on tangentially, the
  /// tangent breaks (counted in `forced`) and the search starts again, from any vertex near
  /// where the furthest chain stopped that a chain of the stalled beam reached with no more
  /// primitives (kKinkSeedMoves): the break is placed where the chain after it does best,
  /// not where the chain before it gave out.
  std::vector<Chosen> beam_stretch(uint32_t a, uint32_t limit, GreedyWalk& greedy, size_t& forced) const;
  /// The seeds of beam_stretch()'s restart after the beam in s_.nodes stalled with `part`
  /// (whose seeds were `seeds`, none for the first beam): per vertex within kKinkSeedMoves
  /// before the end of `part`, the node with the shortest chain there, no longer than `part`.
  void kink_seeds(const std::vector<Chosen>& part, std::span<const Seed> seeds, std::vector<Seed>& out) const;
  /// The G1 chain from `a` to `limit` with the fewest primitives, found breadth first over
  /// states (vertex, tangent leaving it): layer k holds the states k primitives reach, and
  /// each is expanded, along its tangent and along it turned by the joint's whole allowance
  /// either way, by every end its curvature scan allows, each end checked exactly once.
  /// To stay near-linear, a layer keeps one state per tangent bin (kTangentBinShare of the
  /// G1 angle) in each vertex group (the last layer's advance over kLayerGroups), only ends
  /// at or beyond the layer's furthest vertex are taken (the layer before reached the
  /// others with fewer primitives), and the search gives up past kMaxStatesPerVertex states
  /// per vertex. Unlike the beam, no state is dropped for scoring lower, so a chain that
  /// must pass a narrow place with the one right tangent is not lost. Empty when no chain
  /// reaches `limit` tangentially. (The global method's, and the default's where its chain
  /// wiggles.)
  std::vector<Chosen> layered_chain(uint32_t a, uint32_t limit) const;
  /// The G1 chain from `a` to `limit` with the fewest primitives a breadth-first search over
  /// (vertex, range of start tangents) finds (--method global): a state's whole range is
  /// scanned (kRangeSamplesPerDeg), and the starts that reach each end make a range of end
  /// tangents, widened by the joint's turn into the next state's range at that vertex; the
  /// part of it no earlier layer reached is a new state. Only ends at or past the layer's
  /// furthest vertex are taken, and it gives up past kMaxStatesPerVertex states per vertex.
  /// The chain is then read back from the end, each primitive checked exactly and joined
  /// within the joint's turn: where the searches that follow one tangent at a time miss the
  /// one start a chain of few primitives needs, this finds it. Empty when none is found.
  /// With `front_share` (the default's use), a layer's ends short of that share of its
  /// advance past the furthest vertex before make no states. Only chains of at most
  /// `max_primitives` are looked for: the search stops after that many layers.
  std::vector<Chosen> range_chain(uint32_t a, uint32_t limit, size_t max_primitives, double front_share = 0) const;
  static std::vector<Chosen> chain_to(const std::vector<Node>& nodes, int id);
  static Vec2 rotated(const Vec2& T, double rad) { return Turn(rad)(T); }
  /// The input's own directions at `a`, where the tangent is free: those of circles through
  /// the next vertices, of the first chord, and of the input around `a` inside the stretch.
  void input_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const;
  /// Whether the chain arrives at `a` with a tangent it must follow: the start of a stretch
  /// after a fixed move where the path is smooth.
  bool arrives_along(uint32_t a) const { return a == stretch_start_ && in_tangent_.has_value(); }
  /// Where the searches start at `a`: the tangents a smooth joint allows after the incoming
  /// one (turned by no more than a line's chord may add to stay within kJointShare of the
  /// G1 angle), else start_tangents().
  void roots(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const;
  /// The searches' start tangents at `a` where the tangent is free, appended to `out`: for
  /// each end e the first primitive can reach, the range of start tangents whose circle
  /// through e keeps the vertices and move middles between inside the band (start_range())
  /// is known exactly, and its edges (kStartRangeInset inside) are the starts that end at e
  /// turned furthest either way. Those of the kNearStartEnds nearest ends give the turns a
  /// chain can take right after a corner, those of the kFarStartEnds furthest, with the
  /// middle of the furthest, the longest first primitives; the chord to the furthest end a
  /// line reaches, the line; into_next() the start from which the second move follows as a
  /// line. 15 starts at most, where 46 were read off the input (the tangents of circles
  /// through the next vertices, of the first chord and of the input around `a`, each turned
  /// by 0.5° to 4° either way): those missed the narrow ranges that reach furthest and the
  /// turns the band allows over a short first move (the corpus with default options:
  /// 320 706 blocks and 4 024 forced kinks from the fan, 319 352 and 3 396 from the ranges).
  void start_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const;
  /// The start at `a` in range `r` at `share` of the way from its lowest angle to its
  /// highest.
  Vec2 range_start(uint32_t a, const StartRange& r, double share) const;
  /// The furthest vertex e after `a` (up to `limit`) whose chord from `a` passes within the
  /// band of every vertex between (furthest_reached()); `a` itself when the first move has
  /// no length in the plane.
  uint32_t furthest_line_end(uint32_t a, uint32_t limit) const;
  /// The furthest vertex up to `limit` that `reached(e)` holds for, from `from`, which it
  /// holds for: in doubling steps, then halving back between the furthest found and the
  /// nearest beyond it found not to (exact where `reached` holds up to some vertex and not
  /// after it, and a vertex it holds for otherwise).
  template <class Reached>
  static uint32_t furthest_reached(uint32_t from, uint32_t limit, Reached&& reached) {
    uint32_t far = from, beyond = limit + 1;
    for (uint32_t step = 1; far + step <= limit; step *= 2) {
      if (!reached(far + step)) {
        beyond = far + step;
        break;
      }
      far += step;
    }
    while (beyond - far > 1) {
      const uint32_t mid = far + (beyond - far) / 2;
      (reached(mid) ? far : beyond) = mid;
    }
    return far;
  }
  /// The tangent-chord angles (radians, positive turning left of the chord a→e) of the
  /// circles from vertex a through vertex e that pass within the band of every vertex and
  /// move middle between, as [lo, hi] (empty when lo > hi), within the largest sweep. The
  /// scan's test of a point u (from a, off the tangent by u·N) against the circle of
  /// curvature k, |k·(|u|² − ε²) − 2·u·N| <= 2ε, becomes for the circle through e (chord
  /// length L, tangent turned by α from the chord, k = −2·sin α / L) |P·sin α + Q·cos α| <= ε
  /// with P = (|u|² − ε²) / L − u along the chord and Q = u across it: an interval of α
  /// around the zero of R·sin(α + β) (R² = P² + Q²) asin(ε / R) wide each way. The bounds
  /// are kept as directions and compared as pseudo-angles; only the result's are angles.
  /// The band is the in-plane share once a vertex climbs, as in the scan.
  std::pair<double, double> start_range(uint32_t a, uint32_t e) const;
  /// Whether some start at vertex a whose circle through vertex e keeps the vertices, and
  /// with `middles` the move middles, between inside the band lies within the largest sweep.
  /// Each point's starts in the band lie around two zeros half a turn apart, and
  /// start_range() keeps those around one; where a point's starts span much of a half turn
  /// (it lies near the chord's line, close to an end), those around the other reach into the
  /// sweep too, and the starts that reach e may lie only there: on the FreeCAD program at
  /// 0.05 mm, an arc of 143° whose range came out empty. This keeps both, so that false
  /// shows that no start reaches e.
  bool start_reaches(uint32_t a, uint32_t e, bool middles) const;
  /// start_range()'s and start_reaches()'s walk over the points between a and e: for each
  /// point not within the band of `a`, `point(low, high)` gets the edges of the starts
  /// around its first zero, as directions of the tangent-chord angle (of any length);
  /// false when `point` returns false or the chord has no length.
  template <class Point>
  bool start_bounds(uint32_t a, uint32_t e, bool middles, Point&& point) const;
  /// The input's own directions at `a` (input_tangents()), each also turned by 0.5°, 1°, 2°
  /// and 4° either way; appended to `out`. The layered search's starts where the tangent is
  /// free.
  void fanned_input_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const;
  /// The start at `a` whose arc over the first move ends heading along the second: where the
  /// input turns at a + 1 (a slicer's infill between two corners, a short move into a long
  /// one), the one start from which the second move follows as a line, tangent.
  std::optional<Vec2> into_next(uint32_t a, uint32_t limit) const;
  /// Start of a smooth stretch (or after a forced kink): try a few start tangents read off
  /// the input, and the one into the second move, and keep the one whose primitive reaches
  /// furthest.
  Chosen best_free(uint32_t a, uint32_t limit) const;
  /// A stretch of the one move from vertex a: the move itself, or, where a fixed move's
  /// direction is to be met at either end (in_tangent_, out_tangent_), the arc over it that
  /// meets both within the joint's turn, when the band and the options allow it. (The input
  /// turns there by less than a corner; kept as a line, the joint would break.)
  Chosen one_move(uint32_t a) const;
  /// The input's own move from vertex a to a + 1 as a line: always inside the band.
  Chosen input_move(uint32_t a) const;
  /// Tangent at p0 of the circle through p0, p1, p2, pointing towards p1.
  static std::optional<Vec2> circle_tangent(const Vec2& p0, const Vec2& p1, const Vec2& p2);
  const FitOptions& o_;
  Scratch& s_ = thread_scratch();
  RunBuffers& b_ = s_.run;
  std::vector<uint32_t>& at_ = b_.at;  // the run's vertex of each vertex the fitter works on (vertices_kept())
  uint32_t n_ = 0;                     // moves the fitter works on: at_.size() - 1
  std::vector<Vec3>& p_ = b_.p;        // vertices in plane coordinates (first, second, normal)
  // The same in the plane, stored as such: the scans read them as whole vectors, where
  // building each from p_ would stall on the store that assembles it.
  std::vector<Vec2>& q_ = b_.q;
  std::vector<Vec2>& middle_ = b_.middle;             // the middle of each move in the plane
  bool level_ = true;                                 // every vertex at the same height (within kLengthEpsMm)
  std::vector<uint8_t>& hard_ = b_.hard;              // corner: tangent may change, a primitive ends here
  std::vector<uint8_t>& plain_hard_ = b_.plain_hard;  // with spikes found: the corners with none skipped
  std::vector<uint8_t>& soft_ = b_.soft;              // extrusion rate changes: a primitive ends here, tangent kept
  std::vector<uint32_t>& next_soft_ = b_.next_soft;   // the first soft vertex after each vertex (n_ + 1: none)
  // The input's direction at each vertex inside the stretch: sided_tangent() for the
  // searches; the greedy chain, which never goes back on a choice, keeps input_tangent()
  // (with the sided one it breaks the tangent on Bézier 1 at 0.001 mm and y = x³ at 0.01 mm,
  // where the searches find tangent chains, though it needs 1 % fewer blocks on the corpus).
  std::vector<std::optional<Vec2>>& heading_ = b_.heading;
  std::vector<FixedMove>& fixed_ = b_.fixed;      // per move
  uint32_t stretch_start_ = 0;                    // first vertex of the current stretch (after a corner or fixed move)
  uint32_t stretch_end_ = 0;                      // its last vertex (a corner, a fixed move's start, or the end)
  std::optional<Vec2> in_tangent_, out_tangent_;  // directions of the fixed moves around it, where smooth
  uint64_t stretch_id_ = 0;                       // this stretch's number on the thread (GuideScan::stretch)
  ScanLimits lim_{};        // what the scans hold each end to in it: scan_limits(), worked out once a stretch
  double eps_ = 0;          // band the fitter works to, mm
  bool arcs_ = true;        // arcs allowed: by the options, and in this run by its extra axes
  std::vector<int> extra_;  // the extra axes (kA .. kW) that move in the run
  std::vector<double>& extra_values_ = b_.extra_values;  // their values at each vertex, extra_.size() per vertex
  // Where E moves in the run: E at each vertex, and each move's E per mm of its length
  // (|ΔE| / length; empty where E stays).
  std::vector<double>& e_values_ = b_.e_values;
  std::vector<double>& e_rate_ = b_.e_rate;
};

}  // namespace arcpress::fit_detail
