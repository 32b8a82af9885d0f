#include "arcpress/fit/fitter.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <span>
#include <tuple>
#include <unordered_set>

#include "arcpress/core/deviation.hpp"

namespace arcpress {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Share of the tolerance kept back for rounding the printed arc centre (the emitter prints
/// centres with enough digits that rounding moves them by less than this).
constexpr double kRoundingReserve = 0.03;
/// In-plane and normal-axis shares of the band when a primitive moves along the normal axis:
/// 0.8² + 0.6² = 1, so the 3D distance stays inside the band.
constexpr double kPlaneShare = 0.8;
constexpr double kHeightShare = 0.6;
/// Share of the G1 angle by which the fitter may turn the tangent at a smooth joint; printing
/// the arc centres may turn each side by a little more (the emitter re-checks that).
constexpr double kJointShare = 0.9;
/// How much the extrusion or an extra axis per mm may differ between two neighbouring moves
/// inside one primitive, as a share of the larger rate.
constexpr double kRateShare = 0.05;
/// Share of the G1 angle by which the greedy step first turns the tangent at a joint, each
/// way; twice this (kJointShare) is its largest turn, and the searches' turn.
constexpr double kTurnShare = 0.45;
/// Seed 000: pieces of the line detection this short (in moves) are not split further
/// unless they leave the band.
constexpr uint32_t kLoweMinMoves = 2;
/// The default search's chain is searched again layer by layer (as the global method's) when
/// this many arcs in a row each turn the other way from the one before.
constexpr int kWiggleArcs = 4;
/// How far ahead (mm) the input must run straight for the beam to offer lines along tangents
/// turned by half the joint allowance (beam_chain()).
constexpr double kStraightAheadMm = 1.0;
/// Primitives a forced kink must save, at the least, where a chain wiggles (see untangle()).
constexpr size_t kKinkWorth = 4;
/// How many wiggles after the first untangle() mends in the chain it tries after a kink.
constexpr int kUntangleDepth = 4;
/// Candidates per primitive whose next step is looked at before choosing.
constexpr int kLookahead = 6;
/// Places in each layer of the beam for the chains whose last primitive ends furthest.
constexpr size_t kFurthestEnds = 2;
/// Bits of a vertex, and of a candidate's place, in the beam's one-integer ranking keys.
constexpr int kKeyBits = 21;
/// The beam's roots at a free start (start_tangents()): the edges of the ranges of start
/// tangents that reach each of the kNearStartEnds nearest ends and of the kFarStartEnds
/// furthest, taken kStartRangeInset of the range inside.
constexpr size_t kNearStartEnds = 4;
constexpr size_t kFarStartEnds = 2;
constexpr double kStartRangeInset = 0.05;
/// Splits of a stretch into two primitives checked exactly per start tangent when merging.
constexpr size_t kSplitsTried = 12;
/// A primitive whose end tangent is within this of the input's direction is "on course".
constexpr double kOnCourseRad = 1.5 * kPi / 180;
/// Layered search: a layer keeps one state per tangent bin (this share of the G1 angle wide)
/// in each of about kLayerGroups groups of vertices over the stretch the last layer advanced.
constexpr double kTangentBinShare = 0.5;
constexpr uint32_t kLayerGroups = 4;
/// Layered search: it gives up (and the beam's chain stands) past this many states per vertex.
constexpr size_t kMaxStatesPerVertex = 64;

/// The start tangents at a free start whose circles reach vertex e inside the band: their
/// tangent-chord angles (radians, positive to the left of the chord) from lo to hi.
struct StartRange {
  uint32_t e;
  double lo, hi;
};

/// One way to end the primitive that starts at `a`: at vertex e with curvature k.
struct Candidate {
  uint32_t e;
  double k;       // signed curvature, 1/mm (> 0 turns left)
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

/// A rotation by a fixed angle, its cosine and sine worked out once.
struct Turn {
  double c = 1, s = 0;
  explicit Turn(double rad = 0) : c(std::cos(rad)), s(std::sin(rad)) {}
  /// The turn with this cosine and sine.
  static Turn by(double cos_rad, double sin_rad) {
    Turn t;
    t.c = cos_rad;
    t.s = sin_rad;
    return t;
  }
  Vec2 operator()(const Vec2& T) const { return {T.x() * c - T.y() * s, T.x() * s + T.y() * c}; }
};

/// Unit vectors at most a fixed angle (< π/2) apart, its sine worked out once.
struct Cone {
  double sin_rad = 0;
  explicit Cone(double rad = 0) : sin_rad(std::sin(rad)) {}
  bool holds(const Vec2& a, const Vec2& b) const { return a.dot(b) > 0 && std::abs(cross2(a, b)) <= sin_rad; }
};

/// The turns, cones and limits on angles the fitter works with, all from the options' angles
/// (and method): worked out once per thread for the options last seen, not for each run
/// (some 30 sines and cosines).
class FitAngles {
 public:
  FitAngles() = default;
  explicit FitAngles(const FitOptions& o)
      : g1_angle_deg_(o.g1_angle_deg), max_sweep_deg_(o.max_sweep_deg), min_sweep_deg_(o.min_sweep_deg),
        method_(o.method) {
    line_kink_ = deg_to_rad(o.g1_angle_deg) / 4;
    const double g1 = deg_to_rad(o.g1_angle_deg);
    half_left_ = Turn(kTurnShare * g1);
    half_right_ = Turn(-kTurnShare * g1);
    full_left_ = Turn(2 * kTurnShare * g1);
    full_right_ = Turn(-2 * kTurnShare * g1);
    // The greedy method's step turns by the whole joint allowance and by half of it; in the
    // searches, whose chains turn by the whole allowance at every joint, the greedy chain is
    // only the guide and the fallback, and the half turns there cost 3 % of the instructions
    // for nothing (the corpus: 319 353 blocks and 3 396 forced kinks with them, 319 357 and
    // 3 395 without; Xu's curves 567 segments with them, 566 without).
    if (o.method == FitOptions::Method::Greedy) {
      near_turns_ = {half_left_, half_right_, full_left_, full_right_};
      near_turn_count_ = 4;
    } else {
      near_turns_ = {full_left_, full_right_, Turn(), Turn()};
      near_turn_count_ = 2;
    }
    g1_cone_ = Cone(g1);
    same_tangent_cone_ = Cone(g1 / 32);
    // (The margin keeps the largest turn the searches make from failing by rounding.)
    joint_cone_ = Cone(kJointShare * g1 + 1e-9);
    joint_miss_ = 1 - std::cos(kJointShare * g1);
    closer_miss_ = 1 - std::cos(kJointShare * g1 / 4);
    on_course_cone_ = Cone(kOnCourseRad);
    turn_cone_ = Cone(kTurnShare * g1);
    turn_line_cone_ = Cone(kTurnShare * g1 + line_kink_);
    two_turns_line_cone_ = Cone(2 * kTurnShare * g1 + line_kink_);
    root_turns_ = {Turn(0.3 * g1), Turn(-0.3 * g1), Turn(0.6 * g1), Turn(-0.6 * g1)};
    start_sweep_ = Turn(std::min(deg_to_rad(o.max_sweep_deg) / 2, kPi / 2));
    for (size_t i = 0; i < 4; ++i) {
      const double deg = 0.5 * double(1u << i);  // 0.5, 1, 2, 4
      fan_turns_[2 * i] = Turn(deg_to_rad(deg));
      fan_turns_[2 * i + 1] = Turn(-deg_to_rad(deg));
    }
    // Limits on the tangent-chord angle alpha (the sweep is 2 alpha) as pseudo-angles of
    // |alpha| in [0, π], so scan() tests each vertex without trigonometry or division.
    const double half_max_sweep = deg_to_rad(o.max_sweep_deg) / 2;
    max_alpha_ = half_max_sweep >= kPi ? 3.0 : pseudo_angle_of(half_max_sweep);
    min_alpha_ = pseudo_angle_of(std::min(deg_to_rad(o.min_sweep_deg) / 2, kPi));
    line_alpha_ = pseudo_angle_of(line_kink_);
  }

  /// Those of `o`: this thread's last, or worked out again when `o`'s angles differ.
  static const FitAngles& of(const FitOptions& o) {
    thread_local FitAngles last;
    thread_local bool made = false;
    if (!made || last.g1_angle_deg_ != o.g1_angle_deg || last.max_sweep_deg_ != o.max_sweep_deg ||
        last.min_sweep_deg_ != o.min_sweep_deg || last.method_ != o.method) {
      last = FitAngles(o);
      made = true;
    }
    return last;
  }

 protected:
  double g1_angle_deg_ = 0, max_sweep_deg_ = 0, min_sweep_deg_ = 0;  // what they were worked out from
  FitOptions::Method method_ = FitOptions::Method::Arcs;
  Turn half_left_, half_right_;   // kTurnShare of the G1 angle each way: the greedy step's first turns, the beam's for lines
  Turn full_left_, full_right_;   // twice that, the whole joint allowance: its largest, and the searches' turn
  std::array<Turn, 4> near_turns_;  // best_near(): the first near_turn_count_ of them
  size_t near_turn_count_ = 0;
  std::array<Turn, 4> root_turns_;   // roots(): 0.3 and 0.6 of it each way
  Turn start_sweep_;                 // start_range(): half the largest sweep, at most a quarter turn
  std::array<Turn, 8> fan_turns_;    // fanned_input_tangents(): 0.5, 1, 2 and 4 degrees each way
  Cone g1_cone_;                  // the G1 angle: a joint within it is smooth
  Cone same_tangent_cone_;         // 1/32 of it: two tangents a search need not both follow
  Cone joint_cone_;               // kJointShare of it: the turn the fitter may make at a joint
  // pick(): 1 - cos of that turn, and of a quarter of it (closer by more than the printed
  // digits can tilt the input's direction: past a straight side's end, along a side whose
  // every vertex heads exactly along it, the walk back would go on into the side).
  double joint_miss_ = 0, closer_miss_ = 0;
  Cone on_course_cone_;           // kOnCourseRad: a primitive ending along the input
  Cone turn_cone_, turn_line_cone_, two_turns_line_cone_;  // tighten(): one turn, plus a line's, two plus a line's
  double line_kink_ = 0;          // largest tangent-chord angle written as a line, rad
  double max_alpha_ = 0, min_alpha_ = 0, line_alpha_ = 0;  // pseudo-angles, see FitAngles()
};

class RunFitter : private FitAngles {
 public:
  /// `run` spans the moves to fit; `fixed` (per move, empty: none) says which stay as they
  /// are, and `pinned` (per vertex, empty: none) where a primitive must end (where one run
  /// meets the next or a fixed move), the tangent going on there.
  RunFitter(const Interpretation& in, const Run& run, const FitOptions& o, const std::vector<FixedMove>& fixed = {},
            std::vector<uint8_t> pinned = {})
      : FitAngles(FitAngles::of(o)), o_(o) {
    vertices_kept(in, run, fixed, pinned, at_);
    n_ = uint32_t(at_.size() - 1);
    if (!pinned.empty())
      for (uint32_t v = 0; v <= n_; ++v) pinned[v] = pinned[at_[v]];
    fixed_.clear();
    for (uint32_t v = 0; v < n_; ++v) fixed_.push_back(fixed.empty() ? FixedMove{} : fixed[at_[v]]);
    auto vertex = [&](uint32_t v) -> const AxisValues& { return run.vertex(in, at_[v]); };
    auto ax = axes_of(run.plane);
    p_.resize(n_ + 1);
    q_.resize(n_ + 1);
    middle_.resize(n_);
    // (With the extra axes (A/B/C, U/V/W) that move in the run, bit by axis.)
    unsigned moving = 0;
    for (uint32_t v = 0; v <= n_; ++v) {
      const auto& a = vertex(v);
      p_[v] = Vec3(a[ax.first], a[ax.second], a[ax.normal]);
      q_[v] = Vec2(a[ax.first], a[ax.second]);
      if (v > 0) {
        const auto& before = vertex(v - 1);
        for (int x = kA; x < kE; ++x) moving |= unsigned(a[x] != before[x]) << x;
      }
    }
    for (uint32_t v = 0; v < n_; ++v) middle_[v] = 0.5 * (q_[v] + q_[v + 1]);
    // Level: no vertex lies above or below another by more than the scans' test of a climb.
    const auto [low, high] =
        std::minmax_element(p_.begin(), p_.end(), [](const Vec3& x, const Vec3& y) { return x.z() < y.z(); });
    level_ = high->z() - low->z() <= kLengthEpsMm;
    // The extra axes that move in the run, their values at each vertex, and the path length
    // to each vertex they are carried along.
    for (int x = kA; x < kE; ++x)
      if (moving >> x & 1) extra_.push_back(x);
    extra_values_.clear();
    length_.clear();
    if (!extra_.empty()) {
      length_.assign(n_ + 1, 0.0);
      for (uint32_t v = 1; v <= n_; ++v) length_[v] = length_[v - 1] + (p_[v] - p_[v - 1]).norm();
      for (uint32_t v = 0; v <= n_; ++v)
        for (int x : extra_) extra_values_.push_back(vertex(v)[x]);
    }
    arcs_ = o.arcs && (o.extra_axes || extra_.empty());
    eps_ = o.tolerance_mm * (1.0 - kRoundingReserve);
    hard_.assign(n_ + 1, 0);
    heading_.assign(n_ + 1, std::nullopt);
    soft_.assign(n_ + 1, 0);
    auto corner = [&](uint32_t a, uint32_t b, uint32_t c) {
      return is_corner(p_[a], p_[b], p_[c], o.tolerance_mm, o.corner_angle_deg);
    };
    // Seed 004's spikes (option): a lone vertex where the path jags out and back, within half
    // the band of its neighbours' chord, with the path smooth once it is skipped. Noise, not
    // a corner; the fitted path still passes within the band of it.
    std::vector<uint8_t>& spike = b_.spike;
    spike.assign(n_ + 1, 0);
    for (uint32_t v = 2; o.spikes && v + 2 <= n_; ++v)
      spike[v] = !spike[v - 1] && corner(v - 1, v, v + 1) &&
                 point_segment_distance(p_[v], p_[v - 1], p_[v + 1]) <= 0.5 * o.tolerance_mm &&
                 !corner(v - 2, v - 1, v + 1) && !corner(v - 1, v + 1, v + 2);
    // Moves that go nowhere and stay (fixed ones, or those between two vertices that must
    // stay): the corner rule steps past them, as the verifier does.
    std::vector<uint8_t>& nowhere = b_.nowhere;
    nowhere.assign(n_, 0);
    for (uint32_t v = 0; v < n_; ++v) nowhere[v] = in.moves_going(run.first_move + at_[v], run.first_move + at_[v + 1]) == 0;
    // The same corner rule, with the same band, as the verifier uses to judge joints (with
    // spikes skipped when asked): first each vertex alone, then with its neighbours' corners.
    // A vertex's neighbours are the nearest vertices elsewhere, past spikes when skipped.
    auto corners = [&](const std::vector<uint8_t>& skipped, std::vector<uint8_t>& hard) {
      auto before = [&](uint32_t v, bool past_spikes) {
        uint32_t u = v - 1;
        while (u > 0 && (nowhere[u] || (past_spikes && skipped[u]))) --u;
        return u;
      };
      auto after = [&](uint32_t v, bool past_spikes) {
        uint32_t u = v + 1;
        while (u < n_ && (nowhere[u - 1] || (past_spikes && skipped[u]))) ++u;
        return u;
      };
      std::vector<uint8_t>& alone = b_.alone;
      alone.assign(n_ + 1, 0);
      hard.assign(n_ + 1, 0);
      for (uint32_t v = 1; v < n_; ++v) alone[v] = !skipped[v] && corner(before(v, true), v, after(v, true));
      for (uint32_t v = 1; v < n_; ++v) {
        const uint32_t b = before(v, true), a = after(v, true);
        hard[v] = alone[v] || (!skipped[v] && is_corner_beside_corner(b > 0 ? &p_[before(b, false)] : nullptr, p_[b], p_[v],
                                                                      p_[a], a < n_ ? &p_[after(a, false)] : nullptr,
                                                                      alone[b], alone[a], o.tolerance_mm));
      }
    };
    corners(spike, hard_);
    // The verifier knows no spikes: a joint it calls smooth that only skipping a spike made a
    // corner is reported where the tangent breaks there (see report_spike_corners()).
    plain_hard_.clear();
    if (std::find(spike.begin(), spike.end(), 1) != spike.end()) {
      b_.none.assign(n_ + 1, 0);
      corners(b_.none, plain_hard_);
    }
    for (uint32_t v = 1; v < n_; ++v) {
      double l1 = (p_[v] - p_[v - 1]).norm(), l2 = (p_[v + 1] - p_[v]).norm();
      // Extrusion and the extra axes per mm must stay (nearly) constant inside one primitive:
      // a primitive ends where one starts or stops moving or changes its rate.
      auto rate_changes = [&](int x) {
        double d1 = vertex(v)[x] - vertex(v - 1)[x];
        double d2 = vertex(v + 1)[x] - vertex(v)[x];
        double r1 = d1 / l1, r2 = d2 / l2;
        return (d1 == 0) != (d2 == 0) || std::abs(r1 - r2) > kRateShare * std::max(std::abs(r1), std::abs(r2));
      };
      if (rate_changes(kE)) soft_[v] = 1;
      for (int x : extra_)
        if (rate_changes(x)) soft_[v] = 1;
      if (!pinned.empty() && pinned[v]) soft_[v] = 1;
    }
    next_soft_.assign(n_ + 1, n_ + 1);
    for (uint32_t v = n_; v-- > 0;) next_soft_[v] = soft_[v + 1] ? v + 1 : next_soft_[v + 1];
  }

  /// The primitives over all moves (fixed moves as themselves), each marked `kinked` where
  /// the tangent breaks at a smooth joint because the band allows nothing tangent there.
  /// Their end vertices are the run's.
  std::vector<Chosen> fit() {
    std::vector<Chosen> out = fit_kept();
    for (Chosen& c : out) c.prim.end_vertex = at_[c.prim.end_vertex];
    return out;
  }

  /// The run's vertices the fitter works on: all, less those that only repeat the one before
  /// (after a move that goes nowhere: no direction, so no corner either), which the
  /// primitive over their neighbours steps over. Where such a vertex must stay
  /// (the run's end, a pinned vertex) the one it repeats goes instead, unless that must stay
  /// too. (The keep method never gets here: fit_chain() keeps every move itself.)
  static void vertices_kept(const Interpretation& in, const Run& run, const std::vector<FixedMove>& fixed,
                            const std::vector<uint8_t>& pinned, std::vector<uint32_t>& at) {
    const uint32_t n = run.move_count;
    auto must_stay = [&](uint32_t v) { return v == 0 || v == n || (!pinned.empty() && pinned[v]); };
    at.assign(1, 0);
    for (uint32_t v = 1; v <= n; ++v) {
      const bool nowhere = (fixed.empty() || !fixed[v - 1].fixed) && in.goes_nowhere(run.first_move + v - 1);
      if (!nowhere) at.push_back(v);
      else if (must_stay(v) && !must_stay(at.back())) at.back() = v;
      else if (must_stay(v)) at.push_back(v);
    }
  }

 private:
  std::vector<Chosen> fit_kept() {
    if (n_ < 2) return keep();
    std::vector<Chosen> out;
    out.reserve(n_);  // at most one primitive per move
    // Stretches run from corner to corner, or to a fixed move; the tangent is free at a
    // corner and follows the fixed move's direction where the path is smooth.
    bool after_fitted = false;  // the last primitive in `out` was fitted, not fixed
    for (uint32_t a = 0; a < n_;) {
      if (fixed_[a].fixed) {
        Chosen m = input_move(a);
        if (fixed_[a].end) m.end_tangent = *fixed_[a].end;
        const auto& dir = fixed_[a].start;
        m.kinked = made_joint(a, !after_fitted) && !hard_[a] && dir && !out.empty() &&
                   !joint_cone_.holds(out.back().end_tangent, *dir);
        out.push_back(m);
        after_fitted = false;
        ++a;
        continue;
      }
      uint32_t limit = a + 1;
      while (limit < n_ && !hard_[limit] && !fixed_[limit].fixed) ++limit;
      in_tangent_ = a > 0 && fixed_[a - 1].fixed && !hard_[a] ? fixed_[a - 1].end : std::nullopt;
      out_tangent_ = limit < n_ && fixed_[limit].fixed && !hard_[limit] ? fixed_[limit].start : std::nullopt;
      stretch_start_ = a;
      stretch_end_ = limit;
      lim_ = scan_limits();
      stretch_id_ = ++s_.stretches;
      after_fitted = true;
      if (limit == a + 1) {  // one move: its own answer, or the arc over it that meets a fixed move
        Chosen m = one_move(a);
        m.kinked = in_tangent_ && !g1_cone_.holds(*in_tangent_, start_tangent(m, a));
        out.push_back(m);
        a = limit;
        continue;
      }
      const bool search = o_.method == FitOptions::Method::Arcs || o_.method == FitOptions::Method::Global;
      if (search || o_.method == FitOptions::Method::Greedy)
        for (uint32_t v = a + 1; v < limit; ++v)
          heading_[v] = search ? sided_tangent(v, a, limit) : input_tangent(v, a, limit);
      size_t forced = 0;
      std::vector<Chosen> chain;
      if (o_.method == FitOptions::Method::Stream) {
        chain = stream_chain(a, limit, forced);
      } else if (o_.method == FitOptions::Method::Lowe) {
        chain = lowe_chain(a, limit, forced);
      } else {
        // The greedy chain is the answer for stretches it covers in one or two primitives
        // joined tangentially; longer ones, and those it could only cover with a forced
        // kink, are searched again, and the chain with fewer kinks, then fewer primitives,
        // wins. The greedy chain is walked only as far as the search and that choice need.
        GreedyWalk greedy(*this, a, limit);
        const bool searched = search && o_.beam_width > 1 && (greedy.longer_than(2) || greedy.kinks() > 0);
        size_t beam_forced = 0;
        std::vector<Chosen> b;
        if (searched) b = beam_stretch(a, limit, greedy, beam_forced);
        // A beam chain of k primitives without kinks beats a greedy chain with more than k.
        const bool beam_shorter = searched && beam_forced == 0 && greedy.longer_than(b.size());
        if (!beam_shorter) greedy.finish();
        if (beam_shorter || (searched && std::pair(beam_forced, b.size()) < std::pair(greedy.kinks(), greedy.length()))) {
          chain.swap(b);
          forced = beam_forced;
        } else {
          chain = std::move(greedy.chain);
          forced = greedy.kinks();
        }
      }
      if (search && o_.merge) tighten_between_kinks(a, chain);
      // The global method also searches every (vertex, tangent) state layer by layer, for
      // every stretch the greedy chain does not cover with one primitive, and keeps that
      // chain when, merged too, it has fewer kinks, or as few and fewer primitives. The
      // default method does so where its chain wiggles.
      if ((o_.method == FitOptions::Method::Global && chain.size() > 1) ||
          (o_.method == FitOptions::Method::Arcs && wiggles(chain))) {
        auto g = layered_chain(a, limit);
        if (!g.empty() && o_.merge) tighten(a, g, in_tangent_);
        if (!g.empty() && std::pair(size_t(0), g.size()) < std::pair(forced, chain.size())) {
          chain.swap(g);
          forced = 0;
        }
      }
      if ((search || o_.method == FitOptions::Method::Greedy) && wiggles(chain)) untangle(a, limit, chain, forced);
      out.insert(out.end(), chain.begin(), chain.end());
      a = limit;
    }
    report_spike_corners(out);
    return out;
  }

  /// A chain that still wiggles may be paying with S-bends, all the way along, for one joint
  /// the path cannot pass tangentially: a hook, where the input turns at a vertex by more
  /// than a primitive ending there can follow within the band (a pass clipped to the floor it
  /// meets), so every chain that keeps the tangent leaves that vertex heading off the path.
  /// The tangent breaks instead at the joint where the first wiggle starts, or at the one
  /// before or after it, when that at least halves the primitives after the joint and saves
  /// kKinkWorth of them for each kink it adds; the break is a forced kink. The chain after
  /// the break may meet such a joint again further on (the next of plum's inner tips), so
  /// it is mended the same way, up to kUntangleDepth joints deep, before it is weighed:
  /// mended only at its first wiggle, a greedy chain over plum crept through the rest in
  /// S-bends (sampled with 6 000 points and turned by 0.7 rad, at 0.005 mm: 667 blocks; 59
  /// now, with two kinks).
  void untangle(uint32_t a, uint32_t limit, std::vector<Chosen>& chain, size_t& forced, int depth = 0) const {
    const size_t first = wiggle_start(chain);
    std::vector<Chosen> best;
    size_t best_forced = forced;
    // Each forced kink counts as kKinkWorth primitives.
    size_t best_cost = chain.size() + kKinkWorth * forced;
    for (size_t k = std::max<size_t>(first, 2) - 1; k <= first + 1 && k < chain.size(); ++k) {
      const uint32_t v = chain[k - 1].prim.end_vertex;  // the joint at the start of primitive k
      if (chain[k].kinked || hard_[v]) continue;
      size_t rest_forced = 0;
      GreedyWalk greedy(*this, v, limit);
      greedy.tangent.reset();
      std::vector<Chosen> rest;
      if (o_.method == FitOptions::Method::Greedy) {
        greedy.finish();
        rest = std::move(greedy.chain);
        rest_forced = greedy.kinks();
      } else {
        rest = beam_stretch(v, limit, greedy, rest_forced);
      }
      if (rest.empty()) continue;
      if (depth < kUntangleDepth && wiggles(rest)) untangle(v, limit, rest, rest_forced, depth + 1);
      const size_t after = chain.size() - k;
      if (2 * rest.size() > after || rest.size() + kKinkWorth > after) continue;
      rest.front().kinked = true;
      std::vector<Chosen> made(chain.begin(), chain.begin() + static_cast<long>(k));
      made.insert(made.end(), rest.begin(), rest.end());
      if (o_.merge && o_.method != FitOptions::Method::Greedy) tighten_between_kinks(a, made);
      size_t made_forced = 0;
      for (const Chosen& c : made) made_forced += c.kinked;
      if (made.size() + kKinkWorth * made_forced < best_cost) {
        best_cost = made.size() + kKinkWorth * made_forced;
        best.swap(made);
        best_forced = made_forced;
      }
    }
    if (best.empty()) return;
    chain.swap(best);
    forced = best_forced;
  }

  /// The index of the first primitive of the first wiggle in `chain` (see wiggles()), or
  /// its size when none.
  size_t wiggle_start(const std::vector<Chosen>& chain) const {
    int run = 0;
    for (size_t i = 1; i < chain.size(); ++i) {
      const Primitive &p = chain[i].prim, &before = chain[i - 1].prim;
      const bool back = p.kind == Primitive::Kind::Arc && before.kind == Primitive::Kind::Arc && p.ccw != before.ccw;
      run = back ? run + 1 : 0;
      if (run >= kWiggleArcs) return i - static_cast<size_t>(run);
    }
    return chain.size();
  }

  /// Whether `chain` wiggles: several arcs in a row, each turning the other way from the one
  /// before, as a chain does that left a narrow place (plum's inner tips) with a tangent it
  /// can only bring back to the path by S-bends, all tangent, all inside the band, and many.
  bool wiggles(const std::vector<Chosen>& chain) const { return wiggle_start(chain) < chain.size(); }

  /// Whether the joint at vertex v, after a move that is fixed or not, is one the fit made:
  /// between two moves left as they are it is the input's own, unless one side is a line
  /// that replaced several moves in another plane.
  bool made_joint(uint32_t v, bool fixed_before) const {
    return !fixed_[v].fixed || !fixed_before || fixed_[v].fitted_start || (v > 0 && fixed_[v - 1].fitted_end);
  }

  /// Marks as kinked the joints of `chain` (the whole fit) that are corners only because a
  /// spike next to them was skipped, where the tangent breaks there: the verifier, which
  /// skips no spikes, judges them as smooth joints.
  void report_spike_corners(std::vector<Chosen>& chain) const {
    if (plain_hard_.empty()) return;
    for (size_t i = 1; i < chain.size(); ++i) {
      const uint32_t before = i > 1 ? chain[i - 2].prim.end_vertex : 0, from = chain[i - 1].prim.end_vertex;
      if (!hard_[from] || plain_hard_[from] || chain[i].kinked || !made_joint(from, fixed_[before].fixed)) continue;
      const std::optional<Vec2> dir =
          fixed_[from].fixed ? fixed_[from].start : std::optional<Vec2>(start_tangent(chain[i], from));
      if (dir && !joint_cone_.holds(chain[i - 1].end_tangent, *dir)) chain[i].kinked = true;
    }
  }

  std::vector<Chosen> keep() const {
    std::vector<Chosen> out;
    for (uint32_t v = 0; v < n_; ++v) out.push_back(input_move(v));
    return out;
  }

  /// Vertex v in the plane (its first two coordinates).
  const Vec2& q(uint32_t v) const { return q_[v]; }
  /// Whether a change of extrusion rate lies strictly between vertices a and e (it would end
  /// a primitive there).
  bool soft_between(uint32_t a, uint32_t e) const { return next_soft_[a] < e; }

  /// All ends e in (a, limit] for which the arc (or line) leaving `a` along `T` and passing
  /// exactly through vertex e keeps every vertex in between inside the band. For a fixed
  /// start and tangent, each vertex allows an interval of curvatures (exact for the full
  /// circle), so the scan is linear and stops when the intervals no longer meet.
  void scan(uint32_t a, const Vec2& T, uint32_t limit, std::vector<Candidate>& out) const {
    out.clear();
    scan_ends(a, T, limit, [&](const Candidate& c) { out.push_back(c); });
  }

  /// What scan_ends() holds each end to besides the band, read off the options and the
  /// stretch (lim_: once a stretch, not at each of the few million scans).
  struct ScanLimits {
    double max_alpha, min_alpha, line_alpha;  // pseudo-angles, see FitAngles()
    double min_curvature, max_curvature;  // 1/mm: those of the largest and smallest radius
    double min_arc_length_mm;
    uint32_t min_arc_moves;
    bool arcs, helical;
    uint32_t stretch_end;
    const Vec2* out_tangent;  // null: none
  };
  ScanLimits scan_limits() const {
    return {max_alpha_,       min_alpha_,           line_alpha_,
            1 / o_.max_radius_mm, 1 / o_.min_radius_mm, o_.min_arc_length_mm,
            o_.min_arc_moves, arcs_,                o_.helical,
            stretch_end_,     out_tangent_ ? &*out_tangent_ : nullptr};
  }

  /// scan() handing each end to `sink` in order, nothing stored.
  template <class Sink>
  void scan_ends(uint32_t a, const Vec2& T, uint32_t limit, Sink&& sink) const {
    if (level_) {
      scan_ends_in<true>(a, T, limit, sink);
    } else {
      scan_ends_in<false>(a, T, limit, sink);
    }
  }

  /// scan_ends() where every vertex of the run lies at one height (`level`: then no
  /// primitive climbs, which the compiler can see) or not.
  template <bool level, class Sink>
  void scan_ends_in(uint32_t a, const Vec2& T, uint32_t limit, Sink& sink) const {
    const Vec2 N = left_normal(T);
    const Vec2 qa = q(a);
    const double h0 = p_[a].z();
    // The stretch's limits, read once: the sink writes memory, so the compiler would read
    // them again at every vertex.
    const ScanLimits lim = lim_;
    // The band a vertex must stay in: all of it while the primitive is flat, the in-plane
    // share once it climbs (from then on, for every vertex from `a`).
    double eps = eps_;
    double lo = -kInf, hi = kInf;  // curvature interval (1/mm) the interior vertices allow
    // A point u from `a`, off T by b = u·N, is within ε of the circle of curvature k when
    // |k·(|u|² - ε²) - 2b| <= 2ε (exact for the full circle).
    auto narrow_by = [&](const Vec2& u, double uu) {  // u from `a`, uu = |u|²
      const double w = uu - eps * eps;
      if (w > 0) {
        const double b = u.dot(N), inv = 1 / w;
        lo = std::max(lo, (2 * b - 2 * eps) * inv);
        hi = std::min(hi, (2 * b + 2 * eps) * inv);
      }
    };
    auto narrow = [&](uint32_t m) {
      const Vec2 u = q(m) - qa;
      narrow_by(u, u.squaredNorm());
    };
    double arc_lo = -kInf, arc_hi = kInf;
    // No input move may cut inside an arc by more than the band. A move whose middle lies
    // more than ε off T is more than ε inside every circle that turns towards it less than
    // the middle's own lower bound above (a circle turning the other way leaves it more than
    // ε outside, which the bounds of the move's end points already rule out), and the move's
    // point nearest the centre is nearer still, so the exact check would fail. Lines are the
    // chord, not this circle, and are not held to it.
    auto narrow_move = [&](uint32_t m) {  // the move from vertex m to m + 1
      const Vec2 u = middle_[m] - qa;
      const double b = u.dot(N);
      if (b > eps) arc_lo = std::max(arc_lo, (2 * b - 2 * eps) / (u.squaredNorm() - eps * eps));
      if (b < -eps) arc_hi = std::min(arc_hi, (2 * b + 2 * eps) / (u.squaredNorm() - eps * eps));
    };
    bool flat = true;
    Vec2 u{0, 0};  // the end before, from `a`, and its squared length
    double uu = 0;
    // A primitive ends at the first soft vertex at the latest.
    const uint32_t last = std::min(limit, next_soft_[a]);
    for (uint32_t e = a + 1; e <= last; ++e) {
      if (e > a + 1) narrow_by(u, uu);  // vertex e - 1 becomes an interior vertex
      narrow_move(e - 1);
      if (!level && flat && std::abs(p_[e].z() - h0) > kLengthEpsMm) {
        flat = false;
        eps = eps_ * kPlaneShare;
        lo = arc_lo = -kInf;
        hi = arc_hi = kInf;
        for (uint32_t m = a + 1; m < e; ++m) narrow(m);
        for (uint32_t m = a; m < e; ++m) narrow_move(m);
      }
      if (lo > hi) break;
      u = q(e) - qa;
      uu = u.squaredNorm();
      if (uu <= kLengthEpsMm * kLengthEpsMm) {
        if (level || flat) break;  // back at the start: a full circle is not a single primitive here
        // Straight above or below the start (a plunge written in steps): no direction in
        // the plane, so only a line can end here, which the exact check measures in 3D.
        sink(Candidate{e, 0.0, true});
        continue;
      }
      // The tangent-chord angle alpha (sweep = 2 alpha), held to the limits as the
      // pseudo-angle of |alpha|, and the curvature.
      const double ut = u.dot(T), un = u.dot(N), abs_un = std::abs(un);
      if (pseudo_angle_above(ut, abs_un, lim.max_alpha)) break;
      // The curvature k = K / uu of the circle through e, held to the intervals with a
      // relative slack of 1e-12 for rounding, multiplied through by uu > 0.
      const double K = 2 * un, slack = 1e-12 * (uu + std::abs(K));
      if (K + slack < lo * uu || K - slack > hi * uu) continue;
      const bool line = !pseudo_angle_above(ut, abs_un, lim.line_alpha);
      if (!line) {
        if (!lim.arcs || K + slack < arc_lo * uu || K - slack > arc_hi * uu) continue;
        // The radius uu / |K| within the options' limits.
        if (std::abs(K) < lim.min_curvature * uu || std::abs(K) > lim.max_curvature * uu) continue;
        if (e - a < lim.min_arc_moves || pseudo_angle_below(ut, abs_un, lim.min_alpha)) continue;
        if (!level && !flat && !lim.helical) continue;
        if (lim.min_arc_length_mm > 0 && 2 * std::atan2(abs_un, ut) * uu / std::abs(K) < lim.min_arc_length_mm) continue;
      }
      // Before a fixed move, the stretch must end heading along it.
      if (e == lim.stretch_end && lim.out_tangent) {
        const Vec2 c = u / std::sqrt(uu);
        const Vec2 end = line ? c : Vec2(2 * c.dot(T) * c - T);
        if (!joint_cone_.holds(end, *lim.out_tangent)) continue;
      }
      sink(Candidate{e, K / uu, line});
    }
  }

  /// Builds and checks the primitive for candidate `c` from `a` along `T`.
  std::optional<Chosen> make(uint32_t a, const Vec2& T, const Candidate& c) const {
    if (c.line) return make_line(a, c.e, T);
    return make_arc(a, c.e, q(a) + left_normal(T) / c.k, c.k > 0);
  }

  /// Whether every extra axis that moves, carried linearly by path length from vertex a to
  /// vertex e as the controller carries it along one block, passes within the band of its
  /// value at each vertex between (the band's number read in the axis's unit: mm, or
  /// degrees for A/B/C, which keeps a point within the band up to 57 mm from the axis).
  /// The vertices' rates per mm agree with their neighbours' (soft_), but a rate that
  /// drifts slowly would still bend the axis away from the line over a long primitive.
  bool extra_axes_linear(uint32_t a, uint32_t e) const {
    const size_t k = extra_.size();
    if (k == 0 || e <= a + 1) return true;
    const double span = length_[e] - length_[a];
    for (uint32_t m = a + 1; m < e; ++m) {
      const double t = span > 0 ? (length_[m] - length_[a]) / span : 0;
      for (size_t i = 0; i < k; ++i) {
        const double va = extra_values_[a * k + i], ve = extra_values_[e * k + i];
        if (std::abs(extra_values_[m * k + i] - (va + t * (ve - va))) > eps_) return false;
      }
    }
    return true;
  }

  /// The line from vertex a to vertex e, if the moves between stay inside the band.
  std::optional<Chosen> make_line(uint32_t a, uint32_t e, const Vec2& fallback_tangent) const {
    if (!extra_axes_linear(a, e)) return std::nullopt;
    std::span<const Vec3> pts(p_.data() + a, e - a + 1);
    Deviation d = line_deviation(pts, eps_);
    if (!d.ordered || d.max_mm > eps_) return std::nullopt;
    Chosen ch;
    ch.prim.end_vertex = e;
    ch.prim.kind = Primitive::Kind::Line;
    Vec2 chord = q(e) - q(a);
    ch.end_tangent = chord.norm() > 0 ? Vec2(chord.normalized()) : fallback_tangent;
    return ch;
  }

  /// The arc from vertex a to vertex e about `center`, if the moves between stay inside the
  /// band (in-plane share when it climbs) and the arc keeps the options' limits.
  std::optional<Chosen> make_arc(uint32_t a, uint32_t e, const Vec2& center, bool ccw) const {
    if (!arcs_ || e - a < std::max<uint32_t>(o_.min_arc_moves, 1) || !extra_axes_linear(a, e)) return std::nullopt;
    std::span<const Vec3> pts(p_.data() + a, e - a + 1);
    bool flat = true;
    for (const auto& p : pts) flat = flat && std::abs(p.z() - pts.front().z()) <= kLengthEpsMm;
    if (!flat && !o_.helical) return std::nullopt;
    if ((q(e) - q(a)).squaredNorm() < o_.min_chord_mm * o_.min_chord_mm) return std::nullopt;
    ArcGeom g = ArcGeom::through(pts.front(), pts.back(), center, ccw);
    if (!std::isfinite(g.radius_mm) || g.radius_mm < o_.min_radius_mm || g.radius_mm > o_.max_radius_mm)
      return std::nullopt;
    const double sweep_deg = std::abs(g.sweep) * 180 / kPi;
    if (sweep_deg > o_.max_sweep_deg + 1e-9 || sweep_deg < o_.min_sweep_deg) return std::nullopt;
    if (g.radius_mm * std::abs(g.sweep) < o_.min_arc_length_mm) return std::nullopt;
    const double band = flat ? eps_ : eps_ * kPlaneShare;
    Deviation d = arc_deviation(pts, g, band);
    if (!d.ordered || d.max_mm > band) return std::nullopt;
    if (!flat) {
      // Height must follow the helix closely enough for the 3D distance to stay in the band.
      double len_sum = 0;
      for (size_t m = 1; m < pts.size(); ++m) len_sum += (Vec2(pts[m].x(), pts[m].y()) - Vec2(pts[m - 1].x(), pts[m - 1].y())).norm();
      double s = 0;
      for (size_t m = 1; m + 1 < pts.size(); ++m) {
        s += (Vec2(pts[m].x(), pts[m].y()) - Vec2(pts[m - 1].x(), pts[m - 1].y())).norm();
        double h = g.h0 + (g.h1 - g.h0) * (len_sum > 0 ? s / len_sum : 0);
        if (std::abs(pts[m].z() - h) > eps_ * kHeightShare) return std::nullopt;
      }
    }
    Chosen ch;
    ch.prim.end_vertex = e;
    ch.prim.kind = Primitive::Kind::Arc;
    ch.prim.ccw = ccw;
    ch.prim.center = center;
    ch.prim.radius_mm = g.radius_mm;
    ch.end_tangent = arc_tangent(q(e) - center, ccw);
    return ch;
  }

  /// How far the chain reaches in one more step from vertex `e` along `T`: the last end
  /// the curvature scan allows (not yet checked exactly), or `e` itself when nothing fits.
  /// A corner or the end of the stretch counts as reaching the end.
  uint32_t reach_after(uint32_t e, const Vec2& T, uint32_t limit) const {
    if (e >= limit) return limit + 1;
    uint32_t reach = e;
    scan_ends(e, T, limit, [&](const Candidate& c) { reach = c.e; });
    return reach;
  }

  /// The input's own direction at vertex e, from each side apart: the mean of the tangents
  /// at e of the circles through e and two vertices behind it, and through e and two ahead
  /// (0.1 mm apart or more). Where the curvature jumps (a fillet meeting a straight side),
  /// each circle follows its own curve, where one circle through both sides would bend the
  /// tangent towards the tighter (by 0.46° at the end of a 5 mm fillet written in 0.2 mm
  /// moves, more than a joint may turn). input_tangent() where a side lacks the vertices.
  std::optional<Vec2> sided_tangent(uint32_t e, uint32_t lo, uint32_t hi) const {
    if (e <= lo || e >= hi) return std::nullopt;
    uint32_t wl = 1, wr = 1;
    while (e - wl > lo && (q(e - wl) - q(e)).norm() < 0.1) ++wl;
    while (e + wr < hi && (q(e + wr) - q(e)).norm() < 0.1) ++wr;
    if (e >= lo + 2 * wl && e + 2 * wr <= hi) {
      auto tl = circle_tangent(q(e), q(e - wl), q(e - 2 * wl));
      auto tr = circle_tangent(q(e), q(e + wr), q(e + 2 * wr));
      if (tl && tr && (*tr - *tl).squaredNorm() > 0) return Vec2((*tr - *tl).normalized());
    }
    return input_tangent(e, lo, hi);
  }

  /// The input's own direction at vertex e: tangent at e of the circle through e-w, e, e+w,
  /// with w wide enough (0.1 mm each side) that 4-decimal rounding does not steer it.
  /// Nothing at the ends of the stretch [lo, hi].
  std::optional<Vec2> input_tangent(uint32_t e, uint32_t lo, uint32_t hi) const {
    if (e <= lo || e >= hi) return std::nullopt;
    uint32_t w = 1;
    while (e - w > lo && e + w < hi && ((q(e - w) - q(e)).norm() < 0.1 || (q(e + w) - q(e)).norm() < 0.1)) ++w;
    Vec2 a = q(e - w), b = q(e), c = q(e + w);
    auto t = circle_tangent(b, c, a);  // at b, pointing towards c
    return t;
  }

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
  Score score(const Chosen& c, uint32_t limit) const {
    return scored(c, reach_after(c.prim.end_vertex, c.end_tangent, limit));
  }
  /// The score of `c`, after which the chain reaches `reach`.
  Score scored(const Chosen& c, uint32_t reach) const {
    Score sc;
    sc.end = c.prim.end_vertex;
    sc.reach = reach;
    if (const auto& t = heading_[sc.end]) sc.on_course = on_course_cone_.holds(*t, c.end_tangent);
    return sc;
  }

  /// Up to `count` primitives from `a` along `T` that pass the exact check, spread over the
  /// longer half of the scan's candidates, longest first. After a failure the walk steps
  /// back by growing strides to bound the work, and still tries the shortest candidate.
  void checked_from(uint32_t a, const Vec2& T, uint32_t limit, int count, std::vector<Chosen>& out) const {
    std::vector<Candidate>& cand = s_.checked_cand;
    scan(a, T, limit, cand);
    int checked = 0;
    size_t stride = 1;
    for (size_t i = cand.size(); i > 0 && checked < count;) {
      --i;
      if (auto c = make(a, T, cand[i])) {
        ++checked;
        out.push_back(*c);
        size_t step = std::max<size_t>(1, cand.size() / (2 * static_cast<size_t>(count)));
        i = i >= step ? i - step + 1 : 0;
        if (i == 0) break;
        continue;
      }
      if (i < stride) {
        if (i > 0 && stride > 1) {
          i = 1;
          stride = 1;
          continue;
        }
        break;
      }
      i -= stride - 1;
      stride *= 2;
    }
  }

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
                  bool next_to_longest = false, bool reuse = false) const {
    GuideScan* kept = reuse ? guide_scan(a, T, limit) : nullptr;
    if (!kept && s_.guide_record) {
      kept = &s_.guide_scans[s_.guide_next++ % s_.guide_scans.size()];
      kept->stretch = stretch_id_;
      kept->a = a;
      kept->limit = limit;
      kept->T = T;
      kept->reach.clear();
      scan(a, T, limit, kept->ends);
    } else if (!kept) {
      scan(a, T, limit, s_.scanned);
    }
    const std::vector<Candidate>& all = kept ? kept->ends : s_.scanned;
    out.clear();
    const size_t n = all.size(), want = static_cast<size_t>(count);
    const size_t step = std::max<size_t>(1, n / (2 * want));
    for (size_t i = n; i > 0 && out.size() < want; i = i > step ? i - step : 0) out.push_back(all[i - 1]);
    if (next_to_longest && step > 1 && n >= 2) out.push_back(all[n - 2]);
    // Where those two end heading off the input by more than a joint can turn back (an arc
    // run on past the point where its fillet meets a straight side, which the band allows
    // for sqrt(2·R·band): 18 moves of 0.05 mm on a radius of 40 mm), also the longest that
    // ends heading along the input, or one before it while each heads closer still: the
    // input's direction just past a joint of the drawing still leans towards the other side.
    auto misses = [&](size_t i) {  // 1 - cos of the angle between end tangent and input
      const uint32_t e = all[i].e;
      return heading_[e] ? 1 - heading_[e]->dot(unchecked(a, T, all[i]).end_tangent) : 2.0;
    };
    if (next_to_longest && step > 2 && misses(n - 1) > joint_miss_ && misses(n - 2) > joint_miss_)
      for (size_t i = n - 2; i-- > n - step;)
        if (misses(i) <= joint_miss_) {
          while (i > n - step && misses(i - 1) < misses(i) - closer_miss_) --i;
          out.push_back(all[i]);
          break;
        }
    return kept;
  }

  /// The greedy steps' scan from `a` along exactly `T` in this stretch, or null.
  GuideScan* guide_scan(uint32_t a, const Vec2& T, uint32_t limit) const {
    for (GuideScan& g : s_.guide_scans)
      if (g.stretch == stretch_id_ && g.a == a && g.limit == limit && g.T == T) return &g;
    return nullptr;
  }

  /// score() of `c`, a candidate of scan `g`, with the reach the greedy step found when it
  /// scored it too.
  Score guide_score(const GuideScan& g, const Chosen& c, uint32_t limit) const {
    for (const auto& [e, reach] : g.reach)
      if (e == c.prim.end_vertex) return scored(c, reach);
    return score(c, limit);
  }

  /// What candidate `c` from `a` along `T` would be, for scoring before the exact check: its
  /// end vertex and end tangent (T reflected about the chord; a line's is the chord).
  Chosen unchecked(uint32_t a, const Vec2& T, const Candidate& c) const {
    Chosen lite;
    lite.prim.end_vertex = c.e;
    Vec2 chord = q(c.e) - q(a);
    lite.end_tangent = !c.line ? reflected_end(a, T, c.e) : chord.norm() > 0 ? Vec2(chord.normalized()) : T;
    return lite;
  }

  /// Among the checked primitives from `a` along `T`, the one after which the chain reaches
  /// furthest in the next step (two-step look-ahead over a few long candidates); ties go
  /// to the longer primitive. A primitive after which the chain cannot go on tangentially
  /// is taken only when there is no other. `scored`, where given, receives its score.
  std::optional<Chosen> best_from(uint32_t a, const Vec2& T, uint32_t limit, Score* scored = nullptr) const {
    // Scored first, checked exactly in the order of their scores: the first that passes
    // wins, so most steps check one primitive. (A candidate's end tangent is T reflected
    // about its chord, a line's the chord.)
    std::vector<Candidate>& cand = s_.best_cand;
    GuideScan* kept = pick(a, T, limit, kLookahead, cand);
    std::vector<Ranked>& ranked = s_.ranked;
    ranked.clear();
    for (size_t i = 0; i < cand.size(); ++i) ranked.push_back({i, score(unchecked(a, T, cand[i]), limit)});
    if (kept)
      for (const Ranked& r : ranked) kept->reach.emplace_back(cand[r.i].e, r.sc.reach);
    std::stable_sort(ranked.begin(), ranked.end(), [](const Ranked& x, const Ranked& y) { return x.sc > y.sc; });
    for (const Ranked& r : ranked)
      if (auto c = make(a, T, cand[r.i])) {
        if (scored) *scored = r.sc;
        return c;
      }
    // None of those passes the exact check: the walk that steps back over the rest.
    std::vector<Chosen>& made = s_.best_made;
    made.clear();
    checked_from(a, T, limit, kLookahead, made);
    std::optional<Chosen> best;
    Score best_score;
    for (const Chosen& c : made) {
      Score sc = score(c, limit);
      if (!best || sc > best_score) {
        best = c;
        best_score = sc;
      }
    }
    if (scored) *scored = best_score;
    return best;
  }

  /// The chain may turn by less than the G1 angle at a joint. When the exact tangent only
  /// allows a short primitive (the incoming tangent is slightly off the input's), tangents
  /// turned by up to 0.9 of that angle (near_turns_) are tried too, and the one reaching
  /// furthest wins.
  std::optional<Chosen> best_near(uint32_t a, const Vec2& T, uint32_t limit) const {
    // In the searches, this is the greedy chain's step, whose scans the beam takes again.
    struct Recording {
      bool& on;
      ~Recording() { on = false; }
    } recording{s_.guide_record = o_.method == FitOptions::Method::Arcs || o_.method == FitOptions::Method::Global};
    Score best_score;
    auto best = best_from(a, T, limit, &best_score);
    if (best) {
      if (best_score.on_course && (best->prim.end_vertex - a >= 4 || best->prim.end_vertex == limit)) return best;
    }
    for (size_t i = 0; i < near_turn_count_; ++i) consider(a, near_turns_[i](T), limit, best, best_score, &T);
    return best;
  }

  /// Keeps in `best` whichever of it and the best primitive along `T` scores higher. With
  /// `incoming` (the tangent the chain arrives with, T being turned from it), a primitive
  /// that leaves by more than kJointShare of the G1 angle from it is not taken: a line's chord
  /// may lie off T by the line allowance, on top of the turn.
  void consider(uint32_t a, const Vec2& T, uint32_t limit, std::optional<Chosen>& best, Score& best_score,
                const Vec2* incoming = nullptr) const {
    Score sc;
    auto c = best_from(a, T, limit, &sc);
    if (!c) return;
    // (An arc leaves along T itself.)
    if (incoming && !joint_cone_.holds(*incoming, start_tangent(*c, a))) return;
    if (!best || sc > best_score) {
      best = c;
      best_score = sc;
    }
  }

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
  std::vector<Chosen> stream_chain(uint32_t a, uint32_t limit, size_t& forced) const {
    std::vector<Chosen> chain;
    const uint32_t start = a;
    while (a < limit) {
      Chosen best = input_move(a);
      for (uint32_t e = a + 2; e <= limit && e - a <= o_.stream_window && !soft_[e - 1]; ++e) {
        std::optional<Chosen> c = make_line(a, e, best.end_tangent);
        if (!c) c = through_ends(a, e);
        if (!c) break;
        best = *c;
      }
      chain.push_back(best);
      a = best.prim.end_vertex;
    }
    make_tangent(start, chain, forced);
    return chain;
  }

  /// Seed 000's G1 adjustment of a chain from `a` fitted without regard to its joints, joint
  /// by joint from the start. Where the tangent breaks at a smooth joint, the primitive after
  /// it is replaced, where the band allows, by the one through the same end vertex that
  /// leaves along the tangent arriving there, turned within kTurnShare of the G1 angle to
  /// meet the primitive after it (the seed moves the arc's centre so that the tangents
  /// agree); failing that, the two primitives on either side are split again at another
  /// vertex, joined tangentially, leaving the joint before them as the first did and
  /// meeting the one after them (the joint moves, which fixes arcs that overshot it).
  /// Joints that stay broken are marked kinked and counted in `forced`.
  void make_tangent(uint32_t a, std::vector<Chosen>& chain, size_t& forced) const {
    auto from_of = [&](size_t i) { return i == 0 ? a : chain[i - 1].prim.end_vertex; };
    // The tangent arriving at the start of primitive i, where that joint is smooth and unbroken.
    auto arriving = [&](size_t i) -> std::optional<Vec2> {
      if (hard_[from_of(i)] || chain[i].kinked) return std::nullopt;
      return i == 0 ? in_tangent_ : std::optional<Vec2>(chain[i - 1].end_tangent);
    };
    // The tangent primitive i must meet at its end, if any.
    auto leaving = [&](size_t i) -> std::optional<Vec2> {
      const uint32_t to = chain[i].prim.end_vertex;
      if (i + 1 < chain.size()) return start_tangent(chain[i + 1], to);
      return to == stretch_end_ ? out_tangent_ : std::nullopt;
    };
    std::vector<Vec2> starts;
    for (size_t i = 0; i < chain.size(); ++i) {
      const uint32_t from = from_of(i), to = chain[i].prim.end_vertex;
      const std::optional<Vec2> in = arriving(i);
      if (!in || joint_cone_.holds(*in, start_tangent(chain[i], from))) continue;
      const std::optional<Vec2> out = leaving(i);
      std::optional<Chosen> one;
      for (const std::optional<Vec2>& T : {aimed(from, *in, to, out), in})
        if (!one && T && (one = through(from, *T, to)) && !joint_cone_.holds(*in, start_tangent(*one, from))) one.reset();
      if (one) {
        chain[i] = *one;
        continue;
      }
      std::optional<std::pair<Chosen, Chosen>> two;
      if (i > 0) {
        const uint32_t before = from_of(i - 1);
        starts.clear();
        if (auto arrive = arriving(i - 1)) {
          starts = {*arrive, half_left_(*arrive), half_right_(*arrive)};
        } else {
          start_tangents(before, to, starts);
        }
        for (const Vec2& T : starts)
          if ((two = split_through(before, T, to, out, SIZE_MAX))) break;
      }
      if (two) {
        two->first.kinked = chain[i - 1].kinked;
        chain[i - 1] = two->first;
        chain[i] = two->second;
      } else {
        chain[i].kinked = true;
        ++forced;
      }
    }
  }

  /// Seed 000's line detection (Lowe 1987): the stretch from `a` to `limit` is split
  /// recursively at the vertex farthest from the chord, and each piece is rated by its
  /// significance, largest deviation over length (lower is more significant). Bottom up, a
  /// piece stands for itself where it is inside the band, has no change of extrusion rate
  /// inside, and is at least as significant as the most significant piece below it; else it
  /// stands for its pieces. So the split adapts to the scale of the shape: a straight
  /// stretch stays whole however noisy within the band, a curve is cut down to pieces of
  /// kLoweMinMoves moves, whose ends the arcs may then take. The breakpoints, `a` first.
  std::vector<uint32_t> lowe_breaks(uint32_t a, uint32_t limit) const {
    struct Piece {
      uint32_t i, j;
      uint32_t at;          // where it splits: the farthest vertex, or the first change of rate
      double significance;  // largest deviation / length (lower: more significant)
      bool must_split;      // outside the band, or a change of extrusion rate inside
      int left = -1, right = -1;
      double best = 0;      // the most significant significance it stands for
      bool whole = true;    // stands for itself
    };
    std::vector<Piece> pieces;
    auto add = [&](uint32_t i, uint32_t j) {
      double worst = 0;
      uint32_t at = i + 1;
      for (uint32_t m = i + 1; m < j; ++m)
        if (double d = point_segment_distance(p_[m], p_[i], p_[j]); d > worst) {
          worst = d;
          at = m;
        }
      const bool soft = soft_between(i, j);
      if (soft)
        for (at = i + 1; !soft_[at];) ++at;
      const double len = (p_[j] - p_[i]).norm();
      const double sig = worst == 0 ? 0 : len > kLengthEpsMm ? worst / len : kInf;
      pieces.push_back({i, j, at, sig, worst > eps_ || soft});
      return static_cast<int>(pieces.size()) - 1;
    };
    add(a, limit);
    // Top down: pieces are split until they are single moves, or short enough and inside.
    for (size_t n = 0; n < pieces.size(); ++n) {
      const Piece pc = pieces[n];
      if (pc.j - pc.i <= 1 || (!pc.must_split && pc.j - pc.i <= kLoweMinMoves)) continue;
      const int l = add(pc.i, pc.at), r = add(pc.at, pc.j);
      pieces[n].left = l;
      pieces[n].right = r;
    }
    // Bottom up (children come after their parents): which pieces stand for themselves.
    for (size_t n = pieces.size(); n-- > 0;) {
      Piece& pc = pieces[n];
      pc.best = pc.significance;
      if (pc.left < 0) continue;
      const double below = std::min(pieces[pc.left].best, pieces[pc.right].best);
      pc.whole = !pc.must_split && pc.significance <= below;
      if (!pc.whole) pc.best = below;
    }
    std::vector<uint32_t> breaks{a};
    std::vector<int> todo{0};
    while (!todo.empty()) {
      const Piece& pc = pieces[todo.back()];
      todo.pop_back();
      if (pc.whole) {
        breaks.push_back(pc.j);
      } else {
        todo.push_back(pc.right);
        todo.push_back(pc.left);
      }
    }
    return breaks;
  }

  /// Seed 000: Lowe-style line detection, then arcs over runs of the lines. The breakpoints
  /// come from lowe_breaks(); then, from each, a primitive grows over as many following
  /// breakpoints as a line or the arc through both end points (centre on the chord's
  /// bisector, least squares) keeps inside the band. Then the joints are made tangent where
  /// the band allows (make_tangent()).
  std::vector<Chosen> lowe_chain(uint32_t a, uint32_t limit, size_t& forced) const {
    std::vector<uint32_t> breaks = lowe_breaks(a, limit);
    std::vector<Chosen> chain;
    for (size_t k = 0; k + 1 < breaks.size();) {
      const uint32_t from = breaks[k];
      std::optional<Chosen> best = make_line(from, breaks[k + 1], Vec2(1, 0));
      if (!best) {  // a soft split that is not straight: the input's own moves
        best = input_move(from);
        breaks.insert(breaks.begin() + k + 1, from + 1);
      }
      size_t next = k + 1;
      for (size_t j = k + 2; j < breaks.size(); ++j) {
        if (soft_between(from, breaks[j])) break;
        std::optional<Chosen> c = make_line(from, breaks[j], best->end_tangent);
        if (!c) c = through_ends(from, breaks[j]);
        if (!c) break;
        best = c;
        next = j;
      }
      chain.push_back(*best);
      k = next;
    }
    make_tangent(a, chain, forced);
    return chain;
  }

  /// Seed 001's circle: through vertices a and e, centre on the chord's perpendicular
  /// bisector at the offset that minimises the squared algebraic residuals |p - c|² - r² of
  /// the vertices between (linear in the offset, so closed-form); CW or CCW from the polar
  /// angles of the start, second and end vertex about that centre, wrap-around included.
  std::optional<Chosen> through_ends(uint32_t a, uint32_t e) const {
    Vec2 p0 = q(a), p1 = q(e), m = (p0 + p1) / 2;
    Vec2 chord = p1 - p0;
    double h2 = chord.squaredNorm() / 4;
    if (h2 <= kLengthEpsMm * kLengthEpsMm) return std::nullopt;
    Vec2 n = left_normal(chord.normalized());
    double num = 0, den = 0;
    for (uint32_t v = a + 1; v < e; ++v) {
      Vec2 d = q(v) - m;
      double resid = d.squaredNorm() - h2, slope = 2 * d.dot(n);  // residual = resid - s·slope
      num += resid * slope;
      den += slope * slope;
    }
    if (den <= 0) return std::nullopt;
    Vec2 center = m + n * (num / den);
    auto angle = [&](const Vec2& p) { return std::atan2(p.y() - center.y(), p.x() - center.x()); };
    auto ccw_from_start = [&](double t) {
      double d = t - angle(p0);
      while (d < 0) d += 2 * kPi;
      while (d >= 2 * kPi) d -= 2 * kPi;
      return d;
    };
    bool ccw = ccw_from_start(angle(q(a + 1))) < ccw_from_start(angle(p1));
    return make_arc(a, e, center, ccw);
  }

  /// The tangent with which `c`, starting at vertex `from`, leaves it.
  Vec2 start_tangent(const Chosen& c, uint32_t from) const {
    if (c.prim.kind == Primitive::Kind::Line) {
      Vec2 chord = q(c.prim.end_vertex) - q(from);
      return chord.norm() > kLengthEpsMm ? Vec2(chord.normalized()) : c.end_tangent;
    }
    return arc_tangent(q(from) - c.prim.center, c.prim.ccw);
  }

  /// The line or arc leaving vertex a along T and ending exactly at vertex e, if scan()
  /// would offer it (not yet checked exactly).
  std::optional<Candidate> through_candidate(uint32_t a, const Vec2& T, uint32_t e) const {
    Vec2 u = q(e) - q(a);
    double uu = u.squaredNorm();
    if (uu <= kLengthEpsMm * kLengthEpsMm || u.dot(T) <= 0) return std::nullopt;
    if (soft_between(a, e)) return std::nullopt;
    Vec2 N = left_normal(T);
    const Candidate c{e, 2 * u.dot(N) / uu, pseudo_angle(u.dot(T), std::abs(u.dot(N))) <= line_alpha_};
    if (!on_circle(a, T, c)) return std::nullopt;
    return c;
  }

  /// The line or arc leaving vertex a along T and ending exactly at vertex e, checked.
  std::optional<Chosen> through(uint32_t a, const Vec2& T, uint32_t e) const {
    auto c = through_candidate(a, T, e);
    if (!c) return std::nullopt;
    return make(a, T, *c);
  }

  /// scan()'s test of one end: every vertex between `a` and c.e lies within the band of the
  /// full circle (or line) leaving `a` along T with curvature c.k: scan()'s vertex test
  /// without a division. Cheap, and necessary for the exact check, so most candidates that
  /// would fail it are turned away here.
  bool on_circle(uint32_t a, const Vec2& T, const Candidate& c) const {
    const Vec2 N = left_normal(T);
    const double h0 = p_[a].z();
    bool flat = std::abs(p_[c.e].z() - h0) <= kLengthEpsMm;
    for (uint32_t m = a + 1; m < c.e && flat; ++m) flat = std::abs(p_[m].z() - h0) <= kLengthEpsMm;
    const double eps = flat ? eps_ : eps_ * kPlaneShare;
    const double slack = 1e-12 * (1 + std::abs(c.k));
    for (uint32_t m = a + 1; m < c.e; ++m) {
      const Vec2 u = q(m) - q(a);
      const double w = u.squaredNorm() - eps * eps;
      if (w > 0 && std::abs(c.k * w - 2 * u.dot(N)) > 2 * eps + slack * w) return false;
    }
    return true;
  }

  /// Signed angle from a to b, radians.
  static double angle_to(const Vec2& a, const Vec2& b) { return std::atan2(cross2(a, b), a.dot(b)); }

  /// The end tangent of the arc leaving `from` along T through `to`: T reflected about the
  /// chord (a line's is the chord itself, within the line allowance of that).
  Vec2 reflected_end(uint32_t from, const Vec2& T, uint32_t to) const {
    Vec2 c = q(to) - q(from);
    double len = c.norm();
    if (len <= kLengthEpsMm) return T;
    c /= len;
    return 2 * c.dot(T) * c - T;
  }

  /// The start along `in` turned within kTurnShare of the G1 angle so that the arc from
  /// `from` to `to` ends as close to `out` as it can (`in` itself without `out`); nothing
  /// when even the largest turn misses it.
  std::optional<Vec2> aimed(uint32_t from, const Vec2& in, uint32_t to, const std::optional<Vec2>& out) const {
    if (!out) return in;
    const double turn = kTurnShare * deg_to_rad(o_.g1_angle_deg);
    const Vec2 end = reflected_end(from, in, to);
    if (!two_turns_line_cone_.holds(end, *out)) return std::nullopt;
    return rotated(in, std::clamp(-angle_to(end, *out), -turn, turn));
  }

  /// Two primitives from `from` to `to`, the first leaving along T, joined tangentially, the
  /// second turned within kTurnShare of the G1 angle to meet `out` (where given) within it.
  /// Splits whose second primitive can meet `out` are tried longest first; at most `tries`
  /// of them, spread evenly, are checked exactly. (Inlined: tighten() calls it in its
  /// innermost loop, where a call costs 0.3 % of all instructions on the corpus.)
  [[gnu::always_inline]] std::optional<std::pair<Chosen, Chosen>> split_through(uint32_t from, const Vec2& T, uint32_t to,
                                                         const std::optional<Vec2>& out, size_t tries) const {
    std::vector<Candidate>& cand = s_.tighten_cand;
    std::vector<size_t>& split = s_.split;
    scan(from, T, to - 1, cand);
    split.clear();
    for (size_t k = cand.size(); k-- > 0;)
      if (aimed(cand[k].e, reflected_end(from, T, cand[k].e), to, out)) split.push_back(k);
    const double stride = std::max(1.0, double(split.size()) / double(tries));
    for (double x = 0; x < double(split.size()); x += stride) {
      const Candidate& c = cand[split[size_t(x)]];
      // The second primitive's own cheap test first: it fails far more often.
      auto T2_lite = aimed(c.e, unchecked(from, T, c).end_tangent, to, out);
      if (!T2_lite || !through_candidate(c.e, *T2_lite, to)) continue;
      auto first = make(from, T, c);
      if (!first) continue;
      auto T2 = aimed(c.e, first->end_tangent, to, out);
      if (!T2) continue;
      auto second = through(c.e, *T2, to);
      if (second && (!out || turn_cone_.holds(second->end_tangent, *out))) return std::pair(*first, *second);
    }
    return std::nullopt;
  }

  /// tighten() on each tangent-continuous part of a chain that starts at `a`: a forced kink
  /// frees the tangent on both sides of it, as a corner does.
  void tighten_between_kinks(uint32_t a, std::vector<Chosen>& chain) const {
    std::vector<Chosen> out, part;
    for (size_t i = 0; i < chain.size(); ++i) {
      part.push_back(chain[i]);
      if (i + 1 < chain.size() && !chain[i + 1].kinked) continue;
      const bool kinked = part.front().kinked;
      tighten(a, part, out.empty() && !kinked ? in_tangent_ : std::nullopt);
      part.front().kinked = kinked;
      a = part.back().prim.end_vertex;
      out.insert(out.end(), part.begin(), part.end());
      part.clear();
    }
    chain.swap(out);
  }

  /// Local merging after the search: wherever two consecutive primitives can become one, or
  /// three can become two, that leave the joint before them and meet the joint after them
  /// within the turn allowed at a joint, they are replaced, and the joint before is tried again.
  /// The tangent at the start is `incoming` (free when none) and at the end free, or a fixed
  /// move's direction where the chain ends at one. Turning an arc's
  /// start tangent by φ turns its end tangent by -φ (the end tangent is the start tangent
  /// reflected about the chord), so the turn that meets the next joint is solved for, and
  /// only primitives that can meet it are checked exactly.
  void tighten(uint32_t a, std::vector<Chosen>& chain, const std::optional<Vec2>& incoming) const {
    std::vector<Vec2>& starts = s_.starts;
    std::vector<Vec2>& firsts = s_.firsts;
    std::vector<Chosen> repl;
    // After a merge at i, the joint before it may merge too: step back one.
    for (size_t i = 0; i + 1 < chain.size();) {
      bool changed = false;
      {
        const uint32_t from = i == 0 ? a : chain[i - 1].prim.end_vertex;
        for (size_t w : {size_t(2), size_t(3)}) {
          if (i + w > chain.size()) break;
          const uint32_t to = chain[i + w - 1].prim.end_vertex;
          std::optional<Vec2> out;
          if (i + w < chain.size()) {
            out = start_tangent(chain[i + w], to);
          } else if (to == stretch_end_) {
            out = out_tangent_;
          }
          // The tangent arriving at `from`: the previous primitive's, or at the start `incoming`.
          const std::optional<Vec2> in = i > 0 ? std::optional<Vec2>(chain[i - 1].end_tangent) : incoming;
          auto meets = [&](const Chosen& c) { return !out || turn_cone_.holds(c.end_tangent, *out); };
          // Start tangents: the incoming one (turned below), or at the stretch's start the
          // input's own directions; with a fixed next joint, the one ending exactly on it.
          starts.clear();
          if (in) {
            starts.push_back(*in);
          } else if (w == 2) {
            // One primitive from `a` to `to`: its start lies in the range that reaches `to`
            // (the chord first where the line does).
            if (out) starts.push_back(reflected_end(from, *out, to));
            if (const auto [lo, hi] = start_range(a, to); lo <= hi) {
              if (lo <= 0 && 0 <= hi) starts.push_back((q(to) - q(a)).normalized());
              for (double share : {0.5, kStartRangeInset, 1 - kStartRangeInset})
                starts.push_back(range_start(a, {to, lo, hi}, share));
            }
          } else {
            start_tangents(a, to, starts);
          }
          repl.clear();
          for (const Vec2& T0 : starts) {
            if (w == 2) {
              std::optional<Vec2> T = in ? aimed(from, T0, to, out) : std::optional<Vec2>(T0);
              if (!T || (!in && out && !turn_line_cone_.holds(reflected_end(from, T0, to), *out))) continue;
              auto c = through(from, *T, to);
              if (c && meets(*c)) repl = {*c};
            } else {
              firsts.clear();
              if (in) {
                firsts.push_back(T0);
                firsts.push_back(half_left_(T0));
                firsts.push_back(half_right_(T0));
              } else {
                firsts.push_back(T0);
              }
              for (const Vec2& T : firsts)
                if (auto two = split_through(from, T, to, out, kSplitsTried)) {
                  repl = {two->first, two->second};
                  break;
                }
            }
            if (!repl.empty()) break;
          }
          if (repl.empty()) continue;
          chain.erase(chain.begin() + i, chain.begin() + i + w);
          chain.insert(chain.begin() + i, repl.begin(), repl.end());
          changed = true;
          break;
        }
      }
      i = changed ? (i > 0 ? i - 1 : 0) : i + 1;
    }
  }

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
    Chosen c;  ///< unchecked(): end vertex and tangent only
    Score sc;
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
    std::vector<double> extra_values, length;
    std::vector<uint8_t> spike, nowhere, alone, none;  // the constructor's
  };

  /// Buffers the searches reuse from call to call, and from run to run on one thread, so
  /// that once warm they allocate nothing. Each belongs to one function; none of those
  /// calls itself, and none calls another that uses the same buffer.
  struct Scratch {
    RunBuffers run;                       // the fitter's own per-vertex data (see RunBuffers)
    std::vector<Candidate> scanned;       // pick()
    std::vector<Candidate> checked_cand;  // checked_from()
    std::vector<Candidate> best_cand;     // best_from()
    std::vector<Ranked> ranked;           // best_from()
    std::vector<Chosen> best_made;        // best_from()
    std::vector<Vec2> free_starts;        // best_free()
    std::vector<StartRange> reached;      // start_tangents()
    std::vector<Vec2> inputs;             // fanned_input_tangents()
    std::vector<Candidate> tighten_cand;  // tighten()
    std::vector<size_t> split;            // tighten()
    std::vector<Vec2> starts, firsts;     // tighten()
    std::vector<Vec2> roots;              // beam_chain()
    std::vector<Node> nodes;              // beam_chain()
    std::vector<int> layer, next;         // beam_chain()
    std::vector<Made> made;               // beam_chain()
    std::vector<Candidate> beam_out;      // beam_chain()
    std::vector<SeenEnd> seen;            // beam_chain()
    std::vector<std::pair<uint64_t, uint64_t>> keys;  // beam_chain()
    std::vector<uint64_t> packed_keys;                // beam_chain()
    std::vector<std::pair<uint32_t, Vec2>> expanded;  // beam_chain()
    // The greedy steps' latest scans (GuideScan), in turn, and whether best_near() is taking one.
    std::array<GuideScan, 9> guide_scans;
    size_t guide_next = 0;
    bool guide_record = false;
    uint64_t stretches = 0;  // stretches begun on this thread (GuideScan::stretch)
  };
  static Scratch& thread_scratch() {
    thread_local Scratch s;
    return s;
  }

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
  std::vector<Chosen> beam_chain(uint32_t a, uint32_t limit, GreedyWalk* greedy) const {
    std::vector<Node>& nodes = s_.nodes;
    std::vector<int>&layer = s_.layer, &next = s_.next;
    nodes.clear();
    layer.clear();
    roots(a, limit, s_.roots);
    for (const Vec2& T : s_.roots) nodes.push_back({{}, -1, a, T});
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) layer.push_back(i);
    const double bin_rad = deg_to_rad(o_.g1_angle_deg) / 8;
    const size_t width = o_.beam_width;
    // Candidates are scored first and checked exactly only when the beam keeps them.
    std::vector<Made>& made = s_.made;
    std::vector<Candidate>& out = s_.beam_out;
    std::vector<SeenEnd>& seen = s_.seen;
    std::vector<std::pair<uint64_t, uint64_t>>& keys = s_.keys;
    std::vector<uint64_t>& packed_keys = s_.packed_keys;
    std::vector<std::pair<uint32_t, Vec2>>& expanded = s_.expanded;
    int furthest = -1;
    int guide = -1;  // the node the greedy chain would be at: the beam never does worse
    size_t step = 0;
    while (!layer.empty()) {
      made.clear();
      // The greedy chain's next primitive: read off `greedy` (whose first kink ends it) when
      // given, else chosen again.
      std::optional<Chosen> g;
      if (guide == -1) {
        guide = layer.front();
        if (greedy) {
          if (const Chosen* c = greedy->at(0); c && !c->kinked) g = *c;
        } else {
          g = arrives_along(a) ? best_near(a, *in_tangent_, limit) : std::optional<Chosen>(best_free(a, limit));
        }
      } else if (guide >= 0) {
        if (greedy) {
          if (const Chosen* c = greedy->at(step); c && !c->kinked) g = *c;
        } else {
          g = best_near(nodes[guide].v, nodes[guide].T, limit);
        }
      }
      ++step;
      // Each chain goes on along its end tangent or turned by all of the joint allowance
      // either way, and where the input runs straight ahead by half of it too: a line's chord
      // lies within a quarter of the G1 angle of the tangent scanned, so whole turns alone
      // would offer no line whose chord lies between. A tangent another chain at the same
      // vertex follows already is not followed twice.
      expanded.clear();
      for (int i : layer) {
        const Node nd = nodes[i];
        const bool straight = nd.parent >= 0 && straight_ahead(nd.v, limit);  // (roots take no turns)
        for (const Turn* turn : {(const Turn*)nullptr, &full_left_, &full_right_, &half_left_, &half_right_}) {
          if (turn && nd.parent < 0) break;
          if ((turn == &half_left_ || turn == &half_right_) && !straight) break;
          const Vec2 T = turn ? (*turn)(nd.T) : nd.T;
          auto same = [&](const auto& x) { return x.first == nd.v && same_tangent_cone_.holds(x.second, T); };
          if (std::any_of(expanded.begin(), expanded.end(), same)) continue;
          expanded.push_back({nd.v, T});
          const GuideScan* kept = pick(nd.v, T, limit, o_.beam_branch, out, true, i == guide);
          for (const Candidate& cd : out) {
            if (cd.e >= limit) {
              if (auto c = made_from(nd, T, cd)) {
                nodes.push_back({*c, i, c->prim.end_vertex, c->end_tangent});
                return chain_to(nodes, static_cast<int>(nodes.size()) - 1);
              }
              continue;
            }
            Chosen lite = unchecked(nd.v, T, cd);
            made.push_back({i, T, cd, lite, kept ? guide_score(*kept, lite, limit) : score(lite, limit)});
          }
        }
      }
      // Half the beam goes to the chains whose next step reaches furthest, two places to
      // those whose primitive itself ends furthest, the rest to those heading where the input
      // heads (then reaching furthest): each alone loses chains the others find. (A chain
      // that must pass a narrow place, plum's inner tips, with the one arc that fits there
      // reaches least after its primitive ends at the entrance, and the chains that turn in
      // sooner with a longer reach get stuck past it: 53 blocks for plum at 0.003 mm, 49 with
      // the two places.)
      next.clear();
      seen.clear();
      if (g) {
        nodes.push_back({*g, guide, g->prim.end_vertex, g->end_tangent});
        guide = static_cast<int>(nodes.size()) - 1;
        if (g->prim.end_vertex >= limit) return chain_to(nodes, guide);
        next.push_back(guide);
        if (furthest < 0 || nodes[furthest].v < g->prim.end_vertex) furthest = guide;
      } else {
        guide = -2;
      }
      // A layer keeps few of its candidates, so most are never put in order: each ranking
      // packs its keys into integers and takes them best first from a heap, ties in the order
      // made. A tangent's bin is worked out only when another kept chain ends at its vertex.
      auto bin_of = [&](const Vec2& t) { return std::lround(std::atan2(t.y(), t.x()) / bin_rad); };
      // Keeps made[k] when it passes the exact check and no kept chain ends at its vertex
      // with a tangent in the same bin.
      auto take = [&](uint32_t k) {
        Made& m = made[k];
        const uint32_t e = m.c.prim.end_vertex;
        std::optional<long> bin;
        for (SeenEnd& s : seen) {
          if (s.v != e) continue;
          if (!bin) bin = bin_of(m.c.end_tangent);
          if (!s.bin) s.bin = bin_of(s.T);
          if (*s.bin == *bin) return;
        }
        auto c = made_from(nodes[m.from], m.T, m.cand);
        const int from = m.from;
        m.from = -1;
        if (!c) return;
        seen.push_back({e, m.c.end_tangent, bin});
        nodes.push_back({*c, from, e, c->end_tangent});
        int id = static_cast<int>(nodes.size()) - 1;
        if (furthest < 0 || nodes[furthest].v < e) furthest = id;
        next.push_back(id);
      };
      // A ranking orders by (flag, x, y) from each score, then by the order made. Where the
      // vertices and the candidates fit in 21 bits each, as they do but on runs of more than
      // two million moves, the key is one 64-bit integer; else two.
      const bool packed = limit + 2 < (uint32_t(1) << kKeyBits) && made.size() < (size_t(1) << kKeyBits);
      constexpr uint64_t kIndexMask = (uint64_t(1) << kKeyBits) - 1;
      // One ranking in `heap`: key_of(fields, k) makes a key, place_of(key) reads k back.
      auto rank = [&](auto& heap, size_t count, auto fields, auto key_of, auto place_of) {
        heap.clear();
        for (uint32_t k = 0; k < made.size(); ++k)
          if (made[k].from >= 0) heap.push_back(key_of(fields(made[k].sc), k));  // not yet kept, nor failed
        std::make_heap(heap.begin(), heap.end());
        for (auto end = heap.end(); end != heap.begin() && next.size() < count; --end) {
          std::pop_heap(heap.begin(), end);
          take(place_of(*(end - 1)));
        }
      };
      auto keep_best = [&](size_t count, auto fields) {
        if (packed) {
          rank(
              packed_keys, count, fields,
              [&](const auto& f, uint32_t k) {
                const auto [flag, x, y] = f;
                return uint64_t(flag) << (3 * kKeyBits) | uint64_t(x) << (2 * kKeyBits) | uint64_t(y) << kKeyBits |
                       (kIndexMask - k);
              },
              [&](uint64_t key) { return uint32_t(kIndexMask - (key & kIndexMask)); });
        } else {
          rank(
              keys, count, fields,
              [](const auto& f, uint32_t k) {
                const auto [flag, x, y] = f;
                return std::pair(uint64_t(flag) << 32 | x, uint64_t(y) << 32 | (UINT32_MAX - k));
              },
              [](const std::pair<uint64_t, uint64_t>& key) { return UINT32_MAX - uint32_t(key.second); });
        }
      };
      using Fields = std::tuple<uint32_t, uint32_t, uint32_t>;
      keep_best(width / 2, [](const Score& x) { return Fields{0, x.reach, x.end}; });
      keep_best(width / 2 + kFurthestEnds, [](const Score& x) { return Fields{0, x.end, x.reach}; });
      keep_best(width, [](const Score& x) { return Fields{x.on_course, x.reach, x.end}; });
      layer.swap(next);
    }
    return furthest < 0 ? std::vector<Chosen>{} : chain_to(nodes, furthest);
  }

