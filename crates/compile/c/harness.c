/* The host harness of a behaviour compiled by proclaim: reads an impersonator script on standard
 * input (`name = value` from the start, `at 2s name = value` later), runs the behaviour on a
 * virtual clock and writes its trace as `proclaim run --trace --virtual-clock` does, until every
 * machine is in a final state or, given a time (`main 12s`), until then as `--for 12s` stops;
 * given none, until a still round after the script's last step, as `run` with no `--for` does. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <ctype.h>
#include <errno.h>
#include "behaviour.h"

#define MAX_STEPS 4096

struct step {
    uint64_t at_ms;
    int start;
    /* This step's value is the last the trace showed for its type. */
    int shown;
    /* For a type's first step: asked before the script posted it, the impersonator's answer
     * was shown with this value (see `show_answer`). */
    const char *answer_shown;
    char name[128];
    /* A truth word or a whole number, as the trace shows it. */
    char value[24];
};

static struct step steps[MAX_STEPS];
static size_t step_count;
static size_t next_step;

static void json_string(const char *s)
{
    putchar('"');
    for (; *s != '\0'; s++) {
        unsigned char c = (unsigned char)*s;
        if (c == '"' || c == '\\') {
            printf("\\%c", c);
        } else if (c == '\n') {
            printf("\\n");
        } else if (c == '\t') {
            printf("\\t");
        } else if (c == '\r') {
            printf("\\r");
        } else if (c == '\b') {
            printf("\\b");
        } else if (c == '\f') {
            printf("\\f");
        } else if (c < 0x20) {
            printf("\\u%04x", c);
        } else {
            putchar(c);
        }
    }
    putchar('"');
}

/* The run is over once every machine that started with the behaviour is in a final state:
 * the trace ends at the event that made it so, as `proclaim run`'s does. */
static int over;

/* How many of the machines' events so far were changes (all but answers read; not the
 * impersonator's postings): a round that leaves it as it was changed nothing. */
static unsigned long changes;

static void tail(struct world *w)
{
    printf(",\"round\":%llu,\"at_us\":%llu}\n", (unsigned long long)w->round,
           (unsigned long long)(w->now_ms * 1000u));
}

static void on_post(struct world *w, const char *machine, const char *type, const char *content,
                    unsigned long priority)
{
    if (over) {
        return;
    }
    printf("{\"event\":\"posted\",\"machine\":");
    json_string(machine);
    printf(",\"type\":");
    json_string(type);
    printf(",\"content\":");
    json_string(content);
    if (priority != 0) {
        printf(",\"priority\":%lu", priority);
    }
    tail(w);
}

static void on_machine_post(struct world *w, const char *machine, const char *type,
                            const char *content, unsigned long priority)
{
    changes++;
    on_post(w, machine, type, content, priority);
}

static void on_suppressed(struct world *w, const char *machine, const char *type,
                          const char *content, unsigned long priority, const char *by,
                          unsigned long by_priority, uint64_t until_ms)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"suppressed\",\"machine\":");
    json_string(machine);
    printf(",\"type\":");
    json_string(type);
    printf(",\"content\":");
    json_string(content);
    printf(",\"priority\":%lu,\"by\":", priority);
    json_string(by);
    printf(",\"by_priority\":%lu,\"until_us\":%llu", by_priority,
           (unsigned long long)(until_ms * 1000u));
    tail(w);
}

static void on_took_over(struct world *w, const char *machine, const char *type,
                         const char *content, unsigned long priority, uint64_t posted_ms)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"took_over\",\"machine\":");
    json_string(machine);
    printf(",\"type\":");
    json_string(type);
    printf(",\"content\":");
    json_string(content);
    printf(",\"priority\":%lu,\"posted_us\":%llu", priority,
           (unsigned long long)(posted_ms * 1000u));
    tail(w);
}

static void on_entered(struct world *w, const char *machine, const char *state, long id)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"entered\",\"machine\":");
    json_string(machine);
    printf(",\"state\":");
    json_string(state);
    printf(",\"id\":%ld", id);
    tail(w);
}

static void on_finished(struct world *w, const char *machine, const char *state)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"finished\",\"machine\":");
    json_string(machine);
    printf(",\"state\":");
    json_string(state);
    tail(w);
    over = behaviour_finished(w);
}

static void show_answer(struct world *w, const char *atom, int value);

static void on_queried(struct world *w, const char *atom, int value)
{
    if (!over) {
        show_answer(w, atom, value);
    }
}

