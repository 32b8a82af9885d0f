/* SPDX-License-Identifier: GPL-3.0-or-later */
/* Compresses a G-code file with arcpress's C library, reading and writing in pieces:
 * compress_c INPUT OUTPUT [DIALECT]. Exit 0 written, else the arcpress_status. */
#include <arcpress/arcpress.h>

#include <stdio.h>

static int fail(const char* what, const char* message) {
  fprintf(stderr, "compress_c: %s: %s\n", what, message);
  return 2;
}

int main(int argc, char** argv) {
  if (argc < 3) return fail("usage", "compress_c INPUT OUTPUT [DIALECT]");
  arcpress_options* options = arcpress_options_new();
  if (arcpress_options_set_tolerance(options, 0.01) != ARCPRESS_OK ||
      arcpress_options_set_dialect(options, argc > 3 ? argv[3] : "rs274") != ARCPRESS_OK)
    return fail("options", arcpress_options_last_error(options));
  arcpress_compressor* c = NULL;
  if (arcpress_compressor_new(options, argv[1], &c) != ARCPRESS_OK)
    return fail("compressor", arcpress_options_last_error(options));
  FILE* in = fopen(argv[1], "rb");
  FILE* out = fopen(argv[2], "wb");
  if (!in || !out) return fail(argv[in ? 2 : 1], "cannot open");
  char buffer[1 << 16];
  const char* text;
  size_t n, length;
  arcpress_status status = ARCPRESS_OK;
  while (status == ARCPRESS_OK && (n = fread(buffer, 1, sizeof buffer, in)) > 0) {
    status = arcpress_push(c, buffer, n);
    if (arcpress_take(c, &text, &length) == ARCPRESS_OK) fwrite(text, 1, length, out);
  }
  if (status == ARCPRESS_OK) status = arcpress_finish(c);
  if (arcpress_take(c, &text, &length) == ARCPRESS_OK) fwrite(text, 1, length, out);
  fclose(in);
  if (fclose(out) != 0 && status == ARCPRESS_OK) status = ARCPRESS_IO_ERROR;
  fputs(arcpress_diagnostics(c), stderr);
  arcpress_stats stats;
  arcpress_get_stats(c, &stats);
  if (status == ARCPRESS_OK)
    fprintf(stderr, "compress_c: %zu -> %zu bytes, %zu arcs, deviation %.6f mm\n", stats.bytes_in, stats.bytes_out,
            stats.arcs_out, stats.max_deviation_mm);
  else
    fprintf(stderr, "compress_c: %s; the output cannot be used\n", arcpress_last_error(c));
  arcpress_compressor_free(c);
  arcpress_options_free(options);
  return (int)status;
}
