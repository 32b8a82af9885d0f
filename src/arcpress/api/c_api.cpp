// SPDX-License-Identifier: GPL-3.0-or-later
// The C library (arcpress.h) over the C++ one: every call catches what the C++ side throws
// and turns it into a status and a message kept in the handle.
#include "arcpress/arcpress.h"

#include <memory>
#include <new>
#include <optional>
#include <string>

#include "arcpress/arcpress.hpp"

struct arcpress_options {
  arcpress::CompressOptions options;
  std::string error;
  /// arcpress_options_set_units(): kept apart, so that a dialect chosen after it keeps it.
  std::optional<arcpress::StartUnits> units;
  void set_dialect(arcpress::Dialect d) {
    if (units) d.start_units = *units;
    options.dialect = std::move(d);
  }
};

struct arcpress_compressor {
  arcpress::DiagnosticSink sink;
  std::unique_ptr<arcpress::Compressor> compressor;
  std::string taken, diagnostics, error;
  bool finished = false;
};

namespace {

/// Runs `f`, turning an exception into a status with its message in `error`.
template <class F>
arcpress_status guarded(std::string& error, F&& f) {
  try {
    error.clear();
    return f();
  } catch (const arcpress::Error& e) {
    error = e.what();
    return e.exit_code() == arcpress::kExitIo ? ARCPRESS_IO_ERROR : ARCPRESS_BAD_INPUT;
  } catch (const std::bad_alloc&) {
    error = "out of memory";
    return ARCPRESS_INTERNAL;
  } catch (const std::exception& e) {
    error = e.what();
    return ARCPRESS_INTERNAL;
  } catch (...) {
    error = "unknown failure";
    return ARCPRESS_INTERNAL;
  }
}

arcpress_status set_number(arcpress_options* o, double& field, double value, const char* what,
                           const arcpress::OptionRange& range) {
  if (!o) return ARCPRESS_BAD_INPUT;
  if (!range.holds(value)) {
    o->error = std::string(what) + " is out of its range";
    return ARCPRESS_BAD_INPUT;
  }
  field = value;
  o->error.clear();
  return ARCPRESS_OK;
}

}  // namespace

