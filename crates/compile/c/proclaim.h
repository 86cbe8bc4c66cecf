/* proclaim's compiled behaviours: the world a behaviour runs in, the callbacks by which it tells
 * its host what happens, and the functions a host calls. A behaviour's `behaviour.h` defines its
 * sizes (`BEHAVIOUR_MACHINES`, ...) and includes this file. Freestanding C99: no heap, no library
 * beyond <stdint.h>. Copied by `proclaim compile` (do not edit the copy). */
#ifndef PROCLAIM_H
#define PROCLAIM_H
#include <stdint.h>

struct world;

/* What the behaviour tells its host: postings, and the events of `proclaim run --trace`. */
struct world_callbacks {
    /* `priority` is the poster's subsumption layer (the manifest's `priority`, 0 by default). */
    void (*post)(struct world *w, const char *machine, const char *type, const char *content,
                 unsigned long priority);
    /* A posting to a type under subsumption that no reader saw: `by`'s posting, of the higher
     * `by_priority`, holds the type until `until_ms`. */
    void (*suppressed)(struct world *w, const char *machine, const char *type, const char *content,
                       unsigned long priority, const char *by, unsigned long by_priority,
                       uint64_t until_ms);
    /* A hold ran out and this lower posting, made at `posted_ms`, is what readers see now. */
    void (*took_over)(struct world *w, const char *machine, const char *type, const char *content,
                      unsigned long priority, uint64_t posted_ms);
    void (*entered)(struct world *w, const char *machine, const char *state, long id);
    void (*finished)(struct world *w, const char *machine, const char *state);
    /* An expert was asked `atom` and answered `value`, which it posts (may be NULL): the
     * impersonator's answer to an atom its script has not posted yet is the first the trace
     * shows of it. */
    void (*queried)(struct world *w, const char *atom, int value);
    /* The answers a transition's label read, once the label is proved (as the runner reports
     * them). `expert` is NULL when no expert answers the atom (one from outside the host does not
     * supply, or one nobody answers); then `poster` is the module whose posting of the atom the
     * machine read (a machine's `NameIsRunning`: that machine), or NULL when nothing was posted. */
    void (*answered)(struct world *w, const char *machine, const char *atom, int value, const char *expert,
                     const char *poster);
    void (*fired)(struct world *w, const char *machine, long from, long to, const char *label);
    /* A variable's value changed (its text as the trace shows it). */
    void (*assigned)(struct world *w, const char *machine, const char *variable, const char *value);
    void (*printed)(struct world *w, const char *machine, const char *text);
    /* A machine obeys a control command (`On`, `Off`, `suspend`, `resume`, `restart`). */
    void (*control)(struct world *w, const char *machine, const char *command);
    void (*warned)(struct world *w, const char *machine, const char *message);
    /* At the start of each round, before its ringlets: post what came from outside by now. */
    void (*round_started)(struct world *w);
};

/* A variable's value as the runner holds it: a whole number, or a truth value (0 or 1); or
 * none, a whiteboard value never posted. */
struct value {
    int64_t i;
    unsigned char is_bool;
    unsigned char none;
};

#if BEHAVIOUR_SUPPRESSED
/* A posting to a type under subsumption, kept: by whom, when, and its text. */
struct held_posting {
    unsigned char known;
    unsigned machine;
    uint64_t at_ms;
    char text[BEHAVIOUR_HELD_TEXT];
};

/* One type under subsumption: the posting readers see, the newest of each layer (seen or held
 * back), and whether the one seen stands over a lower one that takes over when its hold ends. */
struct held_line {
    struct held_posting shown;
    struct held_posting newest[BEHAVIOUR_LAYERS];
    unsigned char subsuming;
};
#endif

