/* Loads, uses and frees theories a thousand times (by default), good ones and bad ones, by every
 * way of loading, so that a leak checker sees whether a load leaves memory behind: each round
 * loads a good theory, asks it, and frees it; loads a bad one with and without asking for the
 * error; and loads a file that is not there. Prints what it did and exits 1 if an answer is not
 * the expected one.
 *   gcc -I crates/capi/include examples/c/load_loop.c target/release/libproclaim_capi.a
 *       -lpthread -ldl -lm -o load_loop
 *   valgrind --leak-check=full ./load_loop 1000
 * crates/capi/tests/cpp.rs runs it under valgrind and requires no byte definitely or indirectly
 * lost. */

#include "proclaim.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char GOOD[] =
    "input{doorOpen}. input{timeLeft}.\n"
    "Cook: timeLeft => cook.\n"
    "Door: doorOpen -> ~cook.\n";

static const char BAD[] = "input{doorOpen}.\nTimer: timeLeft => .\n";

static int failures = 0;

static void expect(int ok, const char *what, int round) {
  if (!ok) {
    printf("FAILED round %d: %s (%s)\n", round, what, proclaim_last_error_message());
    failures++;
  }
}

int main(int argc, char **argv) {
  int rounds = argc > 1 ? atoi(argv[1]) : 1000;
  if (rounds < 1) {
    fprintf(stderr, "usage: load_loop [ROUNDS]\n");
    return 2;
  }
  for (int round = 0; round < rounds; round++) {
    ProclaimError *error = NULL;
    ProclaimTheory *theory = proclaim_theory_load(GOOD, strlen(GOOD), &error);
    expect(theory != NULL && error == NULL, "the good theory loads", round);
    ProclaimSession *session = proclaim_session_new(theory);
    bool cook = false;
    expect(proclaim_session_set(session, "timeLeft", PROCLAIM_VALUE_TRUE) == PROCLAIM_STATUS_OK,
           "set", round);
    expect(proclaim_session_prove(session, "cook", PROCLAIM_ALGORITHM_BETA, &cook) ==
                   PROCLAIM_STATUS_OK && cook,
           "prove", round);
    expect(proclaim_session_prove(session, "cok", PROCLAIM_ALGORITHM_BETA, &cook) ==
               PROCLAIM_STATUS_UNKNOWN_ATOM,
           "a misspelt atom", round);
    proclaim_session_free(session);
    proclaim_theory_free(theory);

    ProclaimTheory *named = proclaim_theory_load_named("bad.dl", BAD, strlen(BAD), &error);
    expect(named == NULL && error != NULL && error->line == 2, "the bad theory is refused", round);
    proclaim_error_free(error);

    expect(proclaim_theory_load(BAD, strlen(BAD), NULL) == NULL, "refused, no error asked", round);

    error = NULL;
    expect(proclaim_theory_load_file("no/such/theory.dl", &error) == NULL && error != NULL,
           "a missing file is an error", round);
    proclaim_error_free(error);
  }
  printf("%d rounds, %d failures\n", rounds, failures);
  return failures == 0 ? 0 : 1;
}
