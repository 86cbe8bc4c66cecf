/* The host of the `thousand_machines` example: runs a compiled behaviour at 1 kHz of robot time
 * (one round a millisecond, as a fixed-rate control loop would call it) and prints the processor
 * time the rounds took, as a fraction of one core. The door opens and shuts every 50 ms, so the
 * machines move. No output per event: the callbacks only count. */
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
#include "behaviour.h"

static unsigned long long events, fired;

static void on_post(struct world *w, const char *machine, const char *type, const char *content,
                    unsigned long priority)
{
    (void)w;
    (void)machine;
    (void)type;
    (void)content;
    (void)priority;
    events++;
}

static void on_entered(struct world *w, const char *machine, const char *state, long id)
{
    (void)w;
    (void)machine;
    (void)state;
    (void)id;
    events++;
}

static void on_text(struct world *w, const char *machine, const char *a)
{
    (void)w;
    (void)machine;
    (void)a;
    events++;
}

static void on_answered(struct world *w, const char *machine, const char *atom, int value,
                        const char *expert, const char *poster)
{
    (void)w;
    (void)machine;
    (void)atom;
    (void)value;
    (void)expert;
    (void)poster;
    events++;
}

static void on_fired(struct world *w, const char *machine, long from, long to, const char *label)
{
    (void)w;
    (void)machine;
    (void)from;
    (void)to;
    (void)label;
    fired++;
}

static void on_assigned(struct world *w, const char *machine, const char *variable,
                        const char *value)
{
    (void)w;
    (void)machine;
    (void)variable;
    (void)value;
    events++;
}

static double seconds(const struct timespec *t)
{
    return (double)t->tv_sec + (double)t->tv_nsec / 1e9;
}

int main(int argc, char **argv)
{
    static struct world w;
    struct timespec start, end;
    long robot_seconds = argc > 1 ? atol(argv[1]) : 20;
    uint64_t ms, rounds;
    double used;
    if (robot_seconds <= 0) {
        fprintf(stderr, "usage: %s [SECONDS of robot time]\n", argv[0]);
        return 2;
    }
    w.cb.post = on_post;
    w.cb.entered = on_entered;
    w.cb.finished = on_text;
    w.cb.answered = on_answered;
    w.cb.fired = on_fired;
    w.cb.assigned = on_assigned;
    w.cb.printed = on_text;
    w.cb.control = on_text;
    w.cb.warned = on_text;
    w.cb.round_started = NULL;
    behaviour_init(&w);
    (void)behaviour_outside(&w, "doorOpen", "false");
    (void)behaviour_outside(&w, "timeLeft", "true");
    rounds = (uint64_t)robot_seconds * 1000u;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &start);
    for (ms = 0; ms < rounds; ms++) {
        w.now_ms = ms;
        if (ms % 50u == 0) {
            (void)behaviour_outside(&w, "doorOpen", (ms / 50u) % 2u ? "true" : "false");
        }
        (void)behaviour_round(&w);
    }
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &end);
    used = seconds(&end) - seconds(&start);
    printf("%d machines, %llu rounds at 1 kHz (%ld s of robot time): %.3f s of processor time, "
           "%.2f%% of one core; %.2f us a round, %.1f ns a ringlet; %llu transitions fired, %llu "
           "other events\n",
           BEHAVIOUR_MACHINES, (unsigned long long)rounds, robot_seconds, used,
           100.0 * used / (double)robot_seconds, 1e6 * used / (double)rounds,
           1e9 * used / ((double)rounds * BEHAVIOUR_MACHINES), fired, events);
    return 0;
}
