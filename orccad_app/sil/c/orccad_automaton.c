/* orccad_automaton.c: the mission's automaton in the controller process (orccad_automaton.h):
 * one PREFIX_mem, the wire words of a reaction decoded into PREFIX_in and PREFIX_out encoded,
 * generically through the generated PREFIX_inputs / PREFIX_outputs tables. */
#include "orccad_automaton.h"

#include <stdbool.h>
#include <string.h>

static ORC_A(mem) memory;
/* The in/out structs, each in a union as large as its words: a value is copied to or from
 * its offset in the struct by the generic code below. */
static union {
    ORC_A(in) s;
    double words[ORC_AUTOMATON_IN_WORDS];
} inputs;
static union {
    ORC_A(out) s;
    double words[ORC_AUTOMATON_OUT_WORDS];
} outputs;

void orc_automaton_reset(void)
{
    ORC_A(reset)(&memory);
}

int orc_automaton_phase(int site)
{
    return ORC_A(phase)(&memory, site);
}

static int value_words(const orccad_signal_info *info)
{
    switch (info->kind) {
    case ORCCAD_PURE:
        return 0;
    case ORCCAD_INT_VECTOR:
    case ORCCAD_FLOAT_VECTOR:
        return info->size;
    default:
        return 1;
    }
}

/* The words of one value into the struct at `at` (its kind's C type). */
static void decode(const orccad_signal_info *info, char *at, const double *word)
{
    switch (info->kind) {
    case ORCCAD_INT:
    case ORCCAD_INT_VECTOR:
        memcpy(at, word, (size_t)value_words(info) * sizeof(int64_t));
        break;
    case ORCCAD_FLOAT:
    case ORCCAD_FLOAT_VECTOR:
        memcpy(at, word, (size_t)value_words(info) * sizeof(double));
        break;
    case ORCCAD_BOOL: {
        bool value = orc_word_int(word) != 0;
        memcpy(at, &value, sizeof value);
        break;
    }
    case ORCCAD_STRING: {
        int value = (int)orc_word_int(word);
        memcpy(at, &value, sizeof value);
        break;
    }
    default:
        break;
    }
}

/* The value in the struct at `at` into its words. */
static void encode(const orccad_signal_info *info, const char *at, double *word)
{
    switch (info->kind) {
    case ORCCAD_INT:
    case ORCCAD_INT_VECTOR:
        memcpy(word, at, (size_t)value_words(info) * sizeof(int64_t));
        break;
    case ORCCAD_FLOAT:
    case ORCCAD_FLOAT_VECTOR:
        memcpy(word, at, (size_t)value_words(info) * sizeof(double));
        break;
    case ORCCAD_BOOL: {
        bool value;
        memcpy(&value, at, sizeof value);
        orc_word_set_int(word, value ? 1 : 0);
        break;
    }
    case ORCCAD_STRING: {
        int value;
        memcpy(&value, at, sizeof value);
        orc_word_set_int(word, value);
        break;
    }
    default:
        break;
    }
}

int orc_automaton_react(const double *request, uint32_t n, double *reply, uint32_t *n_reply)
{
    char *in = (char *)&inputs;
    const char *out = (const char *)&outputs;
    uint32_t at = 1, put = ORC_REACT_HEAD_WORDS;
    int i, w, status;
    int64_t emitted = 0;
    if (n != ORC_AUTOMATON_IN_WORDS) {
        return -1;
    }
    for (i = 0; i < ORC_A_UP(INPUT_COUNT); i++) {
        const orccad_signal_info *info = &ORC_A(inputs)[i];
        bool present = orc_word_int(&request[at]) != 0;
        memcpy(in + info->present_offset, &present, sizeof present);
        if (present && info->kind != ORCCAD_PURE) {
            decode(info, in + info->value_offset, &request[at + 1]);
        }
        at += 1 + (uint32_t)value_words(info);
    }
    status = ORC_A(step)(&memory, orc_word_int(&request[0]), &inputs.s, &outputs.s);
    for (i = 0; i < ORC_A_UP(OUTPUT_COUNT); i++) {
        const orccad_signal_info *info = &ORC_A(outputs)[i];
        bool present = false;
        if (status >= 0) {
            memcpy(&present, out + info->present_offset, sizeof present);
        }
        orc_word_set_int(&reply[put], present ? 1 : 0);
        for (w = 0; w < value_words(info); w++) {
            orc_word_set_int(&reply[put + 1 + w], 0);
        }
        if (present) {
            emitted += 1;
            if (info->kind != ORCCAD_PURE) {
                encode(info, out + info->value_offset, &reply[put + 1]);
            }
        }
        put += 1 + (uint32_t)value_words(info);
    }
    orc_word_set_int(&reply[0], status);
    orc_word_set_int(&reply[1], status >= 0 ? outputs.s.status : status);
    orc_word_set_int(&reply[2], memory.state);
    orc_word_set_int(&reply[3], memory.reason);
    orc_word_set_int(&reply[4], emitted);
    *n_reply = put;
    return 0;
}
