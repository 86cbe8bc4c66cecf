/* A behaviour written by hand: one machine `Door` that posts `Light: on` on entering its only
 * state, which is final, and one atom `open` from outside that it reads nowhere. It is what
 * `proclaim compile` would write for it, by hand, so that the runtime compiles and runs with no
 * generated code (see `behaviour.h` beside it). */
#include <stdint.h>
#include "behaviour.h"

static const unsigned theory_outputs = 0u;
static const unsigned outputs = 1u;
static const unsigned sensors = 0u;
static const unsigned externs = 1u;
static const unsigned composites = 0u;
static const char *const output_name[] = {"open"};
static const char *const output_expert[] = {"impersonator"};
static const char *const machine_name[] = {"Door"};
static const long machine_initial[] = {1};
static const unsigned char machine_starts[] = {1};
static const unsigned long machine_priority[] = {0};
static const int status_board[] = {-1};
static const char *const extern_name[] = {"Light"};
static const unsigned char extern_bound[] = {0};
static const int output_board[] = {-1};
static const unsigned char value_is_bool[] = {0};
static const unsigned composite_machine[] = {0};
static const char *const sensor_name[] = {0};
static const char *const sensor_atom[] = {0};
static const unsigned sensor_start[] = {0u};
#if BEHAVIOUR_SUPPRESSED
static const char *const held_type[] = {"Light"};
static const uint64_t held_ms[] = {500u};
static const unsigned machine_layer[] = {0u};
#endif
#if BEHAVIOUR_RANGES
static const char *const range_type[] = {"Light"};
static const int64_t range_low[] = {INT64_C(0)};
static const int64_t range_high[] = {INT64_C(1)};
static const char *const range_shown[] = {", outside its declared range 0..1 (the manifest's [ranges]): what `verify` proved assumed it"};
#endif

#include "proclaim_runtime.h"

static int answer(const struct world *w, unsigned k)
{
    return k == 0u && w->input[1];
}

static int apply_input(struct world *w, const char *ty, const char *content)
{
    if (same(ty, "open")) {
        set_input(w, 0u, content);
        return 1;
    }
    return 0;
}

static int ring_machines(struct world *w)
{
    const unsigned m = 0u;
    if (!ringlet_due(w, m)) {
        return 0;
    }
    if (begin_ringlet(w, m)) {
        w->cb.entered(w, "Door", "SHUT", 1);
        post(w, m, "Light", "on");
        report_finished(w, m, "SHUT");
    }
    take_snapshot(w, m);
    obey(w);
    return 0;
}

static int reads(const struct world *w, unsigned m, unsigned k)
{
    (void)w;
    (void)m;
    (void)k;
    return 0;
}

static int reads_extern(const struct world *w, unsigned m, unsigned e)
{
    (void)w;
    (void)m;
    (void)e;
    return 0;
}

static int reads_globals(const struct world *w, unsigned m)
{
    (void)w;
    (void)m;
    return 0;
}

static int final_state(const struct world *w, unsigned m)
{
    return w->state[m] == 1;
}

static uint64_t due_of(const struct world *w, unsigned m, uint64_t due)
{
    (void)w;
    (void)m;
    return due;
}