static void on_answered(struct world *w, const char *machine, const char *atom, int value,
                        const char *expert, const char *poster)
{
    if (over) {
        return;
    }
    printf("{\"event\":\"answered\",\"machine\":");
    json_string(machine);
    printf(",\"atom\":");
    json_string(atom);
    printf(",\"value\":%s,\"by\":", value ? "true" : "false");
    if (expert == NULL && poster != NULL) {
        printf("{\"posted\":");
        json_string(poster);
        printf("}");
    } else if (expert == NULL) {
        printf("\"no_expert\"");
    } else {
        printf("{\"expert\":");
        json_string(expert);
        printf("}");
    }
    tail(w);
}

static void on_fired(struct world *w, const char *machine, long from, long to, const char *label)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"fired\",\"machine\":");
    json_string(machine);
    printf(",\"from\":%ld,\"to\":%ld,\"label\":", from, to);
    json_string(label);
    tail(w);
}

static void on_assigned(struct world *w, const char *machine, const char *variable,
                        const char *value)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"assigned\",\"machine\":");
    json_string(machine);
    printf(",\"variable\":");
    json_string(variable);
    printf(",\"value\":");
    json_string(value);
    tail(w);
}

static void on_printed(struct world *w, const char *machine, const char *text)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"printed\",\"machine\":");
    json_string(machine);
    printf(",\"text\":");
    json_string(text);
    tail(w);
}

static void on_control(struct world *w, const char *machine, const char *command)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"control\",\"machine\":");
    json_string(machine);
    printf(",\"command\":");
    json_string(command);
    tail(w);
}

static void on_warned(struct world *w, const char *machine, const char *message)
{
    if (over) {
        return;
    }
    changes++;
    printf("{\"event\":\"warned\",\"machine\":");
    json_string(machine);
    printf(",\"message\":");
    json_string(message);
    tail(w);
}

/* The first step of `name`, or NULL. */
static struct step *first_step(const char *name)
{
    size_t i;
    for (i = 0; i < step_count; i++) {
        if (strcmp(steps[i].name, name) == 0) {
            return &steps[i];
        }
    }
    return NULL;
}

/* The impersonator answers every query by posting its answer: for an atom of the script asked
 * before the script posted it, that posting (its default) is the first the trace shows. */
static void show_answer(struct world *w, const char *atom, int value)
{
    struct step *first = first_step(atom);
    size_t i;
    if (first == NULL || first->answer_shown != NULL) {
        return;
    }
    for (i = 0; i < next_step; i++) {
        if (strcmp(steps[i].name, atom) == 0) {
            return;
        }
    }
    first->answer_shown = value ? "true" : "false";
    on_post(w, "impersonator", atom, first->answer_shown, 0);
}

/* The impersonator posts a step; the trace shows each type's value once when it changes, as
 * `proclaim run` does. Whether it was news to a machine. */
static int impersonate(struct world *w, struct step *s)
{
    size_t i;
    struct step *first = first_step(s->name);
    if (first != NULL && first->answer_shown != NULL) {
        /* The answer shown stands for the type's last value shown. */
        if (strcmp(first->answer_shown, s->value) == 0) {
            s->shown = 1;
        }
        first->answer_shown = NULL;
    }
    for (i = 0; i < step_count && &steps[i] != s; i++) {
        if (steps[i].shown && strcmp(steps[i].name, s->name) == 0) {
            steps[i].shown = 0;
            if (strcmp(steps[i].value, s->value) == 0) {
                s->shown = 1;
            }
        }
    }
    if (!s->shown) {
        s->shown = 1;
        on_post(w, "impersonator", s->name, s->value, 0);
    }
    return behaviour_outside(w, s->name, s->value);
}

/* Posts the script's steps due by now; whether one was news. */
static int post_due(struct world *w)
{
    int news = 0;
    while (next_step < step_count && steps[next_step].at_ms <= w->now_ms) {
        news |= impersonate(w, &steps[next_step++]);
    }
    return news;
}

static void on_round_started(struct world *w)
{
    (void)post_due(w);
}

static char *trim(char *s)
{
    char *end;
    while (isspace((unsigned char)*s)) {
        s++;
    }
    end = s + strlen(s);
    while (end > s && isspace((unsigned char)end[-1])) {
        *--end = '\0';
    }
    return s;
}

/* `2s`, `500ms`, `1.5s`, `250us`: milliseconds, or -1. */
static long long duration_ms(const char *text)
{
    char *end;
    double value = strtod(text, &end);
    double ms;
    if (end == text || value < 0) {
        return -1;
    }
    if (strcmp(end, "s") == 0) {
        ms = value * 1000.0;
    } else if (strcmp(end, "ms") == 0) {
        ms = value;
    } else if (strcmp(end, "us") == 0 || strcmp(end, "µs") == 0) {
        ms = value / 1000.0;
    } else if (strcmp(end, "min") == 0) {
        ms = value * 60000.0;
    } else {
        return -1;
    }
    if (ms != (double)(long long)ms) {
        return -1;
    }
    return (long long)ms;
}