  /// Whether the input runs straight from vertex v for kStraightAheadMm (or to `limit`): every
  /// vertex up to there within the band of the chord there.
  bool straight_ahead(uint32_t v, uint32_t limit) const {
    uint32_t e = v + 1;
    while (e < limit && (q(e) - q(v)).squaredNorm() < kStraightAheadMm * kStraightAheadMm) ++e;
    const Vec2 chord = q(e) - q(v);
    const double len = chord.norm();
    if (len <= kLengthEpsMm) return false;
    for (uint32_t m = v + 1; m < e; ++m)
      if (std::abs(cross2(chord, q(m) - q(v))) > eps_ * len) return false;
    return true;
  }

  /// Candidate `cd` from node `nd` along `T` (its tangent, or that turned at the joint),
  /// checked exactly, and held to the joint allowance: a line's chord may lie off T by the
  /// line allowance, on top of the turn. (The beam's and the layered search's.)
  std::optional<Chosen> made_from(const Node& nd, const Vec2& T, const Candidate& cd) const {
    auto c = make(nd.v, T, cd);
    if (c && !joint_cone_.holds(nd.T, start_tangent(*c, nd.v))) return std::nullopt;
    return c;
  }

  /// The beam search's chain from `a` to `limit`. Where no chain goes on tangentially, the
  /// tangent breaks at the furthest one's end (counted in `forced`) and the search restarts.
  std::vector<Chosen> beam_stretch(uint32_t a, uint32_t limit, GreedyWalk& greedy, size_t& forced) const {
    std::vector<Chosen> chain;
    while (a < limit) {
      // After the first part, the tangent breaks where the chain before could not go on; the
      // first part breaks it only when nothing leaves along the incoming tangent.
      bool breaks = !chain.empty();
      auto part = beam_chain(a, limit, chain.empty() ? &greedy : nullptr);
      if (part.empty()) {
        part.push_back(best_free(a, limit));
        breaks = breaks || arrives_along(a);
      }
      part.front().kinked = breaks;
      if (breaks) ++forced;
      chain.insert(chain.end(), part.begin(), part.end());
      a = part.back().prim.end_vertex;
    }
    return chain;
  }

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
  /// reaches `limit` tangentially.
  std::vector<Chosen> layered_chain(uint32_t a, uint32_t limit) const {
    std::vector<Node> states;
    std::vector<int> layer, next;
    std::vector<Vec2> starts;
    // Where the tangent is free, from the input's own directions fanned out, not from the
    // beam's starts: those reach further in one primitive, and the later layers, which take
    // only ends at or past the furthest vertex reached, then lose the chains that started
    // shorter (plum at 0.01 mm with the global method: 37 blocks instead of 35).
    if (arrives_along(a)) {
      roots(a, limit, starts);
    } else {
      fanned_input_tangents(a, limit, starts);
      if (auto T = into_next(a, limit)) starts.push_back(*T);
    }
    for (const Vec2& T : starts) {
      states.push_back({{}, -1, a, T});
      layer.push_back(static_cast<int>(states.size()) - 1);
    }
    const double bin_rad = kTangentBinShare * deg_to_rad(o_.g1_angle_deg);
    const size_t max_states = kMaxStatesPerVertex * (limit - a) + states.size();
    std::unordered_set<uint64_t> seen;
    std::vector<Candidate> cand;
    uint32_t front = a, advance = 0;  // the layer's furthest vertex, and how far it moved
    while (!layer.empty()) {
      next.clear();
      uint32_t next_front = front;
      // A state reached by a primitive goes on along its end tangent, or turned at the joint
      // by all of kJointShare of the G1 angle either way (the turns between come in through
      // the states' own spread of tangents).
      for (int i : layer) {
        for (const Turn* turn : {(const Turn*)nullptr, &full_left_, &full_right_}) {
          if (turn && states[i].parent < 0) break;
          const uint32_t v = states[i].v;
          const Vec2 T = turn ? (*turn)(states[i].T) : states[i].T;
          cand.clear();  // only the ends at or beyond the front are taken
          scan_ends(v, T, limit, [&](const Candidate& c) {
            if (c.e >= front) cand.push_back(c);
          });
          for (size_t k = cand.size(); k-- > 0;) {  // furthest first
            const Candidate& c = cand[k];
            const uint32_t group = std::max<uint32_t>(1, std::max(advance, next_front - front) / kLayerGroups);
            const Vec2 end = unchecked(v, T, c).end_tangent;
            const long bin = std::lround(std::atan2(end.y(), end.x()) / bin_rad);
            const uint64_t key = (uint64_t(c.e - c.e % group) << 32) | uint32_t(bin);  // group's first vertex
            if (c.e < limit && seen.count(key)) continue;
            auto made = made_from(states[i], T, c);
            if (!made) continue;
            states.push_back({*made, i, c.e, made->end_tangent});
            const int id = static_cast<int>(states.size()) - 1;
            if (c.e >= limit) return chain_to(states, id);
            seen.insert(key);
            next.push_back(id);
            next_front = std::max(next_front, c.e);
          }
        }
        if (states.size() > max_states) return {};
      }
      advance = next_front - front;
      front = next_front;
      layer.swap(next);
    }
    return {};
  }

