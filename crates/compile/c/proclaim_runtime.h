/* proclaim's runtime for a compiled behaviour: a ringlet's steps (asking, proving, posting,
 * assigning, commanding sub-machines), the snapshot, subsumption and the round schedule, as the
 * interpreter has them (`docs/spec/behaviour.md`). Its functions are `static`: `behaviour.c`
 * defines the behaviour's tables (below), includes this file, then defines the behaviour's own
 * functions (declared here), so a program holds no symbol of it but the `behaviour_` API.
 * Copied by `proclaim compile` (do not edit the copy).
 *
 * The tables `behaviour.c` defines before including it: output_name, output_expert,
 * theory_outputs, outputs, sensors, machine_name, machine_initial, machine_starts, extern_name,
 * externs, extern_bound, output_board, status_board, machine_priority, value_is_bool,
 * sensor_name, sensor_atom, sensor_start; with subsumption also held_type, held_ms and
 * machine_layer. */
#ifndef PROCLAIM_RUNTIME_H
#define PROCLAIM_RUNTIME_H

/* The behaviour's own functions, generated into `behaviour.c`: each output's answer, whether a
 * posting's type sets theory inputs (then set), and each machine's ringlet, what its current
 * state's labels read, whether that state is final and when its time tests come due. */
static int answer(const struct world *w, unsigned k);
static int apply_input(struct world *w, const char *ty, const char *content);
static int ring_machines(struct world *w);
static int reads(const struct world *w, unsigned m, unsigned k);
static int reads_extern(const struct world *w, unsigned m, unsigned e);
static int reads_globals(const struct world *w, unsigned m);
static int final_state(const struct world *w, unsigned m);
static uint64_t due_of(const struct world *w, unsigned m, uint64_t due);

static int same(const char *a, const char *b)
{
    while (*a != '\0' && *a == *b) {
        a++;
        b++;
    }
    return *a == *b;
}

/* Whether `content` is a whole number (an optional `-`, then digits), and whether it is 0. */
static int whole_number(const char *content, int *zero)
{
    const char *c = content;
    *zero = 1;
    if (*c == '-') {
        c++;
    }
    if (*c == '\0') {
        return 0;
    }
    for (; *c != '\0'; c++) {
        if (*c < '0' || *c > '9') {
            return 0;
        }
        *zero &= *c == '0';
    }
    return 1;
}

/* A theory input from a posting's content, as the reasoner expert reads it: true, false, a
 * whole number (true unless 0), or unknown for anything else. */
static void set_input(struct world *w, unsigned v, const char *content)
{
    int zero;
    if (same(content, "true")) {
        w->input[v] = 1;
        w->input[v + 1] = 1;
    } else if (same(content, "false")) {
        w->input[v] = 1;
        w->input[v + 1] = 0;
    } else if (whole_number(content, &zero)) {
        w->input[v] = 1;
        w->input[v + 1] = (unsigned char)!zero;
    } else {
        w->input[v] = 0;
        w->input[v + 1] = 0;
    }
}


static struct value v_bool(int b);

/* An answer a label read, reported once the label is proved. */
static void pend(struct world *w, const char *atom, int value, const char *expert, const char *poster)
{
    if (w->pending_count < BEHAVIOUR_ASKS) {
        struct pending_answer *p = &w->pending[w->pending_count++];
        p->atom = atom;
        p->value = value;
        p->expert = expert;
        p->poster = poster;
    }
}

/* A transition's label is proved: the answers it read are reported, and its truth returned. */
static int proved(struct world *w, unsigned m, int holds)
{
    unsigned i;
    for (i = 0; i < w->pending_count; i++) {
        const struct pending_answer *p = &w->pending[i];
        w->cb.answered(w, machine_name[m], p->atom, p->value, p->expert, p->poster);
    }
    w->pending_count = 0;
    return holds;
}

static int ask(struct world *w, unsigned m, unsigned k)
{
    int value = answer(w, k);
    w->asked[m][k] = 1;
    /* No expert answers it: the runner reads its newest posting instead, from the snapshot. */
    if (!w->supplied[k]) {
        w->ext_read[m] = 1;
    } else if (output_board[k] >= 0) {
        /* An expert answers by posting its answer, which the machines read as a value. */
        w->ext[output_board[k]] = v_bool(value);
        w->ext_known[output_board[k]] = 1;
        w->ext_by[output_board[k]] = output_expert[k];
    }
    if (w->supplied[k]) {
        /* The expert posts its answer: a theory reading the atom as an input sees it. */
        (void)apply_input(w, output_name[k], value ? "true" : "false");
        if (w->cb.queried) {
            w->cb.queried(w, output_name[k], value);
        }
    }
    pend(w, output_name[k], value, w->supplied[k] ? output_expert[k] : 0, 0);
    return value;
}

