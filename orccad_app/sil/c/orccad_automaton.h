/* orccad_automaton.h: the mission's automaton in the controller process. Part of the ORCCAD
 * runtime library; C99, no allocation.
 *
 * The automaton is the C that `orccad codegen` generates for the mission (PREFIX.h/.c,
 * docs/deploy.md part 1); the generated orccad_automaton_binding.h names its prefix
 * (ORC_A(step) is PREFIX_step) and the sizes of one reaction's words.
 *
 * One reaction over the wire (OP_REACT), in 8-byte words, native byte order: the request
 * is the instant's clock [ns] (int64), then, for every input of PREFIX_inputs[] in table
 * order, its presence (int64 0/1) and its value's words (none for a pure signal; one for a
 * scalar: int64, double, bool as int64 0/1, a string as its int64 index in
 * PREFIX_string_names; `size` for a vector). The reply is the step's return (int64: the
 * mission's status, or the negative code of PREFIX_errors), the instant's status, the state
 * reached, the failure reason (string index, -1: none), the number of outputs emitted, then
 * for every output of PREFIX_outputs[] its presence and value's words, as the inputs. */
#ifndef ORCCAD_AUTOMATON_H
#define ORCCAD_AUTOMATON_H

#include <stdint.h>
#include <string.h>

#include "orccad_automaton_binding.h"

#define ORC_REACT_HEAD_WORDS 5

/* An int64 word of a reaction (its bits in the 8-byte slot), read and written. */
static inline int64_t orc_word_int(const double *word)
{
    int64_t value;
    memcpy(&value, word, sizeof value);
    return value;
}

static inline void orc_word_set_int(double *word, int64_t value)
{
    memcpy(word, &value, sizeof value);
}

/* Start (or restart) the mission: the automaton's initial state. */
void orc_automaton_reset(void);
/* One reaction: `request` of `n` words (above) in, the reply's words into `reply`
 * (ORC_AUTOMATON_OUT_WORDS of them); 0, or -1 when the request has the wrong size. */
int orc_automaton_react(const double *request, uint32_t n, double *reply, uint32_t *n_reply);
/* The phase of run site `site` in the current state (1 synchronizing, 2 measuring, 3 active;
 * 0: not running), as the mission layer reads the state's labels. */
int orc_automaton_phase(int site);

#endif
