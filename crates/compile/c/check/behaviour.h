/* The sizes of a behaviour written by hand (`behaviour.c` beside it): the smallest the runtime
 * serves, so that a unit test (`crates/compile/tests/runtime_c.rs`) compiles `proclaim.h`,
 * `proclaim_runtime.h` and `harness.c` alone, with and without subsumption
 * (`-DBEHAVIOUR_SUPPRESSED=1`) and a declared range (`-DBEHAVIOUR_RANGES=1`), as strictly as a generated behaviour is compiled. */
#ifndef BEHAVIOUR_H
#define BEHAVIOUR_H
#include <stdint.h>

#define BEHAVIOUR_MACHINES 1
#define BEHAVIOUR_OUTPUTS 1
#define BEHAVIOUR_VARIABLES 2
#define BEHAVIOUR_VALUES 1
#define BEHAVIOUR_EXTERNS 1
#define BEHAVIOUR_TEXT 16
#define BEHAVIOUR_COMMANDS 1
#define BEHAVIOUR_ASKS 1
#define BEHAVIOUR_PERIOD_MS 100u
#define BEHAVIOUR_LOOP_LIMIT 1000u
#define BEHAVIOUR_COMPOSITES 1
#ifndef BEHAVIOUR_SUPPRESSED
#define BEHAVIOUR_SUPPRESSED 0
#endif
#define BEHAVIOUR_LAYERS 1
#define BEHAVIOUR_HELD_TEXT 16
/* With `-DBEHAVIOUR_RANGES=1`, `Light` has a declared range whose warnings remember two values. */
#ifndef BEHAVIOUR_RANGES
#define BEHAVIOUR_RANGES 0
#endif
#define BEHAVIOUR_RANGE_MEMORY 2

#include "proclaim.h"

#endif