#if BEHAVIOUR_SUPPRESSED
/* Subsumption (Brooks' suppression), as the board's `Suppressor` decides. */
static int held_live(const struct held_posting *p, unsigned t, uint64_t now)
{
    return now < p->at_ms + held_ms[t];
}

/* Whether some posting of a layer below `layer` is known. */
static int held_below(const struct held_line *line, unsigned layer)
{
    unsigned l;
    for (l = 0; l < layer; l++) {
        if (line->newest[l].known) {
            return 1;
        }
    }
    return 0;
}

static void held_keep(struct held_posting *to, unsigned m, uint64_t now, const char *content)
{
    unsigned i = 0;
    to->known = 1;
    to->machine = m;
    to->at_ms = now;
    while (content[i] != '\0' && i + 1 < BEHAVIOUR_HELD_TEXT) {
        to->text[i] = content[i];
        i++;
    }
    to->text[i] = '\0';
}

/* Judges machine `m`'s posting: 1 when a higher layer's live posting holds its type (reported
 * as suppressed, and kept to take over later); 0 when readers see it (and, for a type under
 * subsumption, it holds the type from now). */
static int held_back(struct world *w, unsigned m, const char *type, const char *content)
{
    unsigned t, layer = machine_layer[m];
    for (t = 0; t < BEHAVIOUR_SUPPRESSED; t++) {
        struct held_line *line = &w->held[t];
        if (!same(type, held_type[t])) {
            continue;
        }
        held_keep(&line->newest[layer], m, w->now_ms, content);
        if (line->shown.known && layer < machine_layer[line->shown.machine] &&
            held_live(&line->shown, t, w->now_ms)) {
            unsigned by = line->shown.machine;
            line->subsuming = 1;
            w->cb.suppressed(w, machine_name[m], type, content, machine_priority[m], machine_name[by],
                             machine_priority[by], line->shown.at_ms + held_ms[t]);
            return 1;
        }
        line->subsuming = (unsigned char)held_below(line, layer);
        line->shown = line->newest[layer];
        return 0;
    }
    return 0;
}

/* The posting that takes over once the shown one's hold has run out: of the lower layers', the
 * highest whose own hold still runs, else the newest (the higher layer on a tie); or none. */
static const struct held_posting *held_successor(const struct held_line *line, unsigned t,
                                                 uint64_t now)
{
    const struct held_posting *best = 0;
    unsigned l, top;
    if (!line->shown.known || !line->subsuming || held_live(&line->shown, t, now)) {
        return 0;
    }
    top = machine_layer[line->shown.machine];
    for (l = 0; l < top; l++) {
        if (line->newest[l].known && held_live(&line->newest[l], t, now)) {
            best = &line->newest[l];
        }
    }
    if (best != 0) {
        return best;
    }
    for (l = 0; l < top; l++) {
        if (line->newest[l].known && (best == 0 || line->newest[l].at_ms >= best->at_ms)) {
            best = &line->newest[l];
        }
    }
    return best;
}

/* At a round's start: every held type whose hold ran out with a lower posting behind it gets
 * that posting, in type name order, as the runner's schedule has it. */
static void take_over(struct world *w)
{
    unsigned t;
    for (t = 0; t < BEHAVIOUR_SUPPRESSED; t++) {
        struct held_line *line = &w->held[t];
        const struct held_posting *next = held_successor(line, t, w->now_ms);
        unsigned m;
        if (next == 0) {
            continue;
        }
        line->shown = *next;
        m = line->shown.machine;
        line->subsuming = (unsigned char)(held_live(&line->shown, t, w->now_ms) &&
                                          held_below(line, machine_layer[m]));
        w->cb.took_over(w, machine_name[m], held_type[t], line->shown.text, machine_priority[m],
                        line->shown.at_ms);
        (void)apply_input(w, held_type[t], line->shown.text);
    }
}

/* A hold running out with a lower posting behind it changes what readers see: a round then. */
static uint64_t release_due(const struct world *w, uint64_t due)
{
    unsigned t;
    for (t = 0; t < BEHAVIOUR_SUPPRESSED; t++) {
        const struct held_line *line = &w->held[t];
        if (line->subsuming && line->shown.known) {
            uint64_t at = line->shown.at_ms + held_ms[t];
            uint64_t wait = at > w->now_ms ? at - w->now_ms : 0;
            if (wait < due) {
                due = wait;
            }
        }
    }
    return due;
}
#endif

static void post(struct world *w, unsigned m, const char *type, const char *content)
{
#if BEHAVIOUR_SUPPRESSED
    if (held_back(w, m, type, content)) {
        return;
    }
#endif
    w->cb.post(w, machine_name[m], type, content, machine_priority[m]);
    (void)apply_input(w, type, content);
}

static void snapshot(struct world *w, unsigned m)
{
    unsigned k;
    for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {
        w->seen[m][k] = (unsigned char)answer(w, k);
        w->asked[m][k] = 0;
    }
}

