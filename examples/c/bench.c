/* One input change and one question through the C API, timed: the loop of benches/reasoner.rs's
 * "microwave cook" case (timeLeft toggled, then beta cook), so the two figures compare.
 *   cargo build --release -p proclaim-capi
 *   gcc -O2 -I crates/capi/include examples/c/bench.c target/release/libproclaim_capi.a
 *       -lpthread -ldl -lm -o bench
 *   ./bench theories/microwave.dl 1000000
 * crates/capi/tests/cpp.rs builds and runs it with a few iterations so it keeps compiling. */

#define _POSIX_C_SOURCE 199309L
#include "proclaim.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

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

static double now_ns(void) {
  struct timespec at;
  clock_gettime(CLOCK_MONOTONIC, &at);
  return (double)at.tv_sec * 1e9 + (double)at.tv_nsec;
}

int main(int argc, char **argv) {
  const char *path = argc > 1 ? argv[1] : "theories/microwave.dl";
  long iterations = argc > 2 ? atol(argv[2]) : 1000000;
  size_t len = 0;
  char *text = read_file(path, &len);
  if (!text) {
    fprintf(stderr, "cannot read %s\n", path);
    return 1;
  }
  ProclaimError *error = NULL;
  ProclaimTheory *theory = proclaim_theory_load_named(path, text, len, &error);
  free(text);
  if (!theory) {
    fprintf(stderr, "%s\n", error->message);
    proclaim_error_free(error);
    return 1;
  }
  ProclaimSession *session = proclaim_session_new(theory);
  proclaim_theory_free(theory);
  if (proclaim_session_set(session, "doorOpen", PROCLAIM_VALUE_FALSE) != PROCLAIM_STATUS_OK) return 1;

  long proved = 0;
  double start = now_ns();
  for (long i = 0; i < iterations; i++) {
    bool cook = false;
    ProclaimStatus set = proclaim_session_set(session, "timeLeft", (i & 1) ? PROCLAIM_VALUE_FALSE : PROCLAIM_VALUE_TRUE);
    ProclaimStatus asked = proclaim_session_prove(session, "cook", PROCLAIM_ALGORITHM_BETA, &cook);
    if (set != PROCLAIM_STATUS_OK || asked != PROCLAIM_STATUS_OK) {
      fprintf(stderr, "%s\n", proclaim_status_name(set != PROCLAIM_STATUS_OK ? set : asked));
      return 1;
    }
    proved += cook;
  }
  double elapsed = now_ns() - start;
  proclaim_session_free(session);
  /* Every other iteration sets timeLeft true, when the microwave cooks. */
  if (proved != (iterations + 1) / 2) {
    fprintf(stderr, "cook was proved %ld times in %ld iterations\n", proved, iterations);
    return 1;
  }
  printf("set + prove: %.0f ns per iteration (%ld iterations)\n", elapsed / (double)iterations, iterations);
  return 0;
}
