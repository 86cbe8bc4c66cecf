/* A theory's truth table through the C API, printed as CSV: a header of the inputs and the
 * output headings, then a row per combination of the inputs ("inconsistent" in each output
 * cell of a row whose inputs contradict the axioms).
 *   cargo build --release -p proclaim-capi
 *   gcc -O2 -I crates/capi/include examples/c/table.c target/release/libproclaim_capi.a
 *       -lpthread -ldl -lm -o table
 *   ./table theories/microwave.dl
 * crates/capi/tests/cpp.rs builds it and checks its rows against the Rust table's. */

#include "proclaim.h"

#include <stdio.h>
#include <stdlib.h>

static char *read_file(const char *path, size_t *len) {
  FILE *file = fopen(path, "rb");
  if (!file) return NULL;
  fseek(file, 0, SEEK_END);
  long size = ftell(file);
  fseek(file, 0, SEEK_SET);
  char *text = malloc(size > 0 ? (size_t)size : 1);
  *len = text ? fread(text, 1, (size_t)size, file) : 0;
  fclose(file);
  return text;
}

static const char *truth(bool value) { return value ? "true" : "false"; }

int main(int argc, char **argv) {
  if (argc != 2) {
    fprintf(stderr, "usage: %s THEORY.dl\n", argv[0]);
    return 2;
  }
  size_t len = 0;
  char *text = read_file(argv[1], &len);
  if (!text) {
    fprintf(stderr, "cannot read %s\n", argv[1]);
    return 1;
  }
  ProclaimError *error = NULL;
  ProclaimTheory *theory = proclaim_theory_load_named(argv[1], text, len, &error);
  free(text);
  if (!theory) {
    fprintf(stderr, "%s\n", error->message);
    proclaim_error_free(error);
    return 1;
  }
  ProclaimTable *table = NULL;
  ProclaimStatus status = proclaim_theory_table(theory, &table);
  proclaim_theory_free(theory);
  if (status != PROCLAIM_STATUS_OK) {
    fprintf(stderr, "no table: %s\n", proclaim_status_name(status));
    return 1;
  }
  for (size_t i = 0; i < table->input_count; i++) printf("%s%s", i ? "," : "", table->input_names[i]);
  for (size_t c = 0; c < table->output_count; c++)
    printf("%s%s", table->input_count + c ? "," : "", table->output_names[c]);
  printf("\n");
  for (size_t r = 0; r < table->row_count; r++) {
    for (size_t i = 0; i < table->input_count; i++)
      printf("%s%s", i ? "," : "", truth(table->inputs[r * table->input_count + i]));
    for (size_t c = 0; c < table->output_count; c++) {
      const char *cell = table->consistent[r] ? truth(table->outputs[r * table->output_count + c]) : "inconsistent";
      printf("%s%s", table->input_count + c ? "," : "", cell);
    }
    printf("\n");
  }
  proclaim_table_free(table);
  return 0;
}