static int elapsed_at_least(const struct world *w, unsigned m, uint64_t ms)
{
    return w->now_ms - w->entered_ms[m] >= ms;
}

/* Whether its machine has been in composite state `c` at least `ms`. */
static int composite_elapsed(const struct world *w, unsigned c, uint64_t ms)
{
    return w->now_ms - w->composite_ms[c] >= ms;
}

/* A move enters composite state `c`: its time starts when the move arrives. */
static void enter_composite(struct world *w, unsigned c)
{
    w->composite_entering[c] = 1;
}

/* Machine `m` enters its state as from outside: every composite around it is entered again. */
static void enter_composites(struct world *w, unsigned m)
{
    unsigned c;
    for (c = 0; c < composites; c++) {
        if (composite_machine[c] == m) {
            w->composite_entering[c] = 1;
        }
    }
}

/* A time test still to come due shortens the wait; one already past (its label false for
 * another reason) does not, as the runner's `next_time_test` has it. */
static uint64_t min_due(uint64_t due, uint64_t at, uint64_t now)
{
    if (at <= now) {
        return due;
    }
    return at - now < due ? at - now : due;
}
/* A value as the runner holds it: a whole number, or a truth value (0 or 1); `none` for a
 * whiteboard value never posted, which arithmetic keeps and a comparison finds false. */
#define CONVERT_WHOLE 0
#define CONVERT_TRUTH 1
#define CONVERT_KEPT 2

static struct value v_int(int64_t i)
{
    struct value v;
    v.i = i;
    v.is_bool = 0;
    v.none = 0;
    return v;
}

static struct value v_none(void)
{
    struct value v = v_int(0);
    v.none = 1;
    return v;
}

/* What an activity makes of a value: no value is a whole 0, as the runner's activities have it. */
static struct value v_some(struct value v)
{
    return v.none ? v_int(0) : v;
}

static struct value v_bool(int b)
{
    struct value v;
    v.i = b ? 1 : 0;
    v.is_bool = 1;
    v.none = 0;
    return v;
}

static int truthy(struct value v)
{
    return v.i != 0;
}

/* Wrapping arithmetic, as the runner's `wrapping_add` and kin. */
static int64_t wrap(uint64_t u)
{
    return u <= (uint64_t)INT64_MAX ? (int64_t)u : -(int64_t)(~u) - 1;
}

static struct value v_add(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return v_int(wrap((uint64_t)a.i + (uint64_t)b.i));
}

static struct value v_sub(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return v_int(wrap((uint64_t)a.i - (uint64_t)b.i));
}

static struct value v_mul(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return v_int(wrap((uint64_t)a.i * (uint64_t)b.i));
}

/* Dividing by zero gives the largest whole number, as gufsm's INT_MAX. */
static struct value v_div(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    if (b.i == 0) {
        return v_int(INT64_MAX);
    }
    if (b.i == -1) {
        return v_int(wrap(0u - (uint64_t)a.i));
    }
    return v_int(a.i / b.i);
}

static struct value v_rem(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    if (b.i == 0) {
        return v_int(INT64_MAX);
    }
    if (b.i == -1) {
        return v_int(0);
    }
    return v_int(a.i % b.i);
}

static struct value v_neg(struct value a)
{
    if (a.none) {
        return a;
    }
    return v_int(wrap(0u - (uint64_t)a.i));
}

static struct value v_abs(struct value a)
{
    return a.i < 0 ? v_neg(a) : a;
}

static struct value v_eq(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i == b.i);
}

static struct value v_ne(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i != b.i);
}

static struct value v_lt(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i < b.i);
}

static struct value v_le(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i <= b.i);
}

static struct value v_gt(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i > b.i);
}

static struct value v_ge(struct value a, struct value b)
{
    return v_bool(!a.none && !b.none && a.i >= b.i);
}

/* The first when it is not greater (min) or not less (max), as the runner picks. */
static struct value v_min(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return a.i <= b.i ? a : b;
}

static struct value v_max(struct value a, struct value b)
{
    if (a.none || b.none) {
        return v_none();
    }
    return a.i >= b.i ? a : b;
}

static struct value convert(int conversion, struct value v)
{
    if (conversion == CONVERT_WHOLE) {
        return v_int(v.i);
    }
    if (conversion == CONVERT_TRUTH) {
        return v_bool(truthy(v));
    }
    return v;
}