static const char *truth(const char *word)
{
    if (strcmp(word, "true") == 0 || strcmp(word, "yes") == 0 || strcmp(word, "on") == 0 ||
        strcmp(word, "1") == 0) {
        return "true";
    }
    if (strcmp(word, "false") == 0 || strcmp(word, "no") == 0 || strcmp(word, "off") == 0 ||
        strcmp(word, "0") == 0) {
        return "false";
    }
    return NULL;
}

/* A script's value as a compiled behaviour holds it, into `out` as the trace shows it: a truth
 * word (`yes` is `true`), or a whole number within 64 bits (`+5` is `5`); 0 for anything else. */
static int script_value(const char *word, char *out, size_t size)
{
    const char *t = truth(word), *digits = word + (*word == '-' || *word == '+');
    char *end;
    long long whole;
    if (t != NULL) {
        snprintf(out, size, "%s", t);
        return 1;
    }
    if (!isdigit((unsigned char)*digits)) {
        return 0;
    }
    errno = 0;
    whole = strtoll(word, &end, 10);
    if (*end != '\0' || errno == ERANGE) {
        return 0;
    }
    snprintf(out, size, "%lld", whole);
    return 1;
}

static int read_script(void)
{
    char line[1024];
    int number = 0;
    while (fgets(line, sizeof line, stdin) != NULL) {
        char *code, *hash, *eq, *name, *value;
        struct step s;
        number++;
        hash = strchr(line, '#');
        if (hash != NULL) {
            *hash = '\0';
        }
        code = trim(line);
        if (*code == '\0') {
            continue;
        }
        memset(&s, 0, sizeof s);
        s.start = 1;
        if (strncmp(code, "at ", 3) == 0) {
            char *time = trim(code + 3);
            char *space = time;
            long long ms;
            while (*space != '\0' && !isspace((unsigned char)*space)) {
                space++;
            }
            if (*space == '\0') {
                fprintf(stderr, "stdin:%d: expected `at TIME atom = value`\n", number);
                return 0;
            }
            *space = '\0';
            ms = duration_ms(time);
            if (ms < 0) {
                fprintf(stderr, "stdin:%d: `%s` is not a time in whole milliseconds; write `at 2s` or `at 500ms`\n", number, time);
                return 0;
            }
            s.start = 0;
            s.at_ms = (uint64_t)ms;
            code = space + 1;
        } else if (strncmp(code, "step ", 5) == 0) {
            fprintf(stderr, "stdin:%d: `step N:` lines are not supported by a compiled behaviour\n", number);
            return 0;
        }
        eq = strchr(code, '=');
        if (eq == NULL) {
            fprintf(stderr, "stdin:%d: expected `atom = value`\n", number);
            return 0;
        }
        *eq = '\0';
        name = trim(code);
        value = trim(eq + 1);
        if (*name == '\0' || strlen(name) >= sizeof s.name || !script_value(value, s.value, sizeof s.value)) {
            fprintf(stderr, "stdin:%d: expected `atom = true|false` or a whole number (fractions and text in a script are not supported by a compiled behaviour)\n", number);
            return 0;
        }
        strcpy(s.name, name);
        if (behaviour_answers(s.name)) {
            fprintf(stderr, "stdin:%d: `%s` is a theory's answer: impersonating an answer is not supported by a compiled behaviour\n", number, s.name);
            return 0;
        }
        if (behaviour_is_machine(s.name)) {
            fprintf(stderr, "stdin:%d: `%s` is a machine: control commands from a script are not supported by a compiled behaviour\n", number, s.name);
            return 0;
        }
        if (step_count == MAX_STEPS) {
            fprintf(stderr, "stdin:%d: more than %d steps\n", number, MAX_STEPS);
            return 0;
        }
        steps[step_count++] = s;
    }
    return 1;
}

/* Whether the script sets an atom of every sensor (else the interpreter would run that sensor,
 * which a compiled behaviour does not have); says which it does not. */
static int sensors_scripted(void)
{
    unsigned s, a;
    size_t i;
    const char *name;
    for (s = 0; (name = behaviour_sensor_name(s)) != NULL; s++) {
        const char *atom;
        int set = 0;
        for (a = 0; (atom = behaviour_sensor_atom(s, a)) != NULL; a++) {
            for (i = 0; i < step_count; i++) {
                set |= strcmp(steps[i].name, atom) == 0;
            }
        }
        if (!set) {
            fprintf(stderr, "stdin: sets none of the atoms the module `%s` answers (", name);
            for (a = 0; (atom = behaviour_sensor_atom(s, a)) != NULL; a++) {
                fprintf(stderr, "%s%s", a == 0 ? "" : ", ", atom);
            }
            fprintf(stderr, "): a compiled behaviour has no sensors or expert processes, and takes their atoms from its script (as `proclaim run --script` leaves such a module out when the script sets one of its atoms)\n");
            return 0;
        }
    }
    return 1;
}

