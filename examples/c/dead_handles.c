/* Every kind of handle used after its _free, and freed twice: each call answers
 * PROCLAIM_STATUS_DEAD_HANDLE (a freed theory makes no session: null), never a crash. Prints one
 * line per check and exits 1 if any answer is not the expected one.
 *   cargo build --release -p proclaim-capi
 *   gcc -I crates/capi/include examples/c/dead_handles.c target/release/libproclaim_capi.a
 *       -lpthread -ldl -lm -o dead_handles
 *   ./dead_handles
 * crates/capi/tests/cpp.rs builds it and runs it, under valgrind too when it is installed. */

#include "proclaim.h"

#include <stdio.h>
#include <string.h>

static const char MICROWAVE[] =
    "input{doorOpen}. input{timeLeft}.\n"
    "Cook: timeLeft => cook.\n"
    "Door: doorOpen -> ~cook.\n";

static int failures = 0;

static void expect(const char *what, ProclaimStatus got, ProclaimStatus wanted) {
  int ok = got == wanted;
  printf("%s %s: %s\n", ok ? "ok" : "FAILED", what, proclaim_status_name(got));
  if (!ok) failures++;
}

int main(void) {
  ProclaimTheory *theory = proclaim_theory_load(MICROWAVE, strlen(MICROWAVE), NULL);
  if (!theory) {
    fprintf(stderr, "the theory does not load\n");
    return 1;
  }
  ProclaimInput time_left = 0;
  ProclaimLiteral cook = 0;
  expect("input lookup", proclaim_theory_input(theory, "timeLeft", &time_left),
         PROCLAIM_STATUS_OK);
  expect("literal lookup", proclaim_theory_literal(theory, "cook", &cook), PROCLAIM_STATUS_OK);
  ProclaimSession *session = proclaim_session_new(theory);
  ProclaimTable *table = NULL;
  expect("table", proclaim_theory_table(theory, &table), PROCLAIM_STATUS_OK);

  /* The theory first: the session keeps its own reference and goes on answering. */
  expect("theory free", proclaim_theory_free(theory), PROCLAIM_STATUS_OK);
  expect("theory free again", proclaim_theory_free(theory), PROCLAIM_STATUS_DEAD_HANDLE);
  expect("freed theory input lookup", proclaim_theory_input(theory, "timeLeft", &time_left),
         PROCLAIM_STATUS_DEAD_HANDLE);
  expect("freed theory literal lookup", proclaim_theory_literal(theory, "cook", &cook),
         PROCLAIM_STATUS_DEAD_HANDLE);
  ProclaimTable *no_table = NULL;
  expect("freed theory table", proclaim_theory_table(theory, &no_table),
         PROCLAIM_STATUS_DEAD_HANDLE);
  expect("freed theory makes no session",
         proclaim_session_new(theory) == NULL ? PROCLAIM_STATUS_OK : PROCLAIM_STATUS_PANIC,
         PROCLAIM_STATUS_OK);

  bool answer = false;
  expect("set after the theory's free", proclaim_session_set_input(session, time_left,
                                                                   PROCLAIM_VALUE_TRUE),
         PROCLAIM_STATUS_OK);
  expect("prove after the theory's free",
         proclaim_session_prove_literal(session, cook, PROCLAIM_ALGORITHM_BETA, &answer),
         PROCLAIM_STATUS_OK);
  expect("session free", proclaim_session_free(session), PROCLAIM_STATUS_OK);
  expect("freed session set", proclaim_session_set_input(session, time_left, PROCLAIM_VALUE_TRUE),
         PROCLAIM_STATUS_DEAD_HANDLE);
  expect("freed session set by name", proclaim_session_set(session, "timeLeft", PROCLAIM_VALUE_TRUE),
         PROCLAIM_STATUS_DEAD_HANDLE);
  expect("freed session prove",
         proclaim_session_prove_literal(session, cook, PROCLAIM_ALGORITHM_BETA, &answer),
         PROCLAIM_STATUS_DEAD_HANDLE);
  expect("freed session prove by name",
         proclaim_session_prove(session, "cook", PROCLAIM_ALGORITHM_BETA, &answer),
         PROCLAIM_STATUS_DEAD_HANDLE);
  char *text = NULL;
  expect("freed session explain",
         proclaim_session_explain(session, "cook", PROCLAIM_ALGORITHM_BETA, 1, &text),
         PROCLAIM_STATUS_DEAD_HANDLE);
  expect("freed session budget", proclaim_session_set_budget(session, 10),
         PROCLAIM_STATUS_DEAD_HANDLE);
  expect("session free again", proclaim_session_free(session), PROCLAIM_STATUS_DEAD_HANDLE);

  expect("table free", proclaim_table_free(table), PROCLAIM_STATUS_OK);
  /* A freed table reads as empty: a loop over its rows does nothing. */
  expect("freed table is empty",
         table->row_count == 0 && table->outputs == NULL ? PROCLAIM_STATUS_OK
                                                         : PROCLAIM_STATUS_PANIC,
         PROCLAIM_STATUS_OK);
  expect("table free again", proclaim_table_free(table), PROCLAIM_STATUS_DEAD_HANDLE);

  ProclaimError *error = NULL;
  ProclaimTheory *broken = proclaim_theory_load("R: a => .", 9, &error);
  expect("broken theory is null with an error",
         broken == NULL && error != NULL ? PROCLAIM_STATUS_OK : PROCLAIM_STATUS_PANIC,
         PROCLAIM_STATUS_OK);
  expect("error free", proclaim_error_free(error), PROCLAIM_STATUS_OK);
  expect("freed error is empty",
         error->message == NULL && error->line == 0 ? PROCLAIM_STATUS_OK : PROCLAIM_STATUS_PANIC,
         PROCLAIM_STATUS_OK);
  expect("error free again", proclaim_error_free(error), PROCLAIM_STATUS_DEAD_HANDLE);

  expect("null theory free", proclaim_theory_free(NULL), PROCLAIM_STATUS_OK);
  expect("null session call", proclaim_session_set_budget(NULL, 10), PROCLAIM_STATUS_BAD_ARGUMENT);
  return failures == 0 ? 0 : 1;
}