/* A value's text, as the trace shows it, into `out` (at least 21 bytes); its length. */
static unsigned value_text(char *out, struct value v)
{
    char digits[20];
    unsigned n = 0, len = 0;
    uint64_t u;
    const char *word;
    if (v.is_bool) {
        word = v.i ? "true" : "false";
        while (word[len] != '\0') {
            out[len] = word[len];
            len++;
        }
        out[len] = '\0';
        return len;
    }
    u = v.i < 0 ? 0u - (uint64_t)v.i : (uint64_t)v.i;
    do {
        digits[n++] = (char)('0' + (int)(u % 10u));
        u /= 10u;
    } while (u != 0u);
    if (v.i < 0) {
        out[len++] = '-';
    }
    while (n > 0) {
        out[len++] = digits[--n];
    }
    out[len] = '\0';
    return len;
}

static void text_clear(struct world *w)
{
    w->text_length = 0;
    w->text[0] = '\0';
}

static void text_literal(struct world *w, const char *s)
{
    while (*s != '\0') {
        w->text[w->text_length++] = *s++;
    }
    w->text[w->text_length] = '\0';
}

static void text_value(struct world *w, struct value v)
{
    w->text_length += value_text(w->text + w->text_length, v);
}

static void text_whole(struct world *w, struct value v)
{
    text_value(w, v_int(v.i));
}

/* An assignment as the runner makes it: converted to the variable's type, reported when the
 * value changed; a global's change is news to the labels that read globals. */
static void assign(struct world *w, unsigned m, unsigned slot, int conversion, int global,
                   const char *name, struct value v)
{
    char shown[24];
    v = convert(conversion, v_some(v));
    if (w->var[slot].i == v.i && w->var[slot].is_bool == v.is_bool) {
        return;
    }
    w->var[slot] = v;
    if (global) {
        w->globals_changes++;
    }
    (void)value_text(shown, v);
    w->cb.assigned(w, machine_name[m], name, shown);
}

#define RUNNING 0
#define SUSPENDED 1
#define DORMANT 2
#define COMMAND_UNKNOWN 0
#define COMMAND_ON 1
#define COMMAND_OFF 2
#define COMMAND_SUSPEND 3
#define COMMAND_RESUME 4
#define COMMAND_RESTART 5
#define LOOP_LIMIT BEHAVIOUR_LOOP_LIMIT

static int final_state(const struct world *w, unsigned m);

/* Whether a machine's run is over for now: in a state with no way out, its OnEntry run. */
static int done(const struct world *w, unsigned m)
{
    return !w->just_entered[m] && final_state(w, m);
}

/* A control command posted to machine `m`, obeyed when the ringlet ends. */
static void command(struct world *w, unsigned m, unsigned char code, const char *word)
{
    if (w->command_count[m] < BEHAVIOUR_COMMANDS) {
        w->command[m][w->command_count[m]] = code;
        w->command_word[m][w->command_count[m]] = word;
        w->command_count[m]++;
        w->commands_waiting = 1;
    }
}

/* The runner posts a machine's running state to `NameIsRunning` when it starts and whenever
 * that changes. */
static void post_status(struct world *w, unsigned m)
{
    int e = status_board[m];
    if (e >= 0) {
        w->ext[e] = v_bool(w->status[m] == RUNNING);
        w->ext_known[e] = 1;
        w->ext_by[e] = machine_name[m];
    }
}

static int obey_command(struct world *w, unsigned m, unsigned char code);

/* gufsm's SuspensibleMachine, as the runner's `control`: whether it started the machine. */
static int control(struct world *w, unsigned m, unsigned char code, const char *word)
{
    int was_running = w->status[m] == RUNNING;
    int started;
    w->cb.control(w, machine_name[m], word);
    started = obey_command(w, m, code);
    if (started) {
        enter_composites(w, m);
    }
    if (was_running != (w->status[m] == RUNNING)) {
        post_status(w, m);
    }
    return started;
}

static int obey_command(struct world *w, unsigned m, unsigned char code)
{
    switch (code) {
    case COMMAND_ON:
    case COMMAND_RESUME:
        if (w->status[m] == DORMANT) {
            w->state[m] = w->initial[m];
        } else if (w->status[m] == RUNNING) {
            return 0;
        }
        w->status[m] = RUNNING;
        w->just_entered[m] = 1;
        return 1;
    case COMMAND_RESTART:
        w->status[m] = RUNNING;
        w->state[m] = w->initial[m];
        w->just_entered[m] = 1;
        return 1;
    case COMMAND_SUSPEND:
        if (w->status[m] == RUNNING) {
            w->status[m] = SUSPENDED;
        }
        return 0;
    case COMMAND_OFF:
        w->status[m] = DORMANT;
        return 0;
    default:
        return 0;
    }
}

/* The commands waiting for each machine, in schedule order; a machine started rings from the
 * next round. */
static void obey(struct world *w)
{
    unsigned m, i;
    if (!w->commands_waiting) {
        return;
    }
    w->commands_waiting = 0;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        for (i = 0; i < w->command_count[m]; i++) {
            if (control(w, m, w->command[m][i], w->command_word[m][i])) {
                w->fresh[m] = 1;
            }
        }
        w->command_count[m] = 0;
    }
}