/* Start steps first, then the timed ones in time order (stable: same time keeps file order). */
static void order_steps(void)
{
    size_t i, j;
    for (i = 1; i < step_count; i++) {
        struct step s = steps[i];
        j = i;
        while (j > 0 && (steps[j - 1].start < s.start ||
                         (steps[j - 1].start == s.start && steps[j - 1].at_ms > s.at_ms))) {
            /* `start` steps (1) sort before timed ones (0); timed ones by time. */
            steps[j] = steps[j - 1];
            j--;
        }
        steps[j] = s;
    }
}

/* The runner's bound on rounds that fire one after another (MOST_ROUNDS_WITHOUT_WAITING). */
#define MOST_ROUNDS_WITHOUT_WAITING 10000

int main(int argc, char **argv)
{
    static struct world w;
    size_t i;
    int fired;
    int without_waiting = 0;
    unsigned long before;
    long long limit = -1;
    if (argc > 2 || (argc == 2 && (limit = duration_ms(argv[1])) < 0)) {
        fprintf(stderr, "usage: %s [DURATION] < SCRIPT   (DURATION: 12s, 500ms: stop then; none: once the script is over and nothing changes)\n", argv[0]);
        return 2;
    }
    if (!read_script()) {
        return 2;
    }
    order_steps();
    if (!sensors_scripted()) {
        return 2;
    }
    w.cb.post = on_machine_post;
    w.cb.suppressed = on_suppressed;
    w.cb.took_over = on_took_over;
    w.cb.entered = on_entered;
    w.cb.finished = on_finished;
    w.cb.queried = on_queried;
    w.cb.answered = on_answered;
    w.cb.fired = on_fired;
    w.cb.assigned = on_assigned;
    w.cb.printed = on_printed;
    w.cb.control = on_control;
    w.cb.warned = on_warned;
    w.cb.round_started = NULL;
    behaviour_init(&w);
    for (i = 0; i < step_count; i++) {
        (void)behaviour_supply(&w, steps[i].name);
    }
    w.now_ms = 0;
    /* What the script says from the start is posted before the first round; what it says at
     * 0 ms, as the first round starts. */
    while (next_step < step_count && steps[next_step].start) {
        (void)impersonate(&w, &steps[next_step++]);
    }
    w.cb.round_started = on_round_started;
    for (;;) {
        if (limit >= 0 && w.now_ms >= (uint64_t)limit) {
            break;
        }
        before = changes;
        fired = behaviour_round(&w);
        if (over || behaviour_finished(&w)) {
            break;
        }
        /* Alone with its script and no DURATION, the run ends at the first still round after the
         * script's last step: no change, no time test to come, so every later round would be the
         * same (docs/spec/behaviour.md 3.1). */
        if (limit < 0 && !fired && changes == before && next_step == step_count &&
            behaviour_next_test_ms(&w) == UINT64_MAX) {
            break;
        }
        /* As the runner does: rounds that fire one after another hold time still, so past this
         * many the machines go round a cycle that takes no time (docs/spec/behaviour.md 3.1). */
        without_waiting = fired ? without_waiting + 1 : 0;
        if (without_waiting >= MOST_ROUNDS_WITHOUT_WAITING) {
            fprintf(stderr, "halted: %d rounds fired one after another with no wait: the machines go round a cycle that takes no time, so time cannot pass\n", MOST_ROUNDS_WITHOUT_WAITING);
            return 1;
        }
        /* A round that fired, or whose own postings changed what a label reads, is followed at once. */
        if (fired || behaviour_news(&w)) {
            continue;
        }
        {
            uint64_t wait = behaviour_next_due_ms(&w);
            uint64_t due = wait == UINT64_MAX ? UINT64_MAX : w.now_ms + wait;
            int news = 0;
            uint64_t until = limit >= 0 && (uint64_t)limit < due ? (uint64_t)limit : due;
            while (!news && next_step < step_count && steps[next_step].at_ms < until) {
                w.now_ms = steps[next_step].at_ms;
                news = post_due(&w);
            }
            if (!news && until == UINT64_MAX) {
                /* No machine runs and the script has said all it will: nothing can happen again. */
                break;
            }
            if (!news) {
                w.now_ms = until;
            }
        }
        if (w.round > 100000000u) {
            fprintf(stderr, "stopped after 100,000,000 rounds\n");
            return 1;
        }
    }
    return 0;
}