  static std::vector<Chosen> chain_to(const std::vector<Node>& nodes, int id) {
    std::vector<Chosen> chain;
    for (; nodes[id].parent >= 0; id = nodes[id].parent) chain.push_back(nodes[id].last);
    std::reverse(chain.begin(), chain.end());
    return chain;
  }

  static Vec2 rotated(const Vec2& T, double rad) { return Turn(rad)(T); }

  /// The input's own directions at `a`, where the tangent is free: those of circles through
  /// the next vertices, of the first chord, and of the input around `a` inside the stretch.
  void input_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
    out.clear();
    for (uint32_t w : {2u, 4u, 8u, 16u}) {
      if (a + w > limit) break;
      if (auto t = circle_tangent(q(a), q(a + w / 2), q(a + w))) out.push_back(*t);
    }
    Vec2 chord = q(a + 1) - q(a);
    if (chord.norm() > kLengthEpsMm) out.push_back(chord.normalized());
    if (auto t = input_tangent(a, stretch_start_, limit)) out.push_back(*t);
    // Where the path leaves `a` along the plane's normal (a plunge), it has no direction in
    // the plane: any will do for the lines that follow it.
    if (out.empty()) out.push_back(Vec2(1, 0));
  }

  /// Whether the chain arrives at `a` with a tangent it must follow: the start of a stretch
  /// after a fixed move where the path is smooth.
  bool arrives_along(uint32_t a) const { return a == stretch_start_ && in_tangent_.has_value(); }

  /// Where the searches start at `a`: the tangents a smooth joint allows after the incoming
  /// one (turned by no more than a line's chord may add to stay within kJointShare of the
  /// G1 angle), else start_tangents().
  void roots(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
    out.clear();
    if (!arrives_along(a)) return start_tangents(a, limit, out);
    out.push_back(*in_tangent_);
    for (const Turn& turn : root_turns_) out.push_back(turn(*in_tangent_));
  }

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
  void start_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
    const size_t first = out.size();
    auto add = [&](const Vec2& T) {
      for (size_t i = first; i < out.size(); ++i)
        if (same_tangent_cone_.holds(out[i], T)) return;
      out.push_back(T);
    };
    // The two starts that end at r.e turned furthest either way (kStartRangeInset inside).
    auto put_edges = [&](const StartRange& r, bool middle) {
      add(range_start(a, r, kStartRangeInset));
      add(range_start(a, r, 1 - kStartRangeInset));
      if (middle) add(range_start(a, r, 0.5));
    };
    // A line's tangent is its chord: the one to the furthest end a line reaches (the scan
    // along it offers the lines a vertex or two shorter too). First, so that where a line
    // and an arc do as well, the line is kept.
    if (const uint32_t line_end = furthest_line_end(a, limit); line_end > a) add((q(line_end) - q(a)).normalized());
    // The ends reached, in the order found: the nearest one by one, then the furthest
    // (furthest_reached()) and the one before it.
    std::vector<StartRange>& reached = s_.reached;
    reached.clear();
    auto reach = [&](uint32_t e) {
      if (soft_between(a, e)) return false;
      const auto [lo, hi] = start_range(a, e);
      if (lo <= hi) reached.push_back({e, lo, hi});
      return lo <= hi;
    };
    int misses = 0;  // ends in a row that no start reaches (a later one may be reached again)
    uint32_t e = a + 1;
    for (; e <= limit && reached.size() < kNearStartEnds && misses < 2; ++e) {
      misses = reach(e) ? 0 : misses + 1;
      if (misses == 0) put_edges(reached.back(), false);
    }
    if (reached.size() == kNearStartEnds && e <= limit) {
      const uint32_t far = furthest_reached(e - 1, limit, reach);
      if (far - 1 > a && reached.back().e != far - 1) reach(far - 1);
    }
    std::sort(reached.begin(), reached.end(), [](const StartRange& x, const StartRange& y) { return x.e > y.e; });
    for (size_t i = 0; i < std::min(kFarStartEnds, reached.size()); ++i) put_edges(reached[i], i == 0);
    if (auto T = into_next(a, limit)) add(*T);
    // Where the path leaves `a` along the plane's normal (a plunge), it has no direction in
    // the plane: any will do for the lines that follow it.
    if (out.size() == first) out.push_back(Vec2(1, 0));
  }

  /// The start at `a` in range `r` at `share` of the way from its lowest angle to its
  /// highest.
  Vec2 range_start(uint32_t a, const StartRange& r, double share) const {
    return Turn(r.lo + share * (r.hi - r.lo))((q(r.e) - q(a)).normalized());
  }

  /// The furthest vertex e after `a` (up to `limit`) whose chord from `a` passes within the
  /// band of every vertex between (furthest_reached()); `a` itself when the first move has
  /// no length in the plane.
  uint32_t furthest_line_end(uint32_t a, uint32_t limit) const {
    auto reaches = [&](uint32_t e) {
      const Vec2 chord = q(e) - q(a);
      const double length = chord.norm();
      if (length <= kLengthEpsMm || soft_between(a, e)) return false;
      for (uint32_t m = a + 1; m < e; ++m)
        if (std::abs(cross2(chord, q(m) - q(a))) > eps_ * length) return false;
      return true;
    };
    return reaches(a + 1) ? furthest_reached(a + 1, limit, reaches) : a;
  }

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
  std::pair<double, double> start_range(uint32_t a, uint32_t e) const {
    const Vec2 chord = q(e) - q(a);
    const double length = chord.norm();
    if (length <= kLengthEpsMm) return {1, -1};
    const Vec2 c = chord / length;
    bool flat = true;
    for (uint32_t m = a + 1; m <= e && flat && !level_; ++m) flat = std::abs(p_[m].z() - p_[a].z()) <= kLengthEpsMm;
    const double eps = flat ? eps_ : eps_ * kPlaneShare;
    // Directions (cos α, sin α) in (−π, π), ordered by their pseudo-angle turned half a turn.
    auto order = [](const Vec2& d) { return pseudo_angle(-d.x(), -d.y()); };
    Vec2 lo(start_sweep_.c, -start_sweep_.s), hi(start_sweep_.c, start_sweep_.s);
    double lo_order = order(lo), hi_order = order(hi);
    // Points 2a+1, 2a+2, ..., 2e-1: odd ones the move middles, even ones the vertices.
    for (uint32_t j = 2 * a + 1; j < 2 * e; ++j) {
      const Vec2 u = ((j & 1) ? middle_[j / 2] : q(j / 2)) - q(a);
      const double w = u.squaredNorm() - eps * eps;
      if (w <= 0) continue;  // within the band of `a` itself
      const double P = w / length - u.dot(c), Q = cross2(c, u);
      const double R2 = P * P + Q * Q;
      if (R2 <= eps * eps) continue;
      const double R = std::sqrt(R2), sin_half = eps / R, cos_half = std::sqrt(1 - sin_half * sin_half);
      // The zero of sin(α + β), α = −β, taken in (−π/2, π/2].
      const Vec2 zero = P > 0 || (P == 0 && Q <= 0) ? Vec2(P / R, -Q / R) : Vec2(-P / R, Q / R);
      const Vec2 low = Turn::by(cos_half, -sin_half)(zero), high = Turn::by(cos_half, sin_half)(zero);
      if (const double o = order(low); o > lo_order) {
        lo = low;
        lo_order = o;
      }
      if (const double o = order(high); o < hi_order) {
        hi = high;
        hi_order = o;
      }
      if (lo_order > hi_order) return {1, -1};
    }
    return {std::atan2(lo.y(), lo.x()), std::atan2(hi.y(), hi.x())};
  }

  /// The input's own directions at `a` (input_tangents()), each also turned by 0.5°, 1°, 2°
  /// and 4° either way; appended to `out`. The layered search's starts where the tangent is
  /// free.
  void fanned_input_tangents(uint32_t a, uint32_t limit, std::vector<Vec2>& out) const {
    input_tangents(a, limit, s_.inputs);
    for (const Vec2& T : s_.inputs) {
      out.push_back(T);
      for (const Turn& turn : fan_turns_) out.push_back(turn(T));
    }
  }

  /// The start at `a` whose arc over the first move ends heading along the second: where the
  /// input turns at a + 1 (a slicer's infill between two corners, a short move into a long
  /// one), the one start from which the second move follows as a line, tangent.
  std::optional<Vec2> into_next(uint32_t a, uint32_t limit) const {
    if (a + 2 > limit) return std::nullopt;
    const Vec2 next = q(a + 2) - q(a + 1);
    if (next.norm() <= kLengthEpsMm) return std::nullopt;
    return reflected_end(a, next.normalized(), a + 1);
  }

  /// Start of a smooth stretch (or after a forced kink): try a few start tangents read off
  /// the input, and the one into the second move, and keep the one whose primitive reaches
  /// furthest.
  Chosen best_free(uint32_t a, uint32_t limit) const {
    std::optional<Chosen> best;
    Score best_score;
    input_tangents(a, limit, s_.free_starts);
    if (auto T = into_next(a, limit)) s_.free_starts.push_back(*T);
    for (const Vec2& T : s_.free_starts) consider(a, T, limit, best, best_score);
    if (best) return *best;
    return input_move(a);
  }

  /// A stretch of the one move from vertex a: the move itself, or, where a fixed move's
  /// direction is to be met at either end (in_tangent_, out_tangent_), the arc over it that
  /// meets both within the joint's turn, when the band and the options allow it. (The input
  /// turns there by less than a corner; kept as a line, the joint would break.)
  Chosen one_move(uint32_t a) const {
    const uint32_t e = a + 1;
    std::optional<Vec2> T;
    if (in_tangent_) {
      T = aimed(a, *in_tangent_, e, out_tangent_);
    } else if (out_tangent_) {
      T = reflected_end(a, *out_tangent_, e);
    }
    if (T)
      if (auto c = through(a, *T, e);
          c && (!in_tangent_ || joint_cone_.holds(*in_tangent_, start_tangent(*c, a))) &&
          (!out_tangent_ || joint_cone_.holds(c->end_tangent, *out_tangent_)))
        return *c;
    return input_move(a);
  }

  /// The input's own move from vertex a to a + 1 as a line: always inside the band.
  Chosen input_move(uint32_t a) const {
    Vec2 chord = q(a + 1) - q(a);
    Chosen line;
    line.prim = {a + 1, Primitive::Kind::Line};
    line.end_tangent = chord.norm() > kLengthEpsMm ? Vec2(chord.normalized()) : Vec2(1, 0);
    return line;
  }

  /// Tangent at p0 of the circle through p0, p1, p2, pointing towards p1.
  static std::optional<Vec2> circle_tangent(const Vec2& p0, const Vec2& p1, const Vec2& p2) {
    Vec2 a = p1 - p0, b = p2 - p0;
    double d = 2 * cross2(a, b);
    if (a.norm() <= kLengthEpsMm || b.norm() <= kLengthEpsMm) return std::nullopt;
    // In a line: along it, towards p1 (p2 may lie on either side).
    if (std::abs(d) <= 1e-12 * a.norm() * b.norm()) return Vec2(b.dot(a) < 0 ? -b.normalized() : b.normalized());
    Vec2 c(( b.y() * a.squaredNorm() - a.y() * b.squaredNorm()) / d,
           (-b.x() * a.squaredNorm() + a.x() * b.squaredNorm()) / d);  // centre relative to p0
    Vec2 t = left_normal(-c).normalized();
    if (t.dot(a) < 0) t = -t;
    return t;
  }

  const FitOptions& o_;
  Scratch& s_ = thread_scratch();
  RunBuffers& b_ = s_.run;
  std::vector<uint32_t>& at_ = b_.at;  // the run's vertex of each vertex the fitter works on (vertices_kept())
  uint32_t n_ = 0;                // moves the fitter works on: at_.size() - 1
  std::vector<Vec3>& p_ = b_.p;   // vertices in plane coordinates (first, second, normal)
  // The same in the plane, stored as such: the scans read them as whole vectors, where
  // building each from p_ would stall on the store that assembles it.
  std::vector<Vec2>& q_ = b_.q;
  std::vector<Vec2>& middle_ = b_.middle;  // the middle of each move in the plane
  bool level_ = true;             // every vertex at the same height (within kLengthEpsMm)
  std::vector<uint8_t>& hard_ = b_.hard;  // corner: tangent may change, a primitive ends here
  std::vector<uint8_t>& plain_hard_ = b_.plain_hard;  // with spikes found: the corners with none skipped
  std::vector<uint8_t>& soft_ = b_.soft;  // extrusion rate changes: a primitive ends here, tangent kept
  std::vector<uint32_t>& next_soft_ = b_.next_soft;  // the first soft vertex after each vertex (n_ + 1: none)
  // The input's direction at each vertex inside the stretch: sided_tangent() for the
  // searches; the greedy chain, which never goes back on a choice, keeps input_tangent()
  // (with the sided one it breaks the tangent on Bézier 1 at 0.001 mm and y = x³ at 0.01 mm,
  // where the searches find tangent chains, though it needs 1 % fewer blocks on the corpus).
  std::vector<std::optional<Vec2>>& heading_ = b_.heading;
  std::vector<FixedMove>& fixed_ = b_.fixed;  // per move
  uint32_t stretch_start_ = 0;    // first vertex of the current stretch (after a corner or fixed move)
  uint32_t stretch_end_ = 0;      // its last vertex (a corner, a fixed move's start, or the end)
  std::optional<Vec2> in_tangent_, out_tangent_;  // directions of the fixed moves around it, where smooth
  uint64_t stretch_id_ = 0;       // this stretch's number on the thread (GuideScan::stretch)
  ScanLimits lim_{};              // what the scans hold each end to in it: scan_limits(), worked out once a stretch
  double eps_ = 0;                // band the fitter works to, mm
  bool arcs_ = true;               // arcs allowed: by the options, and in this run by its extra axes
  std::vector<int> extra_;         // the extra axes (kA .. kW) that move in the run
  std::vector<double>& extra_values_ = b_.extra_values;  // their values at each vertex, extra_.size() per vertex
  std::vector<double>& length_ = b_.length;  // path length from vertex 0 to each vertex (mm), when extra_ move
};

}  // namespace