static int same_value(struct value a, struct value b)
{
    return a.i == b.i && a.is_bool == b.is_bool;
}

/* The snapshot (`docs/spec/behaviour.md` 3.1), after OnEntry: from here to the ringlet's end
 * machine `m` reads the whiteboard variables as they are now, and its own postings. */
static void extern_snapshot(struct world *w, unsigned m)
{
    unsigned e;
    w->past_snapshot = 1;
    w->ext_read[m] = 0;
    for (e = 0; e < externs; e++) {
        w->ext_seen[m][e] = w->ext[e];
        w->ext_seen_known[m][e] = w->ext_known[e];
        w->ext_seen_by[m][e] = w->ext_by[e];
        w->ext_owned[m][e] = 0;
        w->asked_posted[m][e] = 0;
    }
}

/* What a whiteboard value never posted reads as. */
static struct value unposted(unsigned e)
{
    return extern_bound[e] ? v_int(0) : v_none();
}

/* Whether machine `m`'s last ringlet asked an output whose atom whiteboard value `e` is. */
static int asked_of_expert(const struct world *w, unsigned m, unsigned e)
{
    unsigned k;
    for (k = 0; k < outputs; k++) {
        if (output_board[k] == (int)e && w->asked[m][k]) {
            return 1;
        }
    }
    return 0;
}

/* The output whose atom whiteboard value `e` is, when an expert answered the ringlet's question
 * of it: the ringlet reads that answer, as the runner holds an expert's answer (-1 otherwise). */
static int answered_here(const struct world *w, unsigned e)
{
    unsigned k;
    for (k = 0; k < outputs; k++) {
        if (output_board[k] == (int)e && w->supplied[k] && w->asked[w->ringing][k]) {
            return (int)k;
        }
    }
    return -1;
}

/* A whiteboard value as the ringlet reads it: live before the snapshot (in OnEntry), then
 * what the ringlet posted itself, else an expert's answer it asked, else the snapshot; `by`
 * is who posted it (NULL: nobody). */
static struct value read_board(struct world *w, unsigned e, const char **by)
{
    unsigned m = w->ringing;
    int k;
    if (!w->past_snapshot || w->ext_owned[m][e]) {
        *by = w->past_snapshot ? machine_name[m] : w->ext_by[e];
        return w->ext_known[e] ? w->ext[e] : unposted(e);
    }
    k = answered_here(w, e);
    if (k >= 0) {
        *by = output_expert[k];
        return v_bool(answer(w, (unsigned)k));
    }
    w->ext_read[m] = 1;
    *by = w->ext_seen_by[m][e];
    return w->ext_seen_known[m][e] ? w->ext_seen[m][e] : unposted(e);
}

static struct value read_extern(struct world *w, unsigned e)
{
    const char *by;
    return read_board(w, e, &by);
}

/* A label atom nobody answers: the runner reads the atom's newest posting as the ringlet sees it
 * and reports who posted it (a never posted atom is false, answered by nobody). */
static int ask_posted(struct world *w, unsigned m, unsigned e, const char *atom)
{
    const char *by = 0;
    struct value v;
    int value;
    if (w->scripted[e]) {
        /* The host's script answers it, as the interpreter's impersonator does: the expert
         * posts its answer. */
        value = w->scripted_value[e];
        w->ext[e] = v_bool(value);
        w->ext_known[e] = 1;
        w->ext_by[e] = "impersonator";
        (void)apply_input(w, atom, value ? "true" : "false");
        if (w->cb.queried) {
            w->cb.queried(w, atom, value);
        }
        w->asked_posted[m][e] = 1;
        w->asked_answer[m][e] = (unsigned char)value;
        pend(w, atom, value, "impersonator", 0);
        return value;
    }
    v = read_board(w, e, &by);
    value = !v.none && truthy(v);
    if (v.none) {
        by = 0;
    }
    w->asked_posted[m][e] = 1;
    w->asked_answer[m][e] = (unsigned char)value;
    pend(w, atom, value, 0, by);
    return value;
}

/* Machine `m` posts `v` to whiteboard variable `e` (an assignment to it, or a posting). */
static void post_extern(struct world *w, unsigned m, unsigned e, struct value v)
{
    char shown[24];
    v = v_some(v);
    (void)value_text(shown, v);
    w->cb.post(w, machine_name[m], extern_name[e], shown, machine_priority[m]);
    (void)apply_input(w, extern_name[e], shown);
    w->ext[e] = v;
    w->ext_known[e] = 1;
    w->ext_by[e] = machine_name[m];
    if (w->past_snapshot) {
        w->ext_own[m][e] = v;
        w->ext_owned[m][e] = 1;
    }
}

/* Whether the board's value of `e` is news to machine `m`: not what it posted itself in its
 * last ringlet, or (when that ringlet read the snapshot) not what the snapshot held. */
