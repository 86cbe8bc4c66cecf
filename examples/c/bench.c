/* One input change and one question through the C API, timed: the loop of benches/reasoner.rs's
 * "microwave cook" case (timeLeft toggled, then beta cook), so the figures compare. Two ways, in
 * turn, each timed in several runs (best and median printed): by name (each call looks the atom
 * up) and by handle (looked up once with proclaim_theory_input / proclaim_theory_literal).
 *   cargo build --release -p proclaim-capi
 *   gcc -O2 -I crates/capi/include examples/c/bench.c target/release/libproclaim_capi.a
 *       -lpthread -ldl -lm -o bench
 *   ./bench theories/microwave.dl 1000000 9
 * crates/capi/tests/cpp.rs builds and runs it with a few iterations so it keeps compiling.
 * `cargo bench -p proclaim-capi --bench overhead` times the same beside the Rust session. */

#define _POSIX_C_SOURCE 199309L
#include "proclaim.h"

#include <stdio.h>
#include <stdlib.h>
#include <time.h>

#define MAX_RUNS 99

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

static int ascending(const void *a, const void *b) {
  double x = *(const double *)a, y = *(const double *)b;
  return (x > y) - (x < y);
}

typedef struct Loop {
  ProclaimSession *session;
  ProclaimInput time_left;
  ProclaimLiteral cook;
} Loop;

/* One run of `iterations`; ns per iteration, or a negative number when a call failed. */
static double by_name(const Loop *loop, long iterations) {
  long proved = 0;
  double start = now_ns();
  for (long i = 0; i < iterations; i++) {
    bool cook = false;
    ProclaimStatus set = proclaim_session_set(loop->session, "timeLeft", (i & 1) ? PROCLAIM_VALUE_FALSE : PROCLAIM_VALUE_TRUE);
    ProclaimStatus asked = proclaim_session_prove(loop->session, "cook", PROCLAIM_ALGORITHM_BETA, &cook);
    if (set != PROCLAIM_STATUS_OK || asked != PROCLAIM_STATUS_OK) return -1;
    proved += cook;
  }
  double elapsed = now_ns() - start;
  /* Every other iteration sets timeLeft true, when the microwave cooks. */
  return proved == (iterations + 1) / 2 ? elapsed / (double)iterations : -1;
}

static double by_handle(const Loop *loop, long iterations) {
  long proved = 0;
  double start = now_ns();
  for (long i = 0; i < iterations; i++) {
    bool cook = false;
    ProclaimStatus set = proclaim_session_set_input(loop->session, loop->time_left, (i & 1) ? PROCLAIM_VALUE_FALSE : PROCLAIM_VALUE_TRUE);
    ProclaimStatus asked = proclaim_session_prove_literal(loop->session, loop->cook, PROCLAIM_ALGORITHM_BETA, &cook);
    if (set != PROCLAIM_STATUS_OK || asked != PROCLAIM_STATUS_OK) return -1;
    proved += cook;
  }
  double elapsed = now_ns() - start;
  return proved == (iterations + 1) / 2 ? elapsed / (double)iterations : -1;
}

int main(int argc, char **argv) {
  const char *path = argc > 1 ? argv[1] : "theories/microwave.dl";
  long iterations = argc > 2 ? atol(argv[2]) : 1000000;
  int runs = argc > 3 ? atoi(argv[3]) : 9;
  if (iterations < 1 || runs < 1 || runs > MAX_RUNS) {
    fprintf(stderr, "usage: %s THEORY ITERATIONS RUNS (1 to %d runs)\n", argv[0], MAX_RUNS);
    return 2;
  }
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
  Loop loop = {proclaim_session_new(theory), 0, 0};
  if (proclaim_theory_input(theory, "timeLeft", &loop.time_left) != PROCLAIM_STATUS_OK ||
      proclaim_theory_literal(theory, "cook", &loop.cook) != PROCLAIM_STATUS_OK ||
      proclaim_session_set(loop.session, "doorOpen", PROCLAIM_VALUE_FALSE) != PROCLAIM_STATUS_OK) {
    fprintf(stderr, "%s has no timeLeft, cook or doorOpen\n", path);
    return 1;
  }
  proclaim_theory_free(theory);

  const char *names[2] = {"by name", "by handle"};
  double (*ways[2])(const Loop *, long) = {by_name, by_handle};
  double times[2][MAX_RUNS];
  /* The two ways alternate run by run, so a machine that slows down slows both. */
  for (int run = 0; run < runs; run++) {
    for (int way = 0; way < 2; way++) {
      times[way][run] = ways[way](&loop, iterations);
      if (times[way][run] < 0) {
        fprintf(stderr, "%s: a call failed or answered wrongly\n", names[way]);
        return 1;
      }
    }
  }
  proclaim_session_free(loop.session);
  for (int way = 0; way < 2; way++) {
    qsort(times[way], (size_t)runs, sizeof(double), ascending);
    printf("set + prove %-9s: best %.0f ns, median %.0f ns per iteration (%d runs of %ld iterations)\n",
           names[way], times[way][0], times[way][runs / 2], runs, iterations);
  }
  return 0;
}
