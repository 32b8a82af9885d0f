#include "arcpress/api/arcpress.hpp"

#include "arcpress/extract/run.hpp"
#include "arcpress/fit/fitter.hpp"
#include "arcpress/lex/lexer.hpp"
#include "arcpress/model/interpreter.hpp"

namespace arcpress {

CompressResult compress(const std::string& name, std::string text, const CompressOptions& opt,
                        DiagnosticSink& sink) {
  sink.set_strict(opt.strict);
  CompressResult r;
  r.bytes_in = text.size();
  Program prog = lex(name, std::move(text), sink);
  r.blocks_in = prog.blocks.size();
  Interpretation in = interpret(prog, sink);
  if (sink.error_count() > 0) return r;
  std::vector<Run> runs;
  std::vector<FitResult> fits;
  if (!opt.passthrough) {
    runs = extract_runs(in);
    fits.reserve(runs.size());
    for (const Run& run : runs) {
      fits.push_back(fit_run(in, run, opt.fit));
      r.forced_kinks += fits.back().forced_kinks;
    }
  }
  r.output = emit_program(prog, in, runs, fits, opt.fit.tolerance_mm, &r.stats);
  r.ok = true;
  r.band_mm = opt.fit.tolerance_mm;
  if (opt.verify && !opt.passthrough) {
    DiagnosticSink out_sink(name + " (output)");
    Program out_prog = lex(name + " (output)", r.output, out_sink);
    Interpretation out_in = interpret(out_prog, out_sink);
    CompareOptions co;
    co.tolerance_mm = opt.fit.tolerance_mm;
    co.g1_angle_deg = opt.fit.g1_angle_deg;
    co.corner_angle_deg = opt.fit.corner_angle_deg;
    r.comparison = compare_paths(prog, in, out_prog, out_in, co);
    r.verified = true;
  }
  return r;
}

}  // namespace arcpress