static int extern_news(const struct world *w, unsigned m, unsigned e)
{
    if (!w->ext_known[e]) {
        return 0;
    }
    if (w->asked_posted[m][e]) {
        return truthy(w->ext[e]) != w->asked_answer[m][e];
    }
    if (asked_of_expert(w, m, e)) {
        /* The answer to the machine's own question: news only when it changes, which the
         * answers' own test sees. */
        return 0;
    }
    if (w->ext_owned[m][e]) {
        return !same_value(w->ext_own[m][e], w->ext[e]);
    }
    if (!w->ext_read[m]) {
        return 0;
    }
    return !w->ext_seen_known[m][e] || !same_value(w->ext_seen[m][e], w->ext[e]);
}

/* A posting from outside to a whiteboard variable's type (a script's truth word): whether it was one. */
/* A value from outside as a compiled behaviour holds it: a truth value, or a whole number (an
 * optional sign, then digits, within 64 bits) as the runner reads a posting's; 0 for anything
 * else (text, a fraction), which it cannot hold. */
static int outside_value(const char *content, struct value *v)
{
    const char *c = content;
    uint64_t magnitude = 0u, limit;
    int negative = *c == '-';
    if (same(content, "true") || same(content, "false")) {
        *v = v_bool(same(content, "true"));
        return 1;
    }
    c += negative || *c == '+';
    limit = negative ? (uint64_t)INT64_MAX + 1u : (uint64_t)INT64_MAX;
    if (*c == '\0') {
        return 0;
    }
    for (; *c != '\0'; c++) {
        if (*c < '0' || *c > '9' || magnitude > (limit - (uint64_t)(*c - '0')) / 10u) {
            return 0;
        }
        magnitude = magnitude * 10u + (uint64_t)(*c - '0');
    }
    *v = v_int(negative ? (int64_t)(0u - magnitude) : (int64_t)magnitude);
    return 1;
}

/* A warning of the impersonator's, as the runner's: `before`, the posting, then `after`, in a
 * bounded buffer (a host's text may be long: it is cut at 64 characters). */
static void warn_posting(struct world *w, const char *before, const char *type, const char *content,
                         const char *after)
{
    char message[400];
    unsigned n = 0, k;
    const char *parts[4];
    parts[0] = before;
    parts[1] = type;
    parts[2] = " = ";
    parts[3] = content;
    for (k = 0; k < 4u; k++) {
        const char *c = parts[k];
        unsigned cut = k == 1u || k == 3u ? 64u : 100u;
        for (; *c != '\0' && cut > 0u; c++, cut--) {
            message[n++] = *c;
        }
    }
    for (; *after != '\0' && n < sizeof message - 1u; after++) {
        message[n++] = *after;
    }
    message[n] = '\0';
    /* A host written before the runtime warned may have left `warned` unset. */
    if (w->cb.warned != 0) {
        w->cb.warned(w, "impersonator", message);
    }
}

/* A posting from outside to a whiteboard variable's type: 1 when it was one. A value the compiled
 * behaviour cannot hold is a warning, and the variable keeps its value. */
static int apply_extern(struct world *w, const char *type, const char *content)
{
    unsigned e;
    struct value v;
    for (e = 0; e < externs; e++) {
        if (same(type, extern_name[e])) {
            if (!outside_value(content, &v)) {
                warn_posting(w, "posted ", type, content,
                             ", which a compiled behaviour cannot hold (it holds whole numbers and truth values): the variable keeps its value");
                return 0;
            }
            w->ext[e] = v;
            w->ext_known[e] = 1;
            w->ext_by[e] = "impersonator";
            w->scripted_value[e] = (unsigned char)same(content, "true");
            return 1;
        }
    }
    return 0;
}

#if BEHAVIOUR_RANGES
/* Whether range `r` has said `v` already; else notes it (and 1 once its memory is full). */
static int range_said(struct world *w, unsigned r, struct value v, int *full)
{
    unsigned k, count = w->range_said_count[r];
    *full = 0;
    for (k = 0; k < count && k < BEHAVIOUR_RANGE_MEMORY; k++) {
        if (w->range_said[r][k] == v.i) {
            return 1;
        }
    }
    if (count > BEHAVIOUR_RANGE_MEMORY) {
        return 1;
    }
    if (count == BEHAVIOUR_RANGE_MEMORY) {
        *full = 1;
    } else {
        w->range_said[r][count] = v.i;
    }
    w->range_said_count[r] = (unsigned char)(count + 1u);
    return 0;
}
#endif

/* Holds a posting from outside to its type's declared range: one that leaves it is a warning,
 * once per type and value, as the runner's (what `verify` proved assumed the range). */
