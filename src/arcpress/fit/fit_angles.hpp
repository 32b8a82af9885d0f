// SPDX-License-Identifier: GPL-3.0-or-later
#pragma once
// The angles the fitter turns by and the cones it tests tangents against, worked out once
// from the options' angles (private to fit/).
#include <array>
#include <cmath>

#include "arcpress/core/deviation.hpp"
#include "arcpress/fit/primitive.hpp"

namespace arcpress::fit_detail {

/// Share of the G1 angle by which the fitter may turn the tangent at a smooth joint; printing
/// the arc centres may turn each side by a little more (the emitter re-checks that).
constexpr double kJointShare = 0.9;
/// Share of the G1 angle by which the greedy step first turns the tangent at a joint, each
/// way; twice this (kJointShare) is its largest turn, and the searches' turn.
constexpr double kTurnShare = 0.45;
/// The searches turn a chain's tangent at a joint by the whole allowance and, where that is
/// wide, by halves of it down to about this (degrees; the whole turn of the default 0.5°
/// G1 angle): a wider allowance adds finer turns, so it never offers fewer than a narrower.
constexpr double kFinestJointTurnDeg = 0.45;
/// A primitive whose end tangent is within this of the input's direction is "on course".
constexpr double kOnCourseRad = 1.5 * kPi / 180;

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
      : g1_angle_deg_(o.g1_angle_deg),
        max_sweep_deg_(o.max_sweep_deg),
        min_sweep_deg_(o.min_sweep_deg),
        method_(o.method) {
    line_kink_ = deg_to_rad(std::min(o.g1_angle_deg, 2 * kFinestJointTurnDeg)) / 4;
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
    joint_turns_.clear();
    for (double t = 2 * kTurnShare * g1;; t /= 2) {
      joint_turns_.push_back(Turn(t));
      joint_turns_.push_back(Turn(-t));
      if (t / 2 < deg_to_rad(kFinestJointTurnDeg) * (1 - 1e-9)) break;
    }
    g1_cone_ = Cone(g1);
    same_tangent_cone_ = Cone(deg_to_rad(std::min(o.g1_angle_deg, 2 * kFinestJointTurnDeg)) / 32);
    // (The margin keeps the largest turn the searches make from failing by rounding.)
    joint_cone_ = Cone(kJointShare * g1 + 1e-9);
    joint_miss_ = 1 - std::cos(kJointShare * g1);
    closer_miss_ = 1 - std::cos(kJointShare * g1 / 4);
    on_course_cone_ = Cone(kOnCourseRad);
    turn_cone_ = Cone(kTurnShare * g1);
    near_turn_cone_ = Cone(kTurnShare * g1 + 1e-9);
    turn_line_cone_ = Cone(kTurnShare * g1 + line_kink_);
    two_turns_line_cone_ = Cone(2 * kTurnShare * g1 + line_kink_);
    // (Where the allowance is wide, halves of the smaller turn too, down to its size at the
    // default angle.)
    root_turns_ = {Turn(0.3 * g1), Turn(-0.3 * g1), Turn(0.6 * g1), Turn(-0.6 * g1)};
    for (double t = 0.15 * g1; t >= 0.3 * deg_to_rad(2 * kFinestJointTurnDeg) * (1 - 1e-9); t /= 2) {
      root_turns_.push_back(Turn(t));
      root_turns_.push_back(Turn(-t));
    }
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
  Turn half_left_,
      half_right_;  // kTurnShare of the G1 angle each way: the greedy step's first turns, the beam's for lines
  Turn full_left_, full_right_;     // twice that, the whole joint allowance: its largest, and the searches' turn
  std::vector<Turn> joint_turns_;   // the searches' turns at a joint: the whole allowance, then halves (kFinestJointTurnDeg)
  std::array<Turn, 4> near_turns_;  // best_near(): the first near_turn_count_ of them
  size_t near_turn_count_ = 0;
  std::vector<Turn> root_turns_;    // roots(): 0.3 and 0.6 of it each way (and halves of 0.3 where wide)
  Turn start_sweep_;                // start_range(): half the largest sweep, at most a quarter turn
  std::array<Turn, 8> fan_turns_;   // fanned_input_tangents(): 0.5, 1, 2 and 4 degrees each way
  Cone g1_cone_;                    // the G1 angle: a joint within it is smooth
  Cone same_tangent_cone_;          // 1/32 of it: two tangents a search need not both follow
  Cone joint_cone_;                 // kJointShare of it: the turn the fitter may make at a joint
  // pick(): 1 - cos of that turn, and of a quarter of it (closer by more than the printed
  // digits can tilt the input's direction: past a straight side's end, along a side whose
  // every vertex heads exactly along it, the walk back would go on into the side).
  double joint_miss_ = 0, closer_miss_ = 0;
  Cone on_course_cone_;                                    // kOnCourseRad: a primitive ending along the input
  Cone turn_cone_, turn_line_cone_, two_turns_line_cone_;  // tighten(): one turn, plus a line's, two plus a line's
  // turn_cone_ with a margin for the rounding between an unchecked end tangent and the checked one
  Cone near_turn_cone_;
  double line_kink_ = 0;                                   // largest tangent-chord angle written as a line, rad
  double max_alpha_ = 0, min_alpha_ = 0, line_alpha_ = 0;  // pseudo-angles, see FitAngles()
};

}  // namespace arcpress::fit_detail