double normal_axis_spread_mm(const FitOptions& o) {
  // A vertex and the height carried between two vertices of the stretch both lie within its
  // spread, so the height check of make_arc() holds at every vertex.
  return o.helical ? o.tolerance_mm * (1.0 - kRoundingReserve) * kHeightShare : 0.0;
}

std::vector<FitResult> fit_chain(const Interpretation& in, const RunChain& chain, std::span<const Run> runs,
                                 const std::function<FitOptions(const Run&)>& options_for) {
  std::span<const Run> own(&runs[chain.first_run], chain.run_count);
  // The keep method: every move its own line, with none of the fit's preparation (the
  // corner rule, the vertices where a primitive must end), so that the pipeline it times is
  // the one without the fitter.
  if (chain.run_count > 0 && options_for(own[0]).method == FitOptions::Method::Keep) {
    std::vector<FitResult> kept(own.size());
    for (size_t r = 0; r < own.size(); ++r)
      for (uint32_t v = 1; v <= own[r].move_count; ++v) kept[r].prims.push_back({v, Primitive::Kind::Line});
    return kept;
  }
  const Move& lead = in.moves[chain.first_move];
  auto base = [&](size_t r) { return own[r].first_move - chain.first_move; };
  auto direction = [](const Vec2& d) -> std::optional<Vec2> {
    if (d.norm() <= kLengthEpsMm) return std::nullopt;
    return Vec2(d.normalized());
  };
  // The ends of each run's fit once made: the chain's vertices of its first and of its last
  // primitive, where that primitive is a line (an arc in another plane leaves the joint
  // unmeasured, as the verifier does).
  struct LineEnds {
    uint32_t from, to;
  };
  std::vector<std::optional<LineEnds>> first_line(own.size()), last_line(own.size());
  std::vector<uint8_t> done(own.size(), 0);
  std::vector<FitResult> out(own.size());

  // The runs in `plane` fitted together, every other move of the chain left as it is: lone
  // moves and input arcs with their own directions, runs already fitted with the directions
  // of their end lines, runs still to be fitted (in another plane) with none.
  auto fit_plane = [&](Plane plane) {
    Run all;  // the chain as one run in `plane`
    all.first_move = chain.first_move;
    all.move_count = chain.move_count;
    all.frame = lead.frame;
    all.plane = plane;
    all.feed_mm_min = lead.feed_mm_min;
    const auto ax = axes_of(plane);
    auto at = [&](uint32_t v) {  // vertex v of the chain in the plane
      const auto& p = all.vertex(in, v);
      return Vec2(p[ax.first], p[ax.second]);
    };
    std::vector<FixedMove> fixed(chain.move_count);
    std::vector<uint8_t> pinned(chain.move_count + 1, 0);
    for (uint32_t m = 0; m < chain.move_count; ++m) fixed[m].fixed = true;
    for (size_t r = 0; r < own.size(); ++r)
      if (own[r].plane == plane)
        for (uint32_t m = base(r); m < base(r) + own[r].move_count; ++m) fixed[m].fixed = false;
    // (The directions of the moves fitted here are not read.)
    for (uint32_t m = 0; m < chain.move_count; ++m) {
      if (!fixed[m].fixed) continue;
      const Move& mv = in.moves[chain.first_move + m];
      if (!is_arc(mv.kind)) {
        fixed[m].start = fixed[m].end = direction(at(m + 1) - at(m));
      } else if (mv.plane == plane) {
        const Vec2 c(mv.center[ax.first], mv.center[ax.second]);
        auto along = [&](const Vec2& radius) -> std::optional<Vec2> {
          if (radius.norm() <= kLengthEpsMm) return std::nullopt;
          return arc_tangent(radius, mv.kind == MoveKind::ArcCCW);
        };
        fixed[m].start = along(at(m) - c);
        fixed[m].end = along(at(m + 1) - c);
      }
    }
    for (size_t r = 0; r < own.size(); ++r) {
      const uint32_t b = base(r), last = b + own[r].move_count - 1;
      pinned[b] = pinned[last + 1] = 1;
      if (own[r].plane == plane) continue;
      for (uint32_t m = b; m < last; ++m) fixed[m].end = fixed[m + 1].start = std::nullopt;
      fixed[b].start = fixed[last].end = std::nullopt;
      if (!done[r]) continue;
      // (A line that stands for one move that goes somewhere is that move: its joints are the input's.)
      auto several = [&](const LineEnds& l) { return in.moves_going(chain.first_move + l.from, chain.first_move + l.to) > 1; };
      if (const auto& l = first_line[r]) {
        fixed[b].start = direction(at(l->to) - at(l->from));
        fixed[b].fitted_start = fixed[b].start && several(*l);
      }
      if (const auto& l = last_line[r]) {
        fixed[last].end = direction(at(l->to) - at(l->from));
        fixed[last].fitted_end = fixed[last].end && several(*l);
      }
    }
    for (uint32_t m = 0; m < chain.move_count; ++m)
      if (fixed[m].fixed) pinned[m] = pinned[m + 1] = 1;
    std::vector<Chosen> fitted = RunFitter(in, all, options_for(all), fixed, std::move(pinned)).fit();
    // Back to each run's own vertices. A tangent break at the start of a fixed move is the
    // joint at the end of the run before it, or at the start of the run it begins.
    size_t r = 0;  // the first run that does not end at or before `from`
    uint32_t from = 0;
    for (const Chosen& c : fitted) {
      while (r < own.size() && base(r) + own[r].move_count <= from) ++r;
      if (!fixed[from].fixed) {
        if (!first_line[r] && from == base(r) && c.prim.kind == Primitive::Kind::Line)
          first_line[r] = LineEnds{from, c.prim.end_vertex};
        if (c.prim.end_vertex == base(r) + own[r].move_count)
          last_line[r] = c.prim.kind == Primitive::Kind::Line ? std::optional(LineEnds{from, c.prim.end_vertex}) : std::nullopt;
        Primitive p = c.prim;
        p.end_vertex -= base(r);
        out[r].prims.push_back(p);
        if (c.kinked) out[r].forced_at.push_back(from - base(r));
      } else if (c.kinked && r > 0 && base(r - 1) + own[r - 1].move_count == from) {
        out[r - 1].forced_at.push_back(own[r - 1].move_count);
      } else if (c.kinked && r < own.size() && base(r) == from) {
        out[r].forced_at.push_back(0);
      }
      from = c.prim.end_vertex;
    }
    for (size_t k = 0; k < own.size(); ++k) done[k] = done[k] || own[k].plane == plane;
  };
  // Runs in other planes than the chain's first, plane by plane, then the chain's plane,
  // which meets their end lines tangentially.
  for (size_t r = 0; r < own.size(); ++r)
    if (!done[r] && own[r].plane != lead.plane) fit_plane(own[r].plane);
  fit_plane(lead.plane);
  // The passes report a run's joints in their own order, a joint beside another plane's run
  // possibly twice.
  for (FitResult& f : out) {
    std::sort(f.forced_at.begin(), f.forced_at.end());
    f.forced_at.erase(std::unique(f.forced_at.begin(), f.forced_at.end()), f.forced_at.end());
  }
  return out;
}

}  // namespace arcpress