static void hold_to_range(struct world *w, const char *type, const char *content)
{
#if BEHAVIOUR_RANGES
    unsigned r;
    int full = 0;
    struct value v;
    for (r = 0; r < BEHAVIOUR_RANGES; r++) {
        if (!same(type, range_type[r])) {
            continue;
        }
        if (!outside_value(content, &v)) {
            if (w->range_text_said[r]) {
                return;
            }
            w->range_text_said[r] = 1;
        } else if ((v.i >= range_low[r] && v.i <= range_high[r]) || range_said(w, r, v, &full)) {
            return;
        }
        warn_posting(w, "posted ", type, content,
                     full ? ", outside its declared range (the manifest's [ranges]): what `verify` proved assumed it; and later values are not said"
                          : range_shown[r]);
        return;
    }
#else
    (void)w;
    (void)type;
    (void)content;
#endif
}

/* Whether machine `m` rings in this round: running, not started in it, and not over. */
static int ringlet_due(const struct world *w, unsigned m)
{
    return w->status[m] == RUNNING && !w->fresh[m] && !done(w, m);
}

/* A ringlet of machine `m` begins: whether it has just entered its state (then its OnEntry
 * runs first). */
static int begin_ringlet(struct world *w, unsigned m)
{
    unsigned c;
    w->ringing = m;
    w->past_snapshot = 0;
    if (!w->just_entered[m]) {
        return 0;
    }
    w->just_entered[m] = 0;
    w->entered_ms[m] = w->now_ms;
    for (c = 0; c < composites; c++) {
        if (composite_machine[c] == m && w->composite_entering[c]) {
            w->composite_entering[c] = 0;
            w->composite_ms[c] = w->now_ms;
        }
    }
    return 1;
}

/* The ringlet's snapshot (`docs/spec/behaviour.md` 3.1), after OnEntry. */
static void take_snapshot(struct world *w, unsigned m)
{
    snapshot(w, m);
    extern_snapshot(w, m);
    w->globals_seen[m] = w->globals_changes;
}

static void report_finished(struct world *w, unsigned m, const char *state)
{
    w->cb.finished(w, machine_name[m], state);
}

static void post_text(struct world *w, unsigned m, const char *type)
{
    post(w, m, type, w->text);
}

static void print_text(struct world *w, unsigned m)
{
    w->cb.printed(w, machine_name[m], w->text);
}

/* The soonest of `due` and `ms` after machine `m` entered its state. */
static uint64_t due_after(const struct world *w, unsigned m, uint64_t ms, uint64_t due)
{
    return min_due(due, w->entered_ms[m] + ms, w->now_ms);
}

/* The soonest of `due` and `ms` after composite state `c` was entered. */
static uint64_t composite_due_after(const struct world *w, unsigned c, uint64_t ms, uint64_t due)
{
    return min_due(due, w->composite_ms[c] + ms, w->now_ms);
}


void behaviour_init(struct world *w)
{
    unsigned v, m, k;
    /* Helpers a behaviour without theories, or whose labels ask none, leaves unused. */
    (void)ask;
    (void)set_input;
    (void)elapsed_at_least;
    (void)composite_elapsed;
    (void)enter_composite;
    (void)composite_due_after;
    (void)min_due;
    (void)v_int;
    (void)v_bool;
    (void)truthy;
    (void)v_add;
    (void)v_sub;
    (void)v_mul;
    (void)v_div;
    (void)v_rem;
    (void)v_abs;
    (void)v_eq;
    (void)v_ne;
    (void)v_lt;
    (void)v_le;
    (void)v_gt;
    (void)v_ge;
    (void)v_min;
    (void)v_max;
    (void)assign;
    (void)text_clear;
    (void)text_literal;
    (void)text_whole;
    (void)command;
    (void)post;
    (void)text_value;
    (void)v_neg;
    (void)read_extern;
    (void)post_extern;
    (void)ask_posted;
    (void)proved;
    (void)begin_ringlet;
    (void)ringlet_due;
    (void)take_snapshot;
    (void)report_finished;
    (void)post_text;
    (void)print_text;
    (void)due_after;
    w->pending_count = 0;
    (void)v_none;
    w->round = 0;
    w->ringing = 0;
    w->past_snapshot = 0;
    for (v = 0; v < externs; v++) {
        w->ext[v] = v_int(0);
        w->ext_known[v] = 0;
        w->ext_by[v] = 0;
        w->scripted[v] = 0;
        w->scripted_value[v] = 0;
    }
    w->globals_changes = 0;
    w->commands_waiting = 0;
    for (v = 0; v < BEHAVIOUR_VARIABLES; v++) {
        w->input[v] = 0;
    }
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        w->entered_ms[m] = 0;
        w->fresh[m] = 0;
        w->globals_seen[m] = 0;
        w->command_count[m] = 0;
        w->ext_read[m] = 0;
        for (v = 0; v < externs; v++) {
            w->ext_owned[m][v] = 0;
            w->ext_seen_known[m][v] = 0;
            w->ext_seen_by[m][v] = 0;
            w->asked_posted[m][v] = 0;
        }
        for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {
            w->seen[m][k] = 0;
            w->asked[m][k] = 0;
        }
    }
    for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {
        w->supplied[k] = k < theory_outputs;
    }