/* The whiteboard's values the behaviour reads and its machines' states. */
struct world {
    struct world_callbacks cb;
    void *user;
    /* The user's millisecond counter: set before each behaviour_round. */
    uint64_t now_ms;
    uint64_t round;
    long state[BEHAVIOUR_MACHINES];
    unsigned char just_entered[BEHAVIOUR_MACHINES];
    uint64_t entered_ms[BEHAVIOUR_MACHINES];
    /* When each composite state was entered, and whether a move into it waits for its
     * machine's next ringlet to arrive (its time starts then, as its state's does). */
    uint64_t composite_ms[BEHAVIOUR_COMPOSITES];
    unsigned char composite_entering[BEHAVIOUR_COMPOSITES];
    /* Each theory input: known, then true. */
    unsigned char input[BEHAVIOUR_VARIABLES];
    /* The answers each machine's last ringlet saw. */
    unsigned char seen[BEHAVIOUR_MACHINES][BEHAVIOUR_OUTPUTS];
    /* Whether each answer has an answerer: a theory's always, an atom from outside once the
     * host supplies it. */
    unsigned char supplied[BEHAVIOUR_OUTPUTS];
    /* The answers each machine's last ringlet asked (a label's `&&` and `||` ask no further than
     * they need): an atom from outside is news only to a machine that asked it. */
    unsigned char asked[BEHAVIOUR_MACHINES][BEHAVIOUR_OUTPUTS];
    long initial[BEHAVIOUR_MACHINES];
    /* Running, suspended or dormant; started in this round (it rings from the next). */
    unsigned char status[BEHAVIOUR_MACHINES];
    unsigned char fresh[BEHAVIOUR_MACHINES];
    /* Each machine's own variables, then the behaviour's globals. */
    struct value var[BEHAVIOUR_VALUES];
    /* Each whiteboard value the machines read: the board's newest value, whether any was posted
     * (one never posted reads as a whole 0 when bound with `extern`, else as none), and who
     * posted it. */
    struct value ext[BEHAVIOUR_EXTERNS];
    unsigned char ext_known[BEHAVIOUR_EXTERNS];
    const char *ext_by[BEHAVIOUR_EXTERNS];
    /* Each whiteboard value a label asks that the host's script answers as the impersonator
     * (no module of the behaviour declares the atom; `behaviour_supply` marks it), and the
     * script's value of it now (false until the script posts one). */
    unsigned char scripted[BEHAVIOUR_EXTERNS];
    unsigned char scripted_value[BEHAVIOUR_EXTERNS];
    /* As each machine's last ringlet saw them: the board at its snapshot, the values it posted
     * itself since, and whether it read the snapshot at all (a ringlet that read nothing of the
     * board finds nothing new in a posting). */
    struct value ext_seen[BEHAVIOUR_MACHINES][BEHAVIOUR_EXTERNS];
    unsigned char ext_seen_known[BEHAVIOUR_MACHINES][BEHAVIOUR_EXTERNS];
    const char *ext_seen_by[BEHAVIOUR_MACHINES][BEHAVIOUR_EXTERNS];
    /* The atoms nobody answers that each machine's last ringlet asked, read from these values,
     * and what it read: news is then a posting whose truth differs. */
    unsigned char asked_posted[BEHAVIOUR_MACHINES][BEHAVIOUR_EXTERNS];
    unsigned char asked_answer[BEHAVIOUR_MACHINES][BEHAVIOUR_EXTERNS];
    struct value ext_own[BEHAVIOUR_MACHINES][BEHAVIOUR_EXTERNS];
    unsigned char ext_owned[BEHAVIOUR_MACHINES][BEHAVIOUR_EXTERNS];
    unsigned char ext_read[BEHAVIOUR_MACHINES];
    /* The machine whose ringlet runs, and whether that ringlet is past its snapshot. */
    unsigned ringing;
    unsigned char past_snapshot;
    /* Changes of globals so far, and as each machine's last ringlet saw them. */
    uint64_t globals_changes;
    uint64_t globals_seen[BEHAVIOUR_MACHINES];
    /* Control commands posted to each machine, obeyed when the ringlet that posted them ends. */
    unsigned char command[BEHAVIOUR_MACHINES][BEHAVIOUR_COMMANDS];
    const char *command_word[BEHAVIOUR_MACHINES][BEHAVIOUR_COMMANDS];
    unsigned command_count[BEHAVIOUR_MACHINES];
    /* The answers the label being proved has read, reported once it is proved. */
    struct pending_answer {
        const char *atom;
        const char *expert;
        const char *poster;
        int value;
    } pending[BEHAVIOUR_ASKS];
    unsigned pending_count;
    /* Whether a command waits (so a ringlet that posted none costs no look at every machine). */
    unsigned char commands_waiting;
    /* The text a posting or a print is built in. */
    char text[BEHAVIOUR_TEXT];
    unsigned text_length;
#if BEHAVIOUR_RANGES
    /* The values from outside already said to leave each declared range (the manifest's
     * `[ranges]`), said once each as the runner says them: at most BEHAVIOUR_RANGE_MEMORY a
     * type, since C has no heap (past that the next value is said with "and later values are
     * not said", then none), and whether a text was said. */
    int64_t range_said[BEHAVIOUR_RANGES][BEHAVIOUR_RANGE_MEMORY];
    unsigned char range_said_count[BEHAVIOUR_RANGES];
    unsigned char range_text_said[BEHAVIOUR_RANGES];
#endif
#if BEHAVIOUR_SUPPRESSED
    /* Each type under subsumption, in name order. */
    struct held_line held[BEHAVIOUR_SUPPRESSED];
#endif
};

void behaviour_init(struct world *w);
/* One round: a ringlet of every machine in manifest order; 1 when one fired (the next round follows at once). */
int behaviour_round(struct world *w);
/* A posting from outside the machines (an impersonator, a sensor); 1 when it is news to a machine's
 * labels. `content` is a truth value (`true`, `false`) or a whole number (`-5`); a variable the
 * machines bind with `extern` keeps its value on anything else, and the `warned` callback says so,
 * as it does of a value that leaves the type's declared range (the manifest's `[ranges]`). */
int behaviour_outside(struct world *w, const char *type, const char *content);
/* 1 when an answer a machine's current labels read differs from what its last ringlet saw. */
int behaviour_news(const struct world *w);
/* 1 when `atom` is an answer of the behaviour's theories. */
int behaviour_answers(const char *atom);
/* The host answers `atom` from outside (a script or its own sensor sets it): 1 when the
 * behaviour's labels ask it, or it is a whiteboard value its machines read (a label asking it is
 * then answered by the impersonator, the script's value, false until the script posts one).
 * Unsupplied, such an atom is false and answered by no expert. */
int behaviour_supply(struct world *w, const char *atom);
/* Module `s`'s name (a sensor wrapper, a Prolog or program expert), NULL past the last; its atom
 * `i`, NULL past the last. A host supplies one of each module's atoms (the interpreter leaves
 * the module out then). */
const char *behaviour_sensor_name(unsigned s);
const char *behaviour_sensor_atom(unsigned s, unsigned i);
/* 1 when `name` is a machine's (a posting to it is a control command). */
int behaviour_is_machine(const char *name);
/* Milliseconds from now_ms until the next round is due without news (a timeout or the ring
 * period); UINT64_MAX while no machine runs (then only news starts a round, as the runner waits). */
uint64_t behaviour_next_due_ms(const struct world *w);
/* Milliseconds from now_ms until a running machine's time test, or a hold with a lower posting
 * behind it, comes due; UINT64_MAX when nothing waits on the clock. */
uint64_t behaviour_next_test_ms(const struct world *w);
/* 1 when every machine that starts with the behaviour is in a final state, its OnEntry run. */
int behaviour_finished(const struct world *w);


#endif