extern "C" {

const char* arcpress_version(void) { return arcpress::kVersion; }

arcpress_options* arcpress_options_new(void) { return new (std::nothrow) arcpress_options(); }
void arcpress_options_free(arcpress_options* options) { delete options; }
const char* arcpress_options_last_error(const arcpress_options* options) {
  return options ? options->error.c_str() : "no options";
}

arcpress_status arcpress_options_set_tolerance(arcpress_options* o, double mm) {
  return set_number(o, o ? o->options.fit.tolerance_mm : mm, mm, "the tolerance", arcpress::kToleranceRange);
}
arcpress_status arcpress_options_set_g1_angle(arcpress_options* o, double degrees) {
  return set_number(o, o ? o->options.fit.g1_angle_deg : degrees, degrees, "the G1 angle", arcpress::kG1AngleRange);
}
arcpress_status arcpress_options_set_corner_angle(arcpress_options* o, double degrees) {
  return set_number(o, o ? o->options.fit.corner_angle_deg : degrees, degrees, "the corner angle",
                    arcpress::kCornerAngleRange);
}

arcpress_status arcpress_options_set_method(arcpress_options* o, const char* method) {
  if (!o || !method) return ARCPRESS_BAD_INPUT;
  const auto picked = arcpress::method_named(method);
  if (!picked) {
    o->error = std::string("unknown method '") + method + "' (arcs, global, greedy, stream, lowe or keep)";
    return ARCPRESS_BAD_INPUT;
  }
  o->options.fit.method = *picked;
  o->error.clear();
  return ARCPRESS_OK;
}

arcpress_status arcpress_options_set_dialect(arcpress_options* o, const char* name) {
  if (!o || !name) return ARCPRESS_BAD_INPUT;
  return guarded(o->error, [&] {
    o->set_dialect(arcpress::dialect_named(name));
    return ARCPRESS_OK;
  });
}

arcpress_status arcpress_options_set_dialect_file(arcpress_options* o, const char* path) {
  if (!o || !path) return ARCPRESS_BAD_INPUT;
  return guarded(o->error, [&] {
    o->set_dialect(arcpress::load_dialect_file(path));
    return ARCPRESS_OK;
  });
}

arcpress_status arcpress_options_set_threads(arcpress_options* o, unsigned threads) {
  if (!o) return ARCPRESS_BAD_INPUT;
  if (threads > arcpress::kMaxThreads) {
    o->error = "the thread count must be from 0 to " + std::to_string(arcpress::kMaxThreads);
    return ARCPRESS_BAD_INPUT;
  }
  o->options.threads = threads;
  o->error.clear();
  return ARCPRESS_OK;
}
arcpress_status arcpress_options_set_verify(arcpress_options* o, int verify) {
  if (!o) return ARCPRESS_BAD_INPUT;
  o->options.verify = verify != 0;
  return ARCPRESS_OK;
}
arcpress_status arcpress_options_set_strict(arcpress_options* o, int strict) {
  if (!o) return ARCPRESS_BAD_INPUT;
  o->options.strict = strict != 0;
  return ARCPRESS_OK;
}

arcpress_status arcpress_options_set_band(arcpress_options* o, const char* band) {
  if (!o || !band) return ARCPRESS_BAD_INPUT;
  const auto picked = arcpress::band_named(band);
  if (!picked) {
    o->error = std::string("unknown band '") + band + "' (executed, program or dialect)";
    return ARCPRESS_BAD_INPUT;
  }
  o->options.band = *picked;
  o->error.clear();
  return ARCPRESS_OK;
}
arcpress_status arcpress_options_set_band_side(arcpress_options* o, const char* side) {
  if (!o || !side) return ARCPRESS_BAD_INPUT;
  const std::string s = side;
  if (s != "left" && s != "right" && s != "both") {
    o->error = "unknown band side '" + s + "' (left, right or both)";
    return ARCPRESS_BAD_INPUT;
  }
  o->options.fit.band_side = s == "left" ? arcpress::BandSide::Left : s == "right" ? arcpress::BandSide::Right
                                                                                   : arcpress::BandSide::Both;
  o->error.clear();
  return ARCPRESS_OK;
}
arcpress_status arcpress_options_set_units(arcpress_options* o, const char* units) {
  if (!o || !units) return ARCPRESS_BAD_INPUT;
  const std::string u = units;
  if (u != "mm" && u != "inch") {
    o->error = "unknown units '" + u + "' (mm or inch)";
    return ARCPRESS_BAD_INPUT;
  }
  o->units = u == "mm" ? arcpress::StartUnits::Mm : arcpress::StartUnits::Inch;
  o->options.dialect.start_units = *o->units;
  o->error.clear();
  return ARCPRESS_OK;
}
arcpress_status arcpress_options_set_extrusion_variance(arcpress_options* o, double share) {
  return set_number(o, o ? o->options.fit.extrusion_variance : share, share, "the extrusion variance",
                    arcpress::kExtrusionVarianceRange);
}
arcpress_status arcpress_options_set_header(arcpress_options* o, int header) {
  if (!o) return ARCPRESS_BAD_INPUT;
  o->options.header = header != 0;
  return ARCPRESS_OK;
}

arcpress_status arcpress_compressor_new(arcpress_options* o, const char* name, arcpress_compressor** out) {
  if (!out) return ARCPRESS_BAD_INPUT;
  *out = nullptr;
  if (!o) return ARCPRESS_BAD_INPUT;
  return guarded(o->error, [&] {
    auto c = std::make_unique<arcpress_compressor>();
    c->sink = arcpress::DiagnosticSink(name ? name : "<program>");
    c->compressor = std::make_unique<arcpress::Compressor>(name ? name : "<program>", o->options, c->sink);
    *out = c.release();
    return ARCPRESS_OK;
  });
}

void arcpress_compressor_free(arcpress_compressor* c) { delete c; }

extern "C++" {
namespace {

/// `give(text)` to compressor `c`, which must be unfinished, of the `length` bytes at `bytes`.
template <class Give>
arcpress_status give_text(arcpress_compressor* c, const char* bytes, size_t length, Give&& give) {
  if (!c || (!bytes && length > 0)) return ARCPRESS_BAD_INPUT;
  if (c->finished) {
    c->error = "the compressor is finished";
    return ARCPRESS_BAD_INPUT;
  }
  return guarded(c->error, [&] {
    give(std::string_view(bytes ? bytes : "", length));
    return c->compressor->result().ok ? ARCPRESS_OK : ARCPRESS_BAD_INPUT;
  });
}

}  // namespace
}  // extern "C++"

arcpress_status arcpress_push(arcpress_compressor* c, const char* bytes, size_t length) {
  return give_text(c, bytes, length, [&](std::string_view text) { c->compressor->push(text); });
}

arcpress_status arcpress_read_jumps(arcpress_compressor* c, const char* bytes, size_t length, unsigned first_line) {
  return give_text(c, bytes, length, [&](std::string_view text) { c->compressor->read_jumps(text, first_line); });
}

arcpress_status arcpress_read_loops(arcpress_compressor* c, const char* bytes, size_t length) {
  return give_text(c, bytes, length, [&](std::string_view text) { c->compressor->read_loops(text); });
}

arcpress_status arcpress_take(arcpress_compressor* c, const char** text, size_t* length) {
  if (!c || !text || !length) return ARCPRESS_BAD_INPUT;
  return guarded(c->error, [&] {
    c->taken.clear();
    c->compressor->take(c->taken);
    *text = c->taken.data();
    *length = c->taken.size();
    return ARCPRESS_OK;
  });
}

arcpress_status arcpress_finish(arcpress_compressor* c) {
  if (!c) return ARCPRESS_BAD_INPUT;
  return guarded(c->error, [&] {
    if (!c->finished) c->compressor->finish();
    c->finished = true;
    const arcpress::CompressResult& r = c->compressor->result();
    if (!r.ok) {
      c->error = "the input has errors (see the diagnostics)";
      return ARCPRESS_BAD_INPUT;
    }
    if (!r.within_band()) {
      c->error = "the output failed its check";
      return ARCPRESS_CHECK_FAILED;
    }
    return ARCPRESS_OK;
  });
}

arcpress_status arcpress_get_stats(const arcpress_compressor* c, arcpress_stats* s) {
  if (!c || !s) return ARCPRESS_BAD_INPUT;
  const arcpress::CompressResult& r = c->compressor->result();
  s->bytes_in = r.bytes_in;
  s->bytes_out = r.bytes_out;
  s->blocks_in = r.blocks_in;
  s->g1_moves = r.g1_moves;
  s->lines_out = r.stats.lines_out;
  s->arcs_out = r.stats.arcs_out;
  s->max_deviation_mm = r.check.max_deviation_mm;
  s->verified = r.verified && c->finished ? 1 : 0;  // measured only once every piece is
  return ARCPRESS_OK;
}

const char* arcpress_diagnostics(arcpress_compressor* c) {
  if (!c) return "";
  c->diagnostics = c->sink.format_all();
  return c->diagnostics.c_str();
}

const char* arcpress_last_error(const arcpress_compressor* c) { return c ? c->error.c_str() : "no compressor"; }

}  // extern "C"
