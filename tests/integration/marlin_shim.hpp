// SPDX-License-Identifier: GPL-3.0-or-later
// What Marlin's Marlin/src/gcode/motion/G2_G3.cpp needs of the rest of the firmware, so that
// its own plan_arc() and GcodeSuite::G2_G3() build on a PC (marlin_executed.sh puts this
// header before the file with -include; the headers it includes are left empty). Prusa's
// Buddy firmware's copy of the file (lib/Marlin/Marlin/src/gcode/motion/G2_G3.cpp) builds
// with it too. The configuration is Marlin 2.1's default (Configuration_adv.h: ARC_SUPPORT
// with MIN_ARC_SEGMENT_MM 0.1, MAX_ARC_SEGMENT_MM 1.0, MIN_CIRCLE_SEGMENTS 72,
// N_ARC_CORRECTION 25; no ARC_SEGMENTS_PER_SEC, ARC_P_CIRCLES, CNC_WORKSPACE_PLANES or
// leveling), each number settable with -D (Buddy's MAX_ARC_DEVIATION and
// MIN_ARC_SEGMENTS_PER_SEC too). The macros and types below do what Marlin's core/macros.h
// and core/types.h do for the words the file uses, in single precision as the firmware
// computes.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>

// --- configuration ---------------------------------------------------------------------
#define ARC_SUPPORT 1
#ifndef MIN_ARC_SEGMENT_MM
#define MIN_ARC_SEGMENT_MM 0.1
#endif
#ifndef MAX_ARC_SEGMENT_MM
#define MAX_ARC_SEGMENT_MM 1.0
#endif
#ifndef MIN_CIRCLE_SEGMENTS
#define MIN_CIRCLE_SEGMENTS 72
#endif
#ifndef N_ARC_CORRECTION
#define N_ARC_CORRECTION 25
#endif
// Options off in the default configuration (each must be 0 or 1: ENABLED() reads it).
#define CNC_WORKSPACE_PLANES 0
#define ARC_P_CIRCLES 0
#define SF_ARC_FIX 0
#define DELTA 0
#define SCARA 0
#define SCARA_FEEDRATE_SCALING 0
#define AUTO_BED_LEVELING_UBL 0
#define FULL_REPORT_TO_HOST_FEATURE 0
#define CANCEL_OBJECTS 0
#define FEEDRATE_SCALING 0
#define HAS_LEVELING 0
#define PLANNER_LEVELING 0
#define HAS_Z_AXIS 1
#define HAS_EXTRUDERS 1
#define LINEAR_AXES 3  // (Marlin 2.0.9 to 2.1.0; later NUM_AXES)
#define NUM_AXES 3

// --- core/macros.h ---------------------------------------------------------------------
#define ENABLED(O) (O)
#define DISABLED(O) (!(O))
#define MARLIN_CAT_(a, b) a##b
#define MARLIN_CAT(a, b) MARLIN_CAT_(a, b)
#define TERN_(O, A) MARLIN_CAT(MARLIN_TERN_, O)(A)
#define MARLIN_TERN_0(A)
#define MARLIN_TERN_1(A) A
#define TERN0(O, A) MARLIN_CAT(MARLIN_TERN0_, O)(A)
#define MARLIN_TERN0_0(A) 0
#define MARLIN_TERN0_1(A) (A)
#define OPTARG(O, ...) MARLIN_CAT(MARLIN_OPTARG_, O)(__VA_ARGS__)
#define MARLIN_OPTARG_0(...)
#define MARLIN_OPTARG_1(...) , __VA_ARGS__
#define MARLIN_SUB2_CAT_(a, b) a##b
#define MARLIN_SUB2_CAT(a, b) MARLIN_SUB2_CAT_(a, b)
#define SUB2(N) MARLIN_SUB2_CAT(MARLIN_SUB2_, N)
#define MARLIN_SUB2_3 1
#define CODE_N(N, ...) MARLIN_CAT(MARLIN_CODE_N_, N)(__VA_ARGS__)
#define MARLIN_CODE_N_1(A, ...) A
#define GANG_N(N, ...) MARLIN_CAT(MARLIN_GANG_N_, N)(__VA_ARGS__)
#define MARLIN_GANG_N_1(A, ...) A
#define CODE_ITEM_E(A) A

#define WITHIN(N, L, H) ((N) >= (L) && (N) <= (H))
#define NEAR_ZERO(x) WITHIN(x, -0.000001f, 0.000001f)
#define NEAR(x, y) NEAR_ZERO((x) - (y))
#define RECIPROCAL(x) (NEAR_ZERO(x) ? 0 : (1 / float(x)))
#define RADIANS(d) ((d) * float(M_PI) / 180.0f)
#define ATAN2(y, x) atan2f(y, x)
#define SQRT(x) sqrtf(x)
#define CEIL(x) ceilf(x)
#define FLOOR(x) floorf(x)
#define HYPOT2(x, y) (sq(x) + sq(y))
#define HYPOT(x, y) SQRT(HYPOT2(x, y))
template <class T> constexpr T sq(T x) { return x * x; }
template <class T> constexpr T ABS(const T v) { return v >= 0 ? v : -v; }
template <class L, class R> constexpr auto _MAX(const L lhs, const R rhs) -> decltype(lhs + rhs) {
  return lhs > rhs ? lhs : rhs;
}
template <class L, class R> constexpr auto _MIN(const L lhs, const R rhs) -> decltype(lhs + rhs) {
  return lhs < rhs ? lhs : rhs;
}
template <class V, class L, class H> constexpr V constrain(V v, L lo, H hi) { return v < lo ? lo : v > hi ? hi : v; }
// Buddy's feature/precise_stepping/internal.hpp: the FPU's square root (vsqrt.f32), as sqrtf.
inline float fast_sqrt(float in) { return sqrtf(in); }
using std::cos;
using std::sin;