#if BEHAVIOUR_SUPPRESSED
    for (v = 0; v < BEHAVIOUR_SUPPRESSED; v++) {
        w->held[v].shown.known = 0;
        w->held[v].subsuming = 0;
        for (k = 0; k < BEHAVIOUR_LAYERS; k++) {
            w->held[v].newest[k].known = 0;
        }
    }
#endif
    for (v = 0; v < BEHAVIOUR_VALUES; v++) {
        w->var[v] = value_is_bool[v] ? v_bool(0) : v_int(0);
    }
    for (k = 0; k < BEHAVIOUR_COMPOSITES; k++) {
        w->composite_ms[k] = 0;
        w->composite_entering[k] = 1;
    }
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        w->state[m] = machine_initial[m];
        w->initial[m] = machine_initial[m];
        w->just_entered[m] = 1;
        w->status[m] = machine_starts[m] ? RUNNING : DORMANT;
    }
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        post_status(w, m);
    }
}

int behaviour_round(struct world *w)
{
    int fired = 0;
    unsigned m;
    w->round++;
    if (w->cb.round_started) {
        w->cb.round_started(w);
    }
#if BEHAVIOUR_SUPPRESSED
    take_over(w);
#endif
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        w->fresh[m] = 0;
    }
    fired = ring_machines(w);
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        fired |= w->fresh[m];
    }
    return fired;
}

int behaviour_outside(struct world *w, const char *type, const char *content)
{
    int applied;
    hold_to_range(w, type, content);
    applied = apply_input(w, type, content);
    applied |= apply_extern(w, type, content);
    return applied && behaviour_news(w);
}

int behaviour_news(const struct world *w)
{
    unsigned m, k, e;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        if (w->status[m] != RUNNING) {
            continue;
        }
        for (k = 0; k < BEHAVIOUR_OUTPUTS; k++) {
            if (reads(w, m, k) && (w->asked[m][k] || (k < theory_outputs && w->ext_read[m])) &&
                answer(w, k) != w->seen[m][k]) {
                return 1;
            }
        }
        if (w->globals_seen[m] != w->globals_changes && reads_globals(w, m)) {
            return 1;
        }
        for (e = 0; e < externs; e++) {
            if (reads_extern(w, m, e) && extern_news(w, m, e)) {
                return 1;
            }
        }
    }
    return 0;
}

int behaviour_answers(const char *atom)
{
    unsigned k;
    for (k = 0; k < theory_outputs; k++) {
        if (same(atom, output_name[k])) {
            return 1;
        }
    }
    return 0;
}

int behaviour_supply(struct world *w, const char *atom)
{
    unsigned k;
    unsigned e;
    for (k = theory_outputs; k < outputs; k++) {
        if (same(atom, output_name[k])) {
            w->supplied[k] = 1;
            return 1;
        }
    }
    /* An atom no module of the behaviour declares, which a label asks of the board: the
     * script answers it as the impersonator. */
    for (e = 0; e < externs; e++) {
        if (same(atom, extern_name[e])) {
            w->scripted[e] = 1;
            return 1;
        }
    }
    return 0;
}

const char *behaviour_sensor_name(unsigned s)
{
    return s < sensors ? sensor_name[s] : 0;
}

const char *behaviour_sensor_atom(unsigned s, unsigned i)
{
    if (s >= sensors || sensor_start[s] + i >= sensor_start[s + 1]) {
        return 0;
    }
    return sensor_atom[sensor_start[s] + i];
}

int behaviour_is_machine(const char *name)
{
    unsigned m;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        if (same(name, machine_name[m])) {
            return 1;
        }
    }
    return 0;
}

uint64_t behaviour_next_test_ms(const struct world *w)
{
    uint64_t due = UINT64_MAX;
    unsigned m;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        if (w->status[m] == RUNNING) {
            due = due_of(w, m, due);
        }
    }
#if BEHAVIOUR_SUPPRESSED
    due = release_due(w, due);
#endif
    return due;
}

uint64_t behaviour_next_due_ms(const struct world *w)
{
    uint64_t due = behaviour_next_test_ms(w);
    unsigned m;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        if (w->status[m] == RUNNING && BEHAVIOUR_PERIOD_MS < due) {
            due = BEHAVIOUR_PERIOD_MS;
        }
    }
    return due;
}

int behaviour_finished(const struct world *w)
{
    unsigned m;
    for (m = 0; m < BEHAVIOUR_MACHINES; m++) {
        if (machine_starts[m] && !done(w, m)) {
            return 0;
        }
    }
    return 1;
}

#endif