// --- core/types.h ------------------------------------------------------------------------
enum AxisEnum : uint8_t { X_AXIS, Y_AXIS, Z_AXIS, E_AXIS };
struct xyze_pos_t {
  float x = 0, y = 0, z = 0, e = 0;
  float& operator[](int a) { return a == X_AXIS ? x : a == Y_AXIS ? y : a == Z_AXIS ? z : e; }
  const float& operator[](int a) const { return a == X_AXIS ? x : a == Y_AXIS ? y : a == Z_AXIS ? z : e; }
};
struct xy_pos_t {
  float x = 0, y = 0;
  xy_pos_t() = default;
  xy_pos_t(float px, float py) : x(px), y(py) {}
  xy_pos_t(const xyze_pos_t& p) : x(p.x), y(p.y) {}
  bool operator!=(const xy_pos_t& o) const { return x != o.x || y != o.y; }
  xy_pos_t operator-(const xy_pos_t& o) const { return {x - o.x, y - o.y}; }
  xy_pos_t operator+(const xy_pos_t& o) const { return {x + o.x, y + o.y}; }
  xy_pos_t operator*(float s) const { return {x * s, y * s}; }
  xy_pos_t operator/(float s) const { return {x / s, y / s}; }
  float magnitude() const { return sqrtf(x * x + y * y); }
};
struct ab_float_t {
  float a = 0, b = 0;
  ab_float_t() = default;
  ab_float_t(float pa, float pb) : a(pa), b(pb) {}
  ab_float_t(const xy_pos_t& p) : a(p.x), b(p.y) {}
  ab_float_t operator-() const { return {-a, -b}; }
  explicit operator bool() const { return a || b; }
  float operator[](int i) const { return i == 0 ? a : b; }
};
typedef float feedRate_t;
typedef uint32_t millis_t;

// --- the firmware around the file --------------------------------------------------------
extern xyze_pos_t current_position, destination;
extern feedRate_t feedrate_mm_s;
extern uint8_t active_extruder;
#define MMS_SCALED(V) (V)
#define MOTION_CONDITIONS true
#define STR_ERR_ARC_ARGS "G2/G3 bad parameters"
void marlin_error(const char* message);
#define SERIAL_ERROR_MSG(S) marlin_error(S)
millis_t millis();
#define ELAPSED(NOW, SOON) (int32_t((NOW) - (SOON)) >= 0)
void idle(bool = false);
inline void apply_motion_limits(xyze_pos_t&) {}
void planned_line(const xyze_pos_t& p);
struct Planner {
  template <class... Rest> bool buffer_line(const xyze_pos_t& p, Rest...) { planned_line(p); return true; }
};
struct PlannerHints {  // (Buddy: what the planner may know of the move)
  float inv_duration = 0, curve_radius = 0, safe_exit_speed_sqr = 0;
};
extern Planner planner;
struct Temperature {
  void manage_heater() {}
  void task() {}
};
extern Temperature thermalManager;
struct GCodeParser {
  /// The block's words, by letter; `seen[letter]` whether it has one with a value.
  float value[26] = {};
  bool seen[26] = {};
  float current = 0;
  bool seenval(char c) {
    const bool s = seen[c - 'A'];
    if (s) current = value[c - 'A'];
    return s;
  }
  float value_linear_units() const { return current; }
  uint8_t byteval(char c) const { return seen[c - 'A'] ? uint8_t(value[c - 'A']) : 0; }
  uint16_t ushortval(char c) const { return seen[c - 'A'] ? uint16_t(value[c - 'A']) : 0; }
};
extern GCodeParser parser;
void get_destination_from_command();
inline void reset_stepper_timeout() {}
struct GcodeSuite {
  static void G2_G3(const bool clockwise);
  static void G0_G1();  // (Buddy: an arc of no length that extrudes is moved as G1)
};
extern GcodeSuite gcode;
void plan_arc(const xyze_pos_t& cart, const ab_float_t& offset, const bool clockwise, const uint8_t circles);

// The firmware's ARM compiler has uint32_t as unsigned long, which Buddy's
// std::max(uint32_t(...), 1ul) relies on: the same in the firmware's file (built with
// MARLIN_FIRMWARE_FILE), after the system's headers.
#ifdef MARLIN_FIRMWARE_FILE
typedef unsigned long marlin_uint32;
#define uint32_t marlin_uint32
#endif
